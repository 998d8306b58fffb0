/*
 * link_framer.h - hal_link_frame_t over a byte stream (the MSP430's UART link), shared by
 * both HAL implementations so that the host tests what the target runs.
 *
 * On the wire: flag 0x7E, the stuffed bytes of header, data and CRC, flag 0x7E. Header: byte
 * 0 = id >> 3, byte 1 = (id & 7) << 5 | len (bit 4 zero). CRC-8 (polynomial 0x07, initial 0)
 * over header and data. Stuffing: 0x7E and 0x7D inside a frame go as 0x7D, byte XOR 0x20.
 * A receiver resynchronises on the next 0x7E after any error.
 */
#ifndef HAL_LINK_FRAMER_H
#define HAL_LINK_FRAMER_H

#include <stdint.h>

#include "hal/link.h"

/** Longest encoding of a frame: flags, stuffed header, data and CRC. */
#define LINK_FRAMER_MAX_BYTES (2 + 2 * (2 + HAL_LINK_MAX_DATA + 1))

/** CRC-8, polynomial x^8 + x^2 + x + 1, initial value 0, no reflection. */
uint8_t link_crc8(const uint8_t *p, uint8_t n);

/** Encode @p f into @p out (LINK_FRAMER_MAX_BYTES); returns the byte count, 0 if malformed. */
uint8_t link_framer_encode(const hal_link_frame_t *f, uint8_t *out);

/** Receiver state. */
typedef struct {
    uint8_t buf[2 + HAL_LINK_MAX_DATA + 1];
    uint8_t n;
    uint8_t escaped;
    uint8_t in_frame;
    uint16_t errors;
} link_framer_rx_t;

/** Reset the receiver (waits for a flag). */
void link_framer_rx_init(link_framer_rx_t *rx);

/**
 * Feed one received byte. Returns 1 when it completed a good frame (written to @p out),
 * 0 otherwise; bad frames are counted in rx->errors.
 */
int link_framer_rx_byte(link_framer_rx_t *rx, uint8_t byte, hal_link_frame_t *out);

#endif
