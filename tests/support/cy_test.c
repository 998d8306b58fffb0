/*
 * cy_test.c - test support on the console of either world (see cy_test.h).
 */
#include "cy_test.h"

#include "hal/console.h"

#ifdef __MSP430__
#include "f2618.h"
#endif

static uint16_t failures;
uint16_t cy_bench_overhead;

void cy_print(const char *s)
{
    hal_console_puts(s);
}

void cy_println(void)
{
    hal_console_putc('\n');
}

static void hex(uint32_t v, int digits)
{
    static const char d[] = "0123456789abcdef";
    for (int i = digits - 1; i >= 0; i--)
        hal_console_putc(d[(v >> (4 * i)) & 0xFu]);
}

void cy_print_hex16(uint16_t v)
{
    hex(v, 4);
}

void cy_print_hex32(uint32_t v)
{
    hex(v, 8);
}

void cy_print_hex64(uint64_t v)
{
    hex((uint32_t)(v >> 32), 8);
    hex((uint32_t)v, 8);
}

void cy_print_dec(int32_t v)
{
    char buf[12];
    int n = 0;
    uint32_t u = v < 0 ? 0u - (uint32_t)v : (uint32_t)v;
    do {
        buf[n++] = (char)('0' + u % 10u);
        u /= 10u;
    } while (u);
    if (v < 0)
        hal_console_putc('-');
    while (n)
        hal_console_putc(buf[--n]);
}

void cy_check(int ok, const char *what)
{
    if (ok)
        return;
    failures++;
    cy_print("FAIL ");
    cy_print(what);
    cy_println();
}

uint16_t cy_failures(void)
{
    return failures;
}

uint32_t cy_rand32(uint32_t *state)
{
    uint32_t x = *state;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    *state = x;
    return x;
}

/* Weak: a kernel check image links tests/target/check/kernel_check.c, which defines both. */
__attribute__((weak)) int cy_kernel_check_mode(void)
{
    return 0;
}

__attribute__((weak)) void cy_kernel_check_end(void) {}

void cy_test_end(void)
{
    cy_kernel_check_end();
    if (failures == 0) {
        cy_print("CY-TEST-END PASS\n");
    } else {
        cy_print("CY-TEST-END FAIL ");
        cy_print_dec(failures);
        cy_println();
    }
}

__attribute__((noinline)) void cy_target_sync(void)
{
    /* The runner's breakpoint. The barrier keeps the call from being optimised away. */
    __asm__ volatile("" ::: "memory");
}

void cy_bench_init(void)
{
#ifdef __MSP430__
    TBCTL = TASSEL_2 | MC_2 | TACLR; /* SMCLK, continuous */
    uint16_t t0 = cy_bench_now();
    uint16_t t1 = cy_bench_now();
    cy_bench_overhead = (uint16_t)(t1 - t0);
#endif
}

uint16_t cy_bench_now(void)
{
#ifdef __MSP430__
    return TBR;
#else
    return 0;
#endif
}

void cy_bench_add(cy_bench_stat_t *st, uint32_t cycles)
{
    if (cycles > st->max)
        st->max = cycles;
    st->sum += cycles;
    st->n++;
}

void cy_bench_report(const cy_bench_stat_t *st)
{
    if (cy_kernel_check_mode())
        return;
    cy_print("@cycles ");
    cy_print(st->name);
    hal_console_putc(' ');
    cy_print_dec((int32_t)st->max);
    hal_console_putc(' ');
    cy_print_dec(st->n ? (int32_t)(st->sum / st->n) : 0);
    hal_console_putc(' ');
    cy_print_dec(st->n);
    cy_println();
}

#ifdef __MSP430__
#define STACK_FILL   0xA5A5u
/* Bytes below cy_stack_fill()'s frame that a measurement fills and scans: far more than any
 * measured call needs (a board image's whole worst case is under 1 KB, docs/stack.md), and a
 * bounded cost per measurement whatever the part's RAM. */
#define STACK_WINDOW 2048u
extern uint16_t __noinit_end[]; /* the lowest address the stack may reach (linker script) */
static uint16_t stack_low;      /* the lowest word the last cy_stack_fill() wrote */
#endif

void cy_stack_fill(void)
{
#ifdef __MSP430__
    uint16_t below = (uint16_t)(cy_sp() - 16u); /* clear of this function's own frame */
    uint16_t low = (uint16_t)(uintptr_t)__noinit_end;
    if (below - low > STACK_WINDOW)
        low = (uint16_t)(below - STACK_WINDOW);
    stack_low = low;
    for (volatile uint16_t *p = (volatile uint16_t *)(uintptr_t)low; (uint16_t)(uintptr_t)p < below;
         p++)
        *p = STACK_FILL;
#endif
}

uint16_t cy_stack_used(uint16_t mark)
{
#ifdef __MSP430__
    const volatile uint16_t *p = (const volatile uint16_t *)(uintptr_t)stack_low;
    while ((uint16_t)(uintptr_t)p < mark && *p == STACK_FILL)
        p++;
    /* the lowest filled word overwritten: the call may have gone deeper than the window */
    cy_check((uint16_t)(uintptr_t)p != stack_low, "cy_stack_used: the measurement window is full");
    return (uint16_t)(mark - (uint16_t)(uintptr_t)p);
#else
    (void)mark;
    return 0;
#endif
}

void cy_stack_report(const cy_stack_stat_t *st)
{
    if (cy_kernel_check_mode())
        return;
    cy_print("@stack-use ");
    cy_print(st->name);
    hal_console_putc(' ');
    cy_print_dec(st->max);
    cy_println();
}
