/*
 * mspabi_test.c - every run-time helper of hal/msp430/mspabi.c on the target, against
 * values the host computes (tests/target/mspabi_check.py recomputes each printed line with Python
 * integers): edge cases (0, +-1, min, max, powers of two, division by zero) crossed with each
 * other, then thousands of random operand pairs.
 *
 * Line format: "<op> <a> <b> <result>" in hex of the operand width. Multiplies and shifts go
 * through the C operators (so the helper clang chose is the one tested); divisions with a
 * zero divisor or MIN / -1 (undefined in C) call the helpers by name.
 */
#include <stdint.h>

#include "cy_test.h"

int16_t __mspabi_mpyi(int16_t a, int16_t b);
int32_t __mspabi_mpyl(int32_t a, int32_t b);
int64_t __mspabi_mpyll(int64_t a, int64_t b);
int16_t __mspabi_divi(int16_t a, int16_t b);
int16_t __mspabi_remi(int16_t a, int16_t b);
uint16_t __mspabi_divu(uint16_t a, uint16_t b);
uint16_t __mspabi_remu(uint16_t a, uint16_t b);
int32_t __mspabi_divli(int32_t a, int32_t b);
int32_t __mspabi_remli(int32_t a, int32_t b);
uint32_t __mspabi_divul(uint32_t a, uint32_t b);
uint32_t __mspabi_remul(uint32_t a, uint32_t b);
int64_t cy_mspabi_divlli(int64_t a, int64_t b);
int64_t cy_mspabi_remlli(int64_t a, int64_t b);
uint64_t cy_mspabi_divull(uint64_t a, uint64_t b);
uint64_t cy_mspabi_remull(uint64_t a, uint64_t b);

#define RANDOM_PER_OP 400

static uint32_t rng = 0x2545F491u;

static uint32_t rnd32(void)
{
    return cy_rand32(&rng);
}

/* Random operands with a spread of magnitudes: full width, or masked to a random length. */
static uint16_t rnd16(void)
{
    uint32_t r = rnd32();
    uint16_t v = (uint16_t)r;
    unsigned bits = (r >> 16) & 15u;
    return (r >> 20) & 1u ? v : (uint16_t)(v >> bits);
}

static uint32_t rnd32w(void)
{
    uint32_t v = rnd32();
    unsigned bits = rnd32() & 31u;
    return rnd32() & 1u ? v : v >> bits;
}

static uint64_t rnd64w(void)
{
    uint64_t v = ((uint64_t)rnd32() << 32) | rnd32();
    unsigned bits = rnd32() & 63u;
    return rnd32() & 1u ? v : v >> bits;
}

static void line16(const char *op, uint16_t a, uint16_t b, uint16_t r)
{
    cy_print(op);
    cy_print(" ");
    cy_print_hex16(a);
    cy_print(" ");
    cy_print_hex16(b);
    cy_print(" ");
    cy_print_hex16(r);
    cy_println();
}

static void line32(const char *op, uint32_t a, uint32_t b, uint32_t r)
{
    cy_print(op);
    cy_print(" ");
    cy_print_hex32(a);
    cy_print(" ");
    cy_print_hex32(b);
    cy_print(" ");
    cy_print_hex32(r);
    cy_println();
}

static void line64(const char *op, uint64_t a, uint64_t b, uint64_t r)
{
    cy_print(op);
    cy_print(" ");
    cy_print_hex64(a);
    cy_print(" ");
    cy_print_hex64(b);
    cy_print(" ");
    cy_print_hex64(r);
    cy_println();
}

/* Operands are read through volatiles so that the compiler cannot fold the operation. */
static volatile int16_t va16, vb16;
static volatile int32_t va32, vb32;
static volatile int64_t va64, vb64;
static volatile int16_t vn;

