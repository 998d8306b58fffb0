/*
 * mcp2515_model.h - a register-level model of the Microchip MCP2515 CAN controller (data sheet
 * DS20001801), for host unit tests and target test images (portable C, no heap, no HAL).
 *
 * The model is driven from two sides:
 *  - SPI, byte by byte with /CS framing: mcp2515_model_select(), mcp2515_model_exchange()
 *    (one byte each way), mcp2515_model_deselect(). tests/support/mcp2515_spi.c puts it
 *    behind hal/spi.h.
 *  - the CAN bus, one frame at a time: mcp2515_model_bus_tick() gives the controller a frame
 *    slot (it sends its most urgent pending transmit buffer through the bus callback, which
 *    says what the bus did), mcp2515_model_receive() delivers another node's frame,
 *    mcp2515_model_rx_error() a receive error, mcp2515_model_idle() recessive bus time.
 *
 * What it models (section numbers of DS20001801):
 *  - the SPI instruction set of Table 12-1: RESET (takes effect as /CS rises), READ and WRITE
 *    with address auto-increment, READ RX BUFFER (4 start addresses; RXnIF clears as /CS
 *    rises), LOAD TX BUFFER (6 start addresses), RTS, READ STATUS and RX STATUS (the same
 *    byte repeated while clocked), BIT MODIFY (only on the bit-modifiable registers of
 *    Table 11-1; elsewhere the mask is forced to 0xFF); MISO is 0xFF (the pull-up) while no
 *    data is driven;
 *  - the register file of Table 11-1 with power-on values, read-only and unimplemented bits
 *    (read as 0), CANSTAT/CANCTRL mirrored at every xEh/xFh address, and the registers that
 *    only configuration mode may write (CNF1-3, TXRTSCTRL, filters, masks): writes elsewhere
 *    are ignored and counted in `violations`, like writes to a transmit buffer whose TXREQ is
 *    set (section 3.1);
 *  - modes (section 10): configuration, normal, sleep (wakes into listen-only on bus
 *    activity, setting WAKIF), listen-only (receives, never sends, counters untouched),
 *    loopback (sent frames go to the own receive path, the bus is neither driven nor heard);
 *    a mode request takes effect at once (no frame is ever in progress between calls);
 *  - three transmit buffers (section 3): TXREQ by RTS or a write, priority by TXP with the
 *    higher buffer number first on a tie, ABTF/MLOA/TXERR cleared when TXREQ is set, abort by
 *    clearing TXREQ or by CANCTRL.ABAT (nothing starts while ABAT is set), TXnIF on success,
 *    automatic retransmission after a lost arbitration or an error;
 *  - two receive buffers (section 4): masks and filters (Table 4-2) including EXIDE and, for
 *    standard frames, the extended filter bits applied to data bytes 0 and 1 (missing bytes
 *    compare as 0x00); RXM = 11 (any frame) and, as in the 2012 revision DS21801G, RXM = 01
 *    (standard only) and 10 (extended only), which the current revision marks reserved;
 *    lower filter numbers first, RXB0 before RXB1, rollover with BUKT, FILHIT, RXRTR,
 *    overflow flags RX0OVR/RX1OVR (section 7.6.1);
 *  - interrupts (section 7): CANINTF flags are set whatever CANINTE says, INT is low while
 *    any enabled flag is set, CANSTAT.ICOD gives the highest-priority enabled flag (error,
 *    wake-up, TXB0, TXB1, TXB2, RXB0, RXB1); ERRIF on an overflow and on every change of the
 *    error state bits of EFLG;
 *  - error confinement (section 6): TEC +8 per transmit error (not for an acknowledge error
 *    while error-passive, CAN 2.0 rule 3 exception 1), -1 per frame sent; REC +1 per receive
 *    error, -1 per frame received, set to 127 from above 127 (the standard allows 119-127);
 *    EFLG's EWARN/RXWAR/TXWAR (>= 96), RXEP/TXEP (>= 128) and TXBO (TEC over 255; TEC then
 *    reads 255); bus-off recovery after 128 occurrences of 11 recessive bits (Figure 6-1),
 *    counters then 0; the occurrences are counted only in normal, listen-only and loopback
 *    mode (an assumption: the data sheet does not say what configuration or sleep mode does
 *    to a bus-off controller; the model keeps it bus-off there without counting).
 * Not modelled: bit timing (CNF values are stored only), one-shot mode (OSM stored only), the
 * RXnBF and TXnRTS pins, CLKOUT, the oscillator start-up time, REC +8 for a dominant bit
 * after an error flag, error frames of other nodes, the message assembly buffer's timing.
 */
#ifndef MCP2515_MODEL_H
#define MCP2515_MODEL_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** A CAN frame on the model's bus. */
typedef struct {
    uint32_t id; /**< 11-bit standard or 29-bit extended identifier */
    uint8_t ext; /**< 1: extended frame */
    uint8_t rtr; /**< 1: remote frame */
    uint8_t dlc; /**< data length code as on the wire, 0..15 (9..15 carry 8 bytes) */
    uint8_t data[8];
} mcp2515_model_frame_t;

