/*
 * cpu_clock_test.c - the clock hal_cpu_init() chooses and what follows it, on the supply the
 * runner emulates (--vcc): which calibration bytes went into the DCO registers, MCLK = SMCLK
 * undivided, the millisecond tick (the advance of Timer_B's CCR0 per tick, in SMCLK cycles)
 * and the link UART's divisors. It prints what it found; tests/target/clock_check.py compares
 * the figures with SLAU144's baud-rate table and the tick with a millisecond of the clock,
 * and ctest pins the clock each supply must give (tests/target/CMakeLists.txt).
 */
#include <stdint.h>

#include "cy_test.h"
#include "f2618.h"
#include "hal/clock.h"
#include "hal/cpu.h"
#include "hal/irq.h"

int main(void)
{
    hal_cpu_init();
    uint8_t bc1 = BCSCTL1, dco = DCOCTL;
    if (bc1 == CALBC1_16MHZ && dco == CALDCO_16MHZ)
        cy_print("clock 16000000");
    else if (bc1 == CALBC1_12MHZ && dco == CALDCO_12MHZ)
        cy_print("clock 12000000");
    else
        cy_print("clock uncalibrated");
    cy_println();
    cy_check(BCSCTL2 == 0u, "MCLK = SMCLK = DCO, undivided");

    hal_clock_init();
    uint16_t c0 = TBCCR0;
    hal_irq_enable();
    uint32_t t0 = hal_clock_ms();
    while (hal_clock_ms() == t0)
        ;
    uint16_t c1 = TBCCR0;
    cy_print("tick ");
    cy_print_dec((uint16_t)(c1 - c0));
    cy_print(" uart ");
    cy_print_dec(UCA0BR0);
    cy_print(" ");
    cy_print_dec(UCA0BR1);
    cy_print(" ");
    cy_print_dec(UCA0MCTL >> 1);
    cy_println();
    cy_test_end();
    return 0;
}