static void ops16(uint16_t a, uint16_t b)
{
    va16 = (int16_t)a;
    vb16 = (int16_t)b;
    line16("mpyi", a, b, (uint16_t)(int16_t)(va16 * vb16));
    line16("mpyi_sw", a, b, (uint16_t)__mspabi_mpyi(va16, vb16));
    line32("mpysl", a, b, (uint32_t)((int32_t)va16 * (int32_t)vb16));
    line32("mpyul", a, b, (uint32_t)(uint16_t)va16 * (uint16_t)vb16);
    line16("divi", a, b, (uint16_t)__mspabi_divi(va16, vb16));
    line16("remi", a, b, (uint16_t)__mspabi_remi(va16, vb16));
    line16("divu", a, b, __mspabi_divu((uint16_t)va16, (uint16_t)vb16));
    line16("remu", a, b, __mspabi_remu((uint16_t)va16, (uint16_t)vb16));
    if (b != 0 && !(a == 0x8000u && b == 0xFFFFu)) {
        line16("divi_c", a, b, (uint16_t)(int16_t)(va16 / vb16));
        line16("remi_c", a, b, (uint16_t)(int16_t)(va16 % vb16));
        line16("divu_c", a, b, (uint16_t)((uint16_t)va16 / (uint16_t)vb16));
        line16("remu_c", a, b, (uint16_t)((uint16_t)va16 % (uint16_t)vb16));
    }
}

static void ops32(uint32_t a, uint32_t b)
{
    va32 = (int32_t)a;
    vb32 = (int32_t)b;
    line32("mpyl", a, b, (uint32_t)(va32 * vb32));
    line32("mpyl_sw", a, b, (uint32_t)__mspabi_mpyl(va32, vb32));
    line32("divli", a, b, (uint32_t)__mspabi_divli(va32, vb32));
    line32("remli", a, b, (uint32_t)__mspabi_remli(va32, vb32));
    line32("divul", a, b, __mspabi_divul((uint32_t)va32, (uint32_t)vb32));
    line32("remul", a, b, __mspabi_remul((uint32_t)va32, (uint32_t)vb32));
    if (b != 0 && !(a == 0x80000000u && b == 0xFFFFFFFFu)) {
        line32("divli_c", a, b, (uint32_t)(va32 / vb32));
        line32("remli_c", a, b, (uint32_t)(va32 % vb32));
        line32("divul_c", a, b, (uint32_t)va32 / (uint32_t)vb32);
        line32("remul_c", a, b, (uint32_t)va32 % (uint32_t)vb32);
    }
}

static void shifts32(uint32_t a, int16_t n)
{
    va32 = (int32_t)a;
    vn = n;
    line32("slll", a, (uint32_t)n, (uint32_t)va32 << vn);
    line32("srll", a, (uint32_t)n, (uint32_t)va32 >> vn);
    line32("sral", a, (uint32_t)n, (uint32_t)(va32 >> vn));
}

static void ops64(uint64_t a, uint64_t b)
{
    va64 = (int64_t)a;
    vb64 = (int64_t)b;
    line64("mpyll", a, b, (uint64_t)(va64 * vb64));
    line64("mpyll_sw", a, b, (uint64_t)__mspabi_mpyll(va64, vb64));
    if (b != 0 && !(a == 0x8000000000000000ull && b == 0xFFFFFFFFFFFFFFFFull)) {
        /* The C operators reach __mspabi_divlli & co. through their special convention. */
        line64("divlli", a, b, (uint64_t)(va64 / vb64));
        line64("remlli", a, b, (uint64_t)(va64 % vb64));
        line64("divull", a, b, (uint64_t)va64 / (uint64_t)vb64);
        line64("remull", a, b, (uint64_t)va64 % (uint64_t)vb64);
    } else {
        line64("divlli", a, b, (uint64_t)cy_mspabi_divlli(va64, vb64));
        line64("remlli", a, b, (uint64_t)cy_mspabi_remlli(va64, vb64));
        line64("divull", a, b, cy_mspabi_divull((uint64_t)va64, (uint64_t)vb64));
        line64("remull", a, b, cy_mspabi_remull((uint64_t)va64, (uint64_t)vb64));
    }
}

static void shifts64(uint64_t a, int16_t n)
{
    va64 = (int64_t)a;
    vn = n;
    line64("shl64", a, (uint64_t)n, (uint64_t)va64 << vn);
    line64("shr64", a, (uint64_t)n, (uint64_t)va64 >> vn);
    line64("sar64", a, (uint64_t)n, (uint64_t)(va64 >> vn));
}

static const uint16_t edge16[] = {0,      1,      2,      3,      7,      0x00FF, 0x0100, 0x4000,
                                  0x7FFF, 0x8000, 0x8001, 0xFFFE, 0xFFFF, 0xAAAA, 0x5555};
static const uint32_t edge32[] = {
    0,          1,          2,          3,          0xFFFF,     0x10000,    0x7FFF,     0x8000,
    0x40000000, 0x7FFFFFFF, 0x80000000, 0x80000001, 0xFFFF8000, 0xFFFFFFFE, 0xFFFFFFFF, 0x12345678};
