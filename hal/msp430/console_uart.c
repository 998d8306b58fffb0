/*
 * console_uart.c - hal/console.h for board images: USCI_A0 as a UART on P3.4 (TXD), 115200
 * baud 8N1 from SMCLK with the divisors of the clock hal_cpu_init() chose (16 MHz: UCBR = 138,
 * UCBRS = 7; 12 MHz: 104, 1; SLAU144's baud-rate table). Each byte waits for the transmit
 * buffer (UCA0TXIFG), so none is lost; hal_console_flush() waits for the shift register too
 * (UCBUSY clear), so that hal_fault() can stop the clocks after the whole message left.
 */
#include "hal/console.h"

#include "cy_clock.h"
#include "f2618.h"

static uint8_t uart_ready;

static void uart_init(void)
{
    UCA0CTL1 = UCSWRST | UCSSEL_2;
    UCA0BR0 = cy_clock->br0;
    UCA0BR1 = cy_clock->br1;
    UCA0MCTL = cy_clock->mctl;
    P3SEL |= 0x30u;      /* P3.4 TXD, P3.5 RXD (hal_cpu_init selected them already) */
    UCA0CTL1 = UCSSEL_2; /* out of reset: UCA0TXIFG is set, the buffer is free */
    uart_ready = 1;
}

void hal_console_putc(char c)
{
    if (!uart_ready)
        uart_init();
    while (!(IFG2 & UCA0TXIFG))
        ;
    UCA0TXBUF = (uint8_t)c;
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

void hal_console_flush(void)
{
    if (!uart_ready)
        return;
    while (!(IFG2 & UCA0TXIFG))
        ;
    while (UCA0STAT & UCBUSY)
        ;
}
