/*
 * can/mcp2515.h - driver of the Microchip MCP2515 stand-alone CAN controller (data sheet
 * DS20001801) over hal/spi.h: portable C, the same on the target (USCI_B0) and in host tests
 * (the register model of tests/support behind hal/spi.h). docs/can.md describes it.
 *
 * The driver owns one controller: its three transmit buffers (a frame goes into a free one;
 * the transmit priorities TXP of the pending buffers are ranked so that the controller sends
 * them by identifier, lowest first - it never sends a less urgent pending frame before a more
 * urgent one - or, with tx_fifo, in the order they were sent) and its two receive buffers (RXB0
 * rolls over into RXB1). mcp2515_isr() is the handler of the controller's INT line (active
 * low, level): it reads received frames with READ RX BUFFER, hands them to the receive
 * callback, frees transmit buffers, clears the flags and follows the error state (EFLG, TEC,
 * REC). Bus-off: pending frames are aborted and sending is refused until the controller is
 * back: by itself after 128 occurrences of 11 recessive bits (DS20001801 Figure 6-1), or,
 * with manual_recovery, held in configuration mode until mcp2515_recover() lets it count.
 *
 * Concurrency: every function runs its SPI frames with interrupts held off
 * (hal_irq_disable), so the main loop and the INT handler may both use the driver.
 */
#ifndef CAN_MCP2515_H
#define CAN_MCP2515_H

#include <stdint.h>

#include "hal/spi.h"

