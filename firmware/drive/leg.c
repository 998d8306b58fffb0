/*
 * leg.c - the nominal leg between two prescribed poses (drive_path.h, drive_leg_solve()):
 * the solver's double arc, or for a heading change over 90 degrees (SPEC B4, D9) two double
 * arcs through one inserted pose.
 *
 * A turn by Delta in (90, 180] degrees is driven as one corner: a straight along A, an arc
 * of radius R turning by Delta, a straight along B (either straight may be empty). In the
 * frame of the direction of travel at the start, turning left (a right turn is mirrored),
 * with the target E = (ex, ey), the corner's arc starts at (cx, 0) with its centre at
 * (cx, R) and ends at (cx + R sin Delta, R (1 - cos Delta)), from where the straight of
 * length s along B reaches E:
 *     ey                          = R (1 - cos Delta) + s sin Delta
 *     ex sin Delta - ey cos Delta = R (1 - cos Delta) + cx sin Delta
 * (the second is E x B). Both straights are >= 0 for every R up to
 *     R_max = min(A x E, E x B) / (1 - cos Delta) = min(ey, ex sin Delta - ey cos Delta)
 *                                                   / (2 sin^2(Delta / 2)),
 * the largest corner that fits, which is the one taken (the gentlest turn: the solver, too,
 * prefers the single arc of cases 4/5 whenever it is wide enough). At R = R_max one straight
 * is empty and the other is |cx - s| with cx - s = ex - ey cot(Delta / 2): no division by
 * sin Delta, so the half turn (Delta = 180 degrees, the U-turn at an aisle end, where
 * R_max = ey / 2 and cx = max(ex, 0)) is the same formula. The inserted pose is the corner's
 * middle, M = (cx + R sin(Delta/2), R (1 - cos(Delta/2))) heading Delta / 2: from the start
 * to M is a straight and an arc (case 5, or a single arc), from M to the target an arc and a
 * straight (case 4), each turning Delta / 2 <= 90 degrees with radius R, so the solver takes
 * both. A corner that does not fit the nominal radius (R_max below it; R_max <= 0 when the
 * target does not lie on the inside of the turn) is refused (DRIVE_ERR_TURN).
 */
#include <stddef.h>

#include "drive/drive_path.h"
#include "drive_math.h"

/* The inserted pose of a turn over 90 degrees from @p from to @p to (see above). */
static drive_status_t turn_via(const drive_pose_t *from, const drive_pose_t *to, fx_q16_t radius,
                               bool reverse, drive_pose_t *via)
{
    /* E in the frame of the direction of travel (Q16 m); the legs it splits into are each
     * within the solver's 64 m, so no coordinate difference beyond 128 m is needed. */
    int32_t dx = (int32_t)((uint32_t)to->x - (uint32_t)from->x);
    int32_t dy = (int32_t)((uint32_t)to->y - (uint32_t)from->y);
    if (((to->x ^ from->x) & (to->x ^ dx)) < 0 || ((to->y ^ from->y) & (to->y ^ dy)) < 0 ||
        drive_abs32(dx) > 2u * (uint32_t)DRIVE_MAX_DIST ||
        drive_abs32(dy) > 2u * (uint32_t)DRIVE_MAX_DIST)
        return DRIVE_ERR_TOO_FAR;
    fx_angle_t travel = from->heading + (reverse ? FX_ANGLE_HALF : 0u);
    int32_t ex, ey;
    drive_to_frame(dx, dy, travel, &ex, &ey);

    /* The turn Delta to the left: a right turn is mirrored, and so is a half turn with the
     * target on the right. */
    int32_t dl = (int32_t)(to->heading - from->heading);
    bool right = dl == INT32_MIN ? ey < 0 : dl < 0;
    fx_angle_t delta = right ? 0u - (fx_angle_t)dl : (fx_angle_t)dl, half = delta / 2u;
    if (right)
        ey = -ey;
    fx_q30_t sd, cd, sh, ch;
    fx_sincos(delta, &sd, &cd);
    fx_sincos(half, &sh, &ch);

    /* The largest corner: R = min(A x E, E x B) / (2 sin^2(Delta / 2)), Q16 m. */
    int32_t exb = fx_mul_q30(ex, sd) - fx_mul_q30(ey, cd), m = ey < exb ? ey : exb, r;
    if (m <= 0 || !fx_div_shift(m, fx_mul_q30(sh, sh), 29, &r) || r < radius)
        return DRIVE_ERR_TURN;

    /* The straight before the arc: cx = max(ex - ey cot(Delta / 2), 0) (sin(Delta/2) >= 0.7). */
    int32_t ey_cot;
    (void)fx_div_shift(fx_mul_q30(ey, ch), sh, 30, &ey_cot);
    int32_t cx = ex - ey_cot > 0 ? ex - ey_cot : 0;

    /* The corner's middle, back in the world. */
    int32_t mx = cx + fx_mul_q30(r, sh), my = r - fx_mul_q30(r, ch), wx, wy;
    drive_to_frame(mx, right ? -my : my, 0u - travel, &wx, &wy);
    via->x = from->x + wx;
    via->y = from->y + wy;
    via->heading = from->heading + (right ? 0u - half : half);
    return DRIVE_OK;
}

drive_status_t drive_leg_solve(const drive_pose_t *from, const drive_pose_t *to, fx_q16_t radius,
                               bool reverse, drive_leg_t *leg)
{
    if (from == NULL || to == NULL || leg == NULL || radius < DRIVE_MIN_RADIUS_MIN ||
        radius > DRIVE_MIN_RADIUS_MAX)
        return DRIVE_ERR_PARAM;
    int32_t dl = (int32_t)(to->heading - from->heading);
    if (dl <= (int32_t)FX_ANGLE_QUARTER && dl >= -(int32_t)FX_ANGLE_QUARTER) {
        leg->parts = 1;
        return drive_solve(from, to, radius, reverse, &leg->sol[0], NULL);
    }
    leg->parts = 2;
    drive_status_t st = turn_via(from, to, radius, reverse, &leg->via);
    if (st == DRIVE_OK)
        st = drive_solve(from, &leg->via, radius, reverse, &leg->sol[0], NULL);
    if (st == DRIVE_OK)
        st = drive_solve(&leg->via, to, radius, reverse, &leg->sol[1], NULL);
    return st;
}
