/*
 * cy_clock.h - the clock hal_cpu_init() chose, for the drivers whose timing follows it (the
 * millisecond tick, the UART baud rates). Private to hal/msp430.
 */
#ifndef CY_CLOCK_H
#define CY_CLOCK_H

#include <stdint.h>

/** One clock setting: MCLK = SMCLK = the DCO. */
typedef struct {
    uint32_t hz;     /**< MCLK = SMCLK frequency, Hz */
    uint16_t per_ms; /**< SMCLK cycles per millisecond (the tick of hal/clock.h) */
    uint8_t br0;     /**< USCI UART at 115200 baud from SMCLK: UCAxBR0 (UCBRx low byte) */
    uint8_t br1;     /**< UCAxBR1 (UCBRx high byte) */
    uint8_t mctl;    /**< UCAxMCTL: UCBRSx << 1 (UCOS16 = 0) */
} cy_clock_t;

/**
 * The clock in use: the reset DCO (about 1 MHz, uncalibrated) until hal_cpu_init() switches
 * to a calibrated frequency the supply allows (hal/msp430/cpu.c, docs/hardware.md).
 */
extern const cy_clock_t *cy_clock;

#endif
