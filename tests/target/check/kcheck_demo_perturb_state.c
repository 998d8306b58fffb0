/*
 * kcheck_demo_perturb_state.c - a deliberately wrong C twin for the check's own test: the
 * accumulator after a = -7, b = 32767 off by 2^16, the return value right (linked with
 * --wrap=kcheck_demo_mac_c). The check image must stop there on the state it compares.
 */
#include "kcheck_demo.h"

int32_t __real_kcheck_demo_mac_c(kcheck_demo_acc_t *acc, int16_t a, int16_t b);
int32_t __wrap_kcheck_demo_mac_c(kcheck_demo_acc_t *acc, int16_t a, int16_t b);

int32_t __wrap_kcheck_demo_mac_c(kcheck_demo_acc_t *acc, int16_t a, int16_t b)
{
    int32_t r = __real_kcheck_demo_mac_c(acc, a, b);
    if (a == -7 && b == 32767)
        acc->sum = (int32_t)((uint32_t)acc->sum + 0x10000u);
    return r;
}
