/*
 * linkmsg.h - the messages between the main board and the nav board, as hal/link.h frames
 * (CAN 2.0A shaped: 11-bit id, up to 8 bytes; lower ids are more urgent on CAN).
 *
 * A pose does not fit one frame (x, y and heading take 12 bytes): such a message travels as
 * an A frame (x, y) followed by a B frame (heading and the rest) whose `tag` byte is the
 * CRC-8 of the A frame's data, so a B frame never completes with a stale or foreign A frame
 * (frames can be lost; the ones of one sender arrive in order). Multi-byte fields are little
 * endian. Formats: fx/fx.h (Q15.16 metres, binary angles).
 *
 *   id     dir        message            payload
 *   0x010  nav->main  STOP               reason (u8): travelled too far without a fix (G6)
 *   0x020  nav->main  POSE A/B (0x021)   x, y | heading, request number (u8), tag
 *   0x030  main->nav  FIX A/B (0x031)    x, y | heading, latch seq (u16), flags, tag
 *   0x032  nav->main  FIX_ACK            status (i8, gnav_err_t), latch seq (u16)
 *   0x040  main->nav  LATCH_REQ          first latch seq (u16), count (u8)
 *   0x041  nav->main  LATCH A/B (0x042)  x, y | heading, seq (u16), status (i8), tag
 *   0x050  main->nav  DIR                1 = driving backwards
 */
#ifndef LINK_LINKMSG_H
#define LINK_LINKMSG_H

#include <stdbool.h>
#include <stdint.h>

#include "fx/fx.h"
#include "hal/link.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LINKMSG_ID_STOP      0x010u
#define LINKMSG_ID_POSE_A    0x020u
#define LINKMSG_ID_POSE_B    0x021u
#define LINKMSG_ID_FIX_A     0x030u
#define LINKMSG_ID_FIX_B     0x031u
#define LINKMSG_ID_FIX_ACK   0x032u
#define LINKMSG_ID_LATCH_REQ 0x040u
#define LINKMSG_ID_LATCH_A   0x041u
#define LINKMSG_ID_LATCH_B   0x042u
#define LINKMSG_ID_DIR       0x050u

/** FIX flags. */
#define LINKMSG_FIX_HAS_REF 0x01u /**< the fix describes the instant of latch `latch` */

typedef enum {
    LINKMSG_NONE = 0,
    LINKMSG_STOP,
    LINKMSG_POSE,
    LINKMSG_FIX,
    LINKMSG_FIX_ACK,
    LINKMSG_LATCH_REQ,
    LINKMSG_LATCH,
    LINKMSG_DIR,
} linkmsg_type_t;

/** A pose: rear-axle centre (Q15.16 m) and heading (binary angle). */
typedef struct {
    fx_q16_t x, y;
    fx_angle_t heading;
} linkmsg_pose_t;

typedef struct {
    uint8_t type; /**< linkmsg_type_t */
    union {
        struct {
            uint8_t reason;
        } stop;
        struct {
            linkmsg_pose_t pose;
            uint8_t request; /**< number of the coordinate request it answers */
        } pose;
        struct {
            linkmsg_pose_t pose;
            uint16_t latch; /**< reference latch (with LINKMSG_FIX_HAS_REF) */
            uint8_t flags;
        } fix;
        struct {
            int8_t status;
            uint16_t latch;
        } fix_ack;
        struct {
            uint16_t first;
            uint8_t count;
        } latch_req;
        struct {
            linkmsg_pose_t pose;
            uint16_t seq;
            int8_t status; /**< 0, or why the latch could not be read (gnav_err_t) */
        } latch;
        struct {
            uint8_t reverse;
        } dir;
    } u;
} linkmsg_t;

/**
 * Frames of @p m into @p out (room for 2); returns how many (1 or 2), 0 for an unknown type.
 */
uint8_t linkmsg_encode(const linkmsg_t *m, hal_link_frame_t out[2]);

/** Reassembly of A/B frame pairs. */
typedef struct {
    uint8_t have[3]; /* an A frame of POSE, FIX, LATCH is waiting */
    uint8_t a[3][8];
    uint16_t errors; /* frames dropped: bad length, B without its A */
} linkmsg_rx_t;

void linkmsg_rx_init(linkmsg_rx_t *rx);

/**
 * Feed one received frame; true when it completes a message (in @p out). Unknown ids are
 * ignored (other traffic on a shared bus), malformed frames counted in rx->errors.
 */
bool linkmsg_rx_feed(linkmsg_rx_t *rx, const hal_link_frame_t *f, linkmsg_t *out);

/**
 * Send @p m with hal_link_send(): both frames of a pair back to back with interrupts held off,
 * and only when the link has room for all of them (a lone A frame would be wasted). Returns
 * 0, -1 for an unknown message, -2 when the link has no room now (nothing sent: try again).
 */
int linkmsg_send(const linkmsg_t *m);

#ifdef __cplusplus
}
#endif

#endif
