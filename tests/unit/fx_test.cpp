// Tests of firmware/fx (fixed-point navigation math) against independent references: libm in
// long double precision for the transcendental functions, exact 128-bit integer arithmetic
// for the roots, multiplies and divides. Each function's largest error over its whole input
// range (dense sweeps, exhaustive where the domain allows, plus random inputs of every
// magnitude) is printed and asserted against the bound documented in fx.h and the floor of
// issue 3 (sin/cos 1e-6, atan2 0.0005 degrees, roots exact).
#include <gtest/gtest.h>

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <random>

extern "C" {
#include "fx/fx.h"
#include "fx/fx_host.h"
}

namespace
{

using ld = long double;
using i128 = __int128;

const ld kPi = 3.141592653589793238462643383279502884L;
const ld kTurn = 4294967296.0L;

ld angle_rad(fx_angle_t a)
{
    return (ld)a * (2 * kPi / kTurn);
}

// Difference of two angles in radians, wrapped to (-pi, pi].
ld angle_diff(fx_angle_t got, ld want_rad)
{
    ld d = angle_rad(got) - want_rad;
    d = std::fmod(d, 2 * kPi);
    if (d > kPi)
        d -= 2 * kPi;
    if (d <= -kPi)
        d += 2 * kPi;
    return d;
}

std::mt19937_64 &gen()
{
    static std::mt19937_64 g(0xC1C10F10u);
    return g;
}

uint32_t r32()
{
    return (uint32_t)gen()();
}

uint64_t r64()
{
    return gen()();
}

// Random value of a random bit length: small and large magnitudes alike.
uint32_t rmag32()
{
    return r32() >> (r32() % 32u);
}

uint64_t rmag64()
{
    return r64() >> (r32() % 64u);
}

int32_t rsigned()
{
    uint32_t m = rmag32();
    return (r32() & 1u) ? (int32_t)(0u - m) : (int32_t)m;
}

struct MaxErr {
    const char *name;
    ld max = 0;
    long n = 0;
    void add(ld e)
    {
        e = std::fabs(e);
        if (e > max)
            max = e;
        n++;
    }
};

// Round n / d to nearest, ties away from zero (exact reference for the divides).
i128 div_round(i128 n, i128 d)
{
    bool neg = (n < 0) != (d < 0);
    i128 an = n < 0 ? -n : n, ad = d < 0 ? -d : d;
    i128 q = an / ad, r = an % ad;
    if (2 * r >= ad)
        q++;
    return neg ? -q : q;
}

bool fits32(i128 v)
{
    return v >= INT32_MIN && v <= INT32_MAX;
}

// ------------------------------------------------------------------ sin, cos

void sin_cos_at(fx_angle_t a, MaxErr &es, MaxErr &ec)
{
    fx_q30_t s = fx_sin(a), c = fx_cos(a);
    ld x = angle_rad(a);
    es.add((ld)s / FX_Q30_ONE - std::sin(x));
    ec.add((ld)c / FX_Q30_ONE - std::cos(x));
    ASSERT_LE(std::abs((long)s), FX_Q30_ONE) << a;
    ASSERT_LE(std::abs((long)c), FX_Q30_ONE) << a;
}

TEST(FxSinCos, MaxErrorOverTheCircle)
{
    MaxErr es{"fx_sin"}, ec{"fx_cos"};
    // Every 1024th angle of the whole turn (4.2 million angles) ...
    for (uint64_t a = 0; a < (1ull << 32); a += 1024)
        sin_cos_at((fx_angle_t)a, es, ec);
    // ... every angle around each table node and quadrant boundary (the fraction's rounding,
    // the fold), and random angles.
    for (uint32_t q = 0; q < 4; q++)
        for (uint32_t k = 0; k <= 128; k++)
            for (int32_t d = -300; d <= 300; d++)
                sin_cos_at((q << 30) + (k << 23) + (uint32_t)d, es, ec);
    for (int i = 0; i < 2000000; i++)
        sin_cos_at(r32(), es, ec);
    std::printf("fx_sin max error %.3Le (%.1Lf LSB of Q1.30) over %ld angles\n", es.max,
                es.max * FX_Q30_ONE, es.n);
    std::printf("fx_cos max error %.3Le (%.1Lf LSB of Q1.30) over %ld angles\n", ec.max,
                ec.max * FX_Q30_ONE, ec.n);
    RecordProperty("fx_sin_max_error", std::to_string((double)es.max));
    RecordProperty("fx_cos_max_error", std::to_string((double)ec.max));
    EXPECT_LE(es.max, 1.1e-7L); // fx.h
    EXPECT_LE(ec.max, 1.1e-7L);
    EXPECT_LE(es.max, 1e-6L); // issue 3 floor
    EXPECT_LE(ec.max, 1e-6L);
}

TEST(FxSinCos, ExhaustiveOverTheFirstQuadrant)
{
    // fx_sin depends on an angle of the first quadrant only through its nearest multiple of
    // 2^7 (the 16-bit fraction of a table step), and sin rises there, so its error is largest
    // at an end of such a window: both ends of all 2^23 windows cover every angle of the
    // quadrant. The other quadrants and cos are exact mirrors (ExactValuesAndSymmetries).
    MaxErr e{"fx_sin"};
    for (uint32_t m = 0; m <= (1u << 23); m++) {
        for (int64_t x : {(int64_t)m * 128 - 64, (int64_t)m * 128 + 63}) {
            if (x < 0 || x >= FX_Q30_ONE)
                continue;
            e.add((ld)fx_sin((fx_angle_t)x) / FX_Q30_ONE - std::sin(angle_rad((fx_angle_t)x)));
        }
    }
    std::printf("fx_sin max error %.3Le over every angle of the first quadrant (%ld window "
                "ends)\n",
                e.max, e.n);
    EXPECT_LE(e.max, 1.1e-7L);
}

TEST(FxSinCos, ExactValuesAndSymmetries)
{
    EXPECT_EQ(fx_sin(0), 0);
    EXPECT_EQ(fx_sin(FX_ANGLE_QUARTER), FX_Q30_ONE);
    EXPECT_EQ(fx_sin(FX_ANGLE_HALF), 0);
    EXPECT_EQ(fx_sin(3 * FX_ANGLE_QUARTER), -FX_Q30_ONE);
    EXPECT_EQ(fx_cos(0), FX_Q30_ONE);
    EXPECT_EQ(fx_cos(FX_ANGLE_QUARTER), 0);
    EXPECT_EQ(fx_cos(FX_ANGLE_HALF), -FX_Q30_ONE);
    for (int i = 0; i < 300000; i++) {
        fx_angle_t a = r32();
        fx_q30_t s = fx_sin(a), c = fx_cos(a), s2, c2;
        ASSERT_EQ(fx_sin(0u - a), -s) << a;              // odd
        ASSERT_EQ(fx_sin(FX_ANGLE_HALF - a), s) << a;    // symmetric about a quarter
        ASSERT_EQ(fx_cos(0u - a), c) << a;               // even
        ASSERT_EQ(c, fx_sin(a + FX_ANGLE_QUARTER)) << a; // the definition
        ASSERT_EQ(fx_sin(a + FX_ANGLE_HALF), -s) << a;   // half-turn
        fx_sincos(a, &s2, &c2);
        ASSERT_EQ(s2, s) << a;
        ASSERT_EQ(c2, c) << a;
    }
}

TEST(FxSinCos, MonotonicInTheFirstQuadrant)
{
    // The interpolation never turns back by more than the rounding of its terms (2 LSB, where
    // sin is flat next to the quarter turn): sin rises over the whole first quadrant.
    fx_q30_t prev = fx_sin(0), dip = 0;
    for (uint32_t a = 64; a <= FX_ANGLE_QUARTER; a += 64) {
        fx_q30_t s = fx_sin(a);
        dip = std::max(dip, prev - s);
        prev = std::max(prev, s);
    }
    std::printf("fx_sin: largest step backwards in the first quadrant %d LSB\n", (int)dip);
    EXPECT_LE(dip, 2);
}

// ------------------------------------------------------------------ tan, cot

// Error of a tan/cot result against the exact value t in units of the Q16 result,
// normalised by its bound 0.5 + 2^16 * 1.6e-7 * (1 + t^2) (fx.h): <= 1 passes.
ld tan_err_ratio(fx_q16_t got, ld t)
{
    ld want = t * 65536;
    ld bound = 0.5L + 65536 * 1.6e-7L * (1 + t * t);
    ld lim = (ld)FX_Q16_MAX;
    if (std::fabs(want) >= lim + bound) // must saturate, with the sign of the true value
        return got == (want > 0 ? FX_Q16_MAX : -FX_Q16_MAX) ? 0 : 1e9L;
    if (std::fabs(want) > lim - bound && std::fabs((ld)got) == lim) // may saturate
        return (got > 0) == (want > 0) ? 0 : 1e9L;
    return std::fabs((ld)got - want) / bound;
}

TEST(FxTanCot, ErrorBoundOverTheCircle)
{
    MaxErr et{"fx_tan"}, ect{"fx_cot"}, unit{"|tan| <= 1"};
    auto at = [&](fx_angle_t a) {
        if ((a & 0x3FFFFFFFu) == 0) // the poles themselves: PolesAndSymmetry
            return;
        ld t = std::tan(angle_rad(a));
        fx_q16_t ft = fx_tan(a), fc = fx_cot(a);
        et.add(tan_err_ratio(ft, t));
        ect.add(tan_err_ratio(fc, 1 / t));
        if (std::fabs(t) <= 1)
            unit.add(ft - t * 65536);
    };
    for (uint64_t a = 0; a < (1ull << 32); a += 4096 + 7)
        at((fx_angle_t)a);
    // Next to the poles and zeros, every angle.
    for (fx_angle_t c : {0x0u, 0x40000000u, 0x80000000u, 0xC0000000u})
        for (int32_t d = -200000; d <= 200000; d++)
            at(c + (uint32_t)d);
    std::printf("fx_tan max error %.3Lf LSB for |tan| <= 1; worst error / bound(0.5 LSB + "
                "1.6e-7 (1 + tan^2)) %.3Lf over %ld angles\n",
                unit.max, et.max, et.n);
    std::printf("fx_cot worst error / bound %.3Lf\n", ect.max);
    EXPECT_LE(et.max, 1.0L);
    EXPECT_LE(ect.max, 1.0L);
    EXPECT_LE(unit.max, 0.55L);
}

TEST(FxTanCot, PolesAndSymmetry)
{
    EXPECT_EQ(fx_tan(0), 0);
    EXPECT_EQ(fx_tan(FX_ANGLE_QUARTER), FX_Q16_MAX);
    EXPECT_EQ(fx_tan(3 * FX_ANGLE_QUARTER), -FX_Q16_MAX);
    EXPECT_EQ(fx_tan(FX_ANGLE_QUARTER / 2), FX_Q16_ONE);
    EXPECT_EQ(fx_cot(0), FX_Q16_MAX);
    EXPECT_EQ(fx_cot(FX_ANGLE_HALF), -FX_Q16_MAX);
    EXPECT_EQ(fx_cot(FX_ANGLE_QUARTER), 0);
    EXPECT_EQ(fx_cot(FX_ANGLE_QUARTER / 2), FX_Q16_ONE);
    // Just before the pole tan saturates positive, just after negative.
    EXPECT_EQ(fx_tan(FX_ANGLE_QUARTER - 1), FX_Q16_MAX);
    EXPECT_EQ(fx_tan(FX_ANGLE_QUARTER + 1), -FX_Q16_MAX);
    for (int i = 0; i < 200000; i++) {
        fx_angle_t a = r32();
        ASSERT_EQ(fx_tan(0u - a), -fx_tan(a)) << a;
        ASSERT_EQ(fx_cot(0u - a), -fx_cot(a)) << a;
        ASSERT_EQ(fx_tan(a + FX_ANGLE_HALF), fx_tan(a)) << a;
    }
}

// ------------------------------------------------------------------ arctangents

struct AtanErr {
    MaxErr precise{"fx_atan2"};
    void at(int32_t y, int32_t x)
    {
        if (x == 0 && y == 0)
            return;
        precise.add(angle_diff(fx_atan2(y, x), std::atan2((ld)y, (ld)x)));
    }
};

TEST(FxAtan2, MaxErrorOverTheCircle)
{
    AtanErr e;
    // Vectors of many lengths in every direction (2^20 directions per length) ...
    for (ld radius : {2.1e9L, 1.0e9L, 123456789.0L, 1048576.0L, 40000.0L, 1000.0L, 37.0L})
        for (uint32_t k = 0; k < (1u << 20); k++) {
            ld th = (k + 0.37L) * (2 * kPi / (1u << 20));
            e.at((int32_t)std::llround(radius * std::sin(th)),
                 (int32_t)std::llround(radius * std::cos(th)));
        }
    // ... every small vector ...
    for (int32_t y = -100; y <= 100; y++)
        for (int32_t x = -100; x <= 100; x++)
            e.at(y, x);
    // ... the extremes and random vectors of every magnitude.
    for (int32_t v : {INT32_MIN, INT32_MIN + 1, INT32_MAX, -1, 0, 1, 0x40000000, -0x40000000})
        for (int32_t w : {INT32_MIN, INT32_MIN + 1, INT32_MAX, -1, 0, 1, 0x40000000, 12345})
            e.at(v, w);
    for (int i = 0; i < 2000000; i++)
        e.at(rsigned(), rsigned());
    std::printf("fx_atan2 max error %.3Le rad = %.3Le deg over %ld vectors\n", e.precise.max,
                e.precise.max * 180 / kPi, e.precise.n);
    EXPECT_LE(e.precise.max, 1.3e-6L);             // fx.h
    EXPECT_LE(e.precise.max * 180 / kPi, 0.0005L); // issue 3 floor
}

TEST(FxAtan2, ExhaustiveOverTheRatioTable)
{
    // With x = 2^24 and 0 <= y <= 2^23 the ratio reaches the table exactly (q = y: no turn,
    // no rounding in the division): every table step and every fraction of it.
    MaxErr e{"fx_atan2 table"};
    for (int32_t y = 0; y <= (1 << 23); y++)
        e.add(angle_diff(fx_atan2(y, 1 << 24), std::atan2((ld)y, (ld)(1 << 24))));
    std::printf("fx_atan2 max error of the interpolated table %.3Le rad over all %ld ratios\n",
                e.max, e.n);
    EXPECT_LE(e.max, 1.3e-6L);
}

TEST(FxAtan2, ExactOnAxesAndDiagonals)
{
    for (int32_t r : {1, 2, 3, 1000, 65536, 0x12345678, INT32_MAX}) {
        EXPECT_EQ(fx_atan2(0, r), 0u);
        EXPECT_EQ(fx_atan2(r, 0), FX_ANGLE_QUARTER);
        EXPECT_EQ(fx_atan2(0, -r), FX_ANGLE_HALF);
        EXPECT_EQ(fx_atan2(-r, 0), 3 * FX_ANGLE_QUARTER);
        EXPECT_EQ(fx_atan2(r, r), FX_ANGLE_QUARTER / 2);
        EXPECT_EQ(fx_atan2(r, -r), 3 * FX_ANGLE_QUARTER / 2);
        EXPECT_EQ(fx_atan2(-r, -r), 5 * FX_ANGLE_QUARTER / 2);
        EXPECT_EQ(fx_atan2(-r, r), 7 * FX_ANGLE_QUARTER / 2);
    }
    EXPECT_EQ(fx_atan2(0, INT32_MIN), FX_ANGLE_HALF);
    EXPECT_EQ(fx_atan2(INT32_MIN, 0), 3 * FX_ANGLE_QUARTER);
    EXPECT_EQ(fx_atan2(INT32_MIN, INT32_MIN), 5 * FX_ANGLE_QUARTER / 2);
    EXPECT_EQ(fx_atan2(0, 0), 0u);
}

TEST(FxAtan2, Symmetries)
{
    for (int i = 0; i < 300000; i++) {
        int32_t y = rsigned(), x = rsigned();
        if (y == INT32_MIN || x == INT32_MIN || (x == 0 && y == 0))
            continue;
        fx_angle_t a = fx_atan2(y, x);
        ASSERT_EQ(fx_atan2(-y, x), 0u - a) << y << " " << x;
        ASSERT_EQ(fx_atan2(y, -x), (fx_angle_t)(FX_ANGLE_HALF - a)) << y << " " << x;
        ASSERT_EQ(fx_atan2(x, y), (fx_angle_t)(FX_ANGLE_QUARTER - a)) << y << " " << x;
    }
}

TEST(FxAtan, RatioAndQ16)
{
    MaxErr er{"fx_atan_ratio"}, eq{"fx_atan_q16"};
    for (int i = 0; i < 1000000; i++) {
        int32_t n = rsigned(), d = rsigned();
        if (d == 0)
            continue;
        fx_angle_t a = fx_atan_ratio(n, d);
        ASSERT_TRUE((int32_t)a >= -(int32_t)FX_ANGLE_QUARTER &&
                    (int32_t)a <= (int32_t)FX_ANGLE_QUARTER);
        er.add(angle_diff(a, std::atan((ld)n / (ld)d)));
    }
    for (int64_t t = INT32_MIN; t <= INT32_MAX; t += 4093)
        eq.add(angle_diff(fx_atan_q16((int32_t)t), std::atan((ld)t / 65536)));
    std::printf("fx_atan_ratio max error %.3Le rad, fx_atan_q16 %.3Le rad\n", er.max, eq.max);
    EXPECT_LE(er.max, 1.3e-6L);
    EXPECT_LE(eq.max, 1.3e-6L);
    EXPECT_EQ(fx_atan_ratio(5, 0), FX_ANGLE_QUARTER);
    EXPECT_EQ(fx_atan_ratio(-5, 0), (fx_angle_t)(0u - FX_ANGLE_QUARTER));
    EXPECT_EQ(fx_atan_ratio(0, 0), 0u);
    EXPECT_EQ(fx_atan_ratio(0, -7), 0u);
    EXPECT_EQ(fx_atan_ratio(3, -3), (fx_angle_t)(0u - FX_ANGLE_QUARTER / 2));
    EXPECT_EQ(fx_atan_q16(FX_Q16_ONE), FX_ANGLE_QUARTER / 2);
    EXPECT_EQ(fx_atan_q16(-FX_Q16_ONE), (fx_angle_t)(0u - FX_ANGLE_QUARTER / 2));
    EXPECT_EQ(fx_atan_q16(0), 0u);
}

TEST(FxAsinAcos, MaxErrorOverTheDomain)
{
    MaxErr es{"fx_asin"}, ec{"fx_acos"};
    auto at = [&](fx_q30_t v) {
        ld x = (ld)v / FX_Q30_ONE;
        es.add(angle_diff(fx_asin(v), std::asin(x)));
        ec.add(angle_diff(fx_acos(v), std::acos(x)));
    };
    for (int64_t v = -FX_Q30_ONE; v <= FX_Q30_ONE; v += 509)
        at((fx_q30_t)v);
    for (int32_t d = 0; d < 100000; d++) {
        at(FX_Q30_ONE - d);
        at(-FX_Q30_ONE + d);
    }
    std::printf("fx_asin max error %.3Le rad, fx_acos %.3Le rad over %ld inputs\n", es.max, ec.max,
                es.n);
    EXPECT_LE(es.max, 1.3e-6L);
    EXPECT_LE(ec.max, 1.3e-6L);
    EXPECT_EQ(fx_asin(FX_Q30_ONE), FX_ANGLE_QUARTER);
    EXPECT_EQ(fx_asin(-FX_Q30_ONE), (fx_angle_t)(0u - FX_ANGLE_QUARTER));
    EXPECT_EQ(fx_asin(0), 0u);
    EXPECT_EQ(fx_acos(FX_Q30_ONE), 0u);
    EXPECT_EQ(fx_acos(-FX_Q30_ONE), FX_ANGLE_HALF);
    EXPECT_EQ(fx_acos(0), FX_ANGLE_QUARTER);
    EXPECT_EQ(fx_asin(INT32_MAX), FX_ANGLE_QUARTER); // clamped
    EXPECT_EQ(fx_acos(INT32_MIN), FX_ANGLE_HALF);
    for (int i = 0; i < 100000; i++) {
        fx_q30_t v = (fx_q30_t)(r32() % (2u * FX_Q30_ONE + 1)) - FX_Q30_ONE;
        ASSERT_EQ(fx_asin(-v), 0u - fx_asin(v)) << v;
        ASSERT_EQ(fx_acos(-v), (fx_angle_t)(FX_ANGLE_HALF - fx_acos(v))) << v;
    }
}

// ------------------------------------------------------------------ roots

void check_sqrt32(uint32_t x)
{
    uint64_t r = fx_sqrt32(x);
    ASSERT_LE(r * r, x) << x;
    ASSERT_GT((r + 1) * (r + 1), x) << x;
}

TEST(FxRoots, Sqrt32ExactEverywhere)
{
    // Every root value with the first and last input that gives it ...
    for (uint64_t k = 0; k <= 0xFFFF; k++) {
        check_sqrt32((uint32_t)(k * k));
        check_sqrt32((uint32_t)(k * k + 2 * k)); // (k + 1)^2 - 1
        if (k)
            check_sqrt32((uint32_t)(k * k - 1));
    }
    // ... every input below 2^22, and random inputs of every magnitude.
    for (uint32_t x = 0; x < (1u << 22); x++)
        check_sqrt32(x);
    for (int i = 0; i < 3000000; i++)
        check_sqrt32(rmag32());
    // Both ends of every aligned block of 512 in [2^30, 2^32) (12.6M inputs). The digit-by-digit
    // method is exact by construction (fx_root.c); these, the root boundaries above and the
    // target's own boundary sweep (tests/vectors/fx_vectors.c) check the code.
    for (uint64_t x = 1u << 30; x < (1ull << 32); x += 512) {
        check_sqrt32((uint32_t)x);
        check_sqrt32((uint32_t)(x + 511));
    }
    check_sqrt32(0xFFFFFFFFu);
    EXPECT_EQ(fx_sqrt32(0xFFFFFFFFu), 0xFFFFu);
    std::printf("fx_sqrt32: floor(sqrt(x)) exact (0 LSB): every root boundary, every x < 2^22, "
                "3M random, both ends of all 6.3M blocks of 512 in [2^30, 2^32)\n");
}

void check_sqrt64(uint64_t x)
{
    unsigned __int128 r = fx_sqrt64(x);
    ASSERT_LE(r * r, x) << x;
    ASSERT_GT((r + 1) * (r + 1), x) << x;
}

TEST(FxRoots, Sqrt64Exact)
{
    for (uint64_t x = 0; x < 100000; x++)
        check_sqrt64(x);
    for (int i = 0; i < 1000000; i++) {
        uint64_t k = rmag32();
        check_sqrt64(k * k);
        check_sqrt64(k * k + 2 * k);
        if (k)
            check_sqrt64(k * k - 1);
        check_sqrt64(rmag64());
    }
    for (uint64_t k = 0xFFFFFFFFull - 1000; k <= 0xFFFFFFFFull; k++) {
        check_sqrt64(k * k);
        check_sqrt64(k * k - 1);
        check_sqrt64(k * k + 2 * k);
    }
    EXPECT_EQ(fx_sqrt64(UINT64_MAX), 0xFFFFFFFFu);
    std::printf("fx_sqrt64: floor(sqrt(x)) exact (0 LSB) over 4.1M inputs and root boundaries\n");
}

TEST(FxRoots, HypotRoundedToNearest)
{
    auto check = [](int32_t x, int32_t y) {
        i128 n = (i128)x * x + (i128)y * y;
        i128 r = fx_hypot(x, y);
        // (r - 1/2)^2 <= n <= (r + 1/2)^2, i.e. |r - sqrt(n)| <= 1/2.
        if (r > 0) {
            ASSERT_LE((2 * r - 1) * (2 * r - 1), 4 * n) << x << " " << y;
        }
        ASSERT_GE((2 * r + 1) * (2 * r + 1), 4 * n) << x << " " << y;
    };
    for (int32_t y = -50; y <= 50; y++)
        for (int32_t x = -50; x <= 50; x++)
            check(x, y);
    for (int i = 0; i < 1000000; i++)
        check(rsigned(), rsigned());
    check(INT32_MIN, INT32_MIN);
    check(INT32_MAX, INT32_MIN);
    EXPECT_EQ(fx_hypot(3, -4), 5u);
    EXPECT_EQ(fx_hypot(INT32_MIN, 0), 0x80000000u);
    EXPECT_EQ(fx_hypot(INT32_MIN, INT32_MIN), 3037000500u); // 2^31 sqrt(2) = 3037000499.98
    std::printf("fx_hypot: max error 0.5 LSB (rounded to nearest) over 1M vectors\n");
}

// ------------------------------------------------------------------ multiply, divide

i128 mul_ref(int32_t a, int32_t b, unsigned shift)
{
    i128 p = (i128)a * b;
    if (shift == 0)
        return p;
    if (shift >= 100)
        return 0;
    return div_round(p, (i128)1 << shift);
}

TEST(FxMulDiv, MulShiftExact)
{
    auto check = [](int32_t a, int32_t b, unsigned shift) {
        i128 want = mul_ref(a, b, shift);
        int32_t out = 0x5A5A5A5A;
        bool ok = fx_mul_shift(a, b, (uint8_t)shift, &out);
        ASSERT_EQ(ok, fits32(want)) << a << " " << b << " " << shift;
        if (ok) {
            ASSERT_EQ((i128)out, want) << a << " " << b << " " << shift;
        } else {
            ASSERT_EQ(out, 0x5A5A5A5A);
        }
        for (unsigned s : {16u, 30u}) {
            i128 w = mul_ref(a, b, s);
            int32_t sat = w > INT32_MAX ? INT32_MAX : w < INT32_MIN ? INT32_MIN : (int32_t)w;
            ASSERT_EQ(s == 16 ? fx_mul_q16(a, b) : fx_mul_q30(a, b), sat) << a << " " << b;
        }
    };
    for (int i = 0; i < 2000000; i++)
        check(rsigned(), rsigned(), r32() % 70u);
    for (int32_t a : {INT32_MIN, INT32_MIN + 1, -1, 0, 1, INT32_MAX, 3, -3})
        for (int32_t b : {INT32_MIN, INT32_MIN + 1, -1, 0, 1, INT32_MAX, 0x40000000, -0x40000000})
            for (unsigned s = 0; s < 80; s++)
                check(a, b, s);
    // Ties go away from zero.
    EXPECT_EQ(fx_mul_q16(1, 0x8000), 1);
    EXPECT_EQ(fx_mul_q16(-1, 0x8000), -1);
    EXPECT_EQ(fx_mul_q30(INT32_MIN, FX_Q30_ONE), INT32_MIN);
    EXPECT_EQ(fx_mul_q30(INT32_MAX, -FX_Q30_ONE), -INT32_MAX);
    std::printf("fx_mul_shift/q16/q30: exact rounding (0.5 LSB) over 2M random operands\n");
}

TEST(FxMulDiv, DivExact)
{
    auto check = [](int32_t n, int32_t d, unsigned shift) {
        int32_t out = 0x5A5A5A5A;
        bool ok = fx_div_shift(n, d, (uint8_t)shift, &out);
        if (d == 0) {
            ASSERT_FALSE(ok);
            ASSERT_EQ(out, 0x5A5A5A5A);
            return;
        }
        bool fits;
        i128 want = 0;
        if (n == 0) {
            fits = true;
        } else if (shift >= 64) {
            fits = false; // |n| * 2^64 / |d| >= 2^33
        } else {
            want = div_round((i128)n * ((i128)1 << shift), d);
            fits = fits32(want);
        }
        ASSERT_EQ(ok, fits) << n << " " << d << " " << shift;
        if (ok) {
            ASSERT_EQ((i128)out, want) << n << " " << d << " " << shift;
        } else {
            ASSERT_EQ(out, 0x5A5A5A5A);
        }
        if (shift == 0) {
            int32_t o2 = 0;
            ASSERT_EQ(fx_div32(n, d, &o2), ok);
            if (ok) {
                ASSERT_EQ(o2, out);
            }
        }
        if (n == 1) {
            int32_t o3 = 0;
            ASSERT_EQ(fx_recip(d, (uint8_t)shift, &o3), ok);
            if (ok) {
                ASSERT_EQ(o3, out);
            }
        }
    };
    for (int i = 0; i < 2000000; i++) {
        check(rsigned(), rsigned(), r32() % 70u);
        check(rsigned(), rsigned(), 0);
        check(1, rsigned(), r32() % 70u);
    }
    for (int32_t n : {INT32_MIN, INT32_MIN + 1, -1, 0, 1, INT32_MAX, 7, -7})
        for (int32_t d : {INT32_MIN, INT32_MIN + 1, -1, 0, 1, 2, -2, INT32_MAX, 3})
            for (unsigned s = 0; s < 80; s++)
                check(n, d, s);
    int32_t q = 0;
    EXPECT_FALSE(fx_div32(INT32_MIN, -1, &q));
    EXPECT_TRUE(fx_div32(7, 2, &q));
    EXPECT_EQ(q, 4); // 3.5 away from zero
    EXPECT_TRUE(fx_div32(-7, 2, &q));
    EXPECT_EQ(q, -4);
    EXPECT_TRUE(fx_div32(5, 3, &q));
    EXPECT_EQ(q, 2);
    std::printf("fx_div32/div_shift/recip: exact rounding (0.5 LSB) over 6M random operands\n");
}

// ------------------------------------------------------------------ goniometer counts

TEST(FxAngle, FromCountsExact)
{
    auto want = [](uint32_t counts, uint32_t cpt) -> fx_angle_t {
        uint64_t r = counts % cpt;
        // round(r 2^32 / cpt), ties up: floor((2 r 2^32 + cpt) / (2 cpt)).
        return (fx_angle_t)(((r << 33) + cpt) / (2ull * cpt));
    };
    for (uint32_t cpt : {50000u, 65535u, 1u, 2u, 3u, 7u, 360u, 1000u, 4096u, 32768u, 65521u})
        for (uint32_t c = 0; c < cpt; c++)
            ASSERT_EQ(fx_angle_from_counts(c, (uint16_t)cpt), want(c, cpt)) << c << "/" << cpt;
    for (int i = 0; i < 1000000; i++) {
        uint32_t cpt = 1 + r32() % 65535u, c = rmag32();
        ASSERT_EQ(fx_angle_from_counts(c, (uint16_t)cpt), want(c, cpt)) << c << "/" << cpt;
    }
    EXPECT_EQ(fx_angle_from_counts(12500, 50000), FX_ANGLE_QUARTER);
    EXPECT_EQ(fx_angle_from_counts(25000, 50000), FX_ANGLE_HALF);
    EXPECT_EQ(fx_angle_from_counts(50000 + 12500, 50000), FX_ANGLE_QUARTER); // wraps
    EXPECT_EQ(fx_angle_from_counts(3, 0), 0u);
    // Against the host conversion: one count is 0.0072 degrees.
    EXPECT_NEAR(fx_angle_to_deg(fx_angle_from_counts(1, 50000)), 0.0072, 0.5 * 360 / kTurn);
    std::printf("fx_angle_from_counts: exact (0.5 LSB rounding) for all counts of 11 "
                "resolutions and 1M random\n");
}

} // namespace
