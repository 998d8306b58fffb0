/*
 * mcp2515_vectors.c - the MCP2515 driver (firmware/can) on both worlds, against the register
 * model (tests/support/mcp2515_model.c) behind hal/spi.h (tests/support/mcp2515_spi.c): the
 * host build and the MSP430 image print the same lines (compared line by line).
 *
 * The INT line is served through the real interrupt path: hal_edge_init(HAL_EDGE_CAN_INT)
 * routes the port-2 interrupt of P2.2 to the driver's handler. On the MSP430 each falling
 * edge of the model's INT is raised by setting P2IFG.2; in the host build the harness raises
 * the same line. (The receive interrupt's cycles are measured through hal/can.h, as the boards
 * run it: tests/target/can_hal_test.c.)
 *
 * Scenario: set-up registers, frames of every length through the filters into both buffers
 * (pseudo-random: xorshift32, fixed seed), rollover and overflow, a run of standard frames of
 * 8 bytes, three pending frames sent in identifier order, transmit errors up to bus-off and
 * the recovery, the loopback self-test.
 */
#include <stdint.h>

#include "can/mcp2515.h"
#include "cy_test.h"
#include "hal/edge.h"
#include "hal/irq.h"
#include "mcp2515_model.h"
#include "mcp2515_spi.h"

#ifdef __MSP430__
#include "f2618.h"
#else
#include "hal_posix/harness.h"
#endif

#define RX_FRAMES 48u
#define RUN_N     16u

static mcp2515_model_t model;
static mcp2515_t drv;
static uint32_t rng = 0x6C8E9CF5u;
static mcp2515_model_tx_t answer = MCP2515_MODEL_TX_ACK;
static uint16_t rx_count;
static uint8_t rx_quiet; /* the measured frames: the callback only sums them */
static uint16_t rx_sum;

static void hex8(uint8_t v)
{
    static const char d[] = "0123456789abcdef";
    char s[3] = {d[v >> 4], d[v & 15u], 0};
    cy_print(s);
}

static void print_frame(const char *tag, uint32_t id, uint8_t ext, uint8_t rtr, uint8_t len,
                        const uint8_t *data)
{
    cy_print(tag);
    cy_print(" ");
    cy_print_hex32(id);
    cy_print(ext ? " x" : " s");
    cy_print(rtr ? "r " : "d ");
    cy_print_dec(len);
    for (uint8_t i = 0; i < len && !rtr && i < 8u; i++) {
        cy_print(" ");
        hex8(data[i]);
    }
    cy_println();
}

static void on_rx(void *arg, const mcp2515_frame_t *f)
{
    (void)arg;
    rx_count++;
    if (rx_quiet) {
        rx_sum = (uint16_t)(rx_sum + f->id + f->len + f->data[0] + f->data[7]);
        return;
    }
    print_frame("rx", f->id, f->ext, f->rtr, f->len, f->data);
}

static mcp2515_model_tx_t on_bus(void *arg, const mcp2515_model_frame_t *f)
{
    (void)arg;
    print_frame("wire", f->id, f->ext, f->rtr, f->dlc, f->data);
    return answer;
}

static void on_int(void *arg)
{
    (void)arg;
    int rc = mcp2515_isr(&drv);
    cy_check(rc >= 0, "mcp2515_isr");
}

/* Serve the INT line while the model holds it low. */
static void serve(void)
{
    for (uint8_t i = 0; i < 8u && mcp2515_model_int(&model) == 0u; i++) {
#ifdef __MSP430__
        P2IFG |= (uint8_t)(1u << 2);
#else
        posix_edge_raise(posix_board_current(), HAL_EDGE_CAN_INT);
        posix_dispatch();
#endif
    }
    cy_check(mcp2515_model_int(&model) == 1u, "INT released");
}

static void print_state(const char *tag)
{
    uint8_t tec, rec;
    mcp2515_error_counters(&drv, &tec, &rec);
    const mcp2515_stats_t *s = mcp2515_stats(&drv);
    cy_print(tag);
    cy_print(" state ");
    cy_print_dec(mcp2515_state(&drv));
    cy_print(" tec ");
    cy_print_dec(tec);
    cy_print(" rec ");
    cy_print_dec(rec);
    cy_print(" rx ");
    cy_print_dec((int32_t)s->rx_frames);
    cy_print(" tx ");
    cy_print_dec((int32_t)s->tx_frames);
    cy_print(" ovr ");
    cy_print_dec(s->rx_overflows);
    cy_print(" txerr ");
    cy_print_dec(s->tx_errors);
    cy_print(" rxerr ");
    cy_print_dec(s->rx_errors);
    cy_print(" passive ");
    cy_print_dec(s->error_passive);
    cy_print(" back ");
    cy_print_dec(s->recoveries);
    cy_print(" abort ");
    cy_print_dec(s->tx_aborted);
    cy_print(" busoff ");
    cy_print_dec(s->bus_offs);
    cy_println();
}

static void print_regs(void)
{
    static const uint8_t addr[] = {0x0E, 0x0F, 0x28, 0x29, 0x2A, 0x2B, 0x2C, 0x2D, 0x00,
                                   0x01, 0x04, 0x08, 0x20, 0x21, 0x24, 0x60, 0x70};
    cy_print("regs");
    for (uint8_t i = 0; i < sizeof addr; i++) {
        cy_print(" ");
        hex8(mcp2515_model_peek(&model, addr[i]));
    }
    cy_println();
}

