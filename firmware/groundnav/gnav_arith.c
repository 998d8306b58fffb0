/*
 * gnav_arith.c - portable definitions of gnav_arith.h (the host build; the MSP430 build
 * assembles msp430/gnav_arith.S instead, GNAV_ASM).
 */
#include "gnav_arith.h"

#ifndef GNAV_ASM
void gnav_add64(int64_t *acc, int32_t v)
{
    *acc = (int64_t)((uint64_t)*acc + (uint64_t)(int64_t)v);
}

void gnav_mac64(int64_t *acc, int16_t a, int16_t b)
{
    int32_t p = (int32_t)a * (int32_t)b;
    *acc = (int64_t)((uint64_t)*acc + (uint64_t)(int64_t)p);
}
#endif
