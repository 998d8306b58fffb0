/*
 * gnav_internal.h - what the groundnav sources share (not part of the API): formats, small
 * helpers and the functions one file provides to another. gnav.c's sections became the files
 * gnav_dr.c (the dl handler), gnav_arc.c (arc closing), gnav_gyro.c (gyro handlers),
 * gnav_cell.c (the heading inside the cell), gnav_latch.c (latches), gnav_coord.c (coordinate
 * request, pose readers), gnav_fix.c (fixes and frames) and gnav_init.c (set-up, accessors).
 *
 * Formats inside:
 *  - positions: int64 in odometer pulses, Q25 (the dl handler adds the cell's unit vector in
 *    Q25 per pulse, so a straight run accumulates exactly n times the same step: the only
 *    drift is the step's rounding, 2^-26 pulse per pulse, 1.5 um per 100 m);
 *  - deficits (E, D, delta): int32 pulses Q16, applied in Q10 with the rounding carried to
 *    the next closing (so it never accumulates); deficit per pulse rho: Q15;
 *  - heading of the current gyro cell: a binary angle with 16 more fraction bits (the step is
 *    not a whole binary angle: 0.25 degrees is 2982616.18 LSB), published rounded;
 *  - latches and frame corrections: int32 pulses Q4 (8 um, +-34 km);
 *  - the outside world (gnav_pose_t): metres Q15.16.
 *
 * The handlers use 16 x 16 products only (the MSP430's multiplier), the dl handler's 64-bit
 * accumulations are kernels (gnav_arith.h); the one sin/cos per gyro edge is in the gyro
 * handler, which knows the new cell first. Nothing the coordinate request (NMI) runs
 * multiplies.
 */
#ifndef GROUNDNAV_GNAV_INTERNAL_H
#define GROUNDNAV_GNAV_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "fx/fx.h"
#include "gnav_arith.h"
#include "groundnav/gnav.h"

/** The working range of positions: +-30,000 m, metres Q16. */
#define GNAV_POS_LIMIT_Q16 (30000l * 65536l)

/* ------------------------------------------------------------------ small arithmetic */

static inline uint32_t gnav_umul16(uint16_t a, uint16_t b)
{
    return (uint32_t)a * (uint32_t)b;
}

static inline int32_t gnav_smul16(int16_t a, int16_t b)
{
    return (int32_t)a * (int32_t)b;
}

/* v (Q25 int64) to Q4 int32, rounded; |v| < 2^52. */
static inline int32_t gnav_q25_to_q4(int64_t v)
{
    uint64_t u = (uint64_t)v + (1ul << 20);
    uint32_t hi = (uint32_t)(u >> 32), lo = (uint32_t)u;
    return (int32_t)((hi << 11) | (lo >> 21));
}

/* Q1.30 to Q1.15, rounded, +1 saturating at 32767. */
static inline int16_t gnav_q30_to_q15(fx_q30_t v)
{
    /* (v + 2^14) >> 15 on the words (|v| <= 2^30: the result fits 16 bits but for +2^15) */
    uint32_t u = (uint32_t)v + (1u << 14);
    uint16_t hi = (uint16_t)(u >> 16), lo = (uint16_t)u;
    if ((int16_t)hi >= 0x4000)
        return 32767;
    return (int16_t)((uint16_t)(hi << 1) | ((int16_t)lo < 0 ? 1u : 0u));
}

/* Q1.30 to the per-pulse step in Q25, rounded: (v + 16) >> 5 on the words. */
static inline int32_t gnav_q30_to_q25(fx_q30_t v)
{
    uint32_t u = (uint32_t)v + 16u;
    uint16_t hi = (uint16_t)(u >> 16), lo = (uint16_t)u;
    uint16_t rl = (uint16_t)((uint16_t)(hi << 11) | (uint16_t)(lo >> 5));
    uint16_t rh = (uint16_t)((int16_t)hi >> 5);
    return (int32_t)(((uint32_t)rh << 16) | rl);
}

/* The heading inside the cell (gyro edge, readers): a one-step interval entered at @p rate
 * pulses per step (<= 2^15) that lasts longer than the rate plus 1/8 and 2 pulses (a steady
 * arc's intervals differ by a pulse) has seen its turn change. */
static inline uint16_t gnav_rate_limit(uint16_t rate)
{
    return (uint16_t)(rate + (rate >> 3) + 2u);
}

/* ... gnav_overdue: the one-step limit passed, or twice it for an excursion into the cell and back
 * (@p twice). */
static inline bool gnav_overdue(uint16_t pulses, uint16_t rate, bool twice)
{
    uint16_t limit = gnav_rate_limit(rate);
    if (pulses <= limit)
        return false;
    return !twice || (uint16_t)(pulses - limit) > limit;
}

/* Pulses since the interval's entry edge for a published k (1 .. 2^15): the edge came between
 * the pulse before P and P, a sighting comes between pulse k and the next (half a pulse
 * each, on average). */
static inline uint16_t gnav_pulses_since_edge(int16_t k)
{
    if (k == GNAV_K_EDGE)
        return 0;
    return (uint16_t)(k < 0 ? 1 - k : k + 1);
}

/* (v + 1) >> 1 for a 32-bit v, on its words (a 32-bit shift is long code on the MSP430). */
static inline int32_t gnav_half_up(uint32_t v)
{
    v += 1u;
    uint16_t hi = (uint16_t)(v >> 16), lo = (uint16_t)v;
    lo = (uint16_t)((lo >> 1) | ((hi & 1u) ? 0x8000u : 0u));
    return (int32_t)(((uint32_t)(uint16_t)(hi >> 1) << 16) | lo);
}

/* ------------------------------------------------------------------ between the files */

/** Fill the free slot of the published pose, then flip (gnav_dr.c). */
void gnav_publish(gnav_t *g);

/** The gyro left the interval's cell: close the arc at this pulse, whose step @p step it
 * applies (gnav_arc.c). */
void gnav_close_arc(gnav_t *g, const int32_t *step);

/** The deferred part of a closing, at the next pulse: the deficit per pulse and the curved
 * step of the new interval (gnav_dr.c). */
void gnav_finish_interval(gnav_t *g);

/** The heading's offset from its cell's centre (gnav_cell.c): see the definition. */
int32_t gnav_cell_offset(const gnav_t *g, int8_t dir, uint16_t rate, uint16_t a, uint16_t a_now,
                         int8_t exit, uint16_t len, uint16_t rate_out);

/** The offset of a published pose (its interval is open: the current one) (gnav_cell.c). */
int32_t gnav_pub_offset(const gnav_t *g, const gnav_pub_t *p);

/** Pulses Q4 to metres Q15.16, rounded, saturating (gnav_coord.c). */
fx_q16_t gnav_q4_to_m(const gnav_t *g, int32_t v);

/** Bring a Q4 pose of generation @p from forward to the current one (gnav_fix.c). */
int gnav_bring_forward(const gnav_t *g, uint8_t from, int32_t *x4, int32_t *y4, fx_angle_t *h);

/** Metres Q16 to pulses Q4 within the working range (gnav_fix.c). */
bool gnav_m_to_q4(const gnav_t *g, fx_q16_t v, int32_t *out);

/** v * 2^n and round(v / 2^n) (ties up), 1 <= n < 32 (gnav_fix.c). */
int64_t gnav_shl64(int64_t v, uint8_t n);
int64_t gnav_sar64r(int64_t v, uint8_t n);

/** Count the stop distance down from now (gnav_init.c). */
void gnav_arm_stop(gnav_t *g);

#endif
