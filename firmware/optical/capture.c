/*
 * capture.c - goniometer capture (optical/capture.h, SPEC O1).
 *
 * Ownership: *cur belongs to the handlers; the other buffer is either free, ready (a
 * completed revolution waiting for the main loop) or held (the main loop computes on it).
 * Only the index handler swaps the buffers, and never while the other one is held. The
 * main-loop calls change the shared flags inside a critical section; the handlers run with
 * interrupts disabled, so each of them is atomic with respect to the main loop. The handlers
 * are kept to a few instructions (no multiply: a pointer to the buffer being filled).
 */
#include "optical/capture.h"

#include <stddef.h>

#include "hal/capture.h"
#include "hal/irq.h"

enum { MODE_STOPPED = 0, MODE_WAIT_INDEX = 1, MODE_RUNNING = 2 };

void optical_capture_init(optical_capture_t *c)
{
    uint8_t *p = (uint8_t *)c;
    for (size_t i = 0; i < sizeof *c; i++)
        p[i] = 0;
    c->cur = &c->buf[0];
}

static optical_rev_t *other(optical_capture_t *c)
{
    return c->cur == &c->buf[0] ? &c->buf[1] : &c->buf[0];
}

void optical_capture_start(optical_capture_t *c)
{
    hal_critical_enter();
    c->pulse = 0;
    c->seq = 0;
    c->ready = 0;
    c->cur->n = 0;
    c->cur->lost = 0;
    c->cov_seen = hal_capture_overflows(HAL_CAPTURE_BEACON);
    c->mode = MODE_WAIT_INDEX;
    hal_critical_exit();
}

void optical_capture_stop(optical_capture_t *c)
{
    hal_critical_enter();
    c->mode = MODE_STOPPED;
    c->pulse = 0;
    c->ready = 0;
    hal_critical_exit();
}

void optical_capture_on_index(void *arg, uint16_t count, uint8_t rising)
{
    optical_capture_t *c = arg;
    (void)rising;
    uint8_t mode = c->mode;
    if (mode == MODE_STOPPED)
        return;
    optical_rev_t *r = c->cur;
    if (mode == MODE_RUNNING) {
        r->period = (uint16_t)(count - c->index);
        if (c->held) {
            c->dropped++; /* the main loop computes on the other buffer: refill this one */
        } else {
            if (c->ready)
                c->dropped++; /* the older ready revolution is replaced by this newer one */
            c->ready = 1;
            r = r == &c->buf[0] ? &c->buf[1] : &c->buf[0];
            c->cur = r;
        }
    } else {
        c->mode = MODE_RUNNING;
    }
    c->index = count;
    r->index_count = count;
    r->seq = ++c->seq;
    r->n = 0;
    r->lost = 0;
    r->cov = 0;
}

void optical_capture_on_edge(void *arg, uint16_t count, uint8_t rising)
{
    optical_capture_t *c = arg;
    if (rising) {
        if (c->pulse)
            c->cur->cov = 1; /* the pending pulse's falling edge was lost */
        c->rise = count;
        c->pulse = c->mode >> 1; /* 1 only when running */
        return;
    }
    if (!c->pulse)
        return; /* a falling edge without its rising edge (started before we ran) */
    c->pulse = 0;
    optical_rev_t *r = c->cur;
    uint8_t n = r->n;
    if (n < OPTICAL_MAX_SIGHTINGS) {
        optical_raw_sighting_t *s = &r->s[n];
        s->start = (uint16_t)(c->rise - c->index);
        s->width = (uint16_t)(count - c->rise);
        r->n = (uint8_t)(n + 1u);
    } else if (r->lost != 0xFFu) {
        r->lost++;
    }
}

const optical_rev_t *optical_capture_take(optical_capture_t *c)
{
    const optical_rev_t *r = NULL;
    hal_critical_enter();
    if (c->ready && !c->held) {
        c->ready = 0;
        c->held = 1;
        optical_rev_t *w = other(c);
        uint16_t cov = hal_capture_overflows(HAL_CAPTURE_BEACON);
        w->cov |= (uint8_t)(cov != c->cov_seen);
        c->cov_seen = cov;
        r = w;
    }
    hal_critical_exit();
    return r;
}

void optical_capture_release(optical_capture_t *c)
{
    hal_critical_enter();
    c->held = 0;
    hal_critical_exit();
}

uint16_t optical_capture_dropped(const optical_capture_t *c)
{
    return c->dropped;
}
