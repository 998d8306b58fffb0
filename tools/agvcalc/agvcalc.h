/*
 * agvcalc.h - the interface between agvcalc's JSON Lines loop (main.c) and its ops.
 *
 * An op is `int agvcalc_op_<name>(json_t *req, json_t *resp, char *err, size_t errlen)`:
 * it reads the request object, fills @p resp (without "ok") and returns 0, or writes a
 * readable reason into @p err and returns -1. The loop adds "ok" and prints the line. Ops run
 * the firmware's own fixed-point code; doubles appear only at this boundary (fx_host.h).
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

#include "jsonval.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifdef __cplusplus
}
#endif

#endif
