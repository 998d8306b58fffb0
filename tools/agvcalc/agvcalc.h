/*
 * agvcalc.h - agvcalc's request handling (agvcalc.c) and the interface to its ops.
 *
 * agvcalc_answer() turns one request line into one response line, in process: main.c loops
 * over stdin with it, the fuzz harness (tests/fuzz/agvcalc_fuzz.c) calls it directly. It
 * keeps no state between calls.
 *
 * An op is `int agvcalc_op_<name>(json_t *req, json_t *resp, char *err, size_t errlen)`:
 * it reads the request object, fills @p resp (without "ok") and returns 0, or writes a
 * readable reason into @p err and returns -1. The loop adds "ok" and prints the line. Ops run
 * the firmware's own fixed-point code; doubles appear only at this boundary (fx_host.h).
 * Each op source also defines `const char agvcalc_fields_<name>[]`: its fields with their
 * units, one per line, for --help.
 *
 * The ac_* readers (jsonval.h) validate as they read: a missing key, a wrong type, a value
 * out of range or not finite becomes an error that names the key (with its path) and the
 * value.
 */
#ifndef AGVCALC_H
#define AGVCALC_H

#include <jansson.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "jsonval.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Longest request line answered, in bytes (without its line end). */
#define AGVCALC_MAX_LINE (1u << 20)

/**
 * The response to one request line: @p len bytes at @p line, without the line end (a NUL byte
 * inside is malformed JSON). Returns one JSON object on one line, without a newline, in
 * malloc()ed memory the caller frees; NULL only when memory runs out. Every response has
 * "ok", and "error" when it is false.
 */
char *agvcalc_answer(const char *line, size_t len);

/** The --help text: usage, units, and every op with its fields. */
void agvcalc_usage(FILE *f);

#ifdef __cplusplus
}
#endif

#endif
