/*
 * f2618_usci_b.h - USCI_B0 of the MSP430F2618 in SPI mode (private to hal/msp430 and target
 * tests), beside f2618.h. Register addresses from TI's data sheet SLAS541 (the USCI_B0 rows of
 * the peripheral register table, the special function registers IE2/IFG2); bit values from the
 * 2xx family user's guide SLAU144, "USCI: SPI Mode" (UCBxCTL0, UCBxCTL1, UCBxSTAT) and the
 * USCI_B0 bits of IE2/IFG2.
 */
#ifndef CY_F2618_USCI_B_H
#define CY_F2618_USCI_B_H

#include "f2618.h"

#define UCB0CTL0  CY_REG8(0x0068)
#define UCB0CTL1  CY_REG8(0x0069)
#define UCB0BR0   CY_REG8(0x006A)
#define UCB0BR1   CY_REG8(0x006B)
#define UCB0STAT  CY_REG8(0x006D)
#define UCB0RXBUF CY_REG8(0x006E)
#define UCB0TXBUF CY_REG8(0x006F)

/* UCB0CTL0 in SPI mode */
#define UCCKPH    0x80u /* clock phase: data captured on the first UCLK edge */
#define UCCKPL    0x40u /* clock polarity: inactive state high */
#define UCMSB     0x20u /* MSB first */
#define UCMST     0x08u /* master */
#define UCSYNC    0x01u /* synchronous mode (UCMODEx = 00: 3-pin SPI) */
/* UCB0CTL1: UCSSEL_2 (BRCLK = SMCLK) and UCSWRST as in f2618.h */
/* UCB0STAT */
#define UCB0BUSY  0x01u /* UCBUSY: a byte is being shifted */
/* IFG2 / IE2 */
#define UCB0RXIFG 0x04u
#define UCB0TXIFG 0x08u

#endif
