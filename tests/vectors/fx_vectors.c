/*
 * fx_vectors.c - firmware/fx on both worlds: the same inputs through every function of fx.h,
 * one line per call ("<function> <inputs...> <result>", hex), compared line by line between
 * the host build and the MSP430 image (bit-identical results, also where the target uses
 * assembly). On the target each call is also timed: "@cycles fx_<function> max mean n" for
 * build/msp430/cycles.json.
 *
 * Inputs: the edge cases of each function (axes, quadrant and table-step boundaries, the
 * int32 extremes, perfect squares and their neighbours, overflow limits) and pseudo-random
 * operands of every magnitude (xorshift32, fixed seed).
 */
#include <stdbool.h>
#include <stdint.h>

#include "cy_test.h"
#include "fx/fx.h"

#define RANDOM_N 400u

static uint32_t rng = 0x9E3779B9u;

static uint32_t rnd32(void)
{
    return cy_rand32(&rng);
}

/* Random value of a random bit length (small and large magnitudes alike). */
static uint32_t rnd_mag(void)
{
    uint32_t v = rnd32();
    uint8_t cut = (uint8_t)(rnd32() & 31u);
    return (rnd32() & 1u) ? v : v >> cut;
}

static int32_t rnd_signed(void)
{
    uint32_t v = rnd_mag();
    return (rnd32() & 1u) ? (int32_t)(0u - v) : (int32_t)v;
}

/* Operands are passed through volatiles so the timed call cannot be hoisted. */
static volatile uint32_t va, vb;
static volatile uint64_t v64;
static volatile uint8_t vs;

static cy_bench_stat_t st_sin = {"fx_sin", 0, 0, 0}, st_cos = {"fx_cos", 0, 0, 0},
                       st_sincos = {"fx_sincos", 0, 0, 0}, st_tan = {"fx_tan", 0, 0, 0},
                       st_cot = {"fx_cot", 0, 0, 0}, st_atan2 = {"fx_atan2", 0, 0, 0},
                       st_atanr = {"fx_atan_ratio", 0, 0, 0}, st_atanq = {"fx_atan_q16", 0, 0, 0},
                       st_asin = {"fx_asin", 0, 0, 0}, st_acos = {"fx_acos", 0, 0, 0},
                       st_sqrt32 = {"fx_sqrt32", 0, 0, 0},
                       st_sqrt32_top = {"fx_sqrt32_x_ge_2e30", 0, 0, 0},
                       st_sqrt64 = {"fx_sqrt64", 0, 0, 0}, st_hypot = {"fx_hypot", 0, 0, 0},
                       st_mulq30 = {"fx_mul_q30", 0, 0, 0}, st_mulq16 = {"fx_mul_q16", 0, 0, 0},
                       st_mulsh = {"fx_mul_shift", 0, 0, 0}, st_div32 = {"fx_div32", 0, 0, 0},
                       st_divsh = {"fx_div_shift", 0, 0, 0}, st_recip = {"fx_recip", 0, 0, 0},
                       st_counts = {"fx_angle_from_counts", 0, 0, 0},
                       st_counts_in = {"fx_angle_from_counts_in_turn", 0, 0, 0};

static void out_head(const char *name, uint32_t a)
{
    cy_print(name);
    cy_print(" ");
    cy_print_hex32(a);
}

static void out_next(uint32_t v)
{
    cy_print(" ");
    cy_print_hex32(v);
}

static void out_ok(bool ok, int32_t r)
{
    cy_print(ok ? " 1 " : " 0 ");
    cy_print_hex32(ok ? (uint32_t)r : 0u);
    cy_println();
}

/* ------------------------------------------------------------------ one call each */

static void angle_fns(fx_angle_t a)
{
    fx_q30_t s, c, s2, c2;
    va = a;
    CY_BENCH(&st_sin, s = fx_sin(va));
    CY_BENCH(&st_cos, c = fx_cos(va));
    CY_BENCH(&st_sincos, fx_sincos(va, &s2, &c2));
    cy_check(s == s2 && c == c2, "fx_sincos == fx_sin, fx_cos");
    fx_q16_t t, ct;
    CY_BENCH(&st_tan, t = fx_tan(va));
    CY_BENCH(&st_cot, ct = fx_cot(va));
    out_head("sincos", a);
    out_next((uint32_t)s);
    out_next((uint32_t)c);
    out_next((uint32_t)t);
    out_next((uint32_t)ct);
    cy_println();
}

