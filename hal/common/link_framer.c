/*
 * link_framer.c - frames over a byte stream (see link_framer.h).
 */
#include "link_framer.h"

#define FLAG 0x7Eu
#define ESC  0x7Du

uint8_t link_crc8(const uint8_t *p, uint8_t n)
{
    uint8_t crc = 0;
    while (n--) {
        crc ^= *p++;
        for (uint8_t b = 0; b < 8; b++)
            crc = (uint8_t)((crc & 0x80u) ? (uint8_t)(crc << 1) ^ 0x07u : (uint8_t)(crc << 1));
    }
    return crc;
}

uint8_t link_framer_encode(const hal_link_frame_t *f, uint8_t *out)
{
    if (f->id > HAL_LINK_MAX_ID || f->len > HAL_LINK_MAX_DATA)
        return 0;
    uint8_t raw[2 + HAL_LINK_MAX_DATA + 1];
    raw[0] = (uint8_t)(f->id >> 3);
    raw[1] = (uint8_t)(((f->id & 7u) << 5) | f->len);
    uint8_t m = 2;
    for (uint8_t i = 0; i < f->len; i++)
        raw[m++] = f->data[i];
    raw[m] = link_crc8(raw, m);
    uint8_t *o = out;
    *o++ = FLAG;
    for (const uint8_t *r = raw; r <= &raw[m]; r++) {
        uint8_t byte = *r;
        if (byte == FLAG || byte == ESC) {
            *o++ = ESC;
            byte ^= 0x20u;
        }
        *o++ = byte;
    }
    *o++ = FLAG;
    return (uint8_t)(o - out);
}

void link_framer_rx_init(link_framer_rx_t *rx)
{
    rx->n = 0;
    rx->escaped = 0;
    rx->in_frame = 0;
    rx->errors = 0;
}

int link_framer_rx_byte(link_framer_rx_t *rx, uint8_t byte, hal_link_frame_t *out)
{
    if (byte == FLAG) {
        int good = 0;
        if (rx->in_frame && rx->n > 0) {
            /*
             * Header bit 4 taken into the length: a frame with it set, like one longer than
             * 8 data bytes, cannot have 3 + len bytes (at most sizeof rx->buf are kept).
             */
            uint8_t len = rx->buf[1] & 0x1Fu;
            if (rx->escaped || rx->n != (uint8_t)(3 + len) ||
                link_crc8(rx->buf, (uint8_t)(rx->n - 1)) != rx->buf[rx->n - 1]) {
                rx->errors++;
            } else {
                out->id = (uint16_t)(((uint16_t)rx->buf[0] << 3) | (rx->buf[1] >> 5));
                out->len = len;
                for (uint8_t i = 0; i < len; i++)
                    out->data[i] = rx->buf[2 + i];
                good = 1;
            }
        }
        /* A flag ends one frame and starts the next (back-to-back frames share no flag). */
        rx->in_frame = 1;
        rx->n = 0;
        rx->escaped = 0;
        return good;
    }
    if (!rx->in_frame)
        return 0;
    if (byte == ESC) {
        rx->escaped = 1;
        return 0;
    }
    if (rx->escaped) {
        byte ^= 0x20u;
        rx->escaped = 0;
    }
    if (rx->n >= sizeof rx->buf) {
        rx->errors++;
        rx->in_frame = 0; /* too long: drop until the next flag */
        return 0;
    }
    rx->buf[rx->n++] = byte;
    return 0;
}