/** What the bus did with a frame the controller sent. */
typedef enum {
    MCP2515_MODEL_TX_ACK = 0, /**< acknowledged: sent */
    MCP2515_MODEL_TX_NO_ACK,  /**< no node acknowledged (acknowledge error) */
    MCP2515_MODEL_TX_ERROR,   /**< bit, stuff or form error while sending */
    MCP2515_MODEL_TX_LOST,    /**< lost arbitration: another node's frame went first */
} mcp2515_model_tx_t;

/** Where mcp2515_model_receive() put a frame. */
enum {
    MCP2515_MODEL_RX_BUF0 = 0,      /**< into RXB0 */
    MCP2515_MODEL_RX_BUF1 = 1,      /**< into RXB1 (by its filters or by rollover) */
    MCP2515_MODEL_RX_REJECTED = -1, /**< no filter matched */
    MCP2515_MODEL_RX_OVERFLOW = -2, /**< matched, but the buffer was full: RXnOVR set */
    MCP2515_MODEL_RX_OFF = -3,      /**< not listening (configuration, sleep, loopback, bus-off) */
};

/** The bus seen from the controller: @p f is being sent; return what happened to it. */
typedef mcp2515_model_tx_t (*mcp2515_model_bus_cb_t)(void *arg, const mcp2515_model_frame_t *f);

/** Model state (fields are the model's; tests read `violations` and the counters). */
typedef struct {
    uint8_t reg[128];          /**< register file (CANSTAT at 0x0E, CANCTRL at 0x0F) */
    uint8_t selected;          /**< /CS low */
    uint8_t phase;             /**< bytes of the current instruction so far (saturates) */
    uint8_t instr;             /**< the current instruction byte */
    uint8_t addr;              /**< address pointer */
    uint8_t mask;              /**< BIT MODIFY mask */
    uint8_t clear_on_deselect; /**< CANINTF bits READ RX BUFFER clears as /CS rises */
    uint8_t reset_on_deselect; /**< RESET received */
    uint16_t tec;              /**< transmit error counter (above 255: bus-off) */
    uint8_t rec;               /**< receive error counter */
    uint8_t bus_off;
    uint8_t idle_sequences; /**< occurrences of 11 recessive bits counted in bus-off */
    mcp2515_model_bus_cb_t bus;
    void *bus_arg;
    uint16_t violations;  /**< writes the data sheet does not allow (ignored) */
    uint32_t spi_bytes;   /**< bytes exchanged while selected */
    uint16_t frames_sent; /**< frames the bus acknowledged (or looped back) */
} mcp2515_model_t;

/** Power-on: registers at their reset values, configuration mode; @p bus (may be NULL: then
 * nothing acknowledges) receives what the controller sends. */
void mcp2515_model_init(mcp2515_model_t *m, mcp2515_model_bus_cb_t bus, void *arg);

/** /CS falls: a new instruction begins. */
void mcp2515_model_select(mcp2515_model_t *m);
/** One byte each way while selected: @p mosi in, the returned byte out (0xFF when the model
 * drives nothing or is not selected). */
uint8_t mcp2515_model_exchange(mcp2515_model_t *m, uint8_t mosi);
/** /CS rises: the instruction ends (RESET and READ RX BUFFER act now). */
void mcp2515_model_deselect(mcp2515_model_t *m);

/** The INT pin: 0 (asserted, low) while any enabled interrupt flag is set, else 1. */
uint8_t mcp2515_model_int(const mcp2515_model_t *m);

/** A register as the controller holds it (no side effects; CANSTAT with its ICOD). */
uint8_t mcp2515_model_peek(const mcp2515_model_t *m, uint8_t addr);

/**
 * One frame slot on the bus: in normal mode the most urgent pending transmit buffer is sent
 * through the bus callback and its result applied; in loopback mode it goes to the own
 * receive path. Returns the buffer number (0..2), or -1 when nothing was sent (no request,
 * another mode, ABAT set, bus-off).
 */
int mcp2515_model_bus_tick(mcp2515_model_t *m);

/** Another node's valid frame @p f on the bus. Returns an MCP2515_MODEL_RX_* code. */
int mcp2515_model_receive(mcp2515_model_t *m, const mcp2515_model_frame_t *f);

/** A receive error on the bus (REC + 1, MERRF) in normal mode; ignored otherwise. */
void mcp2515_model_rx_error(mcp2515_model_t *m);

/** @p n occurrences of 11 consecutive recessive bits (an idle bus): bus-off recovery (not
 * counted in configuration or sleep mode). */
void mcp2515_model_idle(mcp2515_model_t *m, uint16_t n);

#ifdef __cplusplus
}
#endif

#endif
