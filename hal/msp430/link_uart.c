/*
 * link_uart.c - hal/link.h on USCI_A1 as a UART (P3.6 TXD, P3.7 RXD, 115200 8N1 from SMCLK
 * with the divisors of the clock hal_cpu_init() chose):
 * frames go out through a byte ring filled by hal_link_send() and drained by the transmit
 * interrupt; received bytes go through the shared framer (hal/common/link_framer.c) in the
 * receive interrupt, which calls the handler per good frame.
 */
#include <stddef.h>

#include "cy_clock.h"
#include "f2618.h"
#include "hal/irq.h"
#include "hal/link.h"
#include "hal/pinmap.h"
#include "link_framer.h"

#define TX_RING 64u /* a power of two */

static hal_link_rx_cb_t rx_cb;
static void *rx_arg;
static link_framer_rx_t rx;
static uint8_t tx_ring[TX_RING];
static uint8_t tx_head, tx_count;
static uint16_t tx_dropped;

int hal_link_init(hal_link_rx_cb_t cb, void *arg)
{
    if (cb == NULL)
        return -1;
    hal_irq_state_t s = hal_irq_disable();
    rx_cb = cb;
    rx_arg = arg;
    link_framer_rx_init(&rx);
    UCA1CTL1 = UCSWRST | UCSSEL_2;
    UCA1BR0 = cy_clock->br0;
    UCA1BR1 = cy_clock->br1;
    UCA1MCTL = cy_clock->mctl;
    P3SEL |= 0xC0u; /* P3.6 TXD, P3.7 RXD (hal_cpu_init selected them already) */
    UCA1CTL1 = UCSSEL_2;
    UC1IE |= UCA1RXIE;
    hal_irq_restore(s);
    return 0;
}

int hal_link_send(const hal_link_frame_t *f)
{
    uint8_t bytes[LINK_FRAMER_MAX_BYTES];
    uint8_t n = link_framer_encode(f, bytes);
    if (n == 0)
        return -1;
    hal_irq_state_t s = hal_irq_disable();
    if ((uint8_t)(TX_RING - tx_count) < n) {
        tx_dropped++;
        hal_irq_restore(s);
        return -2;
    }
    for (uint8_t i = 0; i < n; i++)
        tx_ring[(uint8_t)(tx_head + tx_count + i) & (TX_RING - 1u)] = bytes[i];
    tx_count = (uint8_t)(tx_count + n);
    UC1IE |= UCA1TXIE; /* the transmit buffer is empty: the ISR starts at once */
    hal_irq_restore(s);
    return 0;
}

uint8_t hal_link_tx_room(void)
{
    hal_irq_state_t s = hal_irq_disable();
    uint8_t free_bytes = (uint8_t)(TX_RING - tx_count);
    hal_irq_restore(s);
    return (uint8_t)(free_bytes / LINK_FRAMER_MAX_BYTES);
}

uint16_t hal_link_errors(void)
{
    return (uint16_t)(rx.errors + tx_dropped);
}

CY_ISR(HAL_VEC_LINK_TX, hal_isr_link_tx)
{
    if (tx_count == 0) {
        UC1IE &= (uint8_t)~UCA1TXIE;
        return;
    }
    UCA1TXBUF = tx_ring[tx_head];
    tx_head = (uint8_t)((tx_head + 1u) & (TX_RING - 1u));
    tx_count--;
}

CY_ISR(HAL_VEC_LINK_RX, hal_isr_link_rx)
{
    hal_link_frame_t f;
    if (link_framer_rx_byte(&rx, UCA1RXBUF, &f))
        rx_cb(rx_arg, &f);
}
