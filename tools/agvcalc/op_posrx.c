/*
 * op_posrx.c - agvcalc op "posrx": seed 002's serial position receiver replayed with the
 * firmware's own code (firmware/posrx, docs/posrx.md).
 *
 *   {"op":"posrx","chunks":[[t_s,"hex bytes"],...],"config":{"min_update_m":0.05,
 *    "max_speed_mps":2.0},"reference":{"x":..,"y":..,"t_s":..}}
 *   -> {"ok":true,"positions":[{"t_s":..,"x":..,"y":..,"z":..,"accepted":true|false,
 *       "reason":"ok"|"zero"|"jump"|"too_close"}],"resyncs":n,"skipped_bytes":n,
 *       "trailing_bytes":n}
 *
 * Each chunk's bytes reach the UART at its t_s (seconds, in order, not decreasing), one
 * after the other, through the receive handler posrx_rx_byte(); the main loop's half
 * (posrx_take(), posrx_check()) runs after every byte, so no packet waits in the queue. The
 * hex text takes two digits per byte, upper or lower case, with any spaces between bytes.
 * `reference` (optional) is the position known before the first packet (the firmware's start
 * pose); without it the first non-zero packet is accepted. Metres in the answer (the packet's
 * millimetres / 1000); `trailing_bytes` were received after the last packet and framed none.
 */
#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "agvcalc.h"
#include "posrx/posrx.h"

#define MAX_T_S 4294967.0 /* the receiver's clock: 32-bit milliseconds */

const char agvcalc_fields_posrx[] =
    "    chunks        [[t_s, \"hex bytes\"], ...]: each chunk's bytes reach the UART at t_s\n"
    "                  (s, [0, 4294967], not decreasing); two hex digits a byte, spaces between\n"
    "                  bytes allowed; packets: 00, x, y, z (int32 big-endian mm), ff\n"
    "    config        optional {min_update_m [0, 65.535] (0.05), max_speed_mps\n"
    "                  [0.001, 65.535] (2.0)}\n"
    "    reference     optional {x, y: m, t_s: s}: the position known before the first packet\n"
    "    -> positions [{t_s, x, y, z: m, accepted, reason: ok|zero|jump|too_close}, ...],\n"
    "       resyncs, skipped_bytes, trailing_bytes\n";

static int hex_digit(int c)
{
    return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c - 'A' + 10;
}

/* Check the hex text of chunks[i]; *n gets its byte count. */
static int check_hex(const char *s, size_t i, size_t *n, char *err, size_t errlen)
{
    size_t digits = 0, k;
    for (k = 0; s[k]; k++) {
        unsigned char c = (unsigned char)s[k];
        if (c == ' ') {
            if (digits % 2)
                return ac_fail(err, errlen,
                               "chunks[%zu][1]: a space at character %zu splits a byte (two hex "
                               "digits per byte)",
                               i, k + 1);
            continue;
        }
        if (!isxdigit(c))
            return ac_fail(err, errlen,
                           "chunks[%zu][1]: character %zu is not a hex digit (code %u)", i, k + 1,
                           (unsigned)c);
        digits++;
    }
    if (digits % 2)
        return ac_fail(err, errlen, "chunks[%zu][1]: an odd number of hex digits (%zu)", i, digits);
    *n = digits / 2;
    return 0;
}

static void add_position(json_t *list, const posrx_pos_t *p, posrx_reason_t why)
{
    json_t *o = json_object();
    ac_set(o, "t_s", p->t_ms / 1000.0, 3);
    ac_set(o, "x", p->x / 1000.0, 3);
    ac_set(o, "y", p->y / 1000.0, 3);
    ac_set(o, "z", p->z / 1000.0, 3);
    json_object_set_new(o, "accepted", json_boolean(why == POSRX_OK));
    json_object_set_new(o, "reason", json_string(posrx_reason_name(why)));
    json_array_append_new(list, o);
}

int agvcalc_op_posrx(json_t *req, json_t *resp, char *err, size_t errlen);

