/*
 * can_mcp2515.c - hal/can.h on the boards: instance 0 is a Microchip MCP2515 with a 16 MHz
 * crystal on USCI_B0 (hal/spi.h, P3.0-P3.3), driven by the portable driver of firmware/can
 * (can/mcp2515.h, docs/can.md). Its /INT is P2.2 (HAL_EDGE_CAN_INT, falling edge): the port-2
 * shim (edge.c) calls can0_on_int(), which runs the driver's handler; when the line is still low
 * after the handler's passes, the shim's flag is set again by software so that the handler
 * comes back after the other pending interrupts (an edge-triggered pin never sees a level).
 *
 * Transmit queue: HAL_CAN_TX_QUEUE frames in all, the ones the MCP2515's three transmit
 * buffers hold and the ones waiting here; the driver keeps the hardware buffers in FIFO order
 * (tx_fifo), and a buffer that becomes free takes the oldest waiting frame (can0_on_tx, in the
 * handler). Bus-off: the driver aborts the buffers, the waiting frames are dropped here; both
 * count as tx_aborted. With manual_recovery the MCP2515 waits in configuration mode until
 * hal_can_recover() (the driver's mcp2515_recover()). Received remote frames (no data frames)
 * are not handed on: hal/can.h carries data frames only; the filters never accept extended
 * frames (standard-only filters, EXIDE = 0).
 */
#include <stddef.h>

#include "can/mcp2515.h"
#include "f2618.h"
#include "hal/can.h"
#include "hal/edge.h"
#include "hal/irq.h"
#include "hal/pinmap.h"

#define CAN0_OSC_HZ 16000000ul /* the MCP2515's crystal (docs/hardware.md) */

static struct {
    mcp2515_t drv;
    hal_can_rx_cb_t rx_cb;
    void *rx_arg;
    /* Frames waiting for a transmit buffer, oldest at head: identifiers, lengths and data in
     * arrays of power-of-two strides (no multiplication in the handler: the main board's
     * handlers must not reach the hardware multiplier, docs/stack.md). */
    uint16_t q_id[HAL_CAN_TX_QUEUE];
    uint8_t q_len[HAL_CAN_TX_QUEUE];
    uint8_t q_data[HAL_CAN_TX_QUEUE][HAL_CAN_MAX_DATA];
    uint8_t head, count;
    uint8_t ready;
    uint32_t rx_frames; /* handed to rx_cb */
    uint16_t dropped;   /* waiting frames dropped at bus-off */
} c0;

static void sat16(uint16_t *c, uint16_t n)
{
    *c = (uint16_t)(*c > 0xFFFFu - n ? 0xFFFFu : *c + n);
}

static void can0_on_rx(void *arg, const mcp2515_frame_t *f)
{
    (void)arg;
    if (f->rtr || f->ext)
        return;
    hal_can_frame_t h;
    h.id = (uint16_t)f->id;
    h.len = f->len;
    for (uint8_t i = 0; i < HAL_CAN_MAX_DATA; i++)
        h.data[i] = f->data[i];
    if (c0.rx_frames != 0xFFFFFFFFul)
        c0.rx_frames++;
    c0.rx_cb(c0.rx_arg, &h);
}

/* Move waiting frames into free transmit buffers, oldest first (interrupts off). */
static void can0_refill(void)
{
    while (c0.count != 0u && mcp2515_tx_free(&c0.drv) != 0u) {
        uint8_t k = c0.head;
        mcp2515_frame_t f = {c0.q_id[k], 0u, 0u, c0.q_len[k], {0}};
        for (uint8_t i = 0; i < f.len; i++)
            f.data[i] = c0.q_data[k][i];
        if (mcp2515_send(&c0.drv, &f) != MCP2515_OK)
            return;
        c0.head = (uint8_t)((c0.head + 1u) % HAL_CAN_TX_QUEUE);
        c0.count--;
    }
}

static void can0_on_tx(void *arg)
{
    (void)arg;
    can0_refill();
}

/* Bus-off empties the transmit queue (hal/can.h). */
static void can0_drop_if_bus_off(void)
{
    if (c0.count != 0u && mcp2515_state(&c0.drv) == MCP2515_BUS_OFF) {
        sat16(&c0.dropped, c0.count);
        c0.count = 0u;
    }
}

