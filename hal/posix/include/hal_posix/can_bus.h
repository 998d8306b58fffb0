/*
 * hal_posix/can_bus.h - the harness's CAN bus model: hal/can.h on the host, deterministic, on
 * the harness's simulated time. Used by sim/ and tests; never by portable firmware.
 *
 * Buses and nodes: POSIX_CAN_BUSES buses (hal/can.h instances 0 and 1); every board that
 * initialised instance N is a node on bus N, and an injected babbling node may join. A node's
 * receive interrupt is a source on its board at (HAL_CAN0_VECTOR, HAL_CAN0_INT_PIN) for bus 0
 * (the MCP2515's /INT on P2.2) and (HAL_CAN0_VECTOR, POSIX_CAN1_INT_PIN) for bus 1.
 *
 * Timing (ISO 11898-1 classical base frames, worst-case bit stuffing): a frame of n data bytes
 * has 34 + 8n bits from SOF through the CRC sequence, which stuffing can lengthen by
 * floor((34 + 8n - 1) / 4) bits, and 13 bits after it (CRC delimiter, ACK slot and delimiter,
 * 7 EOF, 3 intermission): 47 + 8n + floor((33 + 8n) / 4) bits, 135 for 8 bytes, each
 * 1e9 / bitrate ns (the bit time must be a whole number of nanoseconds). An error ends a
 * transmission with an error frame: 6 flag bits, 8 delimiter bits, 3 intermission bits, after
 * the bit where the error was seen (the ACK slot for ACK and CRC errors, the bit after the
 * arbitration field for a transmitter's bit error); error flags of several nodes are taken as
 * overlapping exactly (no echo).
 *
 * Arbitration: when the bus is idle, every node whose head frame is ready contends; the lowest
 * identifier wins (equal identifiers: the lower node number). A node's frames go in the order
 * queued. A frame queued on an idle bus starts at once.
 *
 * Acknowledgement: a frame is acknowledged when at least one other node that is not bus-off and
 * runs at the sender's bit rate receives it. Nodes at another bit rate neither acknowledge nor
 * disturb the frame; to them it is a receive error. No acknowledgement is an ACK error: an
 * error frame, then the automatic retransmission.
 *
 * Fault confinement (ISO 11898-1:2015, 12.1.4.2): the rules implemented are
 *   rule 1  a receiver that detects an error: REC + 1;
 *   rule 3  a transmitter that sends an error flag: TEC + 8, except (exception 1) an
 *           error-passive transmitter that sees an ACK error and no dominant bit while it sends
 *           its passive error flag (nobody else on the bus);
 *   rule 7  a successful transmission: TEC - 1 (when above 0);
 *   rule 8  a successful reception: REC - 1 when 1..127; set to 119 when above 127;
 *   states  error-passive when TEC or REC > 127, error-active again when both <= 127, bus-off
 *           when TEC > 255;
 *   recovery  back to error-active with TEC = REC = 0 after 128 occurrences of 11 consecutive
 *           recessive bits, counted on the bus as it is: an idle bus gives one occurrence per 11
 *           bit times, a good frame or an active error frame ends with 11 recessive bits (ACK
 *           delimiter and EOF and intermission; error delimiter and intermission), a passive
 *           error frame after an ACK error with 19; a dominant bit (a start of frame) ends a run.
 * Not modelled: rules 2, 4, 5, 6 (errors inside error flags, overload frames), stuff errors in
 * arbitration, and suspend transmission's interplay with other nodes starting first (an
 * error-passive node simply waits 8 bit times more before its next frame).
 *
 * Receive buffers: two per node (the MCP2515's RXB0 and RXB1); a frame that finds both full is
 * lost (rx_overruns). The node's interrupt handler empties them and calls the receive handler
 * once per frame. Frames are acknowledged whatever the filters and buffers say.
 *
 * Fault injection (posix_can_add_fault): see posix_can_fault_t.
 */
#ifndef HAL_POSIX_CAN_BUS_H
#define HAL_POSIX_CAN_BUS_H

#include <stdbool.h>
#include <stdint.h>

#include "hal/can.h"
#include "hal_posix/harness.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Buses (hal/can.h instances) the model has. */
#define POSIX_CAN_BUSES      2
/** Node number of the injected babbling node (board nodes are the board ids). */
#define POSIX_CAN_BABBLER    POSIX_MAX_BOARDS
/** Nodes per bus: the boards and the babbler. */
#define POSIX_CAN_NODES      (POSIX_MAX_BOARDS + 1)
/** Pin bit of bus 1's receive interrupt (bus 0: HAL_CAN0_INT_PIN), on HAL_CAN0_VECTOR. */
#define POSIX_CAN1_INT_PIN   3
/** Faults per bus at most. */
#define POSIX_CAN_MAX_FAULTS 16

/** Bits from SOF through the CRC sequence of a frame of @p len data bytes: 34 + 8 len. */
uint32_t posix_can_stuffable_bits(uint8_t len);

/** Most stuff bits those can carry: floor((34 + 8 len - 1) / 4). */
uint32_t posix_can_stuff_bits(uint8_t len);

/** A frame's bits, worst-case stuffing and intermission included: 47 + 8 len + stuff. */
uint32_t posix_can_frame_bits(uint8_t len);

