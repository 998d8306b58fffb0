/*
 * posrx_vectors.c - the serial position receiver on both worlds: a drive's packets (seed
 * 002's format) with garbage, torn packets, zeros, wild positions and repeats between them go
 * byte by byte through the receive handler the main board registers with hal_uart_open(); the
 * decoded positions, their verdicts and the counters are printed, and the MSP430's output must
 * equal the host's. The handler's cycles go to the cycle report as isr_posrx_byte: the body of
 * the receive interrupt; the whole interrupt with the USCI_A1 shim around it
 * (hal/msp430/uart_usci_a1.c: entry, two register reads, the call, RETI) has its static bound
 * in the same entry, from the main board's pursuit image (docs/posrx.md).
 */
#include <stdint.h>

#include "cy_test.h"
#include "hal/uart.h"
#include "posrx/posrx.h"

static uint32_t rng = 0x2545F491u;
static uint32_t now_ms;
static posrx_t rx;
static cy_bench_stat_t st_byte = {"isr_posrx_byte", 0, 0, 0};

static uint32_t rnd(void)
{
    return cy_rand32(&rng);
}

/* The handler as the main board registers it with hal_uart_open() (main_pursuit.c): the byte
 * and the time it arrived (there the millisecond clock, here the drive's own clock). */
static void on_rx(void *arg, uint8_t byte, uint8_t flags)
{
    posrx_rx_byte(arg, byte, flags, now_ms);
}

static void send(uint8_t b, uint8_t flags)
{
    CY_BENCH(&st_byte, on_rx(&rx, b, flags));
    posrx_pos_t p;
    while (posrx_take(&rx, &p)) {
        uint32_t d = 0;
        posrx_reason_t why = posrx_check(&rx, &p, &d);
        cy_print("pos ");
        cy_print_dec(p.x);
        cy_print(" ");
        cy_print_dec(p.y);
        cy_print(" ");
        cy_print_dec(p.z);
        cy_print(" t ");
        cy_print_dec((int32_t)p.t_ms);
        cy_print(" d ");
        cy_print_hex32(d);
        cy_print(" ");
        cy_print(posrx_reason_name(why));
        cy_println();
    }
}

static void send_packet(int32_t x, int32_t y, int32_t z, uint8_t len)
{
    int32_t v[3] = {x, y, z};
    uint8_t b[POSRX_PACKET_BYTES];
    b[0] = POSRX_START_BYTE;
    for (uint8_t i = 0; i < 3u; i++)
        for (uint8_t k = 0; k < 4u; k++)
            b[1u + 4u * i + k] = (uint8_t)((uint32_t)v[i] >> (24u - 8u * k));
    b[13] = POSRX_END_BYTE;
    for (uint8_t i = 0; i < len; i++)
        send(b[i], 0);
}

int main(void)
{
    cy_bench_init();
    const posrx_config_t cfg = {50u, 2000u}; /* seed 002: 5 cm; 2 m/s */
    cy_check(posrx_init(&rx, &cfg), "receiver set up");
    posrx_set_reference(&rx, 2500, 2000, 0);
    int32_t y = 2000;
    for (uint16_t k = 0; k < 400u; k++) {
        now_ms += 100u; /* 10 updates a second at 1 m/s */
        uint32_t kind = rnd() % 20u;
        if (kind == 0) {
            for (uint32_t n = 1u + rnd() % 30u; n; n--) {
                uint8_t b = (uint8_t)rnd(); /* one draw after the other */
                send(b, (rnd() % 8u) == 0 ? HAL_UART_RX_ERROR : 0u);
            }
        } else if (kind == 1) {
            send_packet(2500, y, 1200, (uint8_t)(1u + rnd() % 12u)); /* torn */
        }
        if (kind == 2)
            send_packet(0, 0, 0, POSRX_PACKET_BYTES);
        else if (kind == 3)
            send_packet((int32_t)(2500 + 600 + rnd() % 3000u), y, 1200, POSRX_PACKET_BYTES);
        else if (kind == 4) {
            int32_t x = (int32_t)rnd(), yy = (int32_t)rnd(), z = (int32_t)rnd(); /* in order */
            send_packet(x, yy, z, POSRX_PACKET_BYTES);
        } else if (k % 50u < 5u)
            send_packet(2500, y, 1200, POSRX_PACKET_BYTES); /* standing */
        else {
            y += 100;
            send_packet((int32_t)(2500 + (int32_t)(rnd() % 7u) - 3), y, 1200, POSRX_PACKET_BYTES);
        }
    }
    posrx_stats_t s;
    posrx_stats(&rx, &s);
    const uint32_t n[] = {s.bytes,
                          s.framed,
                          s.resyncs,
                          s.skipped,
                          s.error_bytes,
                          s.dropped,
                          s.reason[POSRX_OK],
                          s.reason[POSRX_ZERO],
                          s.reason[POSRX_JUMP],
                          s.reason[POSRX_TOO_CLOSE]};
    cy_print("stats");
    for (uint8_t i = 0; i < sizeof n / sizeof n[0]; i++) {
        cy_print(" ");
        cy_print_dec((int32_t)n[i]);
    }
    cy_println();
    cy_check(s.reason[POSRX_OK] > 300u && s.reason[POSRX_ZERO] > 5u && s.reason[POSRX_JUMP] > 5u &&
                 s.reason[POSRX_TOO_CLOSE] > 5u && s.resyncs > 5u,
             "every outcome seen");
    cy_bench_report(&st_byte);
    cy_test_end();
    return 0;
}
