/*
 * clock.c - hal/clock.h on Timer_B: continuous mode on SMCLK, CCR0 advanced by one
 * millisecond of SMCLK cycles per interrupt (16,000 at 16 MHz, 12,000 at 12 MHz: the clock
 * hal_cpu_init() chose). cy_bench (tests) reads the same free-running TBR.
 */
#include "hal/clock.h"
#include "cy_clock.h"
#include "f2618.h"
#include "hal/cpu.h"
#include "hal/irq.h"
#include "hal/pinmap.h"

static volatile uint32_t ms;
static uint16_t tick; /* SMCLK cycles per millisecond, 0 until started */

void hal_clock_init(void)
{
    hal_irq_state_t s = hal_irq_disable();
    if (tick == 0u) {
        tick = cy_clock->per_ms;
        if ((TBCTL & MC_2) == 0)
            TBCTL = TASSEL_2 | MC_2 | TACLR;
        TBCCR0 = (uint16_t)(TBR + tick);
        TBCCTL0 = CCIE;
    }
    hal_irq_restore(s);
}

uint32_t hal_clock_ms(void)
{
    hal_irq_state_t s = hal_irq_disable();
    uint32_t v = ms;
    hal_irq_restore(s);
    return v;
}

void hal_clock_wake_at(uint32_t at)
{
    (void)at; /* the tick below wakes the main loop every millisecond */
}

CY_ISR(HAL_VEC_TIMERB0, hal_isr_timerb0)
{
    TBCCR0 = (uint16_t)(TBCCR0 + tick);
    ms++;
    hal_cpu_wake();
}
