// sim/path_index: the grid index gives exactly the distance that the definition gives (the
// minimum over every piece, sim_path_distance), and its work per query does not grow with
// the path's length.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

extern "C" {
#include "sim/path.h"
#include "sim/path_index.h"
}

namespace
{

struct Lcg {
    uint32_t x;
    double next(double lo, double hi)
    {
        x = x * 1664525u + 1013904223u;
        return lo + (hi - lo) * (x >> 8) / 16777216.0;
    }
};

// A serpentine of `lanes` lanes of 20 m, 2 m apart, joined by half circles (distinct pieces).
void serpentine(sim_path_t *p, int lanes)
{
    p->n = 0;
    sim_pose_t s = {0.0, 0.0, 0.0};
    for (int i = 0; i < lanes; i++) {
        ASSERT_EQ(sim_path_append(p, s, 0.0, 20.0, 0), 0);
        ASSERT_EQ(sim_path_append(p, s, (i % 2 ? -1.0 : 1.0), M_PI, 0), 0);
    }
}

TEST(PathIndex, EqualsTheMinimumOverEveryPiece)
{
    static sim_path_t p;
    p.n = 0;
    sim_pose_t s = {1.0, 2.0, 0.3};
    // Straights, left and right arcs, a full circle, a piece driven backwards, and the same
    // loop twice (the second lap repeats the first exactly).
    for (int lap = 0; lap < 2; lap++) {
        ASSERT_EQ(sim_path_append_from(&p, s, 0.0, 3.0, 0), 0);
        ASSERT_EQ(sim_path_append(&p, s, 1.0 / 1.5, 2.5, 0), 0);
        ASSERT_EQ(sim_path_append(&p, s, -1.0 / 0.8, 1.9, 0), 0);
        ASSERT_EQ(sim_path_append(&p, s, 0.5, 4.0 * M_PI, 0), 0);
        ASSERT_EQ(sim_path_append(&p, s, 0.4, 1.0, 1), 0);
    }
    static sim_path_index_t ix;
    ASSERT_EQ(sim_path_index_build(&ix, &p), 0);
    EXPECT_EQ(ix.n_distinct, 5u); // the second lap is filed once
    Lcg r{7};
    for (int i = 0; i < 20000; i++) {
        // Near the path, across the grid and far outside it.
        double span = i < 10000 ? 8.0 : 60.0;
        double x = r.next(-span, span), y = r.next(-span, span);
        double want = sim_path_distance(&p, x, y);
        double got = sim_path_index_distance(&ix, x, y);
        ASSERT_EQ(got, want) << x << "," << y; // bit for bit: the same minimum
    }
    sim_path_index_free(&ix);
}

TEST(PathIndex, EmptyPathIsInfinitelyFar)
{
    static sim_path_t p;
    p.n = 0;
    static sim_path_index_t ix;
    ASSERT_EQ(sim_path_index_build(&ix, &p), 0);
    EXPECT_TRUE(std::isinf(sim_path_index_distance(&ix, 0.0, 0.0)));
    sim_path_index_free(&ix);
}

// Pieces examined per query near the path of a 100 m and a 1 km serpentine: the same.
double examined_per_query(int lanes)
{
    static sim_path_t p;
    serpentine(&p, lanes);
    static sim_path_index_t ix;
    EXPECT_EQ(sim_path_index_build(&ix, &p), 0);
    Lcg r{11};
    const int n = 20000;
    for (int i = 0; i < n; i++) {
        // A point up to 10 cm beside a random point of the path.
        const sim_piece_t &pc = p.piece[(size_t)(r.next(0, (double)p.n)) % p.n];
        sim_piece_t part = pc;
        part.length = r.next(0, pc.length);
        sim_pose_t e = sim_piece_end(&part);
        double off = r.next(-0.1, 0.1);
        double x = e.x - off * std::sin(e.th), y = e.y + off * std::cos(e.th);
        EXPECT_EQ(sim_path_index_distance(&ix, x, y), sim_path_distance(&p, x, y));
    }
    double per = (double)ix.examined / (double)ix.queries;
    sim_path_index_free(&ix);
    return per;
}

TEST(PathIndex, WorkPerQueryIsFlatInPathLength)
{
    double short_route = examined_per_query(4); // 4 x (20 + pi) m = 93 m
    double long_route = examined_per_query(44); // 1,018 m
    std::printf("pieces examined per query: %.3f (93 m), %.3f (1,018 m)\n", short_route,
                long_route);
    EXPECT_LT(long_route, 1.2 * short_route);
    EXPECT_LT(long_route, 4.0);
}

} // namespace
