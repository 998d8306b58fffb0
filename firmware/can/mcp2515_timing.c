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
 * 87.5 % (CiA 301's recommendation); at 8 MHz and 500 kbit/s a bit has only 8 TQ, which puts
 * it at 75 %. tests/unit/mcp2515_test.cpp checks every entry with the data sheet's formulas.
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
    /* Fosc kbit/s  BRP Prop PS1 PS2     N   sample point */
    {8, 125, 1, 5, 8, 2},  /* 16 TQ, 87.5 % */
    {8, 250, 0, 5, 8, 2},  /* 16 TQ, 87.5 % */
    {8, 500, 0, 2, 3, 2},  /*  8 TQ, 75 %   */
    {16, 125, 3, 5, 8, 2}, /* 16 TQ, 87.5 % */
    {16, 250, 1, 5, 8, 2}, /* 16 TQ, 87.5 % */
    {16, 500, 0, 5, 8, 2}, /* 16 TQ, 87.5 % */
    {20, 125, 4, 5, 8, 2}, /* 16 TQ, 87.5 % */
    {20, 250, 1, 8, 8, 3}, /* 20 TQ, 85 %   */
    {20, 500, 0, 8, 8, 3}, /* 20 TQ, 85 %   */
};

#define CNF2_BTLMODE 0x80u

int mcp2515_bit_timing(uint32_t osc_hz, uint32_t bitrate_bps, mcp2515_cnf_t *out)
{
    if (out == NULL)
        return MCP2515_ERR_ARG;
    for (size_t i = 0; i < sizeof table / sizeof table[0]; i++) {
        const timing_t *t = &table[i];
        if (osc_hz != (uint32_t)t->osc_mhz * 1000000ul ||
            bitrate_bps != (uint32_t)t->kbps * 1000ul)
            continue;
        out->cnf1 = t->brp; /* SJW = 1 TQ */
        out->cnf2 = (uint8_t)(CNF2_BTLMODE | (uint8_t)((t->ps1 - 1u) << 3) | (t->prop - 1u));
        out->cnf3 = (uint8_t)(t->ps2 - 1u);
        return MCP2515_OK;
    }
    return MCP2515_ERR_ARG;
}