#ifdef __cplusplus
extern "C" {
#endif

#define MCP2515_MAX_DATA   8u
#define MCP2515_MAX_STD    0x7FFul      /**< largest 11-bit (CAN 2.0A) identifier */
#define MCP2515_MAX_EXT    0x1FFFFFFFul /**< largest 29-bit (CAN 2.0B) identifier */
#define MCP2515_TX_BUFS    3u
#define MCP2515_RX_FILTERS 6u

/** Fastest SPI clock the MCP2515 accepts (DS20001801, SPI timing: 10 MHz). */
#define MCP2515_SPI_MAX_HZ 10000000ul

/** Return codes. */
enum {
    MCP2515_OK = 0,
    MCP2515_ERR_ARG = -1,     /**< a parameter out of range (named in the function's doc) */
    MCP2515_ERR_SPI = -2,     /**< hal/spi.h failed (bus not set up, or it stopped) */
    MCP2515_ERR_DEVICE = -3,  /**< the controller did not enter the requested mode */
    MCP2515_ERR_FULL = -4,    /**< all three transmit buffers hold pending frames */
    MCP2515_ERR_BUS_OFF = -5, /**< the controller is bus-off: nothing is sent */
    MCP2515_ERR_MODE = -6,    /**< not possible in this mode (sending in listen-only) */
    MCP2515_ERR_STATE = -7,   /**< mcp2515_recover(): the controller is not bus-off */
};

/** A CAN frame. */
typedef struct {
    uint32_t id; /**< 0..0x7FF standard, 0..0x1FFFFFFF extended */
    uint8_t ext; /**< 1: 29-bit extended identifier (CAN 2.0B), 0: 11-bit (2.0A) */
    uint8_t rtr; /**< 1: remote frame (no data bytes travel) */
    uint8_t len; /**< data length code 0..8 */
    uint8_t data[MCP2515_MAX_DATA];
} mcp2515_frame_t;

/** Operating modes the driver runs in (CANCTRL.REQOP). */
typedef enum {
    MCP2515_MODE_NORMAL = 0, /**< on the bus: sends, receives, acknowledges */
    MCP2515_MODE_LOOPBACK,   /**< sent frames come back to the own receive buffers; the bus
                                  is not driven (self-test) */
    MCP2515_MODE_LISTEN,     /**< receives only: no acknowledge, no error frames, no sending */
    MCP2515_MODE_COUNT
} mcp2515_mode_t;

/** Error state (the CAN fault confinement states, from EFLG). */
typedef enum {
    MCP2515_ERROR_ACTIVE = 0,
    MCP2515_ERROR_PASSIVE, /**< TEC or REC >= 128 (EFLG.TXEP or RXEP) */
    MCP2515_BUS_OFF,       /**< TEC > 255 (EFLG.TXBO): not on the bus until recovered */
} mcp2515_state_t;

/**
 * Acceptance filters for standard (11-bit) identifiers: RXB0 takes frames that match filter
 * 0 or 1 under mask 0, RXB1 those that match filters 2..5 under mask 1 (a mask bit of 1
 * compares that identifier bit, 0 ignores it). Extended frames are not accepted; with
 * accept_all every frame is (the masks and filters are then off: RXM = 11).
 */
typedef struct {
    uint16_t mask[2];                    /**< RXM0, RXM1: 0..0x7FF */
    uint16_t filter[MCP2515_RX_FILTERS]; /**< RXF0..RXF5: 0..0x7FF */
    uint8_t accept_all;                  /**< 1: every frame, standard or extended */
} mcp2515_filters_t;

/** Received frame: interrupt context, @p f valid during the call. */
typedef void (*mcp2515_rx_cb_t)(void *arg, const mcp2515_frame_t *f);
/** A transmit buffer became free (frame sent, or aborted): interrupt context. */
typedef void (*mcp2515_tx_cb_t)(void *arg);

/** Configuration of mcp2515_init(). */
typedef struct {
    hal_spi_bus_t bus;         /**< SPI bus the controller is on */
    hal_spi_cs_t cs;           /**< its chip select */
    uint32_t osc_hz;           /**< the controller's oscillator: 8, 16 or 20 MHz */
    uint32_t bitrate_bps;      /**< bit/s: a rate mcp2515_bit_timing() knows for osc_hz */
    mcp2515_mode_t mode;       /**< mode after init */
    mcp2515_filters_t filters; /**< acceptance filters */
    uint8_t tx_fifo;           /**< 1: frames leave in the order sent; 0: by identifier */
    uint8_t manual_recovery;   /**< 1: after bus-off wait for mcp2515_recover() */
    mcp2515_rx_cb_t rx_cb;     /**< receive callback, required */
    mcp2515_tx_cb_t tx_cb;     /**< transmit-buffer-free callback, may be NULL */
    void *arg;                 /**< passed to both callbacks */
} mcp2515_config_t;

/**
 * Counters since init (saturating). The MCP2515 flags a message error (MERRF) without saying
 * whether it was sending: an error that raised TEC counts as a transmit error, one that
 * raised REC as a receive error, one that raised neither (an acknowledge error while
 * error-passive) as a transmit error when a frame was pending.
 */
typedef struct {
    uint32_t rx_frames;     /**< frames handed to the receive callback */
    uint32_t tx_frames;     /**< frames the controller reported sent (TXnIF) */
    uint16_t tx_errors;     /**< errors while sending (each one a retransmission) */
    uint16_t rx_errors;     /**< errors while receiving */
    uint16_t rx_overflows;  /**< frames lost because both receive buffers were full (RXnOVR) */
    uint16_t tx_aborted;    /**< pending frames aborted on bus-off */
    uint16_t error_passive; /**< times it became error-passive */
    uint16_t bus_offs;      /**< times it went bus-off */
    uint16_t recoveries;    /**< times it came back from bus-off */
} mcp2515_stats_t;

/** Driver state of one controller (treat as opaque; one per controller). */
typedef struct {
    hal_spi_bus_t bus;
    hal_spi_cs_t cs;
    mcp2515_mode_t mode;
    mcp2515_rx_cb_t rx_cb;
    mcp2515_tx_cb_t tx_cb;
    void *arg;
    uint8_t ready;                    /**< 1 after a successful init */
    uint8_t tx_fifo;                  /**< config: send order */
    uint8_t manual_recovery;          /**< config: hold bus-off until mcp2515_recover() */
    uint8_t held;                     /**< bus-off, held in configuration mode */
    uint8_t recovering;               /**< bus-off and counting its way back */
    uint8_t pending;                  /**< bit n: TXBn holds a frame not reported done */
    uint8_t seq;                      /**< age stamp of the last frame loaded */
    uint8_t tx_seq[MCP2515_TX_BUFS];  /**< age stamp of each pending frame */
    uint8_t tx_prio[MCP2515_TX_BUFS]; /**< TXP of each pending buffer (0..3) */
    uint32_t tx_key[MCP2515_TX_BUFS]; /**< arbitration rank of each pending frame */
    uint8_t eflg;                     /**< EFLG as last read */
    uint8_t tec, rec;                 /**< TEC, REC as last read */
    mcp2515_state_t state;
    mcp2515_stats_t stats;
} mcp2515_t;

/** Register values of a bit timing (CNF1, CNF2, CNF3). */
typedef struct {
    uint8_t cnf1, cnf2, cnf3;
} mcp2515_cnf_t;

/**
 * The bit timing for @p osc_hz (8, 16 or 20 MHz) and @p bitrate_bps (CiA 301's 10, 20, 50,
 * 125, 250, 500, 800 kbit/s and 1 Mbit/s, where an exact timing exists: not 800k and 1M from
 * 8 MHz, not 800k from 20 MHz): exact bit rate, SJW 1 TQ, sample point 75-87.5 % (docs/can.md
 * has the table). Returns MCP2515_OK, or MCP2515_ERR_ARG for another pair (@p out untouched).
 */
int mcp2515_bit_timing(uint32_t osc_hz, uint32_t bitrate_bps, mcp2515_cnf_t *out);

/**
 * Reset the controller and set it up: SPI bus at up to 10 MHz in mode 0,0, bit timing, filters
 * and masks, receive rollover, interrupts (RX0, RX1, TX0-2, ERR, MERR on INT), then the mode
 * of @p cfg. Returns MCP2515_OK; MCP2515_ERR_ARG when @p d or @p cfg is NULL, rx_cb is NULL,
 * the oscillator/bit rate pair has no timing, the mode or a filter/mask value is out of range;
 * MCP2515_ERR_SPI when the bus fails; MCP2515_ERR_DEVICE when the controller does not reach
 * configuration mode after the reset or the requested mode afterwards. On an error the driver
 * stays unusable (every other call returns MCP2515_ERR_DEVICE) until an init succeeds.
 */
int mcp2515_init(mcp2515_t *d, const mcp2515_config_t *cfg);

/**
 * Change the operating mode (configuration is kept). Returns MCP2515_OK, MCP2515_ERR_ARG
 * (mode out of range), MCP2515_ERR_SPI or MCP2515_ERR_DEVICE (not initialised, or the
 * controller did not take the mode).
 */
int mcp2515_set_mode(mcp2515_t *d, mcp2515_mode_t mode);

/**
 * Load @p f into a free transmit buffer and request its transmission. Pending buffers get
 * transmit priorities in the order of their identifiers (lowest first, equal identifiers in
 * the order sent), or with tx_fifo in the order sent. Returns MCP2515_OK; MCP2515_ERR_ARG (NULL, id
 * above the range of its format, len > 8, ext or rtr not 0/1); MCP2515_ERR_FULL (three frames
 * pending); MCP2515_ERR_BUS_OFF; MCP2515_ERR_MODE (listen-only); MCP2515_ERR_SPI;
 * MCP2515_ERR_DEVICE (not initialised). Nothing is sent on an error.
 */
int mcp2515_send(mcp2515_t *d, const mcp2515_frame_t *f);

/** Transmit buffers free right now (0..3; 0 when not initialised). */
uint8_t mcp2515_tx_free(const mcp2515_t *d);

/**
 * The INT line's handler (interrupt context; also safe to call from the main loop). Serves
 * every pending flag, then reads the flags again, up to 4 passes. Returns 0 when the INT line
 * is released (no enabled flag left), 1 when flags remain after 4 passes (the caller raises
 * the handler again later: the line stays low and gives no new falling edge), or a negative
 * MCP2515_ERR_* code.
 */
int mcp2515_isr(mcp2515_t *d);

/**
 * Read EFLG, TEC and REC now and update the error state (after bus-off: notices the
 * controller's own recovery and lets sending resume). Returns MCP2515_OK, MCP2515_ERR_SPI or
 * MCP2515_ERR_DEVICE.
 */
int mcp2515_poll(mcp2515_t *d);

/**
 * Let a bus-off controller come back: with manual_recovery it leaves configuration mode for
 * its mode and counts 128 x 11 recessive bits from now; without, it is counting already and
 * nothing changes. Returns MCP2515_OK, MCP2515_ERR_STATE (not bus-off), MCP2515_ERR_SPI,
 * MCP2515_ERR_DEVICE (not initialised, or the mode was not taken).
 */
int mcp2515_recover(mcp2515_t *d);

/** Non-zero while bus-off and counting its way back (see mcp2515_recover()). */
uint8_t mcp2515_recovering(const mcp2515_t *d);

/** Error state as last read (from the INT handler, mcp2515_poll() or mcp2515_send());
 * MCP2515_BUS_OFF for a driver that is not initialised (or NULL). */
mcp2515_state_t mcp2515_state(const mcp2515_t *d);

/** Transmit and receive error counters (TEC, REC) as last read (0 for NULL @p d); either
 * output pointer may be NULL. */
void mcp2515_error_counters(const mcp2515_t *d, uint8_t *tec, uint8_t *rec);

/** Counters since init (NULL for NULL @p d). */
const mcp2515_stats_t *mcp2515_stats(const mcp2515_t *d);

#ifdef __cplusplus
}
#endif

#endif
