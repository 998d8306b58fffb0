/*
 * hal/cpu.h - CPU start-up services.
 */
#ifndef HAL_CPU_H
#define HAL_CPU_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/**
 * Board bring-up: watchdog held, every pin in its reset-safe state (outputs at their idle
 * level, inputs left alone), MCLK = SMCLK from the calibrated DCO at the fastest frequency
 * the supply allows: 16 MHz at VCC >= 3.35 V (the SVS's level), else 12 MHz at >= 2.8 V
 * (docs/hardware.md). MSP430: stops with HAL_FAULT_CLOCK_UNCALIBRATED when the calibration
 * data is erased, HAL_FAULT_SUPPLY_LOW below 2.8 V. The millisecond tick and the UART baud
 * rates follow the chosen clock. Interrupts stay disabled.
 */
void hal_cpu_init(void);

/**
 * Called by a board's main loop when it has nothing to do. MSP430: returns at once (the main
 * loop polls). POSIX: returns to the harness so that simulated time can advance.
 */
void hal_cpu_idle(void);

/**
 * Called by an interrupt handler that left work for the main loop. MSP430: nothing (the main
 * loop polls). POSIX: the harness runs a pass of that board's main loop after the handler
 * (posix_board_take_wake()), instead of after every event.
 */
void hal_cpu_wake(void);

#ifdef __cplusplus
}
#endif

#endif
