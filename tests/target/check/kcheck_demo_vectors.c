/*
 * kcheck_demo_vectors.c - kcheck_demo_mac on both worlds (the check mode's own test,
 * docs/kernels.md): the products of the int16 extremes and of pseudo-random operands,
 * accumulated; one line per call.
 */
#include <stdint.h>

#include "cy_test.h"
#include "kcheck_demo.h"

static void one(kcheck_demo_acc_t *acc, int16_t a, int16_t b)
{
    int32_t p = kcheck_demo_mac(acc, a, b);
    cy_check(p == (int32_t)a * b, "kcheck_demo_mac returns a * b");
    cy_print("mac ");
    cy_print_hex16((uint16_t)a);
    cy_print(" ");
    cy_print_hex16((uint16_t)b);
    cy_print(" ");
    cy_print_hex32((uint32_t)p);
    cy_print(" ");
    cy_print_hex32((uint32_t)acc->sum);
    cy_print(" ");
    cy_print_hex16(acc->calls);
    cy_println();
}

int main(void)
{
    static const int16_t edge[] = {0, 1, -1, 0x1234, 32767, -32768, -7};
    kcheck_demo_acc_t acc = {0, 0};
    uint32_t rng = 0x2545F491u;
    for (unsigned i = 0; i < sizeof edge / sizeof edge[0]; i++)
        for (unsigned j = 0; j < sizeof edge / sizeof edge[0]; j++)
            one(&acc, edge[i], edge[j]);
    for (unsigned i = 0; i < 200u; i++) {
        uint32_t r = cy_rand32(&rng);
        one(&acc, (int16_t)(uint16_t)r, (int16_t)(uint16_t)(r >> 16));
    }
    cy_test_end();
    return 0;
}
