/*
 * hal/clock.h - the board's millisecond clock (timeouts and settling times of the main loop).
 *
 * MSP430: Timer_B in continuous mode on SMCLK, CCR0 interrupts every millisecond of SMCLK
 * (16,000 cycles at 16 MHz, 12,000 at 12 MHz: the clock hal_cpu_init() chose; vector 29,
 * TIMERB0); the handler counts and tells the main loop (hal_cpu_wake). POSIX: the count is
 * the simulated milliseconds since hal_clock_init(); the harness raises the same vector every
 * simulated millisecond (ticked, the default), or only at the deadlines the main loop states
 * with hal_clock_wake_at() (tickless, posix_clock_set_tickless(): agv-sim's default). Both
 * give the same run, as long as every main loop states what it waits on.
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

/**
 * The main loop waits on something that falls due at millisecond @p ms (hal_clock_ms()'s
 * count; at or before now: the next millisecond). Each pass of a main loop states every
 * deadline it waits on, after its checks; an interrupt handler that leaves work wakes the loop
 * (hal_cpu_wake) instead. MSP430: nothing (the tick wakes the main loop every millisecond, and
 * it polls anyway). POSIX, tickless: the harness runs this board's main loop at the earliest
 * deadline stated (not later than any of them), instead of every millisecond.
 */
void hal_clock_wake_at(uint32_t ms);

#ifdef __cplusplus
}
#endif

#endif
