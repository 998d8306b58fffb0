/*
 * hal/cpu.h - CPU start-up services.
 */
#ifndef HAL_CPU_H
#define HAL_CPU_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** CPU clock the firmware is timed for, Hz (MCLK = SMCLK on the MSP430 target). */
#define HAL_CPU_HZ 16000000ul

/**
 * Board bring-up: watchdog held, MCLK = SMCLK = 16 MHz from the calibrated DCO (when the
 * part carries calibration data; otherwise the reset DCO is left alone), all ports driven low
 * as outputs except the ones the peripheral drivers claim. Interrupts stay disabled.
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
