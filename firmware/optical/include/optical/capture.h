/*
 * optical/capture.h - goniometer capture on the main board (SPEC O1).
 *
 * Timer_A counts the goniometer's angle clock (default 50,000 counts per mirror turn,
 * 16-bit, wrapping); the index pulse and both edges of the photodetector pulse are captured
 * by hal/capture.h and handed to the two portable handlers below. Per sighting the handlers
 * store where the pulse starts (counts after the revolution's index pulse) and how long it
 * lasts (counts, the apparent width); its centre is start + width / 2. At most
 * OPTICAL_MAX_SIGHTINGS per revolution: later ones are only counted (never written past).
 *
 * Two revolution buffers: the handlers fill one while the main loop owns the other. A
 * revolution completed while the main loop still holds the previous one is dropped and
 * counted, so a revolution under computation is never overwritten; a completed revolution
 * the main loop has not taken yet is replaced by the newer one (also counted). The first
 * index pulse after optical_capture_start() only starts the first revolution: sightings seen
 * before it belong to a partial turn and are ignored.
 *
 * Handlers: interrupt context, a few dozen instructions, no multiply or divide (131 and 138
 * cycles per interrupt on the MSP430 including the HAL shim). Main-loop calls:
 * optical_capture_start/stop/take/release (short critical sections, hal/irq.h).
 */
#ifndef OPTICAL_CAPTURE_H
#define OPTICAL_CAPTURE_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Sightings stored per revolution (the 1987 board stored fifteen). */
#define OPTICAL_MAX_SIGHTINGS 15

/** One photodetector pulse, in angle-clock counts. */
typedef struct {
    /**
     * Rising edge relative to the revolution's index pulse, modulo 2^16. A pulse that began
     * before the index pulse and ended after it reads as a negative start (2^16 - its lead,
     * beyond the counts of a turn).
     */
    uint16_t start;
    uint16_t width; /**< falling edge - rising edge, counts (1..65535) */
} optical_raw_sighting_t;

/** One mirror revolution as captured: the index pulse that started it and its sightings. */
typedef struct {
    uint16_t seq;         /**< revolution number since optical_capture_start (1, 2, ...) */
    uint16_t index_count; /**< timer count latched at the index pulse that started it */
    uint16_t period;      /**< counts from that index pulse to the next (the turn, mod 2^16) */
    uint8_t n;            /**< sightings stored, 0..OPTICAL_MAX_SIGHTINGS */
    uint8_t lost;         /**< sightings beyond OPTICAL_MAX_SIGHTINGS (saturates at 255) */
    /** 1 when an edge was lost: the timer's COV since the last take, or two rising edges
     *  in a row (the photodetector's signal alternates; the nav board latched both). */
    uint8_t cov;
    optical_raw_sighting_t s[OPTICAL_MAX_SIGHTINGS];
} optical_rev_t;

/** Capture state: handlers and main loop share it (pass its address as the handlers' arg). */
typedef struct {
    optical_rev_t buf[2];
    optical_rev_t *cur;     /**< the revolution the handlers fill (buf[0] or buf[1]) */
    uint16_t index;         /**< count at the current revolution's index pulse */
    uint16_t rise;          /**< count at the pending rising edge */
    uint16_t seq;           /**< revolutions started */
    uint16_t dropped;       /**< completed revolutions never handed out (wraps) */
    uint16_t cov_seen;      /**< hal_capture_overflows() at the last take */
    volatile uint8_t mode;  /**< 0 stopped, 1 waiting for the first index pulse, 2 running */
    volatile uint8_t pulse; /**< 1 between a rising and a falling edge while running */
    volatile uint8_t ready; /**< 1: the other buffer is a completed revolution not yet taken */
    volatile uint8_t held;  /**< 1: the main loop holds the other buffer */
} optical_capture_t;

/** Reset @p c: stopped, no revolution ready, counters zero. Call before registering. */
void optical_capture_init(optical_capture_t *c);

/**
 * (Re)start capturing: the next index pulse starts the first revolution (it completes none).
 * A revolution the main loop holds stays valid until released. Main loop.
 */
void optical_capture_start(optical_capture_t *c);

/** Stop capturing: the handlers ignore every edge until optical_capture_start(). */
void optical_capture_stop(optical_capture_t *c);

/**
 * Index-pulse handler (hal_capture_cb_t for HAL_CAPTURE_INDEX, arg = the capture state).
 * @param count timer count at the index pulse; @param rising ignored (always 1)
 */
void optical_capture_on_index(void *arg, uint16_t count, uint8_t rising);

/**
 * Photodetector handler (hal_capture_cb_t for HAL_CAPTURE_BEACON, arg = the capture state).
 * @param count timer count at the edge; @param rising 1 rising, 0 falling
 */
void optical_capture_on_edge(void *arg, uint16_t count, uint8_t rising);

/**
 * The newest completed revolution, or NULL when none is ready or one is still held. The
 * handlers leave it alone until optical_capture_release(). Main loop.
 */
const optical_rev_t *optical_capture_take(optical_capture_t *c);

/** Give the revolution from optical_capture_take() back. Main loop. */
void optical_capture_release(optical_capture_t *c);

/** Completed revolutions that were never handed out (main loop busy or late), mod 2^16. */
uint16_t optical_capture_dropped(const optical_capture_t *c);

#ifdef __cplusplus
}
#endif

#endif
