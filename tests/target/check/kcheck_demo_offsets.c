/*
 * kcheck_demo_offsets.c - what kcheck_demo.S needs of kcheck_demo.h, as CY_OFFSET markers
 * (cy_asm_offsets() turns them into kcheck_demo_offsets.h; docs/kernels.md).
 */
#include "cy_offsets.h"
#include "kcheck_demo.h"

void kcheck_demo_offsets(void);

void kcheck_demo_offsets(void)
{
    CY_OFFSET(KCHECK_DEMO_CALLS, offsetof(kcheck_demo_acc_t, calls));
    CY_OFFSET(KCHECK_DEMO_SUM, offsetof(kcheck_demo_acc_t, sum));
}
