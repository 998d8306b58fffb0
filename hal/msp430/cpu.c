/*
 * cpu.c - clock and port bring-up of the MSP430F249.
 */
#include "hal/cpu.h"

#include "f2618.h"

void hal_cpu_init(void)
{
    WDTCTL = WDTPW | WDTHOLD;
    /*
     * DCO to the factory-calibrated 16 MHz. A part whose information memory was erased reads
     * 0xFF there; then the reset DCO (about 1.1 MHz) is kept rather than a guessed setting.
     * The mspdebug simulator runs every instruction at one "cycle" per clock regardless.
     */
    if (CALBC1_16MHZ != 0xFFu && CALDCO_16MHZ != 0xFFu) {
        DCOCTL = 0;
        BCSCTL1 = CALBC1_16MHZ;
        DCOCTL = CALDCO_16MHZ;
    }
    BCSCTL2 = 0; /* MCLK = SMCLK = DCO, no dividers */
    /* Unused pins as outputs driven low (no floating inputs); drivers claim theirs later. */
    P3DIR = 0xFF;
    P3OUT = 0;
    P4DIR = 0xFF;
    P4OUT = 0;
    P5DIR = 0xFF;
    P5OUT = 0;
    P6DIR = 0xFF;
    P6OUT = 0;
}

void hal_cpu_idle(void) {}

void hal_cpu_wake(void) {}
