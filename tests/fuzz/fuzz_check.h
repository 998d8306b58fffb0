/*
 * fuzz_check.h - what the libFuzzer harnesses share (docs/fuzzing.md): the entry point's
 * declaration and FUZZ_CHECK, which turns a broken property into a finding (a message on
 * stderr, then abort(): libFuzzer keeps the input as crash-<sha1>).
 */
#ifndef FUZZ_CHECK_H
#define FUZZ_CHECK_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

/** The harness: one input, 0 always (a finding aborts). */
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/** Abort with "fuzz check failed: <message>" when @p cond is false. */
#define FUZZ_CHECK(cond, ...)                                                                      \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            fprintf(stderr, "fuzz check failed (%s:%d): ", __FILE__, __LINE__);                    \
            fprintf(stderr, __VA_ARGS__);                                                          \
            fputc('\n', stderr);                                                                   \
            abort();                                                                               \
        }                                                                                          \
    } while (0)

#endif
