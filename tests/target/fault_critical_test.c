/*
 * fault_critical_test.c - leaving a critical section that was never entered is a misuse:
 * hal_fault(HAL_FAULT_CRITICAL_UNDERFLOW) stops the image (the runner expects FAULT 0x0101).
 */
#include "cy_test.h"
#include "hal/cpu.h"
#include "hal/irq.h"

int main(void)
{
    hal_cpu_init();
    hal_critical_enter();
    hal_critical_exit();
    cy_print("# balanced enter/exit passed, now an unbalanced exit\n");
    hal_critical_exit();
    cy_print("FAIL the unbalanced exit returned\n");
    cy_test_end();
    return 0;
}
