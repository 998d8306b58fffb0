/*
 * hal/drive_port.h - the main board's parallel bus to the drive board (SPEC D6).
 *
 * One 8-bit write-only bus with a 3-bit register address, as the seed's 8086 saw its 8255
 * and seed 002's PC saw its DAC/digital-output card. Registers 0..3 are an 8255 PPI (ports
 * A, B, C and the control word); registers 4..6 are seed 002's interface: a 2-channel 8-bit
 * DAC (steering angle, speed) and an 8-bit digital output latch (motor enables, brake, turn
 * lights). The byte protocols on top (data inverted, strobe codes, DAC values) are portable
 * firmware (firmware/drive, drive/drive_port.h); this API only moves bytes.
 *
 * MSP430F2618 (hal/msp430/drive_port.c, docs/hardware.md): P4.0..P4.7 = data D0..D7,
 * P5.0..P5.2 = address A0..A2, P5.3 = /WR (active low; the 8255 and the latches take the data
 * on its rising edge). A 74HC138 on the drive board decodes A2 into the 8255's /CS (A2 = 0)
 * and the strobes of the drive board's DAC and output latches (A2 = 1). Host
 * (hal/posix/drive_port.c): every write is recorded with its board and simulated time
 * (hal_posix/drive_port_posix.h).
 */
#ifndef HAL_DRIVE_PORT_H
#define HAL_DRIVE_PORT_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Registers on the drive bus (the value is the bus address A2..A0). */
typedef enum {
    HAL_DRIVE_PPI_A = 0,     /**< 8255 port A: the data byte                                */
    HAL_DRIVE_PPI_B = 1,     /**< 8255 port B: strobe codes                                 */
    HAL_DRIVE_PPI_C = 2,     /**< 8255 port C: transfer begin / done lines                  */
    HAL_DRIVE_PPI_CTRL = 3,  /**< 8255 control word                                         */
    HAL_DRIVE_DAC_ANGLE = 4, /**< seed 002: steering DAC, centre value = straight           */
    HAL_DRIVE_DAC_SPEED = 5, /**< seed 002: speed DAC, 128 = stop                           */
    HAL_DRIVE_DIGITAL = 6,   /**< seed 002: digital outputs (motor enables, brake, lights)  */
    HAL_DRIVE_REG_COUNT
} hal_drive_reg_t;

/** Set up the bus pins (data and address lines driven, /WR idle high). Idempotent. */
void hal_drive_port_init(void);

/**
 * Write @p value to register @p reg (one bus cycle: address and data set up, /WR pulsed).
 * Registers outside hal_drive_reg_t are ignored. Callable from handlers; not reentrant:
 * the caller serialises writes (a protocol sequence must not be interleaved with another).
 */
void hal_drive_port_write(hal_drive_reg_t reg, uint8_t value);

#ifdef __cplusplus
}
#endif

#endif
