/*
 * solve.c - the double-arc solver (drive.h; derivations in docs/drive.md).
 *
 * The problem is solved in the frame of the mean heading u = A rotated by eta = (B - A) / 2,
 * where the target E = (p, q) (p along u, q to the left of u). In that frame every case has
 * a closed form (docs/drive.md):
 *  - arc + straight (cases 4, 5): straight length l = |q| / sin eta, arc chord along u of
 *    length Lc = p - l cos eta, radius Lc / (2 sin eta), sweep 2 eta;
 *  - double arc of equal radii (cases 1, 2, 3): curvature k = 2 X / |E|^2 with
 *    X = sqrt(q^2 + (p sin eta)^2) + |q| cos eta; the junction is J = E/2 + sigma rho u with
 *    rho = sin(eta) / k and sigma = sign(q) the first turn; half-sweeps gamma + eta and -gamma
 *    with gamma the angle of J.
 * Lengths are in the scaled unit L24 (Q24 of 2^k m, -5 <= k <= 4 chosen so that |dx|, |dy| lie
 * in (2, 4] * 2^k m), which keeps about 2^-24 relative resolution at every distance;
 * curvatures come out in Q4.28 /m.
 * A mirror image (heading change to the right) is solved as its reflection (q -> -q) and the
 * turns are mirrored back; reverse travel negates A and B and mirrors the turns.
 */
#include <stddef.h>

#include "drive/drive.h"
#include "drive_internal.h"

/* Straight case: heading change and lateral offset below these (the straight path then
 * misses by under 4e-7 rad and 2e-6 m). */
#define STRAIGHT_ANGLE   256 /* binary angle, 2.1e-5 degrees */
#define STRAIGHT_LAT_L24 16  /* L24 */
/* Half-sweeps below 0.25 rad take their length from the chord (x / sin x series); above,
 * from the radius (s = 2 |tau| r). 0.25 rad as a binary angle: */
#define SMALL_HALF_SWEEP 170891318l

const char *drive_status_text(drive_status_t st)
{
    switch (st) {
    case DRIVE_OK:
        return "ok";
    case DRIVE_ERR_PARAM:
        return "parameter out of range";
    case DRIVE_ERR_TOO_CLOSE:
        return "target closer than the shortest drive (1/64 m)";
    case DRIVE_ERR_TOO_FAR:
        return "target farther than the longest drive (64 m)";
    case DRIVE_ERR_BEHIND:
        return "target not ahead in the direction of travel";
    case DRIVE_ERR_HEADING:
        return "heading change over 90 degrees";
    case DRIVE_ERR_RADIUS:
        return "every double arc to the target needs a radius below the minimum";
    case DRIVE_ERR_SWEEP:
        return "the double arc would turn a full circle";
    case DRIVE_ERR_RANGE:
        return "value out of the drive board's 8-bit range";
    case DRIVE_ERR_PATH:
        return "path not acceptable";
    }
    return "unknown status";
}

/* v / 2^sh rounded to nearest (ties away from zero), 0 <= sh <= 30. */
static int32_t shr_round(int32_t v, uint8_t sh)
{
    if (sh == 0)
        return v;
    int32_t half = (int32_t)1 << (sh - 1);
    return v >= 0 ? (v + half) >> sh : -((-v + half) >> sh);
}

/* Length of an arc of chord @p chord (L24) and half-sweep @p tau (binary angle, |tau| small). */
static int32_t arc_from_chord(int32_t chord, int32_t tau)
{
    return fx_mul_q30(chord, drive_x_over_sin_small(drive_angle_to_rad_q28(tau) * 4));
}

/* Length of an arc of radius @p r (L24) and half-sweep @p tau: 2 |tau| r; -1 on overflow. */
static int32_t arc_from_radius(int32_t r, int32_t tau)
{
    int32_t two_tau = drive_angle_to_rad_q28((int32_t)drive_abs32(tau)) << 1; /* <= 2 pi, Q28 */
    int32_t s;
    if (!fx_mul_shift(r, two_tau, 28, &s))
        return -1;
    return s;
}

