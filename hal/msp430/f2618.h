/*
 * f2618.h - the MSP430F2618 registers and bits this HAL touches (private to hal/msp430 and
 * target tests). Register addresses from TI's data sheet SLAS541 (Table 9-14, the registers
 * of each peripheral module; information memory: the calibration data of segment A); bit
 * values from the 2xx family user's guide SLAU144 (the register descriptions of each module's
 * chapter). tests/target/datasheet_registers_test.py checks every definition here against
 * tables typed from those documents (tests/target/datasheet/). Vector numbers are in
 * hal/pinmap.h. Usable from assembly sources too (the registers are then bare addresses).
 */
#ifndef CY_F2618_H
#define CY_F2618_H

#ifdef __ASSEMBLER__
#define CY_REG8(addr)          (addr)
#define CY_REG16(addr)         (addr)
/* The symbol the linker script's vector table takes for vector N (see CY_ISR below). */
#define CY_VECTOR_SYMBOL_(vec) __cy_vector_##vec
#define CY_VECTOR_SYMBOL(vec)  CY_VECTOR_SYMBOL_(vec)
#else
#include <stdint.h>
#define CY_REG8(addr)  (*(volatile uint8_t *)(uintptr_t)(addr))
#define CY_REG16(addr) (*(volatile uint16_t *)(uintptr_t)(addr))
#endif

/* Special function registers */
#define IE1       CY_REG8(0x0000)
#define IE2       CY_REG8(0x0001)
#define IFG1      CY_REG8(0x0002)
#define IFG2      CY_REG8(0x0003)
#define UC1IE     CY_REG8(0x0006)
#define UC1IFG    CY_REG8(0x0007)
#define NMIIE     0x10u /* IE1 */
#define NMIIFG    0x10u /* IFG1 */
#define UCA0TXIFG 0x02u /* IFG2 */
#define UCA1RXIE  0x01u /* UC1IE */
#define UCA1TXIE  0x02u /* UC1IE */
#define UCA1RXIFG 0x01u /* UC1IFG */

/* Watchdog timer+ */
#define WDTCTL   CY_REG16(0x0120)
#define WDTPW    0x5A00u
#define WDTHOLD  0x0080u
#define WDTNMIES 0x0040u
#define WDTNMI   0x0020u

/* Basic clock module+ and the DCO calibration data in information memory segment A */
#define BCSCTL3      CY_REG8(0x0053)
#define DCOCTL       CY_REG8(0x0056)
#define BCSCTL1      CY_REG8(0x0057)
#define BCSCTL2      CY_REG8(0x0058)
#define CALDCO_16MHZ CY_REG8(0x10F8)
#define CALBC1_16MHZ CY_REG8(0x10F9)
#define CALDCO_12MHZ CY_REG8(0x10FA)
#define CALBC1_12MHZ CY_REG8(0x10FB)

/* Supply voltage supervisor: VLDx (bits 7-4) selects the level and turns the SVS on */
#define SVSCTL   CY_REG8(0x0055)
#define VLD_2V8  0x80u /* VLDx = 8: 2.8 V */
#define VLD_3V35 0xC0u /* VLDx = 12: 3.35 V */
#define PORON    0x08u
#define SVSOP    0x02u

/* Ports 1 and 2 (with interrupts) */
#define P1IN  CY_REG8(0x0020)
#define P1OUT CY_REG8(0x0021)
#define P1DIR CY_REG8(0x0022)
#define P1IFG CY_REG8(0x0023)
#define P1IES CY_REG8(0x0024)
#define P1IE  CY_REG8(0x0025)
#define P1SEL CY_REG8(0x0026)
#define P2IN  CY_REG8(0x0028)
#define P2OUT CY_REG8(0x0029)
#define P2DIR CY_REG8(0x002A)
#define P2IFG CY_REG8(0x002B)
#define P2IES CY_REG8(0x002C)
#define P2IE  CY_REG8(0x002D)
#define P2SEL CY_REG8(0x002E)
/* Ports 3..6 */
#define P3OUT CY_REG8(0x0019)
#define P3DIR CY_REG8(0x001A)
#define P3SEL CY_REG8(0x001B)
#define P4OUT CY_REG8(0x001D)
#define P4DIR CY_REG8(0x001E)
#define P4SEL CY_REG8(0x001F)
#define P5OUT CY_REG8(0x0031)
#define P5DIR CY_REG8(0x0032)
#define P5SEL CY_REG8(0x0033)
#define P6OUT CY_REG8(0x0035)
#define P6DIR CY_REG8(0x0036)

