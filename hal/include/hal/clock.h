/*
 * hal/clock.h - the board's millisecond clock (timeouts and settling times of the main loop).
 *
 * MSP430: Timer_B in continuous mode on SMCLK, CCR0 interrupts every millisecond of SMCLK
 * (16,000 cycles at 16 MHz, 12,000 at 12 MHz: the clock hal_cpu_init() chose; vector 29,
 * TIMERB0); the handler counts and tells the main loop (hal_cpu_wake). POSIX: the harness
 * raises the same vector every simulated millisecond on the board that started its clock.
 */
#ifndef HAL_CLOCK_H
#define HAL_CLOCK_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Start the 1 ms tick (idempotent). Interrupts must be enabled for it to count. */
void hal_clock_init(void);

/** Milliseconds since hal_clock_init(); wraps after 49.7 days (compare with subtraction). */
uint32_t hal_clock_ms(void);

#ifdef __cplusplus
}
#endif

#endif
