/*
 * linkmsg_codec.c - the firmware's message coder (firmware/link/linkmsg.c) on the host, for the
 * DBC round-trip test (tests/link/dbc_test.py): JSON Lines on stdin, one answer per line.
 *
 *   {"op":"encode","message":"FIX","fields":{"x":..,"y":..,"heading":..,"latch":..,"flags":..}}
 *     -> {"ok":true,"frames":[{"id":48,"data":"0011..."},...]}
 *   {"op":"decode","frames":[{"id":48,"data":"..."},...]}
 *     -> {"ok":true,"message":"FIX","fields":{...}} for the message the last frame completed
 *
 * Field values are the raw integers on the wire. Which linkmsg_t member each DBC signal name
 * means is written out below by hand, from linkmsg.h's meaning of the members - not taken from
 * the generated table - so that a signal of messages.toml naming the wrong member shows up as
 * a value in the wrong signal.
 */
#include <jansson.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "link/linkmsg.h"

typedef struct {
    const char *name; /* the DBC signal */
    size_t offset;    /* in linkmsg_t */
    size_t size;
    int is_signed;
} field_t;

#define MEMBER(m) (((linkmsg_t *)0)->u.m)
#define F(m, n, sgn)                                                                               \
    {                                                                                              \
        n, offsetof(linkmsg_t, u.m), sizeof(MEMBER(m)), sgn                                        \
    }

typedef struct {
    const char *name;
    uint8_t type;
    field_t f[5];
    int n;
} message_t;

static const message_t messages[] = {
    {"STOP", LINKMSG_STOP, {F(stop.reason, "reason", 0)}, 1},
    {"POSE",
     LINKMSG_POSE,
     {F(pose.pose.x, "x", 1), F(pose.pose.y, "y", 1), F(pose.pose.heading, "heading", 0),
      F(pose.request, "request", 0)},
     4},
    {"FIX",
     LINKMSG_FIX,
     {F(fix.pose.x, "x", 1), F(fix.pose.y, "y", 1), F(fix.pose.heading, "heading", 0),
      F(fix.latch, "latch", 0), F(fix.flags, "flags", 0)},
     5},
    {"FIX_ACK", LINKMSG_FIX_ACK, {F(fix_ack.status, "status", 1), F(fix_ack.latch, "latch", 0)}, 2},
    {"LATCH_REQ",
     LINKMSG_LATCH_REQ,
     {F(latch_req.first, "first", 0), F(latch_req.count, "count", 0)},
     2},
    {"LATCH",
     LINKMSG_LATCH,
     {F(latch.pose.x, "x", 1), F(latch.pose.y, "y", 1), F(latch.pose.heading, "heading", 0),
      F(latch.seq, "seq", 0), F(latch.status, "status", 1)},
     5},
    {"FIX_QUALITY",
     LINKMSG_FIX_QUALITY,
     {F(fix_quality.latch, "latch", 0), F(fix_quality.quality, "quality", 0),
      F(fix_quality.err, "err", 0), F(fix_quality.resid, "resid", 0),
      F(fix_quality.agree, "agree", 0)},
     5},
    {"DIR", LINKMSG_DIR, {F(dir.reverse, "reverse", 0)}, 1},
    {"MAIN_HEARTBEAT",
     LINKMSG_MAIN_HEARTBEAT,
     {F(heartbeat.counter, "counter", 0), F(heartbeat.flags, "flags", 0),
      F(heartbeat.tec, "tec", 0), F(heartbeat.rec, "rec", 0)},
     4},
    {"NAV_HEARTBEAT",
     LINKMSG_NAV_HEARTBEAT,
     {F(heartbeat.counter, "counter", 0), F(heartbeat.flags, "flags", 0),
      F(heartbeat.tec, "tec", 0), F(heartbeat.rec, "rec", 0)},
     4},
};
#define N_MESSAGES (sizeof messages / sizeof messages[0])

static void put(void *p, size_t size, long long v)
{
    /* Little-endian host: the low bytes of the value. */
    unsigned long long u = (unsigned long long)v;
    for (size_t i = 0; i < size; i++)
        ((uint8_t *)p)[i] = (uint8_t)(u >> (8 * i));
}

static long long get(const void *p, size_t size, int is_signed)
{
    unsigned long long u = 0;
    for (size_t i = 0; i < size; i++)
        u |= (unsigned long long)((const uint8_t *)p)[i] << (8 * i);
    if (is_signed && size < 8 && (u >> (8 * size - 1)) & 1u)
        return (long long)u - (1ll << (8 * size));
    return (long long)u;
}

