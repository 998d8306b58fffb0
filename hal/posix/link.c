/*
 * link.c - hal/link.h on the harness: an in-process bus. A frame sent by one board reaches
 * every other board that started its link, after the bus latency, as a receive interrupt
 * (vector HAL_VEC_LINK_RX). Each board buffers up to POSIX_LINK_RX_DEPTH frames; one more is
 * an overrun (counted, dropped), as a UART would lose bytes. A loss function may drop frames
 * in transit (a disturbed link).
 */
#include <stddef.h>
#include <string.h>

#include "hal/link.h"
#include "hal/pinmap.h"
#include "hal_posix/harness.h"

#define POSIX_LINK_RX_DEPTH  16
#define POSIX_LINK_IN_FLIGHT 256

typedef struct {
    int started;
    hal_link_rx_cb_t cb;
    void *arg;
    int source;
    hal_link_frame_t fifo[POSIX_LINK_RX_DEPTH];
    uint8_t head, count;
    uint16_t errors;
} port_t;

typedef struct {
    int used;
    int dest;
    hal_link_frame_t frame;
} flight_t;

static port_t ports[POSIX_MAX_BOARDS];
static flight_t flights[POSIX_LINK_IN_FLIGHT];
static uint64_t latency_ns = 200000;
static posix_link_tap_fn tap;
static void *tap_ctx;
static posix_link_loss_fn loss;
static void *loss_ctx;

void posix_link_reset(void)
{
    memset(ports, 0, sizeof ports);
    memset(flights, 0, sizeof flights);
    latency_ns = 200000;
    tap = NULL;
    tap_ctx = NULL;
    loss = NULL;
    loss_ctx = NULL;
}

void posix_link_set_latency(uint64_t ns)
{
    latency_ns = ns;
}

void posix_link_set_tap(posix_link_tap_fn fn, void *ctx)
{
    tap = fn;
    tap_ctx = ctx;
}

void posix_link_set_loss(posix_link_loss_fn fn, void *ctx)
{
    loss = fn;
    loss_ctx = ctx;
}

static void rx_isr(void *ctx)
{
    port_t *p = ctx;
    if (p->count == 0)
        return;
    hal_link_frame_t f = p->fifo[p->head];
    p->head = (uint8_t)((p->head + 1u) % POSIX_LINK_RX_DEPTH);
    p->count--;
    if (p->count)
        posix_source_raise(posix_board_current(), p->source); /* the next one */
    p->cb(p->arg, &f);
}

static void deliver(void *ctx, uint64_t t)
{
    (void)t;
    flight_t *fl = ctx;
    port_t *p = &ports[fl->dest];
    fl->used = 0;
    if (p->count >= POSIX_LINK_RX_DEPTH) {
        p->errors++;
        return;
    }
    p->fifo[(p->head + p->count) % POSIX_LINK_RX_DEPTH] = fl->frame;
    p->count++;
    posix_source_raise(fl->dest, p->source);
}

int hal_link_init(hal_link_rx_cb_t cb, void *arg)
{
    if (cb == NULL)
        return -1;
    int b = posix_board_current();
    port_t *p = &ports[b];
    p->cb = cb;
    p->arg = arg;
    p->source = posix_source_register(b, HAL_VEC_LINK_RX, 0, false, rx_isr, p);
    p->started = p->source >= 0;
    return p->started ? 0 : -1;
}

int hal_link_send(const hal_link_frame_t *f)
{
    if (f->id > HAL_LINK_MAX_ID || f->len > HAL_LINK_MAX_DATA)
        return -1;
    int from = posix_board_current();
    if (tap)
        tap(tap_ctx, from, f);
    if (loss && loss(loss_ctx, from, f))
        return 0;
    for (int b = 0; b < POSIX_MAX_BOARDS; b++) {
        if (b == from || !ports[b].started)
            continue;
        flight_t *fl = NULL;
        for (size_t i = 0; i < POSIX_LINK_IN_FLIGHT && !fl; i++)
            if (!flights[i].used)
                fl = &flights[i];
        if (!fl || !posix_schedule(posix_now_ns() + latency_ns, deliver, fl)) {
            ports[from].errors++;
            return -2;
        }
        fl->used = 1;
        fl->dest = b;
        fl->frame = *f;
    }
    return 0;
}

uint8_t hal_link_tx_room(void)
{
    size_t free_slots = 0;
    for (size_t i = 0; i < POSIX_LINK_IN_FLIGHT; i++)
        free_slots += !flights[i].used;
    /* One frame takes a slot per receiving board (at most POSIX_MAX_BOARDS - 1). */
    free_slots /= POSIX_MAX_BOARDS - 1;
    return (uint8_t)(free_slots > 255 ? 255 : free_slots);
}

uint16_t hal_link_errors(void)
{
    return ports[posix_board_current()].errors;
}
