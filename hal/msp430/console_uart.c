/*
 * console_uart.c - hal/console.h for board images: USCI_A0 as a UART on P3.4 (TXD),
 * 115200 baud 8N1 from SMCLK = 16 MHz (UCBR = 138, UCBRS = 7: 0.08 % error). Never blocks:
 * when the transmit buffer is still full the byte is dropped and counted, so diagnostics can
 * never stall an interrupt-driven board.
 */
#include "hal/console.h"

#include "f2618.h"

static uint8_t uart_ready;
static uint16_t dropped;

static void uart_init(void)
{
    UCA0CTL1 = UCSWRST;
    UCA0CTL1 = UCSWRST | UCSSEL_2;
    UCA0BR0 = 138;
    UCA0BR1 = 0;
    UCA0MCTL = 7u << 1;
    P3SEL |= 0x30u;
    UCA0CTL1 = UCSSEL_2; /* out of reset: UCA0TXIFG is set, the buffer is free */
    uart_ready = 1;
}

void hal_console_putc(char c)
{
    if (!uart_ready)
        uart_init();
    if (IFG2 & UCA0TXIFG)
        UCA0TXBUF = (uint8_t)c;
    else
        dropped++;
}

void hal_console_puts(const char *s)
{
    while (*s)
        hal_console_putc(*s++);
}

void hal_console_write(const char *s, size_t n)
{
    while (n--)
        hal_console_putc(*s++);
}

uint16_t hal_console_dropped(void)
{
    return dropped;
}
