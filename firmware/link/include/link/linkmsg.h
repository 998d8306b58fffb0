/*
 * linkmsg.h - the messages between the main board and the nav board, as CAN 2.0A frames
 * (hal/can.h: 11-bit id, up to 8 bytes; lower ids win arbitration).
 *
 * The message table - ids, senders, fields and their order, units - has one source,
 * firmware/link/messages.toml, from which the build generates link/linkmsg_ids.h (ids, types,
 * value constants) and linkmsg.c's field table, and tools/gen_link.py the DBC
 * (firmware/link/cyclopion.dbc) that candump and cantools users decode with.
 *
 * A pose does not fit one frame (x, y and heading take 12 bytes): such a message travels as
 * an A frame (x, y) followed by a B frame (heading and the rest) whose last byte `tag` is the
 * CRC-8 (polynomial 0x07, initial 0) of the A frame's data, so that a B frame never completes
 * with a stale or foreign A frame (a frame can be lost; the frames of one sender arrive in
 * order). Multi-byte fields are little endian. Formats: fx/fx.h (Q15.16 metres, binary
 * angles).
 *
 *   id     dir        message              payload
 *   0x010  nav->main  STOP                 reason: 1 blind distance (G6), 2 main board silent
 *   0x020  nav->main  POSE A/B (0x021)     x, y | heading, request number (u8), tag
 *   0x030  main->nav  FIX A/B (0x031)      x, y | heading, latch seq (u16), flags, tag
 *   0x032  nav->main  FIX_ACK              status (i8, gnav_err_t), latch seq (u16)
 *   0x040  main->nav  LATCH_REQ            first latch seq (u16), count (u8)
 *   0x041  nav->main  LATCH A/B (0x042)    x, y | heading, seq (u16), status (i8), tag
 *   0x033  main->nav  FIX_QUALITY          latch (u16), quality (2^-18 m/mrad), err (2^-8 m),
 *                                          resid (2^-14 turn), agree (u8)
 *   0x050  main->nav  DIR                  1 = driving backwards
 *   0x701  main       MAIN_HEARTBEAT       counter, flags, TEC, REC (u8 each)
 *   0x702  nav        NAV_HEARTBEAT        counter, flags, TEC, REC (u8 each)
 */
#ifndef LINK_LINKMSG_H
#define LINK_LINKMSG_H

#include <stdbool.h>
#include <stdint.h>

#include "fx/fx.h"
#include "hal/can.h"
#include "link/linkmsg_ids.h" /* generated from firmware/link/messages.toml */

#ifdef __cplusplus
extern "C" {
#endif

/** FIX flags. */
#define LINKMSG_FIX_HAS_REF 0x01u /**< the fix describes the instant of latch `latch` */

/** Heartbeat flags. */
#define LINKMSG_HB_HEARS_PEER 0x01u /**< the sender hears the other board */
#define LINKMSG_HB_STOPPED    0x02u /**< main: it stopped the travel; nav: it asked for a stop */

/** A pose: rear-axle centre (Q15.16 m) and heading (binary angle). */
typedef struct {
    fx_q16_t x, y;
    fx_angle_t heading;
} linkmsg_pose_t;

typedef struct {
    uint8_t type; /**< linkmsg_type_t */
    union {
        struct {
            uint8_t reason; /**< LINKMSG_STOP_REASON_* */
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
        struct {
            uint16_t latch;   /**< the latch of the FIX it describes */
            uint16_t quality; /**< geometry, 2^-18 m per mrad, saturated */
            uint16_t err;     /**< predicted position error bound, 2^-8 m, saturated */
            uint8_t resid;    /**< largest residual of the agreeing others, 2^-14 turn, sat. */
            uint8_t agree;    /**< beacons that agree: the triplet and the others */
        } fix_quality;
        struct {
            uint8_t counter; /**< rolling, + 1 per heartbeat */
            uint8_t flags;   /**< LINKMSG_HB_* */
            uint8_t tec;     /**< CAN transmit error counter, saturated at 255 */
            uint8_t rec;     /**< CAN receive error counter, saturated at 255 */
        } heartbeat;         /**< LINKMSG_MAIN_HEARTBEAT and LINKMSG_NAV_HEARTBEAT */
    } u;
} linkmsg_t;

/**
 * Frames of @p m into @p out (room for 2); returns how many (1 or 2), 0 for an unknown type.
 */
uint8_t linkmsg_encode(const linkmsg_t *m, hal_can_frame_t out[2]);

/** Reassembly of A/B frame pairs. */
typedef struct {
    uint8_t have[LINKMSG_PAIRS]; /* an A frame of that pair is waiting */
    uint8_t a[LINKMSG_PAIRS][8];
    uint16_t errors; /* frames dropped: bad length, B without its A */
} linkmsg_rx_t;

void linkmsg_rx_init(linkmsg_rx_t *rx);

/**
 * Feed one received frame; true when it completes a message (in @p out). Unknown ids are
 * ignored (other traffic on a shared bus), malformed frames counted in rx->errors.
 */
bool linkmsg_rx_feed(linkmsg_rx_t *rx, const hal_can_frame_t *f, linkmsg_t *out);

/** The node (LINKMSG_NODE_*) that sends frame @p id, or -1 for an id not in the table. */
int8_t linkmsg_sender(uint16_t id);

#ifdef __cplusplus
}
#endif

#endif
