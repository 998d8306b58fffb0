/*
 * agvcalc_fuzz.c - agvcalc's request lines (tools/agvcalc: agvcalc_answer(), every op), the
 * whole path from a line to its response, in process.
 *
 * The input is split into lines as agvcalc's main loop splits stdin (a trailing CR dropped);
 * each line is answered. Properties beyond memory safety, leaks (LeakSanitizer) and time
 * (libFuzzer's -timeout): every answer is one line of JSON, an object with a boolean "ok";
 * ok:false has a non-empty "error" string; ok:true has the keys its op promises (CONTRACT.md),
 * numbers where numbers are promised, headings in [0, 360) and positions within the
 * firmware's +-32768 m.
 */
#include <jansson.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "agvcalc.h"
#include "fuzz_check.h"

/* The keys an op's ok:true answer must have (numbers, or other JSON for those in "other"). */
static const struct {
    const char *op;
    const char *numbers[4];
    const char *other[3];
} promises[] = {
    {"triangulate", {"x", "y", "heading_deg", "quality"}, {NULL}},
    {"fix", {"x", "y", "heading_deg", "quality"}, {"used", "identified", "widened"}},
    {"reflectors3", {"x", "y", "heading_deg", "quality"}, {"first"}},
    {"doublearc", {NULL}, {"case", "segments", "steering_deg"}},
    {"deadreckon", {"x", "y", "heading_deg"}, {NULL}},
    {"posrx", {"resyncs", "skipped_bytes", "trailing_bytes"}, {"positions"}},
    {"version", {NULL}, {"version", "ops"}},
};

static void check_answer(const char *line, size_t len, const char *answer)
{
    FUZZ_CHECK(answer != NULL, "no answer (out of memory?)");
    FUZZ_CHECK(strchr(answer, '\n') == NULL, "answer spans lines: %s", answer);
    json_error_t jerr;
    json_t *a = json_loads(answer, 0, &jerr);
    FUZZ_CHECK(a != NULL, "answer is not JSON (%s): %s", jerr.text, answer);
    FUZZ_CHECK(json_is_object(a), "answer is not an object: %s", answer);
    json_t *ok = json_object_get(a, "ok");
    FUZZ_CHECK(json_is_boolean(ok), "answer without a boolean \"ok\": %s", answer);
    if (json_is_false(ok)) {
        const char *e = json_string_value(json_object_get(a, "error"));
        FUZZ_CHECK(e != NULL && e[0] != '\0', "ok:false without an error: %s", answer);
    } else {
        json_t *req = json_loadb(line, len, 0, NULL);
        const char *op = json_string_value(json_object_get(req, "op"));
        FUZZ_CHECK(op != NULL, "ok:true for a request without an op: %s", answer);
        for (size_t i = 0; i < sizeof promises / sizeof promises[0]; i++) {
            if (strcmp(op, promises[i].op) != 0)
                continue;
            for (size_t k = 0; k < 4 && promises[i].numbers[k]; k++) {
                json_t *v = json_object_get(a, promises[i].numbers[k]);
                FUZZ_CHECK(json_is_number(v), "%s: ok:true without the number \"%s\": %s", op,
                           promises[i].numbers[k], answer);
            }
            for (size_t k = 0; k < 3 && promises[i].other[k]; k++)
                FUZZ_CHECK(json_object_get(a, promises[i].other[k]) != NULL,
                           "%s: ok:true without \"%s\": %s", op, promises[i].other[k], answer);
        }
        /* CONTRACT.md: headings in [0, 360); positions the firmware can hold (Q15.16 metres) */
        json_t *h = json_object_get(a, "heading_deg");
        if (h)
            FUZZ_CHECK(json_number_value(h) >= 0.0 && json_number_value(h) < 360.0,
                       "%s: heading_deg outside [0, 360): %s", op, answer);
        for (const char *const *k = (const char *const[]){"x", "y", NULL}; *k; k++) {
            json_t *v = json_object_get(a, *k);
            if (v)
                FUZZ_CHECK(fabs(json_number_value(v)) < 32768.0,
                           "%s: %s outside the firmware's range of +-32768 m: %s", op, *k, answer);
        }
        json_decref(req);
    }
    json_decref(a);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *p = (const char *)data, *end = p + size;
    while (p < end) {
        const char *nl = memchr(p, '\n', (size_t)(end - p));
        size_t len = (size_t)((nl ? nl : end) - p);
        while (len > 0 && p[len - 1] == '\r')
            len--;
        char *answer = agvcalc_answer(p, len);
        check_answer(p, len, answer);
        free(answer);
        p = nl ? nl + 1 : end;
    }
    return 0;
}
