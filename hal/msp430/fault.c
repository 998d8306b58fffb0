/*
 * fault.c - hal_fault() on the MSP430: record, report, wait until the report has left the
 * UART, stop (LPM4: every clock off).
 */
#include "hal/fault.h"

#include "f2618.h"
#include "hal/console.h"

/* Survives in RAM for the debugger: `md hal_fault_code 2` after the CPU stopped. */
volatile uint16_t hal_fault_code;

void cy_halt(void) __attribute__((noreturn));

void hal_fault(uint16_t code)
{
    char text[] = "\nFAULT 0x0000\n";
    cy_dint();
    hal_fault_code = code;
    for (char *p = &text[12]; p > &text[8]; p--) {
        uint8_t digit = (uint8_t)(code & 0xFu);
        *p = (char)(digit < 10 ? '0' + digit : 'a' - 10 + digit);
        code >>= 4;
    }
    hal_console_puts(text);
    hal_console_flush();
    cy_halt();
}
