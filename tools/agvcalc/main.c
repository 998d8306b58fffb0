/*
 * agvcalc - the firmware's own algorithms on the host, as JSON Lines.
 *
 * One request object per input line on stdin, one response per line on stdout, in order.
 * Every response has "ok"; when false it has "error". Malformed or out-of-range input gets
 * ok:false and the next line is still answered. The ops are listed by --help; their formats
 * are in ../../../shared/CONTRACT.md and the README.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "agvcalc.h"
#include "agvcalc_ops.h" /* generated: AGVCALC_OPS(X) lists the ops built in */

typedef int (*op_fn)(json_t *, json_t *, char *, size_t);

#define DECLARE_OP(name, help) int agvcalc_op_##name(json_t *, json_t *, char *, size_t);
AGVCALC_OPS(DECLARE_OP)

static int agvcalc_op_version(json_t *, json_t *, char *, size_t);

static const struct {
    const char *name;
    op_fn fn;
    const char *help;
} ops[] = {
#define TABLE_OP(name, help) {#name, agvcalc_op_##name, help},
    AGVCALC_OPS(TABLE_OP){"version", agvcalc_op_version, "{} -> the version and the ops built in"},
};

static int agvcalc_op_version(json_t *req, json_t *resp, char *err, size_t errlen)
{
    (void)req;
    (void)err;
    (void)errlen;
    json_object_set_new(resp, "version", json_string(CY_VERSION));
    json_t *names = json_array();
    for (size_t i = 0; i < sizeof ops / sizeof ops[0]; i++)
        json_array_append_new(names, json_string(ops[i].name));
    json_object_set_new(resp, "ops", names);
    return 0;
}

#define MAX_LINE (1u << 20)

static void usage(FILE *f)
{
    fprintf(f, "usage: agvcalc [--help]\n"
               "Reads one JSON request per line on stdin, writes one JSON response per line.\n"
               "Every request has \"op\"; every response has \"ok\" (and \"error\" when false).\n"
               "Units: metres, seconds, degrees; angles counter-clockwise.\n\nops:\n");
    for (size_t i = 0; i < sizeof ops / sizeof ops[0]; i++)
        fprintf(f, "  %-12s %s\n", ops[i].name, ops[i].help);
}

static void reply_error(const char *msg)
{
    json_t *r = json_object();
    json_object_set_new(r, "ok", json_false());
    json_object_set_new(r, "error", json_string(msg));
    char *s = json_dumps(r, JSON_COMPACT | JSON_PRESERVE_ORDER);
    puts(s ? s : "{\"ok\":false,\"error\":\"out of memory\"}");
    free(s);
    json_decref(r);
}

static void handle(const char *line)
{
    json_error_t jerr;
    json_t *req = json_loads(line, JSON_REJECT_DUPLICATES, &jerr);
    if (!req) {
        char msg[256];
        snprintf(msg, sizeof msg, "malformed JSON at column %d: %s", jerr.column, jerr.text);
        reply_error(msg);
        return;
    }
    if (!json_is_object(req)) {
        reply_error("a request must be a JSON object");
        json_decref(req);
        return;
    }
    const char *op = json_string_value(json_object_get(req, "op"));
    if (!op) {
        reply_error("missing \"op\" (a string)");
        json_decref(req);
        return;
    }
    for (size_t i = 0; i < sizeof ops / sizeof ops[0]; i++) {
        if (strcmp(op, ops[i].name) != 0)
            continue;
        json_t *resp = json_object();
        json_object_set_new(resp, "ok", json_true());
        char err[512] = "";
        if (ops[i].fn(req, resp, err, sizeof err) == 0) {
            char *s =
                json_dumps(resp, JSON_COMPACT | JSON_PRESERVE_ORDER | JSON_REAL_PRECISION(12));
            puts(s);
            free(s);
        } else {
            json_t *fail = json_object();
            json_object_set_new(fail, "ok", json_false());
            json_object_set_new(fail, "error", json_string(err[0] ? err : "failed"));
            /* An op may attach details (e.g. "candidates") to resp on failure. */
            const char *k;
            json_t *v;
            json_object_foreach(resp, k, v)
            {
                if (strcmp(k, "ok") != 0)
                    json_object_set(fail, k, v);
            }
            char *s =
                json_dumps(fail, JSON_COMPACT | JSON_PRESERVE_ORDER | JSON_REAL_PRECISION(12));
            puts(s);
            free(s);
            json_decref(fail);
        }
        json_decref(resp);
        json_decref(req);
        return;
    }
    char msg[256];
    size_t n = (size_t)snprintf(msg, sizeof msg, "unknown op \"%.40s\"; known:", op);
    for (size_t i = 0; i < sizeof ops / sizeof ops[0] && n < sizeof msg; i++)
        n += (size_t)snprintf(msg + n, sizeof msg - n, " %s", ops[i].name);
    reply_error(msg);
    json_decref(req);
}

int main(int argc, char **argv)
{
    if (argc > 1) {
        if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
            usage(stdout);
            return 0;
        }
        fprintf(stderr, "agvcalc: unknown argument %s\n", argv[1]);
        usage(stderr);
        return 2;
    }
    char *line = NULL;
    size_t cap = 0;
    ssize_t len;
    while ((len = getline(&line, &cap, stdin)) != -1) {
        while (len > 0 && (line[len - 1] == '\n' || line[len - 1] == '\r'))
            line[--len] = '\0';
        if (len == 0)
            reply_error("empty request line");
        else if ((size_t)len > MAX_LINE)
            reply_error("request line longer than 1 MiB");
        else
            handle(line);
        fflush(stdout);
    }
    free(line);
    return 0;
}
