/*
 * uart_none.c - hal/uart.h on board images whose USCI_A1 carries the board link
 * (hal/msp430/link_uart.c): both UARTs of the F2618 are taken (USCI_A0 by the console,
 * USCI_A1 by the link), so the board has no serial receiver and hal_uart_open() refuses every
 * instance. hal/CMakeLists.txt links it instead of uart_usci_a1.c while the link is a UART:
 * the two cannot share the USCIAB1RX vector (docs/posrx.md).
 */
#include "hal/uart.h"

int hal_uart_open(uint8_t instance, uint32_t baud, hal_uart_rx_cb_t cb, void *arg)
{
    (void)instance;
    (void)baud;
    (void)cb;
    (void)arg;
    return HAL_UART_E_INSTANCE;
}

void hal_uart_close(uint8_t instance)
{
    (void)instance;
}

uint16_t hal_uart_overruns(uint8_t instance)
{
    (void)instance;
    return 0;
}
