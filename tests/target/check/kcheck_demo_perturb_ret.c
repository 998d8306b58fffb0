/*
 * kcheck_demo_perturb_ret.c - a deliberately wrong C twin for the check's own test: the
 * product of a = 0x1234 and b = -7 off by one (linked with --wrap=kcheck_demo_mac_c). The
 * check image must stop there with "KERNEL-MISMATCH kcheck_demo_mac acc,a,b=..." .
 */
#include "kcheck_demo.h"

int32_t __real_kcheck_demo_mac_c(kcheck_demo_acc_t *acc, int16_t a, int16_t b);
int32_t __wrap_kcheck_demo_mac_c(kcheck_demo_acc_t *acc, int16_t a, int16_t b);

int32_t __wrap_kcheck_demo_mac_c(kcheck_demo_acc_t *acc, int16_t a, int16_t b)
{
    int32_t r = __real_kcheck_demo_mac_c(acc, a, b);
    return (a == 0x1234 && b == -7) ? r + 1 : r;
}