static void atan_fns(int32_t y, int32_t x)
{
    fx_angle_t a, r;
    va = (uint32_t)y;
    vb = (uint32_t)x;
    CY_BENCH(&st_atan2, a = fx_atan2((int32_t)va, (int32_t)vb));
    CY_BENCH(&st_atanr, r = fx_atan_ratio((int32_t)va, (int32_t)vb));
    uint32_t h;
    CY_BENCH(&st_hypot, h = fx_hypot((int32_t)va, (int32_t)vb));
    out_head("atan2", (uint32_t)y);
    out_next((uint32_t)x);
    out_next(a);
    out_next(r);
    out_next(h);
    cy_println();
}

static void unit_fns(fx_q30_t v)
{
    fx_angle_t s, c, t;
    va = (uint32_t)v;
    CY_BENCH(&st_asin, s = fx_asin((fx_q30_t)va));
    CY_BENCH(&st_acos, c = fx_acos((fx_q30_t)va));
    CY_BENCH(&st_atanq, t = fx_atan_q16((fx_q16_t)va));
    out_head("asin", (uint32_t)v);
    out_next(s);
    out_next(c);
    out_next(t);
    cy_println();
}

static void sqrt32_fn(uint32_t x)
{
    uint16_t r;
    va = x;
    CY_BENCH(&st_sqrt32, r = fx_sqrt32(va));
    if (x >= 0x40000000u) /* again, for the figure of the inputs that need no shift */
        CY_BENCH(&st_sqrt32_top, r = fx_sqrt32(va));
    out_head("sqrt32", x);
    out_next(r);
    cy_println();
}

static void sqrt64_fn(uint64_t x)
{
    uint32_t r;
    v64 = x;
    CY_BENCH(&st_sqrt64, r = fx_sqrt64(v64));
    cy_print("sqrt64 ");
    cy_print_hex64(x);
    out_next(r);
    cy_println();
}

static void mul_fns(int32_t a, int32_t b, uint8_t shift)
{
    int32_t q30, q16, r;
    bool ok;
    va = (uint32_t)a;
    vb = (uint32_t)b;
    vs = shift;
    CY_BENCH(&st_mulq30, q30 = fx_mul_q30((int32_t)va, (int32_t)vb));
    CY_BENCH(&st_mulq16, q16 = fx_mul_q16((int32_t)va, (int32_t)vb));
    CY_BENCH(&st_mulsh, ok = fx_mul_shift((int32_t)va, (int32_t)vb, vs, &r));
    out_head("mul", (uint32_t)a);
    out_next((uint32_t)b);
    out_next(shift);
    out_next((uint32_t)q30);
    out_next((uint32_t)q16);
    out_ok(ok, r);
}

static void div_fns(int32_t n, int32_t d, uint8_t shift)
{
    int32_t r1 = 0, r2 = 0, r3 = 0;
    bool ok1, ok2, ok3;
    va = (uint32_t)n;
    vb = (uint32_t)d;
    vs = shift;
    CY_BENCH(&st_div32, ok1 = fx_div32((int32_t)va, (int32_t)vb, &r1));
    CY_BENCH(&st_divsh, ok2 = fx_div_shift((int32_t)va, (int32_t)vb, vs, &r2));
    CY_BENCH(&st_recip, ok3 = fx_recip((int32_t)vb, vs, &r3));
    out_head("div", (uint32_t)n);
    out_next((uint32_t)d);
    out_next(shift);
    cy_print(ok1 ? " 1 " : " 0 ");
    cy_print_hex32(ok1 ? (uint32_t)r1 : 0u);
    cy_print(ok2 ? " 1 " : " 0 ");
    cy_print_hex32(ok2 ? (uint32_t)r2 : 0u);
    out_ok(ok3, r3);
}

