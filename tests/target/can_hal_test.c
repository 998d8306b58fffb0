/*
 * can_hal_test.c - hal/can.h on the MSP430 (hal/msp430/can_mcp2515.c over the MCP2515 driver)
 * in mspdebug's simulator, with the MCP2515 register model (tests/support) linked behind
 * hal/spi.h instead of USCI_B0. The INT line goes through the real interrupt path: whenever
 * the model pulls INT low the test sets P2IFG.2 (the falling edge on P2.2) and the port-2
 * shim runs the board's handler.
 *
 * Checked: arguments and bit rates refused, a missing controller (E_HARDWARE), the filters
 * as the MCP2515's masks and filters, frames received through both buffers (remote frames
 * not handed on), the transmit queue of HAL_CAN_TX_QUEUE frames leaving in FIFO order, error
 * counters and bus-off (queue emptied, counted as aborted, sending refused) with automatic
 * and requested recovery. Measured: "@cycles isr_can_rx", the whole receive interrupt of a
 * standard frame of 8 bytes (entry, port-2 shim, driver handler, the board's callback,
 * RETI), and "@cycles isr_can_rx_spi", its part inside hal_spi_transfer() (here the model
 * answering in software; on the board USCI_B0: see docs/can.md).
 */
#include <stdint.h>

#include "cy_test.h"
#include "f2618.h"
#include "hal/can.h"
#include "hal/irq.h"
#include "mcp2515_model.h"
#include "mcp2515_spi.h"

#define BENCH_N 16u

static mcp2515_model_t model;
static hal_can_frame_t got[2];
static uint8_t n_got;
static uint32_t wire_ids[16];
static uint8_t n_wire;
static mcp2515_model_tx_t answer = MCP2515_MODEL_TX_ACK;

static cy_bench_stat_t st_rx = {"isr_can_rx", 0, 0, 0};
static cy_bench_stat_t st_rx_spi = {"isr_can_rx_spi", 0, 0, 0};
static cy_stack_stat_t sk_rx = {"isr_can_rx", 0};

static void on_rx(void *arg, const hal_can_frame_t *f)
{
    (void)arg;
    if (n_got == 0u)
        got[0] = *f;
    else if (n_got == 1u)
        got[1] = *f; /* constant indices: no multiplication in the handler */
    n_got++;
}

static mcp2515_model_tx_t on_bus(void *arg, const mcp2515_model_frame_t *f)
{
    (void)arg;
    if (n_wire < 16u)
        wire_ids[n_wire] = f->id;
    n_wire++;
    return answer;
}

/* While the model holds INT low: the falling edge on P2.2 (P2IFG.2), taken at once. Returns
 * the cycles of the first interrupt. */
static uint16_t serve(void)
{
    uint16_t first = 0;
    for (uint8_t i = 0; i < 8u && mcp2515_model_int(&model) == 0u; i++) {
        cy_dint();
        P2IFG |= 0x04u;
        uint16_t t0 = cy_bench_now();
        cy_eint();
        uint16_t t1 = cy_bench_now();
        if (i == 0u)
            first = (uint16_t)(t1 - t0 - cy_bench_overhead);
    }
    cy_check(mcp2515_model_int(&model) == 1u, "INT released");
    return first;
}

static hal_can_config_t config(void)
{
    hal_can_config_t c = {500000ul, {{0x100, 0x7FE}, {0x200, 0x700}}, 2u, 0u, on_rx, 0};
    return c;
}

static void put(uint16_t id, uint8_t len, uint8_t rtr)
{
    mcp2515_model_frame_t f = {id, 0u, rtr, len, {1, 2, 3, 4, 5, 6, 7, 8}};
    mcp2515_model_receive(&model, &f);
    serve();
}

static void check_arguments(void)
{
    hal_can_config_t c = config();
    hal_can_frame_t f = {0x10, 0, {0}};
    cy_check(hal_can_send(0, &f) == HAL_CAN_E_STATE, "send before init");
    cy_check(hal_can_init(1, &c) == HAL_CAN_E_PARAM, "instance 1");
    cy_check(hal_can_init(0, 0) == HAL_CAN_E_PARAM, "cfg NULL");
    c.rx_cb = 0;
    cy_check(hal_can_init(0, &c) == HAL_CAN_E_PARAM, "rx_cb NULL");
    c = config();
    c.n_filters = 3u;
    cy_check(hal_can_init(0, &c) == HAL_CAN_E_PARAM, "three filters");
    c = config();
    c.filters[1].mask = 0x800u;
    cy_check(hal_can_init(0, &c) == HAL_CAN_E_PARAM, "mask out of range");
    c = config();
    c.bitrate_bps = 400000ul;
    cy_check(hal_can_init(0, &c) == HAL_CAN_E_BITRATE, "400 kbit/s");
    c.bitrate_bps = 2000000ul;
    cy_check(hal_can_init(0, &c) == HAL_CAN_E_BITRATE, "2 Mbit/s");
    cy_check(mcp2515_spi_stats()->frames == 0u, "nothing on SPI for refused arguments");
    mcp2515_spi_attach(0); /* no controller: SO reads 0xFF */
    c = config();
    cy_check(hal_can_init(0, &c) == HAL_CAN_E_HARDWARE, "no controller");
    mcp2515_spi_attach(&model);
}