static json_t *fail(const char *fmt, const char *what)
{
    char buf[200];
    snprintf(buf, sizeof buf, fmt, what);
    return json_pack("{s:b,s:s}", "ok", 0, "error", buf);
}

static json_t *hexframe(const hal_can_frame_t *f)
{
    char hex[17] = "";
    for (uint8_t i = 0; i < f->len; i++)
        snprintf(hex + 2 * i, 3, "%02x", f->data[i]);
    return json_pack("{s:i,s:s}", "id", f->id, "data", hex);
}

static json_t *encode(json_t *req)
{
    const char *name = json_string_value(json_object_get(req, "message"));
    json_t *fields = json_object_get(req, "fields");
    const message_t *m = NULL;
    for (size_t i = 0; name && i < N_MESSAGES; i++)
        if (strcmp(messages[i].name, name) == 0)
            m = &messages[i];
    if (!m || !json_is_object(fields))
        return fail("unknown message %s or no fields", name ? name : "(none)");
    linkmsg_t msg;
    memset(&msg, 0, sizeof msg);
    msg.type = m->type;
    for (int k = 0; k < m->n; k++) {
        json_t *v = json_object_get(fields, m->f[k].name);
        if (!json_is_integer(v))
            return fail("field %s missing or not an integer", m->f[k].name);
        put((uint8_t *)&msg + m->f[k].offset, m->f[k].size, json_integer_value(v));
    }
    hal_can_frame_t f[2];
    uint8_t n = linkmsg_encode(&msg, f);
    json_t *frames = json_array();
    for (uint8_t i = 0; i < n; i++)
        json_array_append_new(frames, hexframe(&f[i]));
    return json_pack("{s:b,s:o}", "ok", 1, "frames", frames);
}

static json_t *decode(json_t *req)
{
    json_t *frames = json_object_get(req, "frames");
    if (!json_is_array(frames))
        return fail("%s", "frames: expected an array");
    linkmsg_rx_t rx;
    linkmsg_rx_init(&rx);
    linkmsg_t out;
    int done = 0;
    size_t i;
    json_t *fr;
    json_array_foreach(frames, i, fr)
    {
        const char *hex = json_string_value(json_object_get(fr, "data"));
        json_t *id = json_object_get(fr, "id");
        size_t len = hex ? strlen(hex) : 0;
        if (!json_is_integer(id) || !hex || len % 2 || len > 16)
            return fail("%s", "a frame needs an integer id and at most 8 hex bytes");
        hal_can_frame_t f;
        memset(&f, 0, sizeof f);
        f.id = (uint16_t)json_integer_value(id);
        f.len = (uint8_t)(len / 2);
        for (uint8_t k = 0; k < f.len; k++) {
            unsigned b;
            if (sscanf(hex + 2 * k, "%2x", &b) != 1)
                return fail("bad hex %s", hex);
            f.data[k] = (uint8_t)b;
        }
        done = linkmsg_rx_feed(&rx, &f, &out);
    }
    if (!done)
        return json_pack("{s:b,s:s,s:i}", "ok", 0, "error", "no message completed", "errors",
                         rx.errors);
    for (size_t k = 0; k < N_MESSAGES; k++) {
        const message_t *m = &messages[k];
        if (m->type != out.type)
            continue;
        json_t *fields = json_object();
        for (int j = 0; j < m->n; j++)
            json_object_set_new(fields, m->f[j].name,
                                json_integer(get((uint8_t *)&out + m->f[j].offset, m->f[j].size,
                                                 m->f[j].is_signed)));
        return json_pack("{s:b,s:s,s:o}", "ok", 1, "message", m->name, "fields", fields);
    }
    return fail("%s", "a message of an unknown type");
}

int main(void)
{
    char line[4096];
    while (fgets(line, sizeof line, stdin)) {
        json_error_t e;
        json_t *req = json_loads(line, 0, &e);
        const char *op = req ? json_string_value(json_object_get(req, "op")) : NULL;
        json_t *ans = !op                         ? fail("%s", "a JSON object with \"op\"")
                      : strcmp(op, "encode") == 0 ? encode(req)
                      : strcmp(op, "decode") == 0 ? decode(req)
                                                  : fail("unknown op %s", op);
        char *s = json_dumps(ans, JSON_COMPACT);
        puts(s);
        fflush(stdout);
        free(s);
        json_decref(ans);
        json_decref(req);
    }
    return 0;
}