static void can0_on_int(void *arg)
{
    (void)arg;
    if (mcp2515_isr(&c0.drv) == 1)
        P2IFG |= (uint8_t)(1u << hal_edge_pin(HAL_EDGE_CAN_INT));
    can0_drop_if_bus_off();
}

static int hal_rc(int rc)
{
    switch (rc) {
    case MCP2515_OK:
        return 0;
    case MCP2515_ERR_FULL:
        return HAL_CAN_E_FULL;
    case MCP2515_ERR_BUS_OFF:
        return HAL_CAN_E_BUS_OFF;
    case MCP2515_ERR_STATE:
        return HAL_CAN_E_STATE;
    case MCP2515_ERR_ARG:
        return HAL_CAN_E_PARAM;
    default:
        return HAL_CAN_E_HARDWARE;
    }
}

int hal_can_init(hal_can_t can, const hal_can_config_t *cfg)
{
    if (can != 0u || cfg == NULL || cfg->rx_cb == NULL || cfg->n_filters > HAL_CAN_FILTERS ||
        cfg->manual_recovery > 1u)
        return HAL_CAN_E_PARAM;
    for (uint8_t i = 0; i < cfg->n_filters; i++)
        if (cfg->filters[i].id > HAL_CAN_MAX_ID || cfg->filters[i].mask > HAL_CAN_MAX_ID)
            return HAL_CAN_E_PARAM;
    mcp2515_cnf_t cnf;
    if (cfg->bitrate_bps < HAL_CAN_BITRATE_MIN || cfg->bitrate_bps > HAL_CAN_BITRATE_MAX ||
        mcp2515_bit_timing(CAN0_OSC_HZ, cfg->bitrate_bps, &cnf) != MCP2515_OK)
        return HAL_CAN_E_BITRATE;
    /* Filter 0 on RXB0 (RXM0, RXF0, RXF1), filter 1 on RXB1 (RXM1, RXF2-RXF5); one filter on
     * both; none: masks 0, every standard frame. */
    mcp2515_config_t mc = {
        HAL_SPI_BUS_B0,      HAL_SPI_CS_CAN,       CAN0_OSC_HZ, cfg->bitrate_bps,
        MCP2515_MODE_NORMAL, {{0u, 0u}, {0u}, 0u}, 1u,          cfg->manual_recovery,
        can0_on_rx,          can0_on_tx,           NULL};
    if (cfg->n_filters > 0u) {
        const hal_can_filter_t *f0 = &cfg->filters[0];
        const hal_can_filter_t *f1 = &cfg->filters[cfg->n_filters - 1u];
        mc.filters.mask[0] = f0->mask;
        mc.filters.mask[1] = f1->mask;
        for (uint8_t i = 0; i < MCP2515_RX_FILTERS; i++)
            mc.filters.filter[i] = i < 2u ? f0->id : f1->id;
    }
    hal_irq_state_t s = hal_irq_disable();
    c0.ready = 0u;
    int rc = mcp2515_init(&c0.drv, &mc);
    if (rc == MCP2515_OK) {
        c0.rx_cb = cfg->rx_cb;
        c0.rx_arg = cfg->rx_arg;
        c0.head = 0u;
        c0.count = 0u;
        c0.rx_frames = 0u;
        c0.dropped = 0u;
        c0.ready = 1u;
        hal_edge_init(HAL_EDGE_CAN_INT, HAL_EDGE_FALLING, can0_on_int, NULL);
        can0_on_int(NULL); /* INT may have fallen before its edge was watched */
    }
    hal_irq_restore(s);
    return hal_rc(rc);
}

