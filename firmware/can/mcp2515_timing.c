/*
 * mcp2515_timing.c - the MCP2515's bit timing registers for the oscillators and bit rates the
 * boards use (DS20001801 section 5): TQ = 2 (BRP + 1) / Fosc; a bit is SyncSeg (1 TQ) +
 * PropSeg + PS1 + PS2 with PropSeg 1-8, PS1 1-8, PS2 2-8 TQ, PropSeg + PS1 >= PS2 and
 * PS2 > SJW; the sample point lies at the end of PS1. CNF1 = (SJW - 1) << 6 | BRP;
 * CNF2 = BTLMODE | (PS1 - 1) << 3 | (PropSeg - 1) (PS2 from CNF3, one sample per bit);
 * CNF3 = PS2 - 1 (SOF and WAKFIL off).
 *
 * Each entry is exact (Fosc / (2 (BRP + 1) N) = the bit rate) with 16 or 20 TQ a bit where
 * the prescaler allows, SJW = 1 TQ and the sample point as late as the rules allow up to
 * 87.5 % (CiA 301's recommendation), never before 75 %: a bit of 8 TQ (1 Mbit/s from 16 MHz,
 * 500 kbit/s from 8 MHz) puts it at 75 %, one of 10 TQ at 80 %. The rates are CiA 301's
 * (10, 20, 50, 125, 250, 500, 800 kbit/s, 1 Mbit/s) where an exact timing exists: from 8 MHz
 * neither 800 kbit/s nor 1 Mbit/s (5 and 4 TQ a bit), from 20 MHz not 800 kbit/s (12.5 TQ).
 * tests/unit/mcp2515_test.cpp checks every entry with the data sheet's formulas and that no
 * missing pair has a timing within these rules.
 */
#include <stddef.h>

#include "can/mcp2515.h"

typedef struct {
    uint8_t osc_mhz;
    uint16_t kbps;
    uint8_t brp;  /* 0..63 */
    uint8_t prop; /* PropSeg, TQ */
    uint8_t ps1;  /* TQ */
    uint8_t ps2;  /* TQ */
} timing_t;

static const timing_t table[] = {
    /* Fosc kbit/s BRP Prop PS1 PS2      N   sample point */
    {8, 10, 24, 5, 8, 2},   /* 16 TQ, 87.5 % */
    {8, 20, 9, 8, 8, 3},    /* 20 TQ, 85 %   */
    {8, 50, 4, 5, 8, 2},    /* 16 TQ, 87.5 % */
    {8, 125, 1, 5, 8, 2},   /* 16 TQ, 87.5 % */
    {8, 250, 0, 5, 8, 2},   /* 16 TQ, 87.5 % */
    {8, 500, 0, 2, 3, 2},   /*  8 TQ, 75 %   */
    {16, 10, 49, 5, 8, 2},  /* 16 TQ, 87.5 % */
    {16, 20, 24, 5, 8, 2},  /* 16 TQ, 87.5 % */
    {16, 50, 9, 5, 8, 2},   /* 16 TQ, 87.5 % */
    {16, 125, 3, 5, 8, 2},  /* 16 TQ, 87.5 % */
    {16, 250, 1, 5, 8, 2},  /* 16 TQ, 87.5 % */
    {16, 500, 0, 5, 8, 2},  /* 16 TQ, 87.5 % */
    {16, 800, 0, 3, 4, 2},  /* 10 TQ, 80 %   */
    {16, 1000, 0, 2, 3, 2}, /*  8 TQ, 75 %   */
    {20, 10, 49, 8, 8, 3},  /* 20 TQ, 85 %   */
    {20, 20, 24, 8, 8, 3},  /* 20 TQ, 85 %   */
    {20, 50, 9, 8, 8, 3},   /* 20 TQ, 85 %   */
    {20, 125, 4, 5, 8, 2},  /* 16 TQ, 87.5 % */
    {20, 250, 1, 8, 8, 3},  /* 20 TQ, 85 %   */
    {20, 500, 0, 8, 8, 3},  /* 20 TQ, 85 %   */
    {20, 1000, 0, 3, 4, 2}, /* 10 TQ, 80 %   */
};

#define CNF2_BTLMODE 0x80u

int mcp2515_bit_timing(uint32_t osc_hz, uint32_t bitrate_bps, mcp2515_cnf_t *out)
{
    if (out == NULL)
        return MCP2515_ERR_ARG;
    for (size_t i = 0; i < sizeof table / sizeof table[0]; i++) {
        const timing_t *t = &table[i];
        if (osc_hz != (uint32_t)t->osc_mhz * 1000000ul || bitrate_bps != (uint32_t)t->kbps * 1000ul)
            continue;
        out->cnf1 = t->brp; /* SJW = 1 TQ */
        out->cnf2 = (uint8_t)(CNF2_BTLMODE | (uint8_t)((t->ps1 - 1u) << 3) | (t->prop - 1u));
        out->cnf3 = (uint8_t)(t->ps2 - 1u);
        return MCP2515_OK;
    }
    return MCP2515_ERR_ARG;
}