drive_status_t drive_solve(const drive_pose_t *from, const drive_pose_t *to, fx_q16_t min_radius,
                           bool reverse, drive_solution_t *out, int32_t *needed)
{
    if (from == NULL || to == NULL || out == NULL || min_radius < DRIVE_MIN_RADIUS_MIN ||
        min_radius > DRIVE_MIN_RADIUS_MAX)
        return DRIVE_ERR_PARAM;

    /* Directions of travel A and B (negated for reverse travel) and the heading change. */
    fx_angle_t a1 = from->heading, a2 = to->heading;
    if (reverse) {
        a1 += FX_ANGLE_HALF;
        a2 += FX_ANGLE_HALF;
    }
    int32_t dl = (int32_t)(a2 - a1);
    if (dl > (int32_t)FX_ANGLE_QUARTER || dl < -(int32_t)FX_ANGLE_QUARTER)
        return DRIVE_ERR_HEADING;
    int32_t eta = dl / 2;

    /* D and its scale 2^k: |dx|, |dy| <= 4 * 2^k m (Q16: 2^(18 + k)), -5 <= k <= 4. */
    int64_t dx64 = (int64_t)to->x - from->x, dy64 = (int64_t)to->y - from->y;
    uint64_t mx = (uint64_t)(dx64 < 0 ? -dx64 : dx64), my = (uint64_t)(dy64 < 0 ? -dy64 : dy64);
    uint64_t m = mx > my ? mx : my;
    if (m > (uint64_t)DRIVE_MAX_DIST)
        return DRIVE_ERR_TOO_FAR;
    int32_t dx = (int32_t)dx64, dy = (int32_t)dy64;
    int8_t k = -5;
    while (m > ((uint64_t)1 << (18 + k)))
        k++;

    /* E in the u frame, L24: p along u, q to its left. */
    fx_q30_t cu, su;
    fx_sincos(a1 + (fx_angle_t)eta, &su, &cu);
    uint8_t sh = (uint8_t)(22 + k); /* Q16 * Q30 -> L24 */
    int32_t t1, t2, t3, t4;
    (void)fx_mul_shift(dx, cu, sh, &t1); /* |dx| <= 2^22 and sh >= 22: always fits */
    (void)fx_mul_shift(dy, su, sh, &t2);
    (void)fx_mul_shift(dx, su, sh, &t3);
    (void)fx_mul_shift(dy, cu, sh, &t4);
    int32_t p = t1 + t2, q = t4 - t3;

    /* Mirror image: solve a heading change to the left (or none, target on the left). */
    bool mirror = eta < 0 || (eta == 0 && q < 0);
    if (mirror) {
        eta = -eta;
        q = -q;
    }
    fx_q30_t s, c;
    fx_sincos((fx_angle_t)eta, &s, &c);
    uint32_t aq = drive_abs32(q);

    /* P = A . D > 0: the target is ahead. */
    int32_t pc = fx_mul_q30(p, c), qs = fx_mul_q30(q, s);
    int32_t pp = pc - qs;
    if (pp <= 0)
        return DRIVE_ERR_BEHIND;
    int32_t p2 = 0, q2 = 0;
    (void)fx_mul_shift(p, p, 24, &p2); /* |p|, |q| < 5.7 * 2^24: squares < 2^31 */
    (void)fx_mul_shift(q, q, 24, &q2);
    int32_t e2 = p2 + q2; /* |E|^2, L24 m^2 */
    if (k == 4 && e2 > (1l << 28))
        return DRIVE_ERR_TOO_FAR; /* |D| > 64 m */
    if (k == -5 && e2 < (1l << 22))
        return DRIVE_ERR_TOO_CLOSE; /* |D| < 1/64 m */

    int32_t len0, len1;    /* L24 */
    int32_t curv = 0;      /* Q4.28 /m, the first arc's turn, canonical (before mirroring) */
    fx_angle_t sweep0 = 0; /* the first segment's heading change, canonical (wraps) */

    if (dl < STRAIGHT_ANGLE && dl > -STRAIGHT_ANGLE && aq <= STRAIGHT_LAT_L24) {
        /* Straight case: two halves along A. */
        out->kase = DRIVE_CASE_STRAIGHT;
        len0 = pp / 2;
        len1 = pp - len0;
    } else {
        /* A5 = p sin(eta) - |q| cos(eta) = Lc sin(eta): > 0 when an arc and a straight fit
         * (rotation and translation the same way, eta > beta); the arc's radius is then
         * Lc / (2 sin eta) >= rmin when A5 >= 2 sin^2(eta) rmin. For q < 0 it is T = A x D. */
        int32_t a5 = fx_mul_q30(p, s) - fx_mul_q30((int32_t)aq, c);
        int32_t rs, thr = INT32_MAX; /* 2 sin^2(eta) rmin, L24; beyond int32 means no fit */
        if (fx_mul_shift(min_radius, s, sh, &rs) && rs <= INT32_MAX / 2)
            thr = fx_mul_q30(rs * 2, s);
        bool arc_line = false;
        if (a5 > 0 && s > 0 && a5 >= thr) {
            /* Cases 4 (q >= 0: arc, then straight) and 5 (q < 0: straight, then arc), if the
             * arc's radius, exactly as it will be driven, is at least the minimum (the test
             * above is the cheap, approximate filter). */
            int32_t l = (int32_t)drive_udiv(aq, (uint32_t)s, 30);
            int32_t lc = p - fx_mul_q30(l, c);
            int32_t chk;
            curv = lc > 0 ? (int32_t)drive_udiv((uint32_t)s, (uint32_t)lc, (uint8_t)(23 - k)) : -1;
            if (curv > 0 && fx_mul_shift(curv, min_radius, 28, &chk) && chk <= FX_Q16_ONE) {
                arc_line = true;
                int32_t arc;
                if (eta < SMALL_HALF_SWEEP) {
                    arc = arc_from_chord(lc, eta);
                } else {
                    int32_t r = (int32_t)drive_udiv((uint32_t)lc, (uint32_t)s, 29);
                    arc = arc_from_radius(r, eta);
                }
                if (q >= 0) {
                    out->kase = DRIVE_CASE_4;
                    len0 = arc;
                    len1 = l;
                    sweep0 = (fx_angle_t)eta * 2u;
                } else {
                    out->kase = DRIVE_CASE_5;
                    len0 = l;
                    len1 = arc;
                }
            }
        }
        if (!arc_line) {
            /* Double arc of equal radii, first turn sigma = sign(q). */
            int32_t sigma = q >= 0 ? 1 : -1;
            int32_t sp = fx_mul_q30(p, s);
            int32_t x = (int32_t)(drive_hypot(q, sp) + (uint32_t)fx_mul_q30((int32_t)aq, c));
            curv = (int32_t)drive_udiv((uint32_t)x, (uint32_t)e2, (uint8_t)(29 - k));
            if (curv < 0)
                curv = INT32_MAX; /* saturated */
            int32_t chk;
            if (!fx_mul_shift(curv, min_radius, 28, &chk) || chk > FX_Q16_ONE) {
                if (needed != NULL)
                    *needed = curv;
                return DRIVE_ERR_RADIUS;
            }
            /* rho = sin(eta) |E|^2 / (2 X) <= |E| / 2; the doubled junction 2J = (p + 2 sigma
             * rho, q) and 2(E - J) = (p - 2 sigma rho, q). */
            uint64_t se2 = drive_umul((uint32_t)s, (uint32_t)e2); /* Q54 */
            int32_t rho = (int32_t)drive_udiv64(se2 >> 7, (uint32_t)x);
            /* rho <= p/2 whenever |q| sin(eta) <= p cos(eta) (always for sigma > 0, as P > 0):
             * J cannot pass E (sigma > 0) or fall behind O (sigma < 0). When q and p sin(eta)
             * are a few LSB, rho is known only roughly and may overshoot; moving J along u
             * keeps it on the locus of junctions to within (q / |E|) |d rho| < 1 LSB, so the
             * clamp costs nothing and keeps both chords forward. */
            if ((sigma > 0 || pc + qs >= 0) && rho > p / 2)
                rho = p / 2;
            int32_t jx2 = p + 2 * sigma * rho, kx2 = p - 2 * sigma * rho;
            int32_t gamma = (int32_t)fx_atan2(q, jx2);
            int32_t tau0 = gamma + eta, tau1 = -gamma;
            if (sigma < 0 && tau0 > 0)
                return DRIVE_ERR_SWEEP;
            int32_t r = -1;
            if (drive_abs32(tau0) < (uint32_t)SMALL_HALF_SWEEP) {
                len0 = (arc_from_chord((int32_t)drive_hypot(jx2, q), tau0) + 1) >> 1;
            } else {
                r = (int32_t)drive_udiv((uint32_t)e2, (uint32_t)x, 23);
                len0 = arc_from_radius(r, tau0);
            }
            if (drive_abs32(tau1) < (uint32_t)SMALL_HALF_SWEEP) {
                len1 = (arc_from_chord((int32_t)drive_hypot(kx2, q), tau1) + 1) >> 1;
            } else {
                if (r < 0)
                    r = (int32_t)drive_udiv((uint32_t)e2, (uint32_t)x, 23);
                len1 = arc_from_radius(r, tau1);
            }
            if (len0 < 0 || len1 < 0)
                return DRIVE_ERR_SWEEP;
            out->kase = sigma > 0 ? DRIVE_CASE_1 : (a5 >= 0 ? DRIVE_CASE_2 : DRIVE_CASE_3);
            curv *= sigma;
            sweep0 = (fx_angle_t)tau0 * 2u;
        }
    }

    /* Back to the real world: mirror, reverse, units. The sweeps are heading changes of the
     * vehicle (equal to those of the direction of travel); the curvature is the steering's,
     * so reverse travel mirrors it. */
    if (mirror) {
        curv = -curv;
        sweep0 = 0u - sweep0;
    }
    int32_t steer = reverse ? -curv : curv;
    uint8_t osh = (uint8_t)(8 - k);
    drive_segment_t *s0 = &out->seg[0], *s1 = &out->seg[1];
    s0->length = shr_round(len0, osh);
    s1->length = shr_round(len1, osh);
    switch (out->kase) {
    case DRIVE_CASE_STRAIGHT:
        s0->curvature = s1->curvature = 0;
        s0->sweep = s1->sweep = 0;
        break;
    case DRIVE_CASE_4:
        s0->curvature = steer;
        s0->sweep = (fx_angle_t)dl;
        s1->curvature = 0;
        s1->sweep = 0;
        break;
    case DRIVE_CASE_5:
        s0->curvature = 0;
        s0->sweep = 0;
        s1->curvature = steer;
        s1->sweep = (fx_angle_t)dl;
        break;
    default:
        s0->curvature = steer;
        s0->sweep = sweep0;
        s1->curvature = -steer;
        s1->sweep = (fx_angle_t)dl - sweep0;
        break;
    }
    if (out->kase == DRIVE_CASE_4 || out->kase == DRIVE_CASE_5) {
        /* The straight after (or before) the arc can be long: make the arc's heading change
         * exact in the units it is driven in. Its length is rounded up and the curvature set
         * to sweep / length, never above the one checked against the minimum radius. */
        drive_segment_t *arc = out->kase == DRIVE_CASE_4 ? s0 : s1;
        int32_t arc_len = out->kase == DRIVE_CASE_4 ? len0 : len1;
        arc->length = (int32_t)(((uint32_t)arc_len + ((1u << osh) - 1u)) >> osh);
        uint32_t k_out =
            drive_udiv((uint32_t)drive_angle_to_rad_q28(eta) * 2u, (uint32_t)arc->length, 16);
        arc->curvature = steer < 0 ? -(int32_t)k_out : (int32_t)k_out;
    }
    return DRIVE_OK;
}