/* USCI_A0 and USCI_A1 in UART mode */
#define UCA0CTL1  CY_REG8(0x0061)
#define UCA0BR0   CY_REG8(0x0062)
#define UCA0BR1   CY_REG8(0x0063)
#define UCA0MCTL  CY_REG8(0x0064)
#define UCA0STAT  CY_REG8(0x0065)
#define UCA0TXBUF CY_REG8(0x0067)
#define UCA1CTL0  CY_REG8(0x00D0)
#define UCA1CTL1  CY_REG8(0x00D1)
#define UCA1BR0   CY_REG8(0x00D2)
#define UCA1BR1   CY_REG8(0x00D3)
#define UCA1MCTL  CY_REG8(0x00D4)
#define UCA1STAT  CY_REG8(0x00D5)
#define UCA1RXBUF CY_REG8(0x00D6)
#define UCA1TXBUF CY_REG8(0x00D7)
#define UCSSEL_2  0x80u /* UCAxCTL1: BRCLK = SMCLK */
#define UCSWRST   0x01u /* UCAxCTL1 */
#define UCBUSY    0x01u /* UCAxSTAT */
#define UCRXERR   0x04u /* UCAxSTAT: framing, parity or overrun error */
#define UCOE      0x20u /* UCAxSTAT: overrun */

/* USCI_B0 in SPI mode (the MCP2515, hal/msp430/spi_usci_b0.c); UCB0CTL1 has UCAxCTL1's
 * UCSSEL_2 and UCSWRST */
#define UCB0CTL0  CY_REG8(0x0068)
#define UCB0CTL1  CY_REG8(0x0069)
#define UCB0BR0   CY_REG8(0x006A)
#define UCB0BR1   CY_REG8(0x006B)
#define UCB0RXBUF CY_REG8(0x006E)
#define UCB0TXBUF CY_REG8(0x006F)
#define UCCKPH    0x80u /* UCBxCTL0: data captured on the first UCLK edge */
#define UCCKPL    0x40u /* UCBxCTL0: clock inactive high */
#define UCMSB     0x20u /* UCBxCTL0: MSB first */
#define UCMST     0x08u /* UCBxCTL0: master */
#define UCSYNC    0x01u /* UCBxCTL0: synchronous mode (UCMODEx = 00b: 3-pin SPI) */
#define UCB0RXIFG 0x04u /* IFG2 */

/* Timer_A3 */
#define TAIV        CY_REG16(0x012E)
#define TACTL       CY_REG16(0x0160)
#define TACCTL0     CY_REG16(0x0162)
#define TACCTL1     CY_REG16(0x0164)
#define TAR         CY_REG16(0x0170)
#define TACCR0      CY_REG16(0x0172)
#define TACCR1      CY_REG16(0x0174)
#define TAIV_TACCR1 0x0002u /* TAIV: capture/compare 1 */
/* Timer_B7 */
#define TBIV        CY_REG16(0x011E)
#define TBCTL       CY_REG16(0x0180)
#define TBCCTL0     CY_REG16(0x0182)
#define TBR         CY_REG16(0x0190)
#define TBCCR0      CY_REG16(0x0192)

/* Timer control bits (TACTL / TBCTL and the capture/compare controls: same layout) */
#define TASSEL_0 0x0000u /* TACLK */
#define TASSEL_2 0x0200u /* SMCLK */
#define MC_2     0x0020u /* continuous */
#define TACLR    0x0004u
#define CM_1     0x4000u /* capture on rising edge */
#define CM_3     0xC000u /* capture on both edges */
#define SCS      0x0800u
#define CAP      0x0100u
#define CCIE     0x0010u
#define CCI      0x0008u
#define COV      0x0002u
#define CCIFG    0x0001u

/* Hardware multiplier (16 x 16) */
#define MPY   CY_REG16(0x0130)
#define OP2   CY_REG16(0x0138)
#define RESLO CY_REG16(0x013A)
#define RESHI CY_REG16(0x013C)

/* Status register bits */
#define SR_GIE    0x0008u
#define SR_CPUOFF 0x0010u
#define SR_OSCOFF 0x0020u
#define SR_SCG0   0x0040u
#define SR_SCG1   0x0080u

#ifndef __ASSEMBLER__
/* Status register access. */
static inline uint16_t cy_sr_read(void)
{
    uint16_t sr;
    __asm__ volatile("mov r2, %0" : "=r"(sr));
    return sr;
}

/* Disable interrupts; the NOP covers the one instruction DINT needs to take effect. */
static inline void cy_dint(void)
{
    __asm__ volatile("dint\n\tnop" ::: "memory");
}

/* Enable interrupts (NOPs around EINT as the 2xx family guide asks). */
static inline void cy_eint(void)
{
    __asm__ volatile("nop\n\teint\n\tnop" ::: "memory");
}

/* Set GIE again if @p sr had it. */
static inline void cy_gie_restore(uint16_t sr)
{
    if (sr & SR_GIE)
        cy_eint();
}

/*
 * CY_ISR(vector, name) defines an interrupt service routine for vector N of hal/pinmap.h (the
 * word at 0xFFC0 + 2N) and publishes it as __cy_vector_N for the linker script, which fills
 * every unused vector with cy_isr_unexpected. (clang's own interrupt(N) section is discarded.)
 * An assembly entry publishes itself with CY_VECTOR_SYMBOL (hal/msp430/nmi.S).
 */
#define CY_ISR_(vec, name)                                                                         \
    __asm__(".global __cy_vector_" #vec "\n.set __cy_vector_" #vec ", " #name "\n");               \
    void name(void);                                                                               \
    __attribute__((interrupt(vec), used)) void name(void)
#define CY_ISR(vec, name) CY_ISR_(vec, name)
#endif

#endif
