/*
 * hal/uart.h - serial receivers (asynchronous, 8 data bits, no parity, 1 stop bit), by instance:
 * each received byte reaches a portable handler in interrupt context.
 *
 * Instances (docs/posrx.md):
 *  - 0: USCI_A1 (P3.7 = UCA1RXD), receive vector 17 (USCIAB1RX, 0xFFE2): seed 002's serial
 *    position receiver (its RS-232 line runs at 9600 baud).
 *  - 1: a second position receiver (seed 002's future work). The harness has it on vector 23
 *    (USCIAB0RX, 0xFFEE, USCI_A0); on the MSP430 board images USCI_A0 is the console's
 *    (hal/console.h, 115200 baud: one baud-rate generator cannot serve both), so there
 *    hal_uart_open() refuses it with HAL_UART_E_INSTANCE.
 * Baud rates: HAL_UART_BAUD_9600 and HAL_UART_BAUD_115200 on both worlds (the MSP430 takes
 * its divisors for the clock hal_cpu_init() chose from SLAU144's table, UCOS16 = 0).
 *  - MSP430 (hal/msp430/uart_usci_a1.c): the receive interrupt reads UCA1STAT, then UCA1RXBUF
 *    (which clears the flag) and calls the handler; a framing or parity error, or an overrun
 *    (the byte before was not read in time and is lost), marks the byte HAL_UART_RX_ERROR.
 *  - POSIX (hal/posix/uart.c): the device at the other end (posix_uart_send, hal_posix/
 *    harness.h) sends bytes; each arrives 10 bit times after it started (start, 8 data, stop
 *    bits at the opened baud rate), back to back with the bytes before it, as a receive
 *    interrupt of the instance's vector; a byte that arrives while the one before still
 *    waits for its handler overruns it (counted, the new byte delivered with
 *    HAL_UART_RX_ERROR), as the USCI does.
 */
#ifndef HAL_UART_H
#define HAL_UART_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Instances the API names (0..HAL_UART_COUNT-1). */
#define HAL_UART_COUNT 2u

/** Baud rates both worlds support. */
#define HAL_UART_BAUD_9600   9600ul
#define HAL_UART_BAUD_115200 115200ul

/** Return codes of hal_uart_open(). */
#define HAL_UART_OK         0
#define HAL_UART_E_INSTANCE (-1) /**< no such instance on this board */
#define HAL_UART_E_BAUD     (-2) /**< a baud rate the instance cannot make */
#define HAL_UART_E_ARG      (-3) /**< NULL handler */

/** Flag of a received byte: framing or parity error, or the byte before it was overrun. */
#define HAL_UART_RX_ERROR 0x01u

/**
 * Receive handler, interrupt context (keep it short: at 115200 baud the next byte arrives
 * 87 us later): @p byte as received, @p flags HAL_UART_RX_* bits.
 */
typedef void (*hal_uart_rx_cb_t)(void *arg, uint8_t byte, uint8_t flags);

/**
 * Open @p instance at @p baud (bits per second, 8N1) and route every received byte to @p cb;
 * the receive interrupt is enabled at once (it runs when interrupts are enabled). Opening an
 * open instance again replaces its rate and handler. Returns HAL_UART_OK, or
 * HAL_UART_E_INSTANCE, HAL_UART_E_BAUD, HAL_UART_E_ARG (nothing changed then).
 */
int hal_uart_open(uint8_t instance, uint32_t baud, hal_uart_rx_cb_t cb, void *arg);

/** Stop receiving on @p instance (its interrupt disabled; no handler call after return). */
void hal_uart_close(uint8_t instance);

/** Bytes @p instance lost because the one before was not read in time (0..65535, wraps). */
uint16_t hal_uart_overruns(uint8_t instance);

#ifdef __cplusplus
}
#endif

#endif
