/*
 * fault.c - hal_fault() on the MSP430: record, report, stop.
 */
#include "hal/fault.h"

#include "f249.h"
#include "hal/console.h"

/* Survives in RAM for the debugger: `md hal_fault_code 2` after the CPU stopped. */
volatile uint16_t hal_fault_code;

void cy_halt(void) __attribute__((noreturn));

void hal_fault(uint16_t code)
{
    static const char hex[] = "0123456789abcdef";
    char text[] = "\nFAULT 0x0000\n";
    cy_dint();
    hal_fault_code = code;
    for (int i = 0; i < 4; i++)
        text[9 + i] = hex[(code >> (12 - 4 * i)) & 0xFu];
    hal_console_puts(text);
    cy_halt();
}
