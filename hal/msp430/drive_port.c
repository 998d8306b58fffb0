/*
 * drive_port.c - hal/drive_port.h on ports 4 and 5 of the MSP430F2618.
 *
 * P4.0..P4.7 carry the data byte, P5.0..P5.2 the register address, P5.3 is /WR (active
 * low). A bus cycle sets address and data with /WR high, pulls /WR low and releases it; the
 * 8255 (/CS from A2 = 0 through an external 74HC138) and seed 002's DAC and output latches
 * (A2 = 1) take the byte on the rising edge. /WR stays low for one read-modify-write
 * instruction on an absolute address (4 MCLK cycles, 250 ns at 16 MHz; the 82C55A needs
 * 150 ns). Interrupts are held off for the cycle so that a handler's write cannot split one.
 */
#include "hal/drive_port.h"
#include "f2618.h"
#include "hal/irq.h"

#define BUS_ADDR_MASK 0x07u /* P5.0..P5.2 */
#define BUS_WR        0x08u /* P5.3, active low */

void hal_drive_port_init(void)
{
    hal_irq_state_t s = hal_irq_disable();
    P5OUT = (uint8_t)((P5OUT & (uint8_t)~BUS_ADDR_MASK) | BUS_WR);
    P5SEL &= (uint8_t) ~(BUS_ADDR_MASK | BUS_WR);
    P5DIR |= (uint8_t)(BUS_ADDR_MASK | BUS_WR);
    P4OUT = 0x00u; /* the latch before the direction: the bus never shows a stale byte */
    P4SEL = 0x00u;
    P4DIR = 0xFFu;
    hal_irq_restore(s);
}

void hal_drive_port_write(hal_drive_reg_t reg, uint8_t value)
{
    if ((unsigned)reg >= HAL_DRIVE_REG_COUNT)
        return;
    hal_irq_state_t s = hal_irq_disable();
    P4OUT = value;
    P5OUT = (uint8_t)((P5OUT & (uint8_t)~BUS_ADDR_MASK) | (uint8_t)reg | BUS_WR);
    P5OUT &= (uint8_t)~BUS_WR;
    P5OUT |= BUS_WR;
    hal_irq_restore(s);
}