static void receive_frames(void)
{
    static const uint16_t ids[] = {0x100, 0x101, 0x102, 0x200, 0x2A5, 0x2FF, 0x300, 0x7FF};
    for (uint8_t k = 0; k < RX_FRAMES; k++) {
        mcp2515_model_frame_t f = {0};
        uint32_t r = cy_rand32(&rng);
        f.id = ids[r & 7u];
        f.dlc = (uint8_t)((r >> 3) % 9u);
        f.rtr = (r >> 8) % 11u == 0u;
        for (uint8_t i = 0; i < 8u; i++)
            f.data[i] = (uint8_t)(r >> (i * 3u));
        int where = mcp2515_model_receive(&model, &f);
        cy_print("put ");
        cy_print_dec(where);
        cy_println();
        serve();
    }
    /* Rollover and overflow: three frames while nobody serves INT. */
    for (uint8_t k = 0; k < 3u; k++) {
        mcp2515_model_frame_t f = {0x101, 0, 0, 1, {k}};
        cy_print("put ");
        cy_print_dec(mcp2515_model_receive(&model, &f));
        cy_println();
    }
    serve();
    print_state("after rx");
}

/* A run of standard data frames of 8 bytes into RXB0; the callback only sums what it gets
 * (the sum is printed afterwards). */
static void run_rx(void)
{
    rx_quiet = 1u;
    for (uint8_t k = 0; k < RUN_N; k++) {
        mcp2515_model_frame_t f = {0x100, 0, 0, 8, {0}};
        for (uint8_t i = 0; i < 8u; i++)
            f.data[i] = (uint8_t)(k + i);
        cy_check(mcp2515_model_receive(&model, &f) == MCP2515_MODEL_RX_BUF0, "run frame");
        serve();
    }
    rx_quiet = 0u;
    cy_print("run sum ");
    cy_print_dec(rx_sum);
    cy_println();
}

static void send_frames(void)
{
    static const uint16_t ids[3] = {0x300, 0x050, 0x1FF};
    for (uint8_t k = 0; k < 3u; k++) {
        mcp2515_frame_t f = {ids[k], 0, 0, 2, {k, (uint8_t)(k + 0x10u)}};
        cy_check(mcp2515_send(&drv, &f) == MCP2515_OK, "send");
    }
    mcp2515_frame_t extra = {0x001, 0, 0, 0, {0}};
    cy_check(mcp2515_send(&drv, &extra) == MCP2515_ERR_FULL, "fourth frame: full");
    while (mcp2515_model_bus_tick(&model) >= 0)
        ;
    serve();
    print_state("after tx");
}

static void bus_off_and_recovery(void)
{
    mcp2515_frame_t f = {0x321, 0, 0, 1, {0xAB}};
    cy_check(mcp2515_send(&drv, &f) == MCP2515_OK, "send before errors");
    answer = MCP2515_MODEL_TX_ERROR;
    for (uint8_t i = 1; i <= 32u; i++) {
        mcp2515_model_bus_tick(&model);
        serve();
        if (i == 12u || i == 16u || i == 32u)
            print_state("errors");
    }
    cy_check(mcp2515_send(&drv, &f) == MCP2515_ERR_BUS_OFF, "bus-off refuses");
    mcp2515_model_idle(&model, 128u);
    serve();
    print_state("recovered");
    answer = MCP2515_MODEL_TX_ACK;
    cy_check(mcp2515_send(&drv, &f) == MCP2515_OK, "send after recovery");
    mcp2515_model_bus_tick(&model);
    serve();
    print_state("after recovery");
}

static void loopback(void)
{
    cy_check(mcp2515_set_mode(&drv, MCP2515_MODE_LOOPBACK) == MCP2515_OK, "loopback mode");
    mcp2515_frame_t f = {0x101, 0, 0, 4, {0xDE, 0xAD, 0xBE, 0xEF}};
    uint16_t before = rx_count;
    cy_check(mcp2515_send(&drv, &f) == MCP2515_OK, "loopback send");
    mcp2515_model_bus_tick(&model);
    serve();
    cy_check(rx_count == before + 1u, "loopback frame back");
    cy_check(mcp2515_set_mode(&drv, MCP2515_MODE_NORMAL) == MCP2515_OK, "normal mode");
}

int main(void)
{
    mcp2515_model_init(&model, on_bus, 0);
    mcp2515_spi_attach(&model);
    mcp2515_config_t cfg = {HAL_SPI_BUS_B0,
                            HAL_SPI_CS_CAN,
                            16000000ul,
                            500000ul,
                            MCP2515_MODE_NORMAL,
                            {{0x7FF, 0x700}, {0x100, 0x101, 0x200, 0x200, 0x200, 0x200}, 0},
                            0,
                            0,
                            on_rx,
                            0,
                            0};
    cy_check(mcp2515_init(&drv, &cfg) == MCP2515_OK, "init");
    print_regs();
    cy_check(model.violations == 0u, "no forbidden writes");
    cy_check(hal_edge_init(HAL_EDGE_CAN_INT, HAL_EDGE_FALLING, on_int, 0) == 0, "INT line");
    hal_irq_enable();

    receive_frames();
    run_rx();
    send_frames();
    bus_off_and_recovery();
    loopback();
    print_state("end");
    cy_check(model.violations == 0u, "no forbidden writes");

    cy_test_end();
    return 0;
}
