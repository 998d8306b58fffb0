/*
 * uart_usci_a1.c - hal/uart.h on the MSP430F2618: instance 0 is USCI_A1 in UART mode (8N1,
 * P3.7 = UCA1RXD; hal_cpu_init() selected P3.6/P3.7 for the USCI already), clocked by SMCLK
 * with SLAU144's divisors (table "Commonly Used Baud Rates, Settings, and Errors, UCOS16 = 0")
 * for the clock hal_cpu_init() chose. The receive interrupt (vector 17, USCIAB1RX) reads
 * UCA1STAT, then UCA1RXBUF (which clears UCA1RXIFG and the error flags) and calls the handler.
 * Instance 1 (USCI_A0) is the console's on the board images: refused (hal/uart.h).
 */
#include <stddef.h>

#include "cy_clock.h"
#include "f2618.h"
#include "hal/irq.h"
#include "hal/pinmap.h"
#include "hal/uart.h"

/* SLAU144's 9600 baud rows (UCBRx, UCBRSx) for the clocks the boards can run; 115200 baud
 * comes with the clock itself (cy_clock.h: the console's divisors). */
typedef struct {
    uint32_t hz;
    uint16_t br;
    uint8_t brs;
} baud_row_t;

static const baud_row_t rows_9600[] = {
    {16000000ul, 1666u, 6u},
    {12000000ul, 1250u, 0u},
    {1000000ul, 104u, 1u},
};

static hal_uart_rx_cb_t rx_cb;
static void *rx_arg;
static uint16_t overruns;

int hal_uart_open(uint8_t instance, uint32_t baud, hal_uart_rx_cb_t cb, void *arg)
{
    if (instance != 0u)
        return HAL_UART_E_INSTANCE;
    uint16_t br;
    uint8_t mctl;
    if (baud == HAL_UART_BAUD_115200) {
        br = (uint16_t)(cy_clock->br0 | (cy_clock->br1 << 8));
        mctl = cy_clock->mctl;
    } else if (baud == HAL_UART_BAUD_9600) {
        const baud_row_t *r = NULL;
        for (uint8_t i = 0; i < sizeof rows_9600 / sizeof rows_9600[0]; i++)
            if (rows_9600[i].hz == cy_clock->hz)
                r = &rows_9600[i];
        if (r == NULL)
            return HAL_UART_E_BAUD;
        br = r->br;
        mctl = (uint8_t)(r->brs << 1);
    } else {
        return HAL_UART_E_BAUD;
    }
    if (cb == NULL)
        return HAL_UART_E_ARG;
    hal_irq_state_t s = hal_irq_disable();
    rx_cb = cb;
    rx_arg = arg;
    UCA1CTL1 = UCSWRST | UCSSEL_2;
    UCA1CTL0 = 0u; /* UART, 8 data bits, no parity, 1 stop bit, LSB first */
    UCA1BR0 = (uint8_t)br;
    UCA1BR1 = (uint8_t)(br >> 8);
    UCA1MCTL = mctl;
    P3SEL |= 0x80u;      /* P3.7 UCA1RXD */
    UCA1CTL1 = UCSSEL_2; /* out of reset (which cleared UCA1RXIE): receive */
    UC1IE |= UCA1RXIE;
    hal_irq_restore(s);
    return HAL_UART_OK;
}

void hal_uart_close(uint8_t instance)
{
    if (instance != 0u)
        return;
    UC1IE &= (uint8_t)~UCA1RXIE;
}

uint16_t hal_uart_overruns(uint8_t instance)
{
    if (instance != 0u)
        return 0;
    hal_irq_state_t s = hal_irq_disable();
    uint16_t n = overruns;
    hal_irq_restore(s);
    return n;
}

CY_ISR(HAL_VEC_UART0_RX, hal_isr_uart0_rx)
{
    uint8_t st = UCA1STAT;
    uint8_t b = UCA1RXBUF;
    if (st & UCOE)
        overruns++;
    rx_cb(rx_arg, b, (st & UCRXERR) ? HAL_UART_RX_ERROR : 0u);
}