static void counts_fn(uint32_t counts, uint16_t cpt)
{
    fx_angle_t a;
    va = counts;
    vb = cpt;
    CY_BENCH(&st_counts, a = fx_angle_from_counts(va, (uint16_t)vb));
    if (counts < cpt) /* again, for the figure of the normal range (no wrap) */
        CY_BENCH(&st_counts_in, a = fx_angle_from_counts(va, (uint16_t)vb));
    out_head("counts", counts);
    out_next(cpt);
    out_next(a);
    cy_println();
}

/* ------------------------------------------------------------------ input sets */

static void angles(void)
{
    static const uint32_t edge[] = {0u,          1u,          0x3FFFFFFFu, 0x40000000u,
                                    0x40000001u, 0x7FFFFFFFu, 0x80000000u, 0x80000001u,
                                    0xBFFFFFFFu, 0xC0000000u, 0xC0000001u, 0xFFFFFFFFu,
                                    0x20000000u, 0x60000000u, 0x15555555u, 0x2AAAAAABu};
    for (uint16_t i = 0; i < sizeof edge / sizeof edge[0]; i++)
        angle_fns(edge[i]);
    /* Table-step boundaries and the rounding of the fraction. */
    for (uint32_t k = 0; k <= 128u; k += 9u) {
        uint32_t n = k << 23;
        angle_fns(n + 63u);
        angle_fns(n + 64u);
        angle_fns(n - 64u);
        angle_fns(n - 65u);
        angle_fns(n + 0x400000u + 0x8000u);
    }
    for (uint16_t i = 0; i < RANDOM_N; i++)
        angle_fns(rnd32());
}

static void atans(void)
{
    static const int32_t edge[][2] = {
        {0, 0},
        {0, 1},
        {1, 0},
        {0, -1},
        {-1, 0},
        {1, 1},
        {-1, -1},
        {1, -1},
        {-1, 1},
        {INT32_MIN, 0},
        {0, INT32_MIN},
        {INT32_MIN, INT32_MIN},
        {INT32_MAX, INT32_MAX},
        {INT32_MIN, INT32_MAX},
        {INT32_MAX, INT32_MIN},
        {INT32_MAX, -1},
        {1, INT32_MAX},
        {-1, INT32_MIN},
        {0x40000000, 0x7FFFFFFF},
        {0x3FFFFFFF, 0x7FFFFFFF},
        {0x7FFFFFFF, 0x40000000},
        {0x7FFFFFFF, 0x3FFFFFFF},
        {3, 6},
        {3, 7},
        {-5, 9},
        {0x12345678, -0x12345678},
        {65536, 65536},
        {65536, 0x7FFF0000},
    };
    for (uint16_t i = 0; i < sizeof edge / sizeof edge[0]; i++)
        atan_fns(edge[i][0], edge[i][1]);
    /* (One random draw per statement: the order of evaluation of arguments is unspecified.) */
    for (uint16_t i = 0; i < 2u * RANDOM_N; i++) {
        int32_t y = rnd_signed();
        atan_fns(y, rnd_signed());
    }
    for (uint16_t i = 0; i < RANDOM_N / 4u; i++) {
        int32_t y = (int32_t)rnd32();
        atan_fns(y, (int32_t)rnd32());
    }
}

static void units(void)
{
    static const int32_t edge[] = {0,           1,           -1,          0x40000000,  -0x40000000,
                                   0x3FFFFFFF,  -0x3FFFFFFF, 0x40000001,  -0x40000001, INT32_MAX,
                                   INT32_MIN,   0x20000000,  -0x20000000, 0x2D413CCD,  0x3FFF0000,
                                   -0x3FFFFFF0, 65536,       -65536};
    for (uint16_t i = 0; i < sizeof edge / sizeof edge[0]; i++)
        unit_fns(edge[i]);
    for (uint16_t i = 0; i < RANDOM_N; i++) {
        int32_t v = (int32_t)(rnd32() % 0x80000001u) - 0x40000000;
        unit_fns(v);
    }
    for (uint16_t i = 0; i < RANDOM_N / 4u; i++)
        unit_fns(rnd_signed());
}

/*
 * Root values r with the first and the last input that give it (r^2, (r + 1)^2 - 1): every
 * 16th and the last 16 (4,112; the host's fx_test takes every one), checked on the spot (an
 * exact floor is the same on both worlds), nothing printed.
 */
