/*
 * fault_irq_test.c - an interrupt on a vector nobody claimed lands in cy_isr_unexpected
 * (the linker script fills every free vector with it) and faults with 0x0104.
 */
#include "cy_test.h"
#include "hal/cpu.h"
#include "hal/irq.h"

int main(void)
{
    hal_cpu_init();
    hal_irq_enable();
    cy_print("@sim tr trigger 7\n"); /* simulator irq 7: the word at 0xFFEE, USCI_A0/B0 receive: no
                                        ISR */
    cy_target_sync();
    cy_print("FAIL the unexpected interrupt was not trapped\n");
    cy_test_end();
    return 0;
}