static const uint64_t edge64[] = {0,
                                  1,
                                  2,
                                  3,
                                  0xFFFFFFFFull,
                                  0x100000000ull,
                                  0x7FFFFFFFFFFFFFFFull,
                                  0x8000000000000000ull,
                                  0x8000000000000001ull,
                                  0xFFFFFFFFFFFFFFFEull,
                                  0xFFFFFFFFFFFFFFFFull,
                                  0x0123456789ABCDEFull};
#define N(a) (sizeof(a) / sizeof((a)[0]))

/* Cycle cost of the helpers (call included) over random operands, for the cycle report. */
static void bench(void)
{
    static cy_bench_stat_t st[] = {
        {"mspabi_mpyi_hw", 0, 0, 0},  {"mspabi_mpyl_hw", 0, 0, 0}, {"mspabi_mpyl_hw16", 0, 0, 0},
        {"mspabi_mpyll_hw", 0, 0, 0}, {"mspabi_divu", 0, 0, 0},    {"mspabi_divli", 0, 0, 0},
        {"mspabi_divul", 0, 0, 0},    {"mspabi_divlli", 0, 0, 0},  {"mspabi_srll", 0, 0, 0}};
    static volatile int16_t r16 __attribute__((unused));
    static volatile int32_t r32 __attribute__((unused));
    static volatile int64_t r64 __attribute__((unused));
    cy_bench_init();
    for (int k = 0; k < 64; k++) {
        /* Operands are read from volatiles inside the measured statement, so that the
         * operation cannot be scheduled outside the two counter reads. */
        va16 = (int16_t)rnd32();
        vb16 = (int16_t)(rnd32() | 1u);
        va32 = (int32_t)rnd32w();
        vb32 = (int32_t)(rnd32w() | 1u);
        va64 = (int64_t)rnd64w();
        vb64 = (int64_t)(rnd64w() | 1u);
        vn = (int16_t)(rnd32() & 31u);
        CY_BENCH(&st[0], r16 = (int16_t)(va16 * vb16));
        CY_BENCH(&st[1], r32 = va32 * vb32);
        CY_BENCH(&st[2], r32 = (int32_t)va16 * (int32_t)vb16);
        CY_BENCH(&st[3], r64 = va64 * vb64);
        CY_BENCH(&st[4], r16 = (int16_t)((uint16_t)va16 / (uint16_t)vb16));
        CY_BENCH(&st[5], r32 = va32 / vb32);
        CY_BENCH(&st[6], r32 = (int32_t)((uint32_t)va32 / (uint32_t)vb32));
        CY_BENCH(&st[7], r64 = va64 / vb64);
        CY_BENCH(&st[8], r32 = (int32_t)((uint32_t)va32 >> vn));
    }
    for (unsigned i = 0; i < sizeof st / sizeof st[0]; i++)
        cy_bench_report(&st[i]);
}

int main(void)
{
    for (unsigned i = 0; i < N(edge16); i++)
        for (unsigned j = 0; j < N(edge16); j++)
            ops16(edge16[i], edge16[j]);
    for (int k = 0; k < RANDOM_PER_OP; k++)
        ops16(rnd16(), rnd16());

    for (unsigned i = 0; i < N(edge32); i++)
        for (unsigned j = 0; j < N(edge32); j++)
            ops32(edge32[i], edge32[j]);
    for (int k = 0; k < RANDOM_PER_OP; k++)
        ops32(rnd32w(), rnd32w());
    for (unsigned i = 0; i < N(edge32); i++)
        for (int16_t n = 0; n < 32; n++)
            shifts32(edge32[i], n);
    for (int k = 0; k < RANDOM_PER_OP; k++)
        shifts32(rnd32(), (int16_t)(rnd32() & 31u));

    for (unsigned i = 0; i < N(edge64); i++)
        for (unsigned j = 0; j < N(edge64); j++)
            ops64(edge64[i], edge64[j]);
    for (int k = 0; k < RANDOM_PER_OP; k++)
        ops64(rnd64w(), rnd64w());
    for (unsigned i = 0; i < N(edge64); i++)
        for (int16_t n = 0; n < 64; n += 7)
            shifts64(edge64[i], n);
    for (int k = 0; k < RANDOM_PER_OP; k++)
        shifts64(rnd64w(), (int16_t)(rnd32() & 63u));

    bench();
    cy_test_end();
    return 0;
}