static void check_setup(void)
{
    hal_can_config_t c = config();
    cy_check(hal_can_init(0, &c) == 0, "init");
    cy_check(model.violations == 0u, "no forbidden writes");
    cy_check((mcp2515_model_peek(&model, 0x0E) & 0xE0u) == 0x00u, "normal mode");
    /* 500 kbit/s from 16 MHz: Fosc / (2 (BRP + 1) (1 + PropSeg + PS1 + PS2)) (DS20001801 5). */
    uint8_t c1 = mcp2515_model_peek(&model, 0x2A), c2 = mcp2515_model_peek(&model, 0x29),
            c3 = mcp2515_model_peek(&model, 0x28);
    uint32_t n = 1u + (c2 & 7u) + 1u + ((c2 >> 3) & 7u) + 1u + (c3 & 7u) + 1u;
    cy_check(16000000ul / (2u * ((c1 & 0x3Fu) + 1u) * n) == 500000ul, "bit rate");
    /* Filter 0 = RXM0 with RXF0, RXF1; filter 1 = RXM1 with RXF2..RXF5 (SIDH = id >> 3). */
    cy_check(mcp2515_model_peek(&model, 0x20) == (0x7FEu >> 3), "RXM0");
    cy_check(mcp2515_model_peek(&model, 0x00) == (0x100u >> 3), "RXF0");
    cy_check(mcp2515_model_peek(&model, 0x04) == (0x100u >> 3), "RXF1");
    cy_check(mcp2515_model_peek(&model, 0x24) == (0x700u >> 3), "RXM1");
    cy_check(mcp2515_model_peek(&model, 0x18) == (0x200u >> 3), "RXF5");
    cy_check(hal_can_tx_room(0) == HAL_CAN_TX_QUEUE, "room");
}

static void check_receive(void)
{
    n_got = 0u;
    put(0x101, 3, 0); /* filter 0 (0x100/0x7FE) */
    put(0x102, 3, 0); /* neither */
    put(0x2F0, 8, 0); /* filter 1 (0x200/0x700) */
    put(0x100, 2, 1); /* a remote frame: not handed on */
    cy_check(n_got == 2u, "two data frames");
    cy_check(got[0].id == 0x101u && got[0].len == 3u && got[0].data[2] == 3u, "first frame");
    cy_check(got[1].id == 0x2F0u && got[1].len == 8u && got[1].data[7] == 8u, "second frame");
    hal_can_stats_t s;
    cy_check(hal_can_stats(0, &s) == 0 && s.rx_frames == 2u, "rx_frames");
}

static void bench_receive(void)
{
    for (uint8_t k = 0; k < BENCH_N; k++) {
        mcp2515_model_frame_t f = {0x100, 0u, 0u, 8u, {k, 1, 2, 3, 4, 5, 6, 7}};
        cy_check(mcp2515_model_receive(&model, &f) == MCP2515_MODEL_RX_BUF0, "bench frame");
        uint32_t spi0 = mcp2515_spi_stats()->cycles;
        uint16_t c = 0;
        CY_STACK(&sk_rx, c = serve());
        cy_bench_add(&st_rx, c);
        cy_bench_add(&st_rx_spi, mcp2515_spi_stats()->cycles - spi0);
    }
}

