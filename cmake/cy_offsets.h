/*
 * cy_offsets.h - the marker macro of the generated assembly offsets (docs/kernels.md).
 *
 * A module's msp430/M_offsets.c includes this and its own headers and lists, inside one
 * non-static function, what its assembly needs:
 *
 *     void gnav_offsets(void);
 *     void gnav_offsets(void)
 *     {
 *         CY_OFFSET(GNAV_X, offsetof(gnav_t, x));
 *         CY_OFFSET(GNAV_SIZE, sizeof(gnav_t));
 *     }
 *
 * cy_asm_offsets() (cmake/cyclopion.cmake) compiles it for the MSP430 with -S, and
 * tools/gen_asm_offsets.py turns each marker into `#define GNAV_X 0` of the generated header
 * the .S files include. The function is never linked: only its assembly text is read.
 */
#ifndef CY_OFFSETS_H
#define CY_OFFSETS_H

#include <stddef.h>

/** Emit the marker "->SYM value" (value: an integer constant expression). */
#define CY_OFFSET(sym, value)                                                                      \
    __asm__ volatile("\n.ascii \"->" #sym " %0\"" : : "i"((long long)(value)))

#endif
