/*
 * pose.c - following a segment: drive_pose_advance() and drive_radius_of() (drive.h).
 *
 * Along an arc of curvature k the heading changes by delta = s k over a length s, and the
 * point moves along the chord: length s sin(delta / 2) / (delta / 2), in the direction of
 * travel turned by delta / 2 (a straight is the limit delta = 0).
 */
#include "drive/drive.h"
#include "drive_math.h"

/* 8 / pi - 2 in Q30: r * 8 / pi = 2 r + r (8 / pi - 2) turns radians Q28 into a binary angle. */
#define RAD_Q28_TO_ANGLE   586777454l
/* Below this half change (0.2 rad, Q28) sin x / x comes from its series. */
#define HALF_CHANGE_SERIES 53687091l

/* Series coefficients (drive_series()): sin x / x for |x| <= 0.2 rad. */
static const int32_t sin_over_x[3] = {-178956971l, 8947849l, -213044l}; /* -1/6, 1/120, -1/5040 */

/* A change in radians Q28 as a binary angle (error below 1.5 LSB, wrapping). */
static fx_angle_t angle_of(int32_t rad28)
{
    return (fx_angle_t)rad28 * 2u + (fx_angle_t)fx_mul_q30(rad28, RAD_Q28_TO_ANGLE);
}

drive_pose_t drive_pose_advance(const drive_pose_t *pose, int32_t curvature, fx_q16_t dist,
                                bool reverse)
{
    drive_pose_t r = *pose;
    if (dist <= 0)
        return r;
    /* The heading change delta = dist * curvature (negated when reversing), radians Q28,
     * saturating far beyond any arc of the solver, and its half. */
    int32_t delta;
    if (!fx_mul_shift(dist, curvature, 16, &delta))
        delta = curvature >= 0 ? INT32_MAX : -INT32_MAX;
    if (reverse)
        delta = -delta;
    int32_t half = delta / 2;
    fx_angle_t half_angle = angle_of(half);
    /* The chord: dist * sin(half) / half (Q30; negative beyond half a turn: it points back). */
    int32_t ratio;
    if (drive_abs32(half) < (uint32_t)HALF_CHANGE_SERIES)
        ratio = drive_series(half * 4, sin_over_x);
    else
        (void)fx_div_shift(fx_sin(half_angle), half, 28, &ratio);
    int32_t chord = fx_mul_q30(dist, ratio);
    /* ... along the direction of travel turned by the half change. */
    fx_q30_t s, c;
    fx_sincos(pose->heading + (reverse ? FX_ANGLE_HALF : 0u) + half_angle, &s, &c);
    r.x += fx_mul_q30(chord, c);
    r.y += fx_mul_q30(chord, s);
    r.heading += angle_of(delta);
    return r;
}

fx_q16_t drive_radius_of(int32_t curvature)
{
    if (curvature == 0)
        return 0;
    uint32_t a = drive_abs32(curvature);
    int32_t r; /* 2^28 / k metres = 2^44 / k in Q16 */
    if (!fx_recip((int32_t)a, 44, &r))
        r = INT32_MAX;
    return curvature < 0 ? -r : r;
}
