/*
 * link_vectors.c - the link framer on both worlds: the encoded bytes of pseudo-random frames
 * and the frames decoded back from the stream, printed in hex; the MSP430's output must equal
 * the host's. Also the framer's cycle cost on the target.
 */
#include <stdint.h>

#include "cy_test.h"
#include "link_framer.h"

static uint32_t rng = 0x9E3779B9u;

static uint32_t rnd(void)
{
    return cy_rand32(&rng);
}

int main(void)
{
    static uint8_t stream[40 * LINK_FRAMER_MAX_BYTES];
    uint16_t n = 0;
    cy_bench_stat_t enc = {"link_encode", 0, 0, 0}, dec = {"link_rx_byte", 0, 0, 0};
    cy_bench_init();
    for (int i = 0; i < 40; i++) {
        hal_link_frame_t f;
        f.id = (uint16_t)(rnd() & 0x7FFu);
        f.len = (uint8_t)(rnd() % 9u);
        for (uint8_t k = 0; k < f.len; k++)
            f.data[k] = (rnd() & 3u) ? (uint8_t)rnd() : (uint8_t)(0x7Du + (rnd() & 1u));
        uint8_t m = 0;
        CY_BENCH(&enc, m = link_framer_encode(&f, stream + n));
        cy_print("enc");
        for (uint8_t k = 0; k < m; k++) {
            cy_print(" ");
            cy_print_hex16(stream[n + k]);
        }
        cy_println();
        n = (uint16_t)(n + m);
    }
    link_framer_rx_t rx;
    link_framer_rx_init(&rx);
    for (uint16_t i = 0; i < n; i++) {
        hal_link_frame_t f;
        int got = 0;
        CY_BENCH(&dec, got = link_framer_rx_byte(&rx, stream[i], &f));
        if (got) {
            cy_print("dec ");
            cy_print_hex16(f.id);
            for (uint8_t k = 0; k < f.len; k++) {
                cy_print(" ");
                cy_print_hex16(f.data[k]);
            }
            cy_println();
        }
    }
    cy_check(rx.errors == 0, "no framing errors");
    cy_bench_report(&enc);
    cy_bench_report(&dec);
    cy_test_end();
    return 0;
}