int hal_can_send(hal_can_t can, const hal_can_frame_t *f)
{
    if (can != 0u || f == NULL || f->id > HAL_CAN_MAX_ID || f->len > HAL_CAN_MAX_DATA)
        return HAL_CAN_E_PARAM;
    if (!c0.ready)
        return HAL_CAN_E_STATE;
    hal_irq_state_t s = hal_irq_disable();
    int rc = 0;
    uint8_t in_hw = (uint8_t)(MCP2515_TX_BUFS - mcp2515_tx_free(&c0.drv));
    if (mcp2515_state(&c0.drv) == MCP2515_BUS_OFF) {
        rc = hal_rc(mcp2515_poll(&c0.drv)); /* it may have come back by itself */
        if (rc == 0 && mcp2515_state(&c0.drv) == MCP2515_BUS_OFF)
            rc = HAL_CAN_E_BUS_OFF;
        in_hw = 0u;
    }
    if (rc == 0 && (uint8_t)(c0.count + in_hw) >= HAL_CAN_TX_QUEUE)
        rc = HAL_CAN_E_FULL;
    if (rc == 0) {
        uint8_t k = (uint8_t)((c0.head + c0.count) % HAL_CAN_TX_QUEUE);
        c0.q_id[k] = f->id;
        c0.q_len[k] = f->len;
        for (uint8_t i = 0; i < f->len; i++)
            c0.q_data[k][i] = f->data[i];
        c0.count++;
        can0_refill();
    }
    hal_irq_restore(s);
    return rc;
}

uint8_t hal_can_tx_room(hal_can_t can)
{
    if (can != 0u || !c0.ready)
        return 0u;
    hal_irq_state_t s = hal_irq_disable();
    uint8_t used = (uint8_t)(c0.count + MCP2515_TX_BUFS - mcp2515_tx_free(&c0.drv));
    uint8_t room = mcp2515_state(&c0.drv) == MCP2515_BUS_OFF || used >= HAL_CAN_TX_QUEUE
                       ? 0u
                       : (uint8_t)(HAL_CAN_TX_QUEUE - used);
    hal_irq_restore(s);
    return room;
}

int hal_can_status(hal_can_t can, hal_can_status_t *out)
{
    if (can != 0u || out == NULL)
        return HAL_CAN_E_PARAM;
    if (!c0.ready)
        return HAL_CAN_E_STATE;
    hal_irq_state_t s = hal_irq_disable();
    int rc = hal_rc(mcp2515_poll(&c0.drv));
    can0_drop_if_bus_off();
    uint8_t tec, rec;
    mcp2515_error_counters(&c0.drv, &tec, &rec);
    mcp2515_state_t st = mcp2515_state(&c0.drv);
    out->state = (uint8_t)(st == MCP2515_BUS_OFF         ? HAL_CAN_BUS_OFF
                           : st == MCP2515_ERROR_PASSIVE ? HAL_CAN_ERROR_PASSIVE
                                                         : HAL_CAN_ERROR_ACTIVE);
    out->recovering = mcp2515_recovering(&c0.drv);
    out->tec = st == MCP2515_BUS_OFF ? 256u : tec; /* the MCP2515 reads 255 when bus-off */
    out->rec = rec;
    hal_irq_restore(s);
    return rc;
}

int hal_can_stats(hal_can_t can, hal_can_stats_t *out)
{
    if (can != 0u || out == NULL)
        return HAL_CAN_E_PARAM;
    if (!c0.ready)
        return HAL_CAN_E_STATE;
    hal_irq_state_t s = hal_irq_disable();
    const mcp2515_stats_t *d = mcp2515_stats(&c0.drv);
    out->tx_frames = d->tx_frames;
    out->rx_frames = c0.rx_frames;
    out->tx_errors = d->tx_errors;
    out->rx_errors = d->rx_errors;
    out->rx_overruns = d->rx_overflows;
    out->tx_aborted = d->tx_aborted;
    sat16(&out->tx_aborted, c0.dropped);
    out->error_passive = d->error_passive;
    out->bus_off = d->bus_offs;
    out->recoveries = d->recoveries;
    hal_irq_restore(s);
    return 0;
}

void hal_can_wake_on_room(hal_can_t can)
{
    (void)can; /* the main loop polls: hal/can.h */
}

int hal_can_recover(hal_can_t can)
{
    if (can != 0u)
        return HAL_CAN_E_PARAM;
    if (!c0.ready)
        return HAL_CAN_E_STATE;
    hal_irq_state_t s = hal_irq_disable();
    int rc = hal_rc(mcp2515_recover(&c0.drv));
    hal_irq_restore(s);
    return rc;
}
