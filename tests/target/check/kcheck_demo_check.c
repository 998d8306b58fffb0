/*
 * kcheck_demo_check.c - the check-mode wrapper of kcheck_demo_mac (kernel_check.h).
 */
#include "kcheck_demo.h"
#include "kernel_check.h"

int32_t __real_kcheck_demo_mac(kcheck_demo_acc_t *acc, int16_t a, int16_t b);
int32_t __wrap_kcheck_demo_mac(kcheck_demo_acc_t *acc, int16_t a, int16_t b);
int32_t kcheck_demo_mac_c(kcheck_demo_acc_t *acc, int16_t a, int16_t b);

int32_t __wrap_kcheck_demo_mac(kcheck_demo_acc_t *acc, int16_t a, int16_t b)
{
    static kcheck_stat_t st = KCHECK_STAT("kcheck_demo_mac");
    const uint32_t in[] = {(uint32_t)acc->sum, (uint32_t)(int32_t)a, (uint32_t)(int32_t)b};
    kcheck_demo_acc_t acc_c = *acc;
    int32_t r_asm, r_c;
    KCHECK_RUN(&st, r_asm = __real_kcheck_demo_mac(acc, a, b),
               r_c = kcheck_demo_mac_c(&acc_c, a, b));
    const uint32_t oa[] = {(uint32_t)r_asm}, oc[] = {(uint32_t)r_c};
    kcheck_words("kcheck_demo_mac", "acc,a,b", in, 3, oa, oc, 1);
    kcheck_bytes("kcheck_demo_mac", "acc,a,b", in, 3, acc, &acc_c, sizeof acc_c);
    return r_asm;
}