int agvcalc_op_posrx(json_t *req, json_t *resp, char *err, size_t errlen)
{
    double min_update = 0.05, max_speed = 2.0;
    json_t *cfg = json_object_get(req, "config");
    if (cfg && !json_is_object(cfg))
        return ac_fail(err, errlen, "config: expected an object");
    if (cfg &&
        (ac_number(cfg, "min_update_m", 0.0, 65.535, false, 0.05, &min_update, err, errlen) ||
         ac_number(cfg, "max_speed_mps", 0.001, 65.535, false, 2.0, &max_speed, err, errlen)))
        return -1;
    json_t *ref = json_object_get(req, "reference");
    double rx = 0, ry = 0, rt = 0;
    if (ref && (!json_is_object(ref) ||
                ac_number(ref, "x", -32768.0, 32767.0, true, 0, &rx, err, errlen) ||
                ac_number(ref, "y", -32768.0, 32767.0, true, 0, &ry, err, errlen) ||
                ac_number(ref, "t_s", 0.0, MAX_T_S, false, 0, &rt, err, errlen)))
        return err[0] ? -1 : ac_fail(err, errlen, "reference: expected an object {x, y, t_s}");
    json_t *chunks = json_object_get(req, "chunks");
    if (!chunks)
        return ac_fail(err, errlen, "missing \"chunks\"");
    if (!json_is_array(chunks))
        return ac_fail(err, errlen, "chunks: expected an array of [t_s, \"hex bytes\"]");
    /* validate every chunk before replaying */
    double last_t = 0;
    for (size_t i = 0; i < json_array_size(chunks); i++) {
        json_t *c = json_array_get(chunks, i);
        if (!json_is_array(c) || json_array_size(c) != 2 || !json_is_string(json_array_get(c, 1)))
            return ac_fail(err, errlen, "chunks[%zu]: expected [t_s, \"hex bytes\"]", i);
        char what[40];
        double t;
        size_t n;
        snprintf(what, sizeof what, "chunks[%zu][0] (t_s)", i);
        if (ac_number_value(json_array_get(c, 0), what, 0.0, MAX_T_S, &t, err, errlen) ||
            check_hex(json_string_value(json_array_get(c, 1)), i, &n, err, errlen))
            return -1;
        if (i > 0 && t < last_t)
            return ac_fail(err, errlen,
                           "chunks[%zu][0] (t_s): %g is before the chunk ahead of it (%g): "
                           "bytes reach the UART in time order",
                           i, t, last_t);
        last_t = t;
    }

    posrx_config_t pc = {(uint16_t)lround(min_update * 1000.0),
                         (uint16_t)lround(max_speed * 1000.0)};
    posrx_t r;
    if (!posrx_init(&r, &pc))
        return ac_fail(err, errlen, "config: max_speed_mps %g is below 1 mm/s", max_speed);
    if (ref)
        posrx_set_reference(&r, (int32_t)lround(rx * 1000.0), (int32_t)lround(ry * 1000.0),
                            (uint32_t)llround(rt * 1000.0));
    json_t *list = json_array();
    uint32_t trailing = 0;
    for (size_t i = 0; i < json_array_size(chunks); i++) {
        json_t *c = json_array_get(chunks, i);
        uint32_t t_ms = (uint32_t)llround(json_number_value(json_array_get(c, 0)) * 1000.0);
        const char *s = json_string_value(json_array_get(c, 1));
        for (size_t k = 0; s[k]; k++) {
            if (s[k] == ' ')
                continue;
            uint8_t b = (uint8_t)(hex_digit(s[k]) << 4 | hex_digit(s[k + 1]));
            k++;
            uint32_t framed = r.st.framed;
            posrx_rx_byte(&r, b, 0, t_ms);
            trailing = r.st.framed != framed ? 0 : trailing + 1u;
            posrx_pos_t p;
            while (posrx_take(&r, &p))
                add_position(list, &p, posrx_check(&r, &p, NULL));
        }
    }
    posrx_stats_t st;
    posrx_stats(&r, &st);
    json_object_set_new(resp, "positions", list);
    json_object_set_new(resp, "resyncs", json_integer(st.resyncs));
    json_object_set_new(resp, "skipped_bytes", json_integer(st.skipped));
    json_object_set_new(resp, "trailing_bytes", json_integer(trailing));
    return 0;
}
