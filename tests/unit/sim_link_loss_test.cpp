// sim/link_loss: frames lost with the scenario's probability (each independently: the count is
// binomial), every frame in an outage window, none without a disturbance; the same seed loses
// the same frames.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

extern "C" {
#include "sim/link_loss.h"
}

namespace
{

sim_scenario_t quiet()
{
    sim_scenario_t sc;
    std::memset(&sc, 0, sizeof sc);
    sc.seed = 11;
    return sc;
}

TEST(LinkLoss, NoDisturbanceLosesNothing)
{
    sim_scenario_t sc = quiet();
    EXPECT_FALSE(sim_link_loss_active(&sc));
    sim_link_loss_t l;
    sim_link_loss_init(&l, &sc);
    for (int i = 0; i < 1000; i++)
        EXPECT_FALSE(sim_link_loss_frame(&l, i * 0.01));
    EXPECT_EQ(l.sent, 1000u);
    EXPECT_EQ(l.lost, 0u);
}

TEST(LinkLoss, DropsAreBinomialAndRepeatable)
{
    sim_scenario_t sc = quiet();
    sc.link_drop = 0.1;
    EXPECT_TRUE(sim_link_loss_active(&sc));
    sim_link_loss_t l, again;
    sim_link_loss_init(&l, &sc);
    sim_link_loss_init(&again, &sc);
    const int n = 20000;
    int lost = 0;
    for (int i = 0; i < n; i++) {
        bool x = sim_link_loss_frame(&l, i * 0.001);
        EXPECT_EQ(x, sim_link_loss_frame(&again, i * 0.001));
        lost += x;
    }
    double mean = n * 0.1, sd = std::sqrt(n * 0.1 * 0.9);
    EXPECT_LT(std::fabs(lost - mean), 5 * sd) << lost;
    EXPECT_EQ(l.lost, (uint32_t)lost);
}

TEST(LinkLoss, OutagesLoseEveryFrameInTheirWindow)
{
    sim_scenario_t sc = quiet();
    sc.n_link_outages = 2;
    sc.link_outage[0] = {1.0, 0.5};
    sc.link_outage[1] = {3.0, 0.25};
    EXPECT_TRUE(sim_link_loss_active(&sc));
    sim_link_loss_t l;
    sim_link_loss_init(&l, &sc);
    for (int i = 0; i < 4000; i++) {
        double t = i * 0.001;
        bool in = (t >= 1.0 && t < 1.5) || (t >= 3.0 && t < 3.25);
        EXPECT_EQ(sim_link_loss_frame(&l, t), in) << t;
    }
}

} // namespace
