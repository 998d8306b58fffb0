/*
 * fx_host.h - conversions between the fixed-point formats and double, for host code only
 * (tests, agvcalc, the simulator). Never included by firmware: the MSP430 has no FPU.
 */
#ifndef FX_FX_HOST_H
#define FX_FX_HOST_H

#ifdef __MSP430__
#error "fx_host.h is host-only"
#endif

#include <math.h>
#include <stdint.h>

#include "fx/fx.h"

static inline double fx_angle_to_deg(fx_angle_t a)
{
    return (double)a * (360.0 / 4294967296.0);
}

/** Signed view, (-180, 180]. */
static inline double fx_angle_to_deg_signed(fx_angle_t a)
{
    return (double)(int32_t)a * (360.0 / 4294967296.0);
}

static inline double fx_angle_to_rad(fx_angle_t a)
{
    return (double)a * (2.0 * M_PI / 4294967296.0);
}

/** Any degrees (wrapped to one turn), rounded to the nearest binary angle. */
static inline fx_angle_t fx_angle_from_deg(double deg)
{
    double turns = deg / 360.0;
    turns -= floor(turns);
    return (fx_angle_t)(uint64_t)llround(turns * 4294967296.0);
}

static inline fx_angle_t fx_angle_from_rad(double rad)
{
    return fx_angle_from_deg(rad * (180.0 / M_PI));
}

static inline double fx_q30_to_double(fx_q30_t v)
{
    return (double)v / 1073741824.0;
}

static inline double fx_q16_to_double(fx_q16_t v)
{
    return (double)v / 65536.0;
}

/** Metres (or any Q16 quantity) to Q16.16, rounded; the caller keeps |v| < 32768. */
static inline fx_q16_t fx_q16_from_double(double v)
{
    return (fx_q16_t)llround(v * 65536.0);
}

#endif
