/*
 * hal/link.h - frames between the two boards (the original boards' "request for position"
 * and "position response" lines, and the nav board's latches).
 *
 * Frames are CAN 2.0A shaped (11-bit identifier, 0..8 data bytes) so that the same messages
 * can travel over CAN later. Within one sender, frames arrive in the order sent.
 *  - MSP430: USCI_A1 as a UART (P3.6 TXD, P3.7 RXD; 115200 8N1 from SMCLK = 16 MHz); frames
 *    travel as HDLC-like byte streams (hal/common/link_framer.h: flag 0x7E, byte stuffing,
 *    CRC-8); the receive interrupt (vector 4) decodes and calls the handler per good frame.
 *  - POSIX: the harness's in-process bus: a frame reaches every other board on the bus after a
 *    latency, as a receive interrupt on vector 4 (posix_link_*, hal_posix/harness.h).
 */
#ifndef HAL_LINK_H
#define HAL_LINK_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define HAL_LINK_MAX_DATA 8
#define HAL_LINK_MAX_ID   0x7FFu

typedef struct {
    uint16_t id; /**< 0..0x7FF; lower is more urgent on CAN */
    uint8_t len; /**< 0..8 */
    uint8_t data[HAL_LINK_MAX_DATA];
} hal_link_frame_t;

/** Receive handler: interrupt context, one call per good frame; @p f valid during the call. */
typedef void (*hal_link_rx_cb_t)(void *arg, const hal_link_frame_t *f);

/** Start the link and route received frames to @p cb. Returns 0, or -1 when cb is NULL. */
int hal_link_init(hal_link_rx_cb_t cb, void *arg);

/**
 * Queue @p f for sending. Returns 0, -1 when the frame is malformed (id or len out of range)
 * or -2 when the transmit queue is full (nothing queued).
 */
int hal_link_send(const hal_link_frame_t *f);

/**
 * Frames that hal_link_send() can take right now whatever their contents (worst-case size).
 * A sender of several frames that belong together checks this first.
 */
uint8_t hal_link_tx_room(void);

/** Frames lost so far: received with a bad CRC or length, or dropped on a full queue. */
uint16_t hal_link_errors(void);

#ifdef __cplusplus
}
#endif

#endif
