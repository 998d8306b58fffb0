// sim/possrc: the simulated laser positioning system against seed 002's packet format decoded
// here, the receivers' true positions worked here, the update rate, the lag, the bit timing of
// the line, the noise's spread, and each trouble: outages, dropouts, zeros, wild positions,
// garbage, corrupted bytes, a transmitter out of sight or range, a line too slow for the rate.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

extern "C" {
#include "drive/drive_cmd.h"
#include "drive/drive_proto.h"
#include "hal/irq.h"
#include "hal/uart.h"
#include "hal_posix/harness.h"
#include "sim/possrc.h"
}

namespace
{

struct Byte {
    uint8_t b;
    uint64_t t;
    int line;
};
std::vector<Byte> g_bytes;

void on_byte0(void *, uint8_t b, uint8_t)
{
    g_bytes.push_back({b, posix_now_ns(), 0});
}
void on_byte1(void *, uint8_t b, uint8_t)
{
    g_bytes.push_back({b, posix_now_ns(), 1});
}

// A seed-002 packet in a byte stream: the 14 bytes ending at index i.
struct Packet {
    int32_t x, y, z;
    uint64_t t;
    int line;
};

int32_t be32(const uint8_t *b)
{
    return (int32_t)((uint32_t)b[0] << 24 | (uint32_t)b[1] << 16 | (uint32_t)b[2] << 8 | b[3]);
}

// Packets of one line: each 0x00 .. 0xFF run of 14 bytes (clean streams only).
std::vector<Packet> packets(int line)
{
    std::vector<uint8_t> s;
    std::vector<uint64_t> t;
    for (const Byte &b : g_bytes)
        if (b.line == line) {
            s.push_back(b.b);
            t.push_back(b.t);
        }
    std::vector<Packet> out;
    for (size_t i = 0; i + 14 <= s.size();) {
        if (s[i] == 0x00 && s[i + 13] == 0xFF) {
            out.push_back({be32(&s[i + 1]), be32(&s[i + 5]), be32(&s[i + 9]), t[i + 13], line});
            i += 14;
        } else {
            i++;
        }
    }
    return out;
}

struct Bench {
    int board;
    sim_scenario_t sc{};
    sim_drive_t d;
    sim_possrc_t src;
    explicit Bench(double heading = 0.0, double speed_mps = 0.0)
    {
        posix_reset();
        g_bytes.clear();
        board = posix_board_create("main");
        posix_board_select(board);
        EXPECT_EQ(hal_uart_open(0, HAL_UART_BAUD_9600, on_byte0, nullptr), HAL_UART_OK);
        EXPECT_EQ(hal_uart_open(1, HAL_UART_BAUD_9600, on_byte1, nullptr), HAL_UART_OK);
        hal_irq_enable();
        sc.seed = 11;
        sc.world.n_beacons = 3;
        sc.world.beacon[0] = {0, 0, 0.08, SIM_BEACON_KIND_CYLINDER};
        sc.world.beacon[1] = {10, 0, 0.08, SIM_BEACON_KIND_CYLINDER};
        sc.world.beacon[2] = {0, 8, 0.08, SIM_BEACON_KIND_CYLINDER};
        sc.src.rate_hz = 10;
        sc.src.lag = 0.5;
        sc.src.range = 250;
        sc.src.height = 1.2;
        sc.src.baud = 9600;
        sc.src.wild_m = 1.0;
        drive_board_t units = DRIVE_BOARD_SEED;
        sim_drive_init(&d, &units, 0.762, board, {3.0, 2.0, heading}, nullptr, nullptr, nullptr);
        if (speed_mps > 0) { // straight ahead at that speed (seed 002's DAC style)
            drive_wseq_t s;
            drive_dac_start(132, &s);
            for (int i = 0; i < s.n; i++)
                sim_drive_write(&d, s.w[i].reg, s.w[i].value);
            drive_dac_set(132, drive_dac_speed_byte((int8_t)std::lround(speed_mps / 0.01755)), &s);
            for (int i = 0; i < s.n; i++)
                sim_drive_write(&d, s.w[i].reg, s.w[i].value);
        }
    }
    void start()
    {
        sim_possrc_init(&src, &sc, &d, board);
        sim_possrc_start(&src);
    }
    void run(double t)
    {
        posix_run_until((uint64_t)(t * 1e9));
    }
};

TEST(Possrc, PacketsAtTheRateAfterTheLag)
{
    Bench b;
    b.sc.src.height = 1.25;
    b.start();
    b.run(10.05);
    auto p = packets(0);
    // updates at 0.1, 0.2, ... s; sent 0.5 s later; 140 bit times on the line
    ASSERT_EQ(p.size(), 95u); // 0.1 .. 9.5 s: the last four still lagging
    const double packet_s = 140.0 / 9600;
    for (size_t k = 0; k < p.size(); k++) {
        EXPECT_NEAR(p[k].t * 1e-9, 0.1 * (k + 1) + 0.5 + packet_s, 1e-6) << k;
        EXPECT_EQ(p[k].x, 3000);
        EXPECT_EQ(p[k].y, 2000);
        EXPECT_EQ(p[k].z, 1250);
    }
    EXPECT_TRUE(packets(1).empty()) << "one receiver: nothing on the second line";
    EXPECT_EQ(b.src.st.updates, 100u);
    EXPECT_EQ(b.src.st.sent, 95u);
}

TEST(Possrc, ReceiversMountedOnTheMovingVehicle)
{
    Bench b(M_PI / 2, 1.0); // heading north at 57 counts x 1.755 cm/s
    b.sc.src.lag = 0.3;
    b.sc.src.n_receivers = 2;
    b.sc.src.receiver[0] = {0.3, 0.1}; // 0.3 m ahead, 0.1 m left
    b.sc.src.receiver[1] = {0.0, 0.0};
    b.start();
    b.run(3.0);
    auto p1 = packets(0), p2 = packets(1);
    ASSERT_EQ(p1.size(), p2.size());
    ASSERT_GT(p1.size(), 20u);
    double v = 57 * 1150.0 / 65536; // the board's Q16 speed unit
    for (size_t k = 0; k < p1.size(); k++) {
        double tm = 0.1 * (k + 1); // the instant measured
        // heading north: ahead is +y, left is -x
        EXPECT_EQ(p1[k].x, std::lround((3.0 - 0.1) * 1000));
        EXPECT_NEAR(p1[k].y, (2.0 + 0.3 + v * tm) * 1000, 0.51);
        EXPECT_EQ(p2[k].x, 3000);
        EXPECT_NEAR(p2[k].y, (2.0 + v * tm) * 1000, 0.51);
        EXPECT_EQ(p1[k].t, p2[k].t) << "same instant, same lag, same line speed";
    }
}

TEST(Possrc, NoiseRelativeToTheFarthestTransmitter)
{
    Bench b;
    b.sc.src.noise_rel = 1e-3; // 1 part in 1,000 to see it in millimetres
    b.start();
    b.run(300.0);
    auto p = packets(0);
    ASSERT_GT(p.size(), 2900u);
    // transmitters at the beacons' corners (0, 0), (10, 0), (0, 8): the farthest from (3, 2)
    // is (10, 0), at sqrt(49 + 4) m
    double sigma = 1e-3 * std::sqrt(53.0) * 1000; // mm
    double sx = 0, sxx = 0, sy = 0, syy = 0;
    for (const Packet &q : p) {
        sx += q.x - 3000;
        sxx += (q.x - 3000.0) * (q.x - 3000.0);
        sy += q.y - 2000;
        syy += (q.y - 2000.0) * (q.y - 2000.0);
    }
    double n = (double)p.size();
    EXPECT_NEAR(std::sqrt(sxx / n - (sx / n) * (sx / n)), sigma, 0.05 * sigma);
    EXPECT_NEAR(std::sqrt(syy / n - (sy / n) * (sy / n)), sigma, 0.05 * sigma);
    EXPECT_NEAR(sx / n, 0, 0.1 * sigma);
}

TEST(Possrc, OutagesDropoutsAndZeros)
{
    Bench b;
    b.sc.src.n_outages = 2;
    b.sc.src.outage[0] = {2.0, 4.0};
    b.sc.src.outage[1] = {95.0, 1000.0}; // the last packets are on the line by the end
    b.sc.src.dropout = 0.3;
    b.sc.src.zero = 0.2;
    b.start();
    b.run(100.0);
    auto p = packets(0);
    size_t zeros = 0, in_outage = 0;
    for (const Packet &q : p) {
        double tm = (q.t * 1e-9) - 0.5 - 140.0 / 9600; // the instant measured
        in_outage += tm >= 2.0 - 1e-9 && tm < 4.0 - 1e-9;
        zeros += q.x == 0 && q.y == 0 && q.z == 0;
    }
    EXPECT_EQ(in_outage, 0u);
    EXPECT_EQ(b.src.st.outage, 20u + 51u);
    double measured = b.src.st.updates - b.src.st.outage;
    EXPECT_NEAR(b.src.st.dropouts / measured, 0.3, 0.03);
    EXPECT_EQ(zeros, b.src.st.zeros);
    EXPECT_NEAR(zeros / (measured - b.src.st.dropouts), 0.2, 0.03);
    EXPECT_EQ(p.size(), b.src.st.sent);
}

TEST(Possrc, WildPositionsAreHalfToOneAndAHalfTimesOff)
{
    Bench b;
    b.sc.src.wild = 0.5;
    b.sc.src.wild_m = 2.0;
    b.sc.src.n_outages = 1;
    b.sc.src.outage[0] = {55.0, 1000.0}; // the last packets are on the line by the end
    b.start();
    b.run(60.0);
    size_t wild = 0;
    for (const Packet &q : packets(0)) {
        double d = std::hypot(q.x - 3000.0, q.y - 2000.0) / 1000;
        if (d > 0.001) {
            wild++;
            EXPECT_GE(d, 1.0 - 1e-3);
            EXPECT_LE(d, 3.0 + 1e-3);
        }
    }
    EXPECT_EQ(wild, b.src.st.wilds);
    EXPECT_GT(wild, 200u);
}

TEST(Possrc, GarbageAndCorruptBytes)
{
    Bench b;
    b.sc.src.garbage = 1.0;
    b.sc.src.corrupt = 0.01;
    b.sc.src.n_outages = 1;
    b.sc.src.outage[0] = {15.0, 1000.0}; // the last packets are on the line by the end
    b.start();
    b.run(20.0);
    size_t bytes = 0;
    for (const Byte &x : g_bytes)
        bytes += x.line == 0;
    EXPECT_EQ(bytes, 14u * b.src.st.sent + b.src.st.garbage_bytes);
    EXPECT_GE(b.src.st.garbage_bytes, b.src.st.sent); // 1 to 20 a packet
    EXPECT_LE(b.src.st.garbage_bytes, 20u * b.src.st.sent);
    EXPECT_GT(b.src.st.corrupt_bytes, 0u);
}

TEST(Possrc, OutOfSightOrRange)
{
    Bench b;
    b.sc.world.n_occluders = 1; // a wall between the vehicle and the transmitter at (0, 8)
    b.sc.world.occluder[0] = {-1.0, 5.0, 5.0, 5.0};
    b.start();
    b.run(5.0);
    EXPECT_TRUE(packets(0).empty());
    EXPECT_EQ(b.src.st.no_sight, b.src.st.updates);
    Bench c;
    c.sc.src.range = 6.0; // (0, 8) is 6.7 m away
    c.sc.src.n_transmitters = 3;
    c.sc.src.transmitter[0] = {0, 0};
    c.sc.src.transmitter[1] = {10, 0};
    c.sc.src.transmitter[2] = {0, 8};
    c.start();
    c.run(5.0);
    EXPECT_TRUE(packets(0).empty());
    EXPECT_EQ(c.src.st.no_sight, c.src.st.updates);
}

TEST(Possrc, ALineTooSlowForTheRate)
{
    Bench b;
    b.sc.src.rate_hz = 100; // 9600 baud carries 68.6 packets a second
    b.start();
    b.run(20.5);
    double per_s = b.src.st.sent / 20.0;
    EXPECT_LE(per_s, 9600.0 / 140 + 1);
    EXPECT_GT(per_s, 60.0);
    EXPECT_GT(b.src.st.line_busy, 500u);
    EXPECT_EQ(b.src.st.sent + b.src.st.line_busy + 50u, b.src.st.updates) << "50 still lagging";
}

} // namespace
