/*
 * hal/can.h - CAN controllers: classical CAN 2.0A frames (ISO 11898-1, 11-bit identifiers, 0..8
 * data bytes), one controller per bus instance, in the manner of RIOT's periph/can and
 * Zephyr's can API. The board link (firmware/link) runs on instance 0.
 *
 * Instances (hal_can_t):
 *  - MSP430: 0 = a Microchip MCP2515 on USCI_B0 in SPI mode 0,0 (P3.0 /CS, P3.1 SI, P3.2 SO,
 *    P3.3 SCK); its /INT output on P2.2, the PORT2 vector (HAL_VEC_PORT2), falling edge
 *    (HAL_CAN0_INT_PORT / HAL_CAN0_INT_PIN in hal/pinmap.h).
 *  - POSIX: the harness's CAN bus model (hal_posix/can_bus.h): instances 0 and 1 are two
 *    separate buses; every board that initialised instance N is a node on bus N. Its receive
 *    interrupt is the same vector and pin bit as the target's.
 *
 * Behaviour both implementations give:
 *  - Sending is non-blocking: hal_can_send() puts the frame in the instance's transmit queue
 *    (HAL_CAN_TX_QUEUE frames) and returns. Frames leave in the order they were queued (a FIFO:
 *    a lower identifier queued later waits behind the earlier frames of the same node); across
 *    nodes the bus arbitrates by identifier (lower wins). A frame that meets an error on the
 *    bus (no acknowledgement, a bit or CRC error) is retransmitted automatically until it goes
 *    through or the node goes bus-off.
 *  - Receiving: each frame that another node sends, that this node receives without error and
 *    that passes the acceptance filters, is handed to the receive handler in interrupt context
 *    (interrupts disabled), one call per frame, in bus order. A node never receives its own
 *    frames. Frames that arrive while the controller's receive buffers (two: the MCP2515's RXB0
 *    and RXB1) are still full are lost and counted (rx_overruns); they were acknowledged on the
 *    bus all the same, so their sender does not repeat them.
 *  - Error confinement (ISO 11898-1, 12.1.4): the transmit and receive error counters (TEC,
 *    REC) give the state: error-active while both are at most 127, error-passive when either
 *    exceeds 127, bus-off when TEC exceeds 255. A bus-off node neither sends nor receives nor
 *    acknowledges; its transmit queue is emptied (the frames count as tx_aborted) and
 *    hal_can_send() refuses frames until it is back. It comes back error-active, with both
 *    counters 0, after 128 occurrences of 11 consecutive recessive bits on the bus (at least
 *    1,408 bit times) - by itself, or only once hal_can_recover() asked when the configuration
 *    says manual_recovery.
 *
 * Acceptance filters: a frame is accepted when (frame id & mask) == (filter id & mask) for any
 * of the n_filters filters; without filters every frame is accepted. HAL_CAN_FILTERS is what
 * the MCP2515 can do exactly with its two masks: filter 0 is RXM0 with RXF0 and RXF1, filter 1
 * is RXM1 with RXF2..RXF5.
 *
 * Bit rates: from HAL_CAN_BITRATE_MIN to HAL_CAN_BITRATE_MAX bit/s, those the controller can
 * make exactly; CiA 301's 10, 20, 50, 125, 250, 500, 800 kbit/s and 1 Mbit/s on both worlds
 * (the MCP2515 from a 16 MHz crystal; the bus model takes every rate whose bit time is a whole
 * number of nanoseconds). Others are refused with HAL_CAN_E_BITRATE.
 *
 * Calls: hal_can_send(), hal_can_tx_room(), hal_can_status() and hal_can_stats() may be called
 * from the main loop and from handlers; hal_can_init() and hal_can_recover() from the main loop.
 */
#ifndef HAL_CAN_H
#define HAL_CAN_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** A controller instance (bus): 0 .. the board's last (MSP430: 0 only; POSIX: 0 and 1). */
typedef uint8_t hal_can_t;

#define HAL_CAN_MAX_DATA    8         /**< data bytes of a classical frame */
#define HAL_CAN_MAX_ID      0x7FFu    /**< 11-bit identifiers (CAN 2.0A); lower is more urgent */
#define HAL_CAN_FILTERS     2         /**< acceptance filters (id, mask) per instance */
#define HAL_CAN_TX_QUEUE    8         /**< frames an instance holds waiting to be sent */
#define HAL_CAN_BITRATE_MIN 10000ul   /**< bit/s */
#define HAL_CAN_BITRATE_MAX 1000000ul /**< bit/s */

/** Return codes (0 is success). */
#define HAL_CAN_E_PARAM    (-1) /**< an argument out of range (instance, frame, filter, NULL) */
#define HAL_CAN_E_FULL     (-2) /**< the transmit queue is full: nothing queued, try later */
#define HAL_CAN_E_BUS_OFF  (-3) /**< the controller is bus-off: nothing queued */
#define HAL_CAN_E_STATE    (-4) /**< not initialised, or (hal_can_recover) not bus-off */
#define HAL_CAN_E_BITRATE  (-5) /**< the controller cannot make this bit rate */
#define HAL_CAN_E_HARDWARE (-6) /**< the controller does not answer (MCP2515: no SPI reply) */