static void check_send(void)
{
    n_wire = 0u;
    for (uint8_t k = 0; k < HAL_CAN_TX_QUEUE; k++) {
        hal_can_frame_t f = {(uint16_t)(0x300u - 0x20u * k), 1, {k}};
        cy_check(hal_can_send(0, &f) == 0, "queued");
    }
    hal_can_frame_t extra = {0x001, 0, {0}};
    cy_check(hal_can_send(0, &extra) == HAL_CAN_E_FULL, "queue full");
    cy_check(hal_can_tx_room(0) == 0u, "no room");
    hal_can_frame_t bad = {0x800, 0, {0}};
    cy_check(hal_can_send(0, &bad) == HAL_CAN_E_PARAM, "id 0x800");
    bad.id = 1;
    bad.len = 9;
    cy_check(hal_can_send(0, &bad) == HAL_CAN_E_PARAM, "len 9");
    while (mcp2515_model_bus_tick(&model) >= 0)
        serve(); /* each sent frame frees a buffer: the handler loads the next one */
    cy_check(n_wire == HAL_CAN_TX_QUEUE, "all sent");
    uint8_t fifo = 1u;
    for (uint8_t k = 0; k < HAL_CAN_TX_QUEUE; k++)
        fifo &= (uint8_t)(wire_ids[k] == 0x300u - 0x20u * k);
    cy_check(fifo, "FIFO order, although the identifiers fall");
    cy_check(hal_can_tx_room(0) == HAL_CAN_TX_QUEUE, "room again");
    hal_can_stats_t s;
    cy_check(hal_can_stats(0, &s) == 0 && s.tx_frames == HAL_CAN_TX_QUEUE, "tx_frames");
}

static void to_bus_off(void)
{
    for (uint8_t k = 0; k < 5u; k++) {
        hal_can_frame_t f = {(uint16_t)(0x400u + k), 0, {0}};
        cy_check(hal_can_send(0, &f) == 0, "queued before errors");
    }
    answer = MCP2515_MODEL_TX_ERROR;
    for (uint8_t i = 0; i < 32u; i++) {
        mcp2515_model_bus_tick(&model);
        serve();
    }
    answer = MCP2515_MODEL_TX_ACK;
}

static void check_bus_off(void)
{
    hal_can_status_t st;
    to_bus_off();
    cy_check(hal_can_status(0, &st) == 0, "status");
    cy_check(st.state == HAL_CAN_BUS_OFF && st.tec == 256u && st.recovering == 1u, "bus-off");
    hal_can_stats_t s;
    hal_can_stats(0, &s);
    cy_check(s.tx_aborted == 5u, "3 in the buffers and 2 waiting aborted");
    cy_check(s.bus_off == 1u && s.error_passive == 1u && s.tx_errors == 32u, "counted");
    hal_can_frame_t f = {0x10, 0, {0}};
    cy_check(hal_can_send(0, &f) == HAL_CAN_E_BUS_OFF, "refused while bus-off");
    cy_check(hal_can_tx_room(0) == 0u, "no room while bus-off");
    mcp2515_model_idle(&model, 128u);
    serve();
    cy_check(hal_can_status(0, &st) == 0 && st.state == HAL_CAN_ERROR_ACTIVE && st.tec == 0u,
             "back by itself");
    hal_can_stats(0, &s);
    cy_check(s.recoveries == 1u, "recoveries");
    cy_check(hal_can_recover(0) == HAL_CAN_E_STATE, "recover: not bus-off");
    cy_check(hal_can_send(0, &f) == 0, "sending again");
    mcp2515_model_bus_tick(&model);
    serve();

    hal_can_config_t c = config();
    c.manual_recovery = 1u;
    cy_check(hal_can_init(0, &c) == 0, "init, manual recovery");
    hal_can_stats(0, &s);
    cy_check(s.tx_frames == 0u && s.bus_off == 0u, "statistics restart");
    to_bus_off();
    mcp2515_model_idle(&model, 200u);
    cy_check(hal_can_status(0, &st) == 0 && st.state == HAL_CAN_BUS_OFF && st.recovering == 0u,
             "waits for the request");
    cy_check(hal_can_recover(0) == 0, "recover");
    cy_check(hal_can_status(0, &st) == 0 && st.recovering == 1u, "recovering");
    mcp2515_model_idle(&model, 128u);
    serve();
    cy_check(hal_can_status(0, &st) == 0 && st.state == HAL_CAN_ERROR_ACTIVE, "back");
}

int main(void)
{
    cy_bench_init();
    mcp2515_model_init(&model, on_bus, 0);
    mcp2515_spi_attach(&model);
    hal_irq_enable();
    check_arguments();
    check_setup();
    check_receive();
    bench_receive();
    check_send();
    check_bus_off();
    cy_check(model.violations == 0u, "no forbidden writes at the end");
    cy_bench_report(&st_rx);
    cy_bench_report(&st_rx_spi);
    cy_stack_report(&sk_rx);
    cy_test_end();
    return 0;
}