static void sqrt32_boundaries(void)
{
    uint16_t bad = 0;
    for (uint32_t r = 0; r <= 0xFFFFu; r += r < 0xFFF0u ? 16u : 1u) {
        uint32_t sq = r * r;
        if (fx_sqrt32(sq) != r || fx_sqrt32(sq + 2u * r) != r)
            bad++;
    }
    cy_print("sqrt32-boundaries ");
    cy_print_dec(bad);
    cy_println();
    cy_check(bad == 0, "fx_sqrt32 at 4112 root boundaries");
}

/*
 * The same for fx_sqrt64 at 4096 roots of every magnitude (r^2 - 1, r^2, (r + 1)^2 - 1):
 * the root's every bit, in particular bit 31, through each of the four word phases.
 */
static void sqrt64_boundaries(void)
{
    uint16_t bad = 0;
    for (uint16_t i = 0; i < 4096u; i++) {
        uint32_t r = i < 64u ? 0xFFFFFFFFu - i : rnd_mag();
        uint64_t sq = (uint64_t)r * r;
        if (fx_sqrt64(sq) != r || fx_sqrt64(sq + 2u * (uint64_t)r) != r ||
            (r != 0 && fx_sqrt64(sq - 1u) != r - 1u))
            bad++;
    }
    cy_print("sqrt64-boundaries ");
    cy_print_dec(bad);
    cy_println();
    cy_check(bad == 0, "fx_sqrt64 at 4096 root boundaries");
}

static void roots(void)
{
    sqrt32_boundaries();
    sqrt64_boundaries();
    static const uint32_t edge[] = {0u,          1u,          2u,          3u,
                                    4u,          5u,          8u,          9u,
                                    0xFFFFu,     0x10000u,    0xFFFFFFFFu, 0xFFFE0001u,
                                    0xFFFE0000u, 0x80000000u, 0x3FFFFFFFu, 0x40000000u};
    for (uint16_t i = 0; i < sizeof edge / sizeof edge[0]; i++)
        sqrt32_fn(edge[i]);
    for (uint16_t i = 0; i < RANDOM_N; i++) {
        uint32_t k = rnd_mag() & 0xFFFFu;
        uint32_t sq = k * k;
        sqrt32_fn(sq);
        sqrt32_fn(sq - 1u);
        sqrt32_fn(rnd_mag());
    }
    static const uint64_t edge64[] = {0u,
                                      1u,
                                      2u,
                                      3u,
                                      4u,
                                      0xFFFFFFFFu,
                                      0x100000000u,
                                      0xFFFFFFFFFFFFFFFFu,
                                      0xFFFFFFFE00000001u,
                                      0xFFFFFFFE00000000u,
                                      0x8000000000000000u,
                                      0x4000000000000000u,
                                      0x3FFFFFFFFFFFFFFFu};
    for (uint16_t i = 0; i < sizeof edge64 / sizeof edge64[0]; i++)
        sqrt64_fn(edge64[i]);
    for (uint16_t i = 0; i < RANDOM_N; i++) {
        uint64_t k = rnd_mag();
        uint64_t sq = k * k;
        sqrt64_fn(sq);
        sqrt64_fn(sq - 1u);
        uint64_t v = rnd_mag();
        v <<= rnd32() & 31u;
        sqrt64_fn(v ^ rnd32());
    }
}

static void muls(void)
{
    static const int32_t edge[][3] = {
        {0, 0, 0},
        {INT32_MIN, INT32_MIN, 62},
        {INT32_MIN, INT32_MIN, 63},
        {INT32_MIN, INT32_MIN, 64},
        {INT32_MIN, -1, 0},
        {INT32_MIN, 1, 0},
        {INT32_MAX, INT32_MAX, 30},
        {INT32_MAX, 0x40000000, 30},
        {INT32_MIN, 0x40000000, 30},
        {INT32_MIN, -0x40000000, 30},
        {3, 1, 1},
        {-3, 1, 1},
        {1, 1, 1},
        {-1, 1, 1},
        {0x12345678, 0x40000000, 30},
        {65536, 65536, 16},
        {0x8000, 0x10000, 0},
        {-32768, 0x10000, 0},
    };
    for (uint16_t i = 0; i < sizeof edge / sizeof edge[0]; i++)
        mul_fns(edge[i][0], edge[i][1], (uint8_t)edge[i][2]);
    for (uint16_t i = 0; i < RANDOM_N; i++) {
        int32_t a = rnd_signed(), b = rnd_signed();
        mul_fns(a, b, (uint8_t)(rnd32() % 70u));
    }
    for (uint16_t i = 0; i < RANDOM_N / 2u; i++) {
        int32_t s = (int32_t)(rnd32() % 0x80000001u) - 0x40000000;
        mul_fns(rnd_signed(), s, 30);
    }
}

