/*
 * kernel_check.c - the support of kernel check images (kernel_check.h, docs/kernels.md):
 * the mismatch line, the stop, and the kernels' cycle figures at the end of the run.
 *
 * Compiled into each check image with CY_KCHECK_IMAGE naming its vector program; the figures
 * go to the cycle report as "@cycles kernel/<program>/<kernel>/asm|c max mean n".
 */
#include "kernel_check.h"

#include "hal/console.h"
#include "hal/irq.h"

#ifndef CY_KCHECK_IMAGE
#error "CY_KCHECK_IMAGE (the vector program's name) is set by cy_vector_program()"
#endif

void cy_halt(void) __attribute__((noreturn)); /* hal/msp430/crt0.S: the runner's stop */

static kcheck_stat_t *stats; /* registered kernels, the latest first */

int cy_kernel_check_mode(void)
{
    return 1;
}

void kcheck_register(kcheck_stat_t *st)
{
    if (st->registered)
        return;
    hal_irq_state_t s = hal_irq_disable();
    if (cy_bench_overhead == 0u) /* the program has not started the cycle counter */
        cy_bench_init();
    if (!st->registered) {
        st->next = stats;
        stats = st;
        st->registered = 1;
    }
    hal_irq_restore(s);
}

void kcheck_add(kcheck_cycles_t *c, uint16_t cycles)
{
    if (cycles > c->max)
        c->max = cycles;
    c->sum += cycles;
    c->n++;
}

static void report(const char *name, const kcheck_cycles_t *c, const char *kind)
{
    cy_print("@cycles kernel/" CY_KCHECK_IMAGE "/");
    cy_print(name);
    cy_print("/");
    cy_print(kind);
    cy_print(" ");
    cy_print_dec((int32_t)c->max);
    cy_print(" ");
    cy_print_dec(c->n ? (int32_t)(c->sum / c->n) : 0);
    cy_print(" ");
    cy_print_dec((int32_t)c->n);
    cy_println();
}

void cy_kernel_check_end(void)
{
    for (const kcheck_stat_t *st = stats; st != 0; st = st->next) {
        report(st->name, &st->asm_cycles, "asm");
        report(st->name, &st->c_cycles, "c");
    }
}

static void head(const char *kernel, const char *in_names, const uint32_t *in, uint8_t n_in)
{
    cy_print("KERNEL-MISMATCH ");
    cy_print(kernel);
    cy_print(" ");
    cy_print(in_names);
    cy_print("=");
    for (uint8_t i = 0; i < n_in; i++) {
        if (i)
            cy_print(",");
        cy_print("0x");
        cy_print_hex32(in[i]);
    }
}

static void words(const char *label, const uint32_t *w, uint8_t n)
{
    cy_print(label);
    for (uint8_t i = 0; i < n; i++) {
        if (i)
            cy_print(",");
        cy_print("0x");
        cy_print_hex32(w[i]);
    }
}

static void __attribute__((noreturn)) stop(void)
{
    cy_println();
    cy_halt();
}

void kcheck_words(const char *kernel, const char *in_names, const uint32_t *in, uint8_t n_in,
                  const uint32_t *out_asm, const uint32_t *out_c, uint8_t n_out)
{
    uint8_t i = 0;
    while (i < n_out && out_asm[i] == out_c[i])
        i++;
    if (i == n_out)
        return;
    head(kernel, in_names, in, n_in);
    words(" asm=", out_asm, n_out);
    words(" c=", out_c, n_out);
    stop();
}

void kcheck_bytes(const char *kernel, const char *in_names, const uint32_t *in, uint8_t n_in,
                  const void *asm_state, const void *c_state, uint16_t size)
{
    const uint8_t *a = asm_state, *c = c_state;
    uint16_t i = 0;
    while (i < size && a[i] == c[i])
        i++;
    if (i == size)
        return;
    uint16_t at = (uint16_t)(i & ~1u); /* the 16-bit word holding the first difference */
    uint16_t wa = a[at], wc = c[at];
    if (at + 1u < size) {
        wa = (uint16_t)(wa | (uint16_t)(a[at + 1u] << 8));
        wc = (uint16_t)(wc | (uint16_t)(c[at + 1u] << 8));
    }
    head(kernel, in_names, in, n_in);
    cy_print(" asm=@");
    cy_print_dec(at);
    cy_print(":0x");
    cy_print_hex16(wa);
    cy_print(" c=@");
    cy_print_dec(at);
    cy_print(":0x");
    cy_print_hex16(wc);
    stop();
}
