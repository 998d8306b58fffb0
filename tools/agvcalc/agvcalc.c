/*
 * agvcalc.c - one request line to one response line (see agvcalc.h): parse, dispatch to the
 * op, add "ok" (and "error"), print compactly. No state survives a call.
 */
#include "agvcalc.h"

#include <stdlib.h>
#include <string.h>

#include "agvcalc_ops.h" /* generated: AGVCALC_OPS(X) lists the ops built in */

typedef int (*op_fn)(json_t *, json_t *, char *, size_t);

#define DECLARE_OP(name, help)                                                                     \
    int agvcalc_op_##name(json_t *, json_t *, char *, size_t);                                     \
    extern const char agvcalc_fields_##name[];
AGVCALC_OPS(DECLARE_OP)

static int agvcalc_op_version(json_t *, json_t *, char *, size_t);
static const char agvcalc_fields_version[] = "    (no fields)\n"
                                             "    -> version: the program's version (text)\n"
                                             "       ops: the names of the ops built in\n";

static const struct {
    const char *name;
    op_fn fn;
    const char *help;
    const char *fields;
} ops[] = {
#define TABLE_OP(name, help) {#name, agvcalc_op_##name, help, agvcalc_fields_##name},
    AGVCALC_OPS(TABLE_OP){"version", agvcalc_op_version, "{} -> version, ops",
                          agvcalc_fields_version},
};
#define OP_COUNT (sizeof ops / sizeof ops[0])

static int agvcalc_op_version(json_t *req, json_t *resp, char *err, size_t errlen)
{
    (void)req;
    (void)err;
    (void)errlen;
    json_object_set_new(resp, "version", json_string(CY_VERSION));
    json_t *names = json_array();
    for (size_t i = 0; i < OP_COUNT; i++)
        json_array_append_new(names, json_string(ops[i].name));
    json_object_set_new(resp, "ops", names);
    return 0;
}

void agvcalc_usage(FILE *f)
{
    fprintf(f, "usage: agvcalc [--help]\n"
               "Reads one JSON request per line on stdin, writes one JSON response per line.\n"
               "Every request has \"op\"; every response has \"ok\" (and \"error\" when false).\n"
               "Malformed or out-of-range input gets ok:false naming the value; the next line\n"
               "is still answered. Lines longer than 1 MiB are refused.\n"
               "Units: metres, seconds, degrees; angles counter-clockwise (headings from +x).\n"
               "Fields marked ? are optional.\n\nops:\n");
    for (size_t i = 0; i < OP_COUNT; i++)
        fprintf(f, "  %s  %s\n%s\n", ops[i].name, ops[i].help, ops[i].fields);
}

static char *dump(json_t *obj)
{
    return json_dumps(obj, JSON_COMPACT | JSON_PRESERVE_ORDER | JSON_REAL_PRECISION(12));
}

/* Replace every byte of @p s that is not part of a well-formed UTF-8 sequence with '?', in
 * place: error texts quote input cut to a length ("%.40s"), which can split a character, and
 * JSON strings must be valid UTF-8 (jansson refuses them otherwise). */
static void utf8_repair(char *s)
{
    unsigned char *p = (unsigned char *)s;
    while (*p) {
        unsigned c = *p, n = c < 0x80                 ? 0
                             : c >= 0xC2 && c <= 0xDF ? 1
                             : c >= 0xE0 && c <= 0xEF ? 2
                             : c >= 0xF0 && c <= 0xF4 ? 3
                                                      : 4;
        unsigned long cp = n == 1 ? c & 0x1Fu : n == 2 ? c & 0x0Fu : c & 0x07u;
        unsigned k = 1;
        while (n < 4 && k <= n && (p[k] & 0xC0u) == 0x80u)
            cp = cp << 6 | (p[k++] & 0x3Fu);
        bool good = n == 0 || (n < 4 && k == n + 1 && !(n == 2 && cp < 0x800) &&
                               !(n == 3 && (cp < 0x10000 || cp > 0x10FFFF)) &&
                               !(cp >= 0xD800 && cp <= 0xDFFF));
        if (!good) {
            *p++ = '?';
            continue;
        }
        p += n + 1;
    }
}

static char *failure(const char *msg)
{
    char text[512];
    snprintf(text, sizeof text, "%s", msg);
    utf8_repair(text);
    json_t *r = json_object();
    json_object_set_new(r, "ok", json_false());
    json_object_set_new(r, "error", json_string(text));
    char *s = dump(r);
    json_decref(r);
    return s;
}

/* The op's answer: resp with "ok":true first, or "ok":false, "error" and whatever details the
 * op attached to resp (e.g. "candidates"). */
static char *run_op(size_t i, json_t *req)
{
    json_t *resp = json_object();
    json_object_set_new(resp, "ok", json_true());
    char err[512] = "";
    char *s;
    if (ops[i].fn(req, resp, err, sizeof err) == 0) {
        s = dump(resp);
    } else {
        json_t *fail = json_object();
        json_object_set_new(fail, "ok", json_false());
        utf8_repair(err);
        json_object_set_new(fail, "error", json_string(err[0] ? err : "failed"));
        const char *k;
        json_t *v;
        json_object_foreach(resp, k, v)
        {
            if (strcmp(k, "ok") != 0)
                json_object_set(fail, k, v);
        }
        s = dump(fail);
        json_decref(fail);
    }
    json_decref(resp);
    return s;
}

char *agvcalc_answer(const char *line, size_t len)
{
    if (len == 0)
        return failure("empty request line");
    if (len > AGVCALC_MAX_LINE)
        return failure("request line longer than 1 MiB");
    json_error_t jerr;
    json_t *req = json_loadb(line, len, JSON_REJECT_DUPLICATES, &jerr);
    if (!req) {
        char msg[256];
        snprintf(msg, sizeof msg, "malformed JSON at column %d: %s", jerr.column, jerr.text);
        return failure(msg);
    }
    char *s;
    const char *op = json_string_value(json_object_get(req, "op"));
    if (!json_is_object(req)) {
        s = failure("a request must be a JSON object");
    } else if (!op) {
        s = failure("missing \"op\" (a string)");
    } else {
        size_t i = 0;
        while (i < OP_COUNT && strcmp(op, ops[i].name) != 0)
            i++;
        if (i < OP_COUNT) {
            s = run_op(i, req);
        } else {
            char msg[256];
            size_t n = (size_t)snprintf(msg, sizeof msg, "unknown op \"%.40s\"; known:", op);
            for (size_t k = 0; k < OP_COUNT && n < sizeof msg; k++)
                n += (size_t)snprintf(msg + n, sizeof msg - n, " %s", ops[k].name);
            s = failure(msg);
        }
    }
    json_decref(req);
    return s;
}