/** A classical CAN 2.0A data frame. */
typedef struct {
    uint16_t id; /**< 0..HAL_CAN_MAX_ID */
    uint8_t len; /**< data bytes, 0..8 (the DLC) */
    uint8_t data[HAL_CAN_MAX_DATA];
} hal_can_frame_t;

/** An acceptance filter: frames with (id & mask) == (filter.id & mask) pass. */
typedef struct {
    uint16_t id;   /**< 0..HAL_CAN_MAX_ID */
    uint16_t mask; /**< 0..HAL_CAN_MAX_ID; a 1 bit must match, a 0 bit is "don't care" */
} hal_can_filter_t;

/**
 * Receive handler: interrupt context, interrupts disabled, one call per accepted frame;
 * @p f is valid during the call only.
 */
typedef void (*hal_can_rx_cb_t)(void *arg, const hal_can_frame_t *f);

typedef struct {
    uint32_t bitrate_bps;                      /**< HAL_CAN_BITRATE_MIN..MAX, bit/s */
    hal_can_filter_t filters[HAL_CAN_FILTERS]; /**< the first n_filters are used */
    uint8_t n_filters;                         /**< 0..HAL_CAN_FILTERS; 0 accepts every frame */
    uint8_t manual_recovery; /**< 0: bus-off ends by itself; 1: only after hal_can_recover() */
    hal_can_rx_cb_t rx_cb;   /**< receive handler (required) */
    void *rx_arg;            /**< its argument */
} hal_can_config_t;

/** Fault-confinement state (ISO 11898-1, 12.1.4). */
typedef enum {
    HAL_CAN_ERROR_ACTIVE = 0,  /**< TEC and REC <= 127: sends active error flags */
    HAL_CAN_ERROR_PASSIVE = 1, /**< TEC or REC > 127: passive error flags, suspend transmission */
    HAL_CAN_BUS_OFF = 2        /**< TEC > 255: off the bus until recovered */
} hal_can_state_t;

typedef struct {
    uint8_t state;      /**< hal_can_state_t */
    uint8_t recovering; /**< bus-off and counting the 128 x 11 recessive bits back */
    uint16_t tec;       /**< transmit error counter, 0..255 (256 and up: bus-off) */
    uint16_t rec;       /**< receive error counter, 0..255 */
} hal_can_status_t;

/** Counters since hal_can_init() (each saturates at its type's maximum). */
typedef struct {
    uint32_t tx_frames;     /**< frames sent and acknowledged */
    uint32_t rx_frames;     /**< frames handed to the receive handler */
    uint16_t tx_errors;     /**< errors met while sending (each one a retransmission) */
    uint16_t rx_errors;     /**< errors met while receiving (CRC, stuffing, form) */
    uint16_t rx_overruns;   /**< accepted frames lost: the receive buffers were full */
    uint16_t tx_aborted;    /**< queued frames dropped when the controller went bus-off */
    uint16_t error_passive; /**< times it became error-passive */
    uint16_t bus_off;       /**< times it went bus-off */
    uint16_t recoveries;    /**< times it came back from bus-off */
} hal_can_stats_t;

/**
 * (Re)start instance @p can with @p cfg (copied): counters and statistics 0, the transmit
 * queue empty, error-active, joining the bus at once. Returns 0, HAL_CAN_E_PARAM (no such
 * instance, cfg or rx_cb NULL, n_filters or a filter out of range), HAL_CAN_E_BITRATE or
 * HAL_CAN_E_HARDWARE; on an error the instance is left as it was.
 */
int hal_can_init(hal_can_t can, const hal_can_config_t *cfg);

/**
 * Queue @p f for sending. Returns 0, HAL_CAN_E_PARAM (id or len out of range, f NULL, no such
 * instance), HAL_CAN_E_FULL, HAL_CAN_E_BUS_OFF or HAL_CAN_E_STATE (not initialised).
 */
int hal_can_send(hal_can_t can, const hal_can_frame_t *f);

/** Frames hal_can_send() would take now (0 when full, bus-off or not initialised). */
uint8_t hal_can_tx_room(hal_can_t can);

/**
 * The main loop waits for room in @p can's transmit queue (hal_can_tx_room() too small now):
 * like hal_clock_wake_at(), a wait stated on each pass that needs it, after its checks. MSP430:
 * nothing (the main loop polls). POSIX: the harness runs this board's main loop once, the next
 * time the room may have grown (a frame of this instance sent and acknowledged, or the end of
 * its bus-off), instead of after every event. No such instance, or not initialised: nothing.
 */
void hal_can_wake_on_room(hal_can_t can);

/** The state and error counters of @p can into @p out. Returns 0 or HAL_CAN_E_PARAM / _STATE. */
int hal_can_status(hal_can_t can, hal_can_status_t *out);

/** The statistics of @p can into @p out. Returns 0 or HAL_CAN_E_PARAM / _STATE. */
int hal_can_stats(hal_can_t can, hal_can_stats_t *out);

/**
 * Start the way back from bus-off (with manual_recovery; also allowed without): the controller
 * is error-active again after 128 x 11 recessive bits. Returns 0, HAL_CAN_E_PARAM, or
 * HAL_CAN_E_STATE when the instance is not bus-off (or not initialised).
 */
int hal_can_recover(hal_can_t can);

#ifdef __cplusplus
}
#endif

#endif