typedef enum {
    /** The receivers acknowledge the frame and lose it (as an overrun of their buffers would):
     * no error, no retransmission; the frame is counted in their rx_overruns. */
    POSIX_CAN_FAULT_DROP = 0,
    /** A bit of the frame flips on the wire: the receivers see a CRC error and send an error
     * frame; the sender retransmits. */
    POSIX_CAN_FAULT_CORRUPT,
    /** The frame waits delay_ns in its sender before it may contend (a slow driver); the
     * frames queued behind it wait too. */
    POSIX_CAN_FAULT_DELAY,
    /** A babbling node joins the bus from `from_ns` to `until_ns` and sends frames of id `id`
     * and `len` bytes (a counter), one every `period_ns` from start to start (0: back to
     * back). It acknowledges the others' frames while it is there. */
    POSIX_CAN_FAULT_BABBLE,
    /** From `from_ns` every transmission of board `sender` fails with a bit error (a broken
     * transceiver) until its TEC takes it bus-off (32 attempts from error-active); then the
     * fault clears and the node recovers as hal/can.h says. */
    POSIX_CAN_FAULT_BUSOFF,
} posix_can_fault_kind_t;

typedef struct {
    posix_can_fault_kind_t kind;
    uint64_t from_ns, until_ns; /**< the window [from, until); busoff: only from counts */
    int sender;                 /**< DROP/CORRUPT/DELAY: whose frames (board id, -1 any);
                                     BUSOFF: the board */
    int id;                     /**< DROP/CORRUPT/DELAY: which id (-1 any); BABBLE: its id */
    uint32_t count;             /**< DROP/CORRUPT/DELAY: frames it hits, 0 = all in the window;
                                     a retransmission is another frame */
    uint64_t delay_ns;          /**< DELAY */
    uint8_t len;                /**< BABBLE: data bytes 0..8 */
    uint64_t period_ns;         /**< BABBLE */
} posix_can_fault_t;

/**
 * Add fault @p f to bus @p bus (before or during the run). Returns 0, or -1 when an argument is
 * out of range (kind, window, id, len, no room, a second babbler on the bus).
 */
int posix_can_add_fault(hal_can_t bus, const posix_can_fault_t *f);

/** What the observer is told. */
typedef enum {
    POSIX_CAN_EV_FRAME = 0, /**< a frame went through (acknowledged) */
    POSIX_CAN_EV_ERROR,     /**< a transmission ended in an error frame (it is repeated) */
    POSIX_CAN_EV_STATE,     /**< a node changed state (error-active/-passive, bus-off) */
} posix_can_ev_kind_t;

/** Why a transmission failed. */
typedef enum {
    POSIX_CAN_ERR_NONE = 0,
    POSIX_CAN_ERR_ACK, /**< nobody acknowledged */
    POSIX_CAN_ERR_CRC, /**< the receivers saw a CRC error (a corrupted frame) */
    POSIX_CAN_ERR_BIT, /**< the transmitter saw a bit error (a faulty transceiver) */
} posix_can_err_t;

typedef struct {
    uint8_t kind;          /**< posix_can_ev_kind_t */
    uint8_t bus;           /**< 0..POSIX_CAN_BUSES-1 */
    int8_t node;           /**< FRAME, ERROR: the sender; STATE: the node (POSIX_CAN_BABBLER too) */
    uint8_t state;         /**< STATE: the new hal_can_state_t */
    uint8_t error;         /**< ERROR: posix_can_err_t */
    uint8_t recovered;     /**< STATE: bus-off ended (error-active with both counters 0) */
    uint16_t delivered;    /**< FRAME: nodes (bit per node) whose receive buffers took it */
    uint16_t lost;         /**< FRAME: nodes that acknowledged it but lost it */
    hal_can_frame_t frame; /**< FRAME, ERROR: the frame (as delivered: see carrier) */
    uint64_t queued_ns;    /**< FRAME, ERROR: when hal_can_send() took it */
    uint64_t start_ns, end_ns; /**< FRAME, ERROR: on the bus (end: intermission done);
                                    STATE: both the instant of the change */
} posix_can_event_t;

/** Observer of every bus event (telemetry, logs); NULL removes it. */
typedef void (*posix_can_tap_fn)(void *ctx, const posix_can_event_t *ev);
void posix_can_set_tap(posix_can_tap_fn fn, void *ctx);

/**
 * Carrier: called for every frame that goes through, before the receivers get it, with the
 * frame @p sent; it writes into @p got the frame the receivers get (a real SocketCAN socket
 * carries it there and back) and returns 0, or returns non-zero when it could not (the
 * receivers then get @p sent; the carrier keeps its own error). NULL removes it.
 */
typedef int (*posix_can_carrier_fn)(void *ctx, hal_can_t bus, const hal_can_frame_t *sent,
                                    hal_can_frame_t *got);
void posix_can_set_carrier(posix_can_carrier_fn fn, void *ctx);

/** What a bus carried since posix_reset(). */
typedef struct {
    uint32_t bitrate_bps;  /**< of its first node (0: no node yet) */
    uint64_t frames;       /**< frames that went through */
    uint64_t error_frames; /**< transmissions that ended in an error frame */
    uint64_t busy_ns;      /**< time the bus carried frames or error frames */
    uint64_t lost;         /**< frame copies acknowledged and lost by a receiver */
} posix_can_bus_stats_t;

/** Bus @p bus's counters into @p out; -1 for no such bus. */
int posix_can_bus_stats(hal_can_t bus, posix_can_bus_stats_t *out);

/**
 * Node @p node of bus @p bus (a board id or POSIX_CAN_BABBLER), from the host side without
 * selecting a board: its statistics and status. Returns 0, or -1 when it never joined.
 */
int posix_can_node(hal_can_t bus, int node, hal_can_stats_t *stats, hal_can_status_t *status);

#ifdef __cplusplus
}
#endif

#endif
