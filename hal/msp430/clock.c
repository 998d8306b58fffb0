/*
 * clock.c - hal/clock.h on Timer_B: continuous mode on SMCLK (16 MHz), CCR0 advanced by
 * 16,000 counts per interrupt. cy_bench (tests) reads the same free-running TBR.
 */
#include "hal/clock.h"
#include "f2618.h"
#include "hal/cpu.h"
#include "hal/irq.h"
#include "hal/pinmap.h"

#define TBCCTL0_REG CY_REG16(0x0182)
#define TICK        16000u

static volatile uint32_t ms;
static uint8_t started;

void hal_clock_init(void)
{
    hal_irq_state_t s = hal_irq_disable();
    if (!started) {
        if ((TBCTL & MC_2) == 0)
            TBCTL = TASSEL_2 | MC_2 | TACLR;
        TBCCR0 = (uint16_t)(TBR + TICK);
        TBCCTL0_REG = CCIE;
        started = 1;
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

CY_ISR(HAL_VEC_TIMERB0, hal_isr_timerb0)
{
    TBCCR0 = (uint16_t)(TBCCR0 + TICK);
    ms++;
    hal_cpu_wake();
}
