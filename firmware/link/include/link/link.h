/*
 * link.h - the board link on CAN: the messages of link/linkmsg.h as CAN 2.0A frames on
 * hal/can.h instance LINK_CAN, a heartbeat with a rolling counter, and a watch on the other
 * board (docs/integration.md, "The board link").
 *
 * Each board owns one link_t (the harness runs both boards in one process, so nothing here is
 * static). Every heartbeat_ms the board sends its heartbeat (MAIN_HEARTBEAT or NAV_HEARTBEAT:
 * counter + 1, flags, its TEC and REC); any frame from the other board (by the table's
 * senders) shows it alive. When nothing came from it for silence_ms, link_poll() says
 * LINK_EV_SILENT once; the board decides what that means (the main board stops the drive, the
 * nav board asks for a stop). Bus-off: the controller recovers by itself (hal/can.h, 128 x 11
 * recessive bits); the link counts the bus-off events and recoveries.
 *
 * Contexts: link_init() and link_poll() in the main loop; link_send() in the main loop (it
 * holds interrupts off while it queues the frames of one message); the message handler is
 * called in the CAN receive interrupt.
 */
#ifndef LINK_LINK_H
#define LINK_LINK_H

#include <stdbool.h>
#include <stdint.h>

#include "hal/can.h"
#include "link/linkmsg.h"

#ifdef __cplusplus
extern "C" {
#endif

/** The CAN instance the board link uses. */
#define LINK_CAN 0u

/** Configuration ranges. */
#define LINK_HEARTBEAT_MS_MIN 1u
#define LINK_HEARTBEAT_MS_MAX 10000u
#define LINK_SILENCE_MS_MAX   60000u

/** Return codes of link_init() (besides hal/can.h's) and link_send(). */
#define LINK_E_CONFIG  (-10) /**< link_init: node, heartbeat or silence out of range */
#define LINK_E_MESSAGE (-11) /**< link_send: unknown message type */
#define LINK_E_FULL    (-12) /**< link_send: no room for all its frames now (nothing sent) */
#define LINK_E_BUS_OFF (-13) /**< link_send: the controller is bus-off (nothing sent) */
#define LINK_E_DOWN    (-14) /**< link_send: the link never came up (link_init failed) */

typedef struct {
    uint8_t node;          /**< this board: LINKMSG_NODE_MAIN or LINKMSG_NODE_NAV */
    uint32_t bitrate_bps;  /**< the bus's bit rate (hal/can.h) */
    uint16_t heartbeat_ms; /**< own heartbeat period, LINK_HEARTBEAT_MS_MIN..MAX */
    uint16_t silence_ms;   /**< the other board is silent after this long without a frame
                                from it: more than heartbeat_ms, at most LINK_SILENCE_MS_MAX */
} link_config_t;

/** Message handler: interrupt context; @p m valid during the call. Heartbeats stay inside. */
typedef void (*link_msg_fn)(void *ctx, const linkmsg_t *m);

/** What link_poll() noticed. */
typedef enum {
    LINK_EV_NONE = 0,
    LINK_EV_SILENT, /**< the other board has just fallen silent (nothing for silence_ms) */
    LINK_EV_HEARD,  /**< it is heard again after a silence */
} link_event_t;

typedef struct {
    uint32_t heartbeats_sent; /**< own heartbeats queued */
    uint32_t peer_heartbeats; /**< the other board's heartbeats received */
    uint16_t peer_missed;     /**< heartbeats of the other board missing (counter gaps) */
    uint16_t silences;        /**< times the other board fell silent */
    uint16_t send_refused;    /**< link_send() calls refused (no room, bus-off) */
    uint16_t rx_errors;       /**< frames dropped: bad length, B frame without its A */
    hal_can_stats_t can;      /**< the controller's statistics (bus-off, recoveries, ...) */
} link_stats_t;

/** A board's link (fields private to link.c). */
typedef struct {
    link_config_t cfg;
    link_msg_fn on_msg;
    void *ctx;
    linkmsg_rx_t rx;
    volatile uint32_t last_heard; /* ms of the last frame from the other board */
    uint32_t next_heartbeat;      /* ms */
    uint8_t counter;              /* own heartbeat counter */
    uint8_t peer_counter;         /* the other board's last heartbeat counter */
    uint8_t peer_seen;            /* one of its heartbeats arrived */
    uint8_t silent;               /* the other board is silent */
    uint8_t flags;                /* own LINKMSG_HB_STOPPED */
    uint8_t up;                   /* link_init succeeded */
    link_stats_t stats;
} link_t;

/**
 * Start the link of board @p cfg->node: the clock (hal/clock.h), CAN instance LINK_CAN at
 * cfg->bitrate_bps with filters for the table's ids (0x000-0x0FF, 0x700-0x703), automatic
 * bus-off recovery; received messages go to @p on_msg (may be NULL). The silence is timed from
 * now. Returns 0, LINK_E_CONFIG, or hal_can_init()'s error; after an error the link is down:
 * link_send() refuses (LINK_E_DOWN), link_poll() does nothing.
 */
int link_init(link_t *l, const link_config_t *cfg, link_msg_fn on_msg, void *ctx);

/**
 * Send @p m: all its frames queued back to back with interrupts held off, or none. Returns 0,
 * LINK_E_MESSAGE, LINK_E_FULL (try again later), LINK_E_BUS_OFF or LINK_E_DOWN.
 */
int link_send(link_t *l, const linkmsg_t *m);

/** Frames link_send() can queue now (0 when bus-off): a message of two frames needs 2. */
uint8_t link_tx_room(const link_t *l);

/**
 * The main loop waits for link_tx_room() to grow (hal_can_wake_on_room() on the link's bus):
 * stated on each pass that finds too little room.
 */
void link_wake_on_room(const link_t *l);

/**
 * Main-loop work: the heartbeat when it is due (retried on the next call when the queue is
 * full), and the watch on the other board. Returns what changed. States its deadlines (the
 * next heartbeat, the moment the other board would fall silent) with hal_clock_wake_at(); a
 * frame from a silent board wakes the main loop.
 */
link_event_t link_poll(link_t *l);

/** Set the heartbeat's LINKMSG_HB_STOPPED flag (@p stopped non-zero) or clear it. */
void link_set_stopped(link_t *l, uint8_t stopped);

/** True when link_init() succeeded. */
bool link_up(const link_t *l);

/** True while the other board is silent. */
bool link_peer_silent(const link_t *l);

/** A copy of the counters, with the controller's. */
void link_stats(const link_t *l, link_stats_t *out);

#ifdef __cplusplus
}
#endif

#endif