fx_q16_t drive_radius_of(int32_t curvature)
{
    if (curvature == 0)
        return 0;
    uint32_t a = drive_abs32(curvature);
    /* r = 2^28 / k metres = 2^44 / k in Q16 */
    uint32_t r = drive_udiv(1u << 30, a, 14);
    if (r > (uint32_t)INT32_MAX)
        r = (uint32_t)INT32_MAX;
    return curvature < 0 ? -(int32_t)r : (int32_t)r;
}

drive_pose_t drive_pose_advance(const drive_pose_t *pose, int32_t curvature, fx_q16_t dist,
                                bool reverse)
{
    drive_pose_t r = *pose;
    if (dist <= 0)
        return r;
    /* Heading change delta = dist * curvature (negated when reversing), radians Q28. */
    int32_t d28 = 0;
    if (!fx_mul_shift(dist, curvature, 16, &d28))
        d28 = curvature > 0 ? INT32_MAX : INT32_MIN;
    if (reverse)
        d28 = -d28;
    /* Chord: dist * sin(delta/2) / (delta/2), along the direction of travel + delta/2. */
    int32_t half28 = d28 / 2;
    fx_angle_t half = drive_rad_q28_to_angle(half28);
    int32_t ratio; /* Q30 */
    if (drive_abs32((int32_t)half) < (uint32_t)SMALL_HALF_SWEEP) {
        ratio = drive_sin_over_x_small(drive_angle_to_rad_q28((int32_t)half) * 4);
    } else {
        fx_q30_t sh = fx_sin(half);
        uint32_t num = drive_abs32(sh), den = drive_abs32(half28);
        ratio = (int32_t)drive_udiv(num, den, 28); /* |sin x| / |x| in Q30 */
    }
    int32_t chord = fx_mul_q30(dist, ratio);
    fx_angle_t dir = pose->heading + (reverse ? FX_ANGLE_HALF : 0u) + half;
    fx_q30_t sd, cd;
    fx_sincos(dir, &sd, &cd);
    r.x += fx_mul_q30(chord, cd);
    r.y += fx_mul_q30(chord, sd);
    r.heading = pose->heading + drive_rad_q28_to_angle(d28);
    return r;
}
