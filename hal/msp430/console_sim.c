/*
 * console_sim.c - hal/console.h for test images: the mspdebug simulator's console device
 * (`simio add console`) prints every byte written to address 0x00FF at once.
 */
#include "hal/console.h"

#include "f2618.h"

#define SIM_CONSOLE CY_REG8(0x00FF)

void hal_console_putc(char c)
{
    SIM_CONSOLE = (uint8_t)c;
}

void hal_console_puts(const char *s)
{
    while (*s)
        SIM_CONSOLE = (uint8_t)*s++;
}

void hal_console_write(const char *s, size_t n)
{
    while (n--)
        SIM_CONSOLE = (uint8_t)*s++;
}

/* The device prints each byte as it is written: nothing is ever pending. */
void hal_console_flush(void) {}
