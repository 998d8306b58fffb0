/*
 * signal.c - hal/signal.h: P2.1 (coordinate request) as an active-low output.
 */
#include "hal/signal.h"
#include "f2618.h"

#define COORD_PIN 0x02u /* P2.1 */

void hal_signal_init(hal_signal_t s)
{
    if (s != HAL_SIGNAL_COORD_REQUEST)
        return;
    P2SEL &= (uint8_t)~COORD_PIN;
    P2OUT |= COORD_PIN;
    P2DIR |= COORD_PIN;
}

void hal_signal_pulse(hal_signal_t s)
{
    if (s != HAL_SIGNAL_COORD_REQUEST)
        return;
    P2OUT &= (uint8_t)~COORD_PIN;
    __asm__ volatile("nop\n\tnop\n\tnop\n\tnop"); /* >= 250 ns low at 16 MHz */
    P2OUT |= COORD_PIN;
}
