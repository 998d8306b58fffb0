/*
 * kcheck_demo_k.c - the C twin of kcheck_demo.S (kcheck_demo.h).
 */
#include "kcheck_demo.h"

int32_t kcheck_demo_mac(kcheck_demo_acc_t *acc, int16_t a, int16_t b)
{
    int32_t p = (int32_t)a * b;
    acc->sum = (int32_t)((uint32_t)acc->sum + (uint32_t)p);
    acc->calls++;
    return p;
}
