/*
 * posrx.h - seed 002's serial position receiver (SPEC P3; docs/posrx.md): the laser
 * positioning system sends the receiver's position as 14-byte packets,
 *     0x00, x (4 bytes), y (4 bytes), z (4 bytes), 0xFF
 * each coordinate a signed 32-bit big-endian number of millimetres (seed 002, its INT.C
 * ser_int and SPSI.C Update_Pos), 8N1 at 9600 baud.
 *
 * Two halves:
 *  - posrx_rx_byte(), interrupt context (the UART's receive handler): bytes go into a
 *    32-byte ring; a packet is framed when the last 14 bytes, all received since the previous
 *    packet and without a receive error, start with 0x00 and end with 0xFF (the seed's test).
 *    Bytes skipped before a packet (garbage, a torn packet) count as one resync. The framed
 *    packet's 12 coordinate bytes and its time wait in a queue of POSRX_QUEUE for the main loop;
 *    a full queue drops the oldest (counted). No multiplication, no division.
 *  - posrx_take() and posrx_check(), main loop: the oldest packet, decoded; then judged
 *    against the last accepted position (the reference): an all-zero packet is refused
 *    (POSRX_ZERO: the seed's system sent zeros when it had no position), a position the
 *    vehicle cannot have reached at max_speed in the time since the reference is a jump
 *    (POSRX_JUMP: the seed's future work "filtering of invalid data"), one closer than the
 *    minimum update distance to the reference is too close (POSRX_TOO_CLOSE: the seed's 5 cm
 *    rule, which keeps the heading from two positions meaningful). Only an accepted position
 *    (POSRX_OK) becomes the next reference. Without a reference the first non-zero position
 *    is accepted, as the seed took its start position.
 * Units: millimetres and milliseconds (the packet's own), no floating point, no heap.
 */
#ifndef POSRX_POSRX_H
#define POSRX_POSRX_H

#include <stdbool.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define POSRX_PACKET_BYTES 14u
#define POSRX_START_BYTE   0x00u
#define POSRX_END_BYTE     0xFFu
/** The byte ring (the seed's BLENGTH): a power of two, at least a packet. */
#define POSRX_RING         32u
/** Framed packets that wait for the main loop. */
#define POSRX_QUEUE        4u
/** Largest |x|, |y| a reference can have (the firmware's Q16 metres: +-32,768 m); a packet
 * beyond 2^25 mm (33.5 km) is a jump from any reference. */
#define POSRX_RANGE_MM     33554432l
/** Longest time since the reference that widens the jump allowance (10 minutes). */
#define POSRX_MAX_DT_MS    600000ul

/** What posrx_check() decided. */
typedef enum {
    POSRX_OK = 0,    /**< accepted: the new reference                                     */
    POSRX_ZERO,      /**< all-zero packet                                                 */
    POSRX_JUMP,      /**< farther from the reference than max_speed allows in the time     */
    POSRX_TOO_CLOSE, /**< plausible, but nearer the reference than the minimum update distance */
    POSRX_REASON_COUNT
} posrx_reason_t;

/** Acceptance rules. */
typedef struct {
    uint16_t min_update_mm;  /**< 0..65535 mm (seed 002: 50) */
    uint16_t max_speed_mm_s; /**< 1..65535 mm/s: the fastest the vehicle moves */
} posrx_config_t;

/** A decoded packet. */
typedef struct {
    int32_t x, y, z; /**< mm, as sent */
    uint32_t t_ms;   /**< the time its last byte arrived (the caller's millisecond clock) */
} posrx_pos_t;

/** Counters (posrx_stats()). */
typedef struct {
    uint32_t bytes;                      /**< bytes received */
    uint32_t framed;                     /**< packets framed */
    uint32_t resyncs;                    /**< runs of bytes skipped before a packet */
    uint32_t skipped;                    /**< bytes skipped in them */
    uint32_t error_bytes;                /**< bytes received with HAL_UART_RX_ERROR */
    uint32_t dropped;                    /**< framed packets lost to a full queue */
    uint32_t reason[POSRX_REASON_COUNT]; /**< packets judged, by outcome */
} posrx_stats_t;

/** A queued packet: its coordinate bytes, as received, and its time. */
typedef struct {
    uint8_t raw[12];
    uint32_t t_ms;
} posrx_raw_t;

/** The receiver (one per serial line). */
typedef struct {
    /* interrupt side */
    uint8_t ring[POSRX_RING];
    uint8_t w;      /* next ring index (mod POSRX_RING) */
    uint8_t run;    /* bytes since the last packet or error byte (saturates at 255) */
    uint16_t since; /* bytes since the last packet (saturates at 65535) */
    posrx_raw_t q[POSRX_QUEUE];
    uint8_t q_head, q_n;
    /* main-loop side */
    posrx_config_t cfg;
    posrx_pos_t ref;
    bool has_ref;
    posrx_stats_t st;
} posrx_t;

/**
 * Set @p r up with @p cfg: empty ring and queue, no reference, counters zero. Returns false
 * (and leaves @p r untouched) when cfg->max_speed_mm_s is 0.
 */
bool posrx_init(posrx_t *r, const posrx_config_t *cfg);

/** Make (x_mm, y_mm) at @p t_ms the reference (the vehicle's known start). Main loop. */
void posrx_set_reference(posrx_t *r, int32_t x_mm, int32_t y_mm, uint32_t t_ms);

/**
 * The UART's receive handler (interrupt context; also callable with interrupts disabled):
 * one received @p byte with its @p flags (hal/uart.h: HAL_UART_RX_ERROR marks a byte that
 * cannot belong to a packet) at @p now_ms.
 */
void posrx_rx_byte(posrx_t *r, uint8_t byte, uint8_t flags, uint32_t now_ms);

/** The oldest framed packet, decoded, into @p out; false when none waits. Main loop. */
bool posrx_take(posrx_t *r, posrx_pos_t *out);

/**
 * Judge @p p (posrx_take()'s) against the reference and count the outcome; on POSRX_OK @p p
 * becomes the reference. @p dist_mm (may be NULL) receives the distance from the reference
 * in millimetres (0 without one, or for POSRX_ZERO; saturates at UINT32_MAX).
 */
posrx_reason_t posrx_check(posrx_t *r, const posrx_pos_t *p, uint32_t *dist_mm);

/** Short name of @p reason: "ok", "zero", "jump", "too_close" ("?" out of range). */
const char *posrx_reason_name(posrx_reason_t reason);

/** A consistent copy of the counters (main loop). */
void posrx_stats(const posrx_t *r, posrx_stats_t *out);

#ifdef __cplusplus
}
#endif

#endif
