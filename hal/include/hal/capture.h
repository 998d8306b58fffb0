/*
 * hal/capture.h - goniometer capture (main board).
 *
 * MSP430: Timer_A counts the goniometer's angle clock on TACLK (P1.0; 50,000 counts per
 * mirror turn by default, so one 16-bit count is an angle). The index pulse (P1.1 = CCI0A)
 * is captured by CCR0 on its rising edge; the photodetector (P1.2 = CCI1A) by CCR1 on both
 * edges. Each capture calls the registered portable handler with the captured count, so the
 * handler never reads the timer itself. POSIX: the harness raises the same two vectors with
 * the counts its goniometer model computes.
 */
#ifndef HAL_CAPTURE_H
#define HAL_CAPTURE_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Capture channels. */
typedef enum {
    HAL_CAPTURE_INDEX = 0,  /**< index pulse, rising edge, vector TIMERA0 (7) */
    HAL_CAPTURE_BEACON = 1, /**< photodetector, both edges, vector TIMERA1 (6) */
    HAL_CAPTURE_COUNT
} hal_capture_channel_t;

/**
 * Portable capture handler, interrupt context.
 * @param count  timer count latched at the edge, 0..65535 (wraps)
 * @param rising 1 for a rising edge, 0 for a falling one (always 1 on HAL_CAPTURE_INDEX)
 */
typedef void (*hal_capture_cb_t)(void *arg, uint16_t count, uint8_t rising);

/** Register @p cb on @p ch and enable it. Returns 0, or -1 on a bad channel or NULL cb. */
int hal_capture_init(hal_capture_channel_t ch, hal_capture_cb_t cb, void *arg);

/** Mask (0) or unmask (non-zero) a capture channel. */
void hal_capture_enable(hal_capture_channel_t ch, uint8_t enable);

/** Captures lost because the previous one was not yet handled (the timer's COV flag). */
uint16_t hal_capture_overflows(hal_capture_channel_t ch);

#ifdef __cplusplus
}
#endif

#endif