static void divs(void)
{
    static const int32_t edge[][3] = {
        {0, 0, 0},
        {1, 0, 0},
        {INT32_MIN, -1, 0},
        {INT32_MIN, 1, 0},
        {INT32_MAX, -1, 0},
        {INT32_MIN, 2, 1},
        {INT32_MIN, -2, 1},
        {7, 2, 0},
        {-7, 2, 0},
        {5, -2, 0},
        {1, 3, 0},
        {2, 3, 0},
        {1, 2, 0},
        {-1, 2, 0},
        {1, 1, 31},
        {1, -1, 31},
        {1, 1, 62},
        {1, 0x7FFFFFFF, 62},
        {1, INT32_MIN, 62},
        {1, INT32_MIN, 63},
        {3, 2, 32},
        {65536, 3, 16},
        {0x40000000, 0x40000000, 30},
        {1, 65536, 48},
        {-1, 65536, 47},
        {0x7FFFFFFF, 0x7FFFFFFF, 31},
    };
    for (uint16_t i = 0; i < sizeof edge / sizeof edge[0]; i++)
        div_fns(edge[i][0], edge[i][1], (uint8_t)edge[i][2]);
    for (uint16_t i = 0; i < RANDOM_N; i++) {
        int32_t n = rnd_signed(), d = rnd_signed();
        div_fns(n, d, (uint8_t)(rnd32() % 66u));
    }
    for (uint16_t i = 0; i < RANDOM_N / 2u; i++) {
        int32_t n = rnd_signed();
        div_fns(n, rnd_signed(), 0);
    }
}

static void counts(void)
{
    static const uint32_t edge[][2] = {
        {0u, 50000u},
        {1u, 50000u},
        {12500u, 50000u},
        {25000u, 50000u},
        {49999u, 50000u},
        {50000u, 50000u},
        {50001u, 50000u},
        {0xFFFFFFFFu, 50000u},
        {0u, 1u},
        {5u, 1u},
        {1u, 3u},
        {2u, 3u},
        {0xFFFFFFFFu, 65535u},
        {65534u, 65535u},
        {7u, 0u},
        {1u, 2u},
    };
    for (uint16_t i = 0; i < sizeof edge / sizeof edge[0]; i++)
        counts_fn(edge[i][0], (uint16_t)edge[i][1]);
    for (uint16_t i = 0; i < RANDOM_N; i++)
        counts_fn(rnd32() % 50000u, 50000u);
    for (uint16_t i = 0; i < RANDOM_N; i++) {
        uint32_t c = rnd_mag();
        counts_fn(c, (uint16_t)(rnd32() | 1u));
    }
}

int main(void)
{
    cy_bench_init();
    cy_print("# fx vectors\n");
    angles();
    atans();
    units();
    roots();
    muls();
    divs();
    counts();
    const cy_bench_stat_t *st[] = {&st_sin,    &st_cos,        &st_sincos, &st_tan,   &st_cot,
                                   &st_atan2,  &st_atanr,      &st_atanq,  &st_asin,  &st_acos,
                                   &st_sqrt32, &st_sqrt32_top, &st_sqrt64, &st_hypot, &st_mulq30,
                                   &st_mulq16, &st_mulsh,      &st_div32,  &st_divsh, &st_recip,
                                   &st_counts, &st_counts_in};
    for (uint16_t i = 0; i < sizeof st / sizeof st[0]; i++)
        cy_bench_report(st[i]);
    cy_test_end();
    return 0;
}
