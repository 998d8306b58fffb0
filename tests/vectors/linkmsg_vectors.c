/*
 * linkmsg_vectors.c - the board link's messages on both worlds: pseudo-random messages of
 * every type encoded into CAN frames (printed in hex) and decoded back (printed field bytes);
 * the MSP430's output must equal the host's. Also the encoder's and the receive path's cycle
 * cost on the target (linkmsg_rx_feed runs in the CAN receive interrupt).
 */
#include <stdint.h>

#include "cy_test.h"
#include "link/linkmsg.h"

static uint32_t rng = 0x9E3779B9u;

static uint32_t rnd(void)
{
    return cy_rand32(&rng);
}

/* Message @p type with pseudo-random fields (set by name: the struct layouts of the two
 * worlds differ, the wire bytes must not). */
static void fill(linkmsg_t *m, uint8_t type)
{
    linkmsg_pose_t p = {(fx_q16_t)rnd(), (fx_q16_t)rnd(), (fx_angle_t)rnd()};
    m->type = type;
    switch (type) {
    case LINKMSG_STOP:
        m->u.stop.reason = (uint8_t)rnd();
        break;
    case LINKMSG_POSE:
        m->u.pose.pose = p;
        m->u.pose.request = (uint8_t)rnd();
        break;
    case LINKMSG_FIX:
        m->u.fix.pose = p;
        m->u.fix.latch = (uint16_t)rnd();
        m->u.fix.flags = (uint8_t)rnd();
        break;
    case LINKMSG_FIX_ACK:
        m->u.fix_ack.status = (int8_t)rnd();
        m->u.fix_ack.latch = (uint16_t)rnd();
        break;
    case LINKMSG_LATCH_REQ:
        m->u.latch_req.first = (uint16_t)rnd();
        m->u.latch_req.count = (uint8_t)rnd();
        break;
    case LINKMSG_LATCH:
        m->u.latch.pose = p;
        m->u.latch.seq = (uint16_t)rnd();
        m->u.latch.status = (int8_t)rnd();
        break;
    case LINKMSG_DIR:
        m->u.dir.reverse = (uint8_t)rnd();
        break;
    case LINKMSG_FIX_QUALITY:
        m->u.fix_quality.latch = (uint16_t)rnd();
        m->u.fix_quality.quality = (uint16_t)rnd();
        m->u.fix_quality.err = (uint16_t)rnd();
        m->u.fix_quality.resid = (uint8_t)rnd();
        m->u.fix_quality.agree = (uint8_t)rnd();
        break;
    default: /* the heartbeats */
        m->u.heartbeat.counter = (uint8_t)rnd();
        m->u.heartbeat.flags = (uint8_t)rnd();
        m->u.heartbeat.tec = (uint8_t)rnd();
        m->u.heartbeat.rec = (uint8_t)rnd();
        break;
    }
}

static void print_frame(const char *what, const hal_can_frame_t *f)
{
    cy_print(what);
    cy_print_hex16(f->id);
    for (uint8_t b = 0; b < f->len; b++) {
        cy_print(" ");
        cy_print_hex16(f->data[b]);
    }
    cy_println();
}

int main(void)
{
    cy_bench_stat_t enc = {"linkmsg_encode", 0, 0, 0}, dec = {"linkmsg_rx_feed", 0, 0, 0};
    cy_bench_init();
    linkmsg_rx_t rx;
    linkmsg_rx_init(&rx);
    uint16_t done = 0, same = 0;
    for (int i = 0; i < 90; i++) {
        linkmsg_t m;
        fill(&m, (uint8_t)(1 + i % (LINKMSG_TYPES - 1)));
        hal_can_frame_t f[2];
        uint8_t n = 0;
        CY_BENCH(&enc, n = linkmsg_encode(&m, f));
        for (uint8_t k = 0; k < n; k++) {
            print_frame("frame ", &f[k]);
            linkmsg_t out;
            bool got = false;
            CY_BENCH(&dec, got = linkmsg_rx_feed(&rx, &f[k], &out));
            if (!got)
                continue;
            done++;
            cy_print("message ");
            cy_print_hex16(out.type);
            cy_print(" from ");
            cy_print_hex16((uint16_t)linkmsg_sender(f[k].id));
            cy_println();
            /* Decoded and encoded again: the same frames. */
            hal_can_frame_t g[2];
            uint8_t n2 = linkmsg_encode(&out, g);
            uint8_t eq = n2 == n;
            for (uint8_t j = 0; j < n2 && eq; j++) {
                eq = g[j].id == f[j].id && g[j].len == f[j].len;
                for (uint8_t b = 0; b < g[j].len && eq; b++)
                    eq = g[j].data[b] == f[j].data[b];
            }
            same += eq;
        }
    }
    cy_check(done == 90, "every message decoded");
    cy_check(same == 90, "every decoded message encodes to its frames");
    cy_check(rx.errors == 0, "no malformed frames");
    cy_bench_report(&enc);
    cy_bench_report(&dec);
    cy_test_end();
    return 0;
}
