/*
 * startup.c - C part of the start-up: .data copy and .bss clear, and the handler of every
 * vector nobody claimed.
 */
#include <stdint.h>

#include "f2618.h"
#include "hal/fault.h"

extern uint16_t __data_load_start[];
extern uint16_t __data_start[];
extern uint16_t __data_end[];
extern uint16_t __bss_start[];
extern uint16_t __bss_end[];

void cy_crt_init(void);
void cy_isr_unexpected(void);

/* Runs before main with the stack set and nothing else initialised: no globals used here. */
void cy_crt_init(void)
{
    const uint16_t *src = __data_load_start;
    for (uint16_t *dst = __data_start; dst < __data_end;)
        *dst++ = *src++;
    for (uint16_t *dst = __bss_start; dst < __bss_end;)
        *dst++ = 0;
}

/* Every vector without an ISR points here (see ld/f2618_sections.ld). */
__attribute__((interrupt(0))) void cy_isr_unexpected(void)
{
    hal_fault(HAL_FAULT_UNEXPECTED_IRQ);
}
