/*
 * console_uart_test.c - the board images' console (hal/msp430/console_uart.c) with the
 * runner emulating USCI_A0's transmitter (--uart: the transmit flag is clear for a while
 * after each byte): every byte of a line arrives, and hal_fault()'s message leaves the UART
 * completely before the CPU stops (the runner fails a halt while the UART is busy).
 */
#include "cy_test.h"
#include "hal/cpu.h"
#include "hal/fault.h"

int main(void)
{
    hal_cpu_init();
    cy_print("no byte lost: 0123456789 abcdefghijklmnopqrstuvwxyz");
    cy_println();
    cy_test_end();
    hal_fault(HAL_FAULT_ASSERT);
}
