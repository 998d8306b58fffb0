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
 * curvatures come out in Q4.28 /m. The scale is carried as sh = 8 - k: L24 = Q16 * 2^sh.
 * A mirror image (heading change to the right) is solved as its reflection (q -> -q) and the
 * turns are mirrored back; reverse travel negates A and B and mirrors the turns.
 *
 * The formulas are programs of drive_internal.h's interpreter on the frame of solve_frame.h
 * (flash: 4 bytes per fx call instead of about 28); the decisions between them are C here and
 * MSP430 assembly on the target (msp430/solve.S, step for step the same; the vector program
 * proves the two bit-identical).
 */
#include <stddef.h>

#include "drive/drive.h"
#include "drive_internal.h"
#include "solve_frame.h"

_Static_assert(DRIVE_MIN_RADIUS_MIN_Q16 == DRIVE_MIN_RADIUS_MIN &&
                   DRIVE_MIN_RADIUS_MAX_Q16 == DRIVE_MIN_RADIUS_MAX &&
                   DRIVE_MAX_DIST_Q16 == DRIVE_MAX_DIST,
               "solve_frame.h: the limits differ from drive.h's");
_Static_assert(DRIVE_ERR_PARAM_N == DRIVE_ERR_PARAM &&
                   DRIVE_ERR_TOO_CLOSE_N == DRIVE_ERR_TOO_CLOSE &&
                   DRIVE_ERR_TOO_FAR_N == DRIVE_ERR_TOO_FAR &&
                   DRIVE_ERR_BEHIND_N == DRIVE_ERR_BEHIND &&
                   DRIVE_ERR_HEADING_N == DRIVE_ERR_HEADING &&
                   DRIVE_ERR_RADIUS_N == DRIVE_ERR_RADIUS && DRIVE_ERR_SWEEP_N == DRIVE_ERR_SWEEP &&
                   DRIVE_ERR_RANGE_N == DRIVE_ERR_RANGE,
               "solve_frame.h: the status codes differ from drive.h's");
_Static_assert(SV_KC + 1 == SV_ARCQ && SV_ARCQ + 1 == SV_DL && SV_K0 + 3 == SV_K1,
               "solve_frame.h: a segment's slots must follow each other");

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

/* clang-format off */
/* The programs (drive_internal.h) on the frame of solve_frame.h; also run by msp430/solve.S. */

/* The canonical problem's parameters (P, Q and ETA set). */
const uint8_t drive_p_canon[] = {
    DRIVE_SINCOS(SV_S, SV_ETA),
    DRIVE_ABS(SV_AQ, SV_Q),
    DRIVE_MUL(SV_PC, SV_P, SV_C),     DRIVE_MUL(SV_QS, SV_Q, SV_S),   DRIVE_SUB(SV_PP, SV_PC, SV_QS),
    DRIVE_SHL(SV_T0, SV_P, 3),        DRIVE_SHL(SV_T1, SV_Q, 3),      /* |E|^2 */
    DRIVE_MUL(SV_T0, SV_T0, SV_T0),   DRIVE_MUL(SV_T1, SV_T1, SV_T1), DRIVE_ADD(SV_E2, SV_T0, SV_T1),
    DRIVE_MUL(SV_SP, SV_P, SV_S),     DRIVE_MUL(SV_CQ, SV_AQ, SV_C),  DRIVE_SUB(SV_A5, SV_SP, SV_CQ),
    DRIVE_END};

/* Cases 4, 5, eta < 0.2 rad (L = |q| / sin eta set): the arc from its chord, x / sin x as a
 * series. */
const uint8_t drive_p_line_small[] = {
    DRIVE_MULK(SV_E30, SV_ETA, DRIVE_K_PI_2),
    DRIVE_MUL(SV_T0, SV_L, SV_C),     DRIVE_SUB(SV_LC, SV_P, SV_T0),
    DRIVE_POLY(SV_T1, SV_E30, DRIVE_K_XOS), DRIVE_MUL(SV_ARC, SV_LC, SV_T1),
    DRIVE_END};

/* Cases 4, 5, eta >= 0.2 rad (INVS set): l = 4 |q| inv_s, arc = 2 eta r. */
const uint8_t drive_p_line_big[] = {
    DRIVE_MULK(SV_E30, SV_ETA, DRIVE_K_PI_2),
    DRIVE_SHL(SV_T0, SV_AQ, 2),       DRIVE_MUL(SV_L, SV_T0, SV_INVS),
    DRIVE_MUL(SV_T0, SV_L, SV_C),     DRIVE_SUB(SV_LC, SV_P, SV_T0),
    DRIVE_SHL(SV_T0, SV_LC, 1),       DRIVE_MUL(SV_T0, SV_T0, SV_INVS),
    DRIVE_SHL(SV_T1, SV_E30, 1),      DRIVE_MUL(SV_ARC, SV_T0, SV_T1),
    DRIVE_END};

/* Double arc: W = hypot(|q|, p sin eta) as a projection on its own direction (cheaper than
 * the 64-bit square root; exact but for the rounding of the two products), X. */
const uint8_t drive_p_x[] = {
    DRIVE_ATAN2(SV_Z, SV_SP, SV_AQ),  DRIVE_ROT(SV_W, SV_AQ, SV_Z),   DRIVE_ADD(SV_X, SV_W, SV_CQ),
    DRIVE_END};

/* Double arc: junction and half-sweeps (RS = sigma rho set). */
const uint8_t drive_p_junction[] = {
    DRIVE_SHL(SV_T0, SV_RS, 1),       DRIVE_ADD(SV_JX2, SV_P, SV_T0), DRIVE_SUB(SV_KX2, SV_P, SV_T0),
    DRIVE_ATAN2(SV_G, SV_Q, SV_JX2),  DRIVE_ADD(SV_TAU0, SV_G, SV_ETA), DRIVE_NEG(SV_TAU1, SV_G),
    DRIVE_END};

/* Double arc: the segments (KC with the first turn's sign set), the lengths still L24. */
const uint8_t drive_p_da_tail[] = {
    DRIVE_SHL(SV_K0, SV_KC, 0),       DRIVE_NEG(SV_K1, SV_KC),
    DRIVE_SHL(SV_W0, SV_TAU0, 1),     DRIVE_SUB(SV_W1, SV_DL, SV_W0),
    DRIVE_END};

/* Straight case: the two halves of P, L24. */
const uint8_t drive_p_halves[] = {
    DRIVE_HALF(SV_T0, SV_PP),         DRIVE_SUB(SV_T1, SV_PP, SV_T0),
    DRIVE_END};

/* Arc lengths, |tau| < 0.03 rad: chord * sec(chord angle) * tau / sin(tau) with the factor
 * from the squares of the binary angles scaled by 32 (a' = (32 tau)^2 / 2^30, tau^2 =
 * a' pi^2 / 4096 in Q30): 1 + g^2/2 + tau^2/6 = 1 + (a' + 3 b') pi^2 / 24576; the fourth-order
 * terms stay below 3e-7. Arc 1 runs from O to J (chord angle -tau1, half-sweep tau0), arc 2
 * from J to E (chord angle tau0, half-sweep tau1). chord * (1 + f) is computed as
 * chord + chord * f: the same rounding, as f >= 0. */
const uint8_t drive_p_len_tiny[] = {
    DRIVE_SHL(SV_T0, SV_TAU0, 5),     DRIVE_MUL(SV_A0, SV_T0, SV_T0),
    DRIVE_SHL(SV_T0, SV_TAU1, 5),     DRIVE_MUL(SV_A1, SV_T0, SV_T0),
    DRIVE_ADD(SV_T0, SV_A1, SV_A1),   DRIVE_ADD(SV_T0, SV_T0, SV_A1), DRIVE_ADD(SV_T0, SV_T0, SV_A0),
    DRIVE_MULK(SV_T0, SV_T0, DRIVE_K_TINY),
    DRIVE_HALF(SV_T2, SV_JX2),        DRIVE_MUL(SV_LEN0, SV_T2, SV_T0), DRIVE_ADD(SV_LEN0, SV_LEN0, SV_T2),
    DRIVE_ADD(SV_T0, SV_A0, SV_A0),   DRIVE_ADD(SV_T0, SV_T0, SV_A0), DRIVE_ADD(SV_T0, SV_T0, SV_A1),
    DRIVE_MULK(SV_T0, SV_T0, DRIVE_K_TINY),
    DRIVE_HALF(SV_T2, SV_KX2),        DRIVE_MUL(SV_LEN1, SV_T2, SV_T0), DRIVE_ADD(SV_LEN1, SV_LEN1, SV_T2),
    DRIVE_END};

/* Arc lengths, long legs with a large radius and |tau| < 0.2 rad: the same with the sixth-
 * order series of sec and x / sin x. */
const uint8_t drive_p_len_small[] = {
    DRIVE_MULK(SV_T0, SV_TAU0, DRIVE_K_PI_2), DRIVE_MULK(SV_T1, SV_TAU1, DRIVE_K_PI_2),
    DRIVE_HALF(SV_T2, SV_JX2),        DRIVE_POLY(SV_T3, SV_T1, DRIVE_K_SEC), DRIVE_MUL(SV_T2, SV_T2, SV_T3),
    DRIVE_POLY(SV_T3, SV_T0, DRIVE_K_XOS),    DRIVE_MUL(SV_LEN0, SV_T2, SV_T3),
    DRIVE_HALF(SV_T2, SV_KX2),        DRIVE_POLY(SV_T3, SV_T0, DRIVE_K_SEC), DRIVE_MUL(SV_T2, SV_T2, SV_T3),
    DRIVE_POLY(SV_T3, SV_T1, DRIVE_K_XOS),    DRIVE_MUL(SV_LEN1, SV_T2, SV_T3),
    DRIVE_END};

/* Arc lengths from the radius (r <= |E| / (2 sin 0.03) < 95 * 2^k m here): 2 |tau| r =
 * |tau (binary)| pi r / 2^30; rp = pi r / 4 (L24), s = fx_mul_q30(rp, |tau|) * 4. */
const uint8_t drive_p_len_radius[] = {
    DRIVE_SHL(SV_T0, SV_R20, 4),      DRIVE_MULK(SV_T0, SV_T0, DRIVE_K_PI_4),
    DRIVE_ABS(SV_T1, SV_TAU0),        DRIVE_MUL(SV_T1, SV_T0, SV_T1), DRIVE_SHL(SV_LEN0, SV_T1, 2),
    DRIVE_ABS(SV_T1, SV_TAU1),        DRIVE_MUL(SV_T1, SV_T0, SV_T1), DRIVE_SHL(SV_LEN1, SV_T1, 2),
    DRIVE_END};
/* clang-format on */

#ifndef DRIVE_ASM /* MSP430: msp430/solve.S, the same steps */

/* L24 -> Q16: round(x / 2^sh) for x >= 0. */
static int32_t unscale(int32_t x, uint8_t sh)
{
    return (x + ((int32_t)1 << (sh - 1))) >> sh;
}

/* Cases 4 and 5: an arc and a straight, when the arc's radius (as driven) is >= rmin.
 * Straight l = |q| / sin(eta); the arc's chord Lc = p - l cos(eta) lies along u. The straight
 * next to the arc can be long: the arc's heading change is made exact in the units it is
 * driven in (length rounded up to Q16, curvature = sweep / length, never above the true one,
 * and that curvature checked against the minimum radius). Sets the canonical result. */
static bool line(int32_t *v, uint8_t sh, fx_q16_t rmin)
{
    if (v[SV_ETA] < TAU_SMALL) {
        if (!fx_div_shift(v[SV_AQ], v[SV_S], 30, &v[SV_L]))
            return false;
        drive_vm_run(v, drive_p_line_small);
    } else {
        (void)fx_div_shift(FX_Q30_ONE, v[SV_S], 28, &v[SV_INVS]); /* <= 5.1 */
        drive_vm_run(v, drive_p_line_big);
    }
    if (v[SV_LC] <= 0 || v[SV_ARC] <= 0)
        return false;
    v[SV_ARCQ] = (v[SV_ARC] + ((int32_t)1 << sh) - 1) >> sh; /* Q16, rounded up */
    if (!fx_div_shift(v[SV_E30], v[SV_ARCQ], 15, &v[SV_KC]) ||
        fx_mul_q16(v[SV_KC], rmin) > DRIVE_CURV_ONE)
        return false;
    /* The arc (KC, ARCQ, DL) first (case 4) or second (case 5), the straight the other. */
    int32_t *arc = &v[v[SV_Q] >= 0 ? SV_K0 : SV_K1], *str = &v[v[SV_Q] >= 0 ? SV_K1 : SV_K0];
    for (uint8_t i = 0; i < 3u; i++)
        arc[i] = v[SV_KC + i];
    str[0] = str[2] = 0;
    str[1] = unscale(v[SV_L], sh);
    return true;
}

/* Cases 1, 2 and 3: a double arc of equal radii, first turn sigma = sign(q).
 * X = sqrt(q^2 + (p sin eta)^2) + |q| cos eta, curvature 2 X / |E|^2, radius r = |E|^2 / (2 X),
 * rho = r sin(eta), junction 2J = (p + 2 sigma rho, q), half-sweeps gamma + eta and -gamma
 * with gamma the angle of J. Sets the canonical result. */
static drive_status_t double_arc(int32_t *v, uint8_t sh, fx_q16_t rmin, int32_t *needed)
{
    drive_vm_run(v, drive_p_x);
    bool fits = fx_div_shift(v[SV_X], v[SV_E2], (uint8_t)(21 + sh), &v[SV_KC]);
    if (!fits || fx_mul_q16(v[SV_KC], rmin) > DRIVE_CURV_ONE) {
        if (needed != NULL)
            *needed = fits ? v[SV_KC] : INT32_MAX;
        return DRIVE_ERR_RADIUS;
    }
    /* The radius (L20: fits below 2048 * 2^k m), rho = r sin eta (L24) in RS. */
    v[SV_RS] = 0;
    if (!fx_div_shift(v[SV_E2], v[SV_X], 19, &v[SV_R20])) {
        v[SV_R20] = INT32_MAX; /* as large as it gets, for the choice of lengths below */
        (void)fx_div_shift(fx_mul_q30(v[SV_E2], v[SV_S]), v[SV_X], 23, &v[SV_RS]);
    } else if (v[SV_R20] < (1l << 27)) {
        v[SV_RS] = fx_mul_q30(v[SV_R20] * 16, v[SV_S]);
    } else {
        v[SV_RS] = fx_mul_q30(v[SV_R20], v[SV_S]) * 16;
    }
    /* rho <= p/2 whenever |q| sin(eta) <= p cos(eta) (always for sigma > 0, as P > 0): J
     * cannot pass E (sigma > 0) or fall behind O (sigma < 0). When q and p sin(eta) are a few
     * LSB, rho is known only roughly and may overshoot; moving J along u keeps it on the locus
     * of junctions to within (q / |E|) |d rho| < 1 LSB, so the clamp costs nothing and keeps
     * both chords forward. */
    if ((v[SV_Q] >= 0 || v[SV_PC] + v[SV_QS] >= 0) && v[SV_RS] > v[SV_P] / 2)
        v[SV_RS] = v[SV_P] / 2;
    if (v[SV_Q] < 0)
        v[SV_RS] = -v[SV_RS]; /* sigma rho */
    drive_vm_run(v, drive_p_junction);
    if (v[SV_Q] < 0 && v[SV_TAU0] > 0)
        return DRIVE_ERR_SWEEP;
    uint32_t t0 = drive_abs32(v[SV_TAU0]), t1 = drive_abs32(v[SV_TAU1]), big = t0 > t1 ? t0 : t1;
    /* Lengths. From the radius, s = 2 |tau| r, unless the radius is large: an error d in tau
     * (fx_atan2: 1.3e-6 rad) costs 2 r d, so below |tau| = 0.03 rad (r > 16 |E|: at most
     * 190 m for legs up to 8 m) and, for longer legs (k >= 2), for radii over 256 m below
     * 0.2 rad, they come from the chords. */
    const uint8_t *len = drive_p_len_radius;
    if (big < (uint32_t)TAU_TINY)
        len = drive_p_len_tiny;
    else if (sh <= 6 && big < (uint32_t)TAU_SMALL && v[SV_R20] >= ((int32_t)1 << (20 + sh)))
        len = drive_p_len_small;
    drive_vm_run(v, len);
    if (v[SV_LEN0] < 0 || v[SV_LEN1] < 0)
        return DRIVE_ERR_SWEEP;
    if (v[SV_Q] < 0)
        v[SV_KC] = -v[SV_KC];
    drive_vm_run(v, drive_p_da_tail);
    v[SV_L0] = unscale(v[SV_LEN0], sh);
    v[SV_L1] = unscale(v[SV_LEN1], sh);
    return DRIVE_OK;
}

drive_status_t drive_solve(const drive_pose_t *from, const drive_pose_t *to, fx_q16_t min_radius,
                           bool reverse, drive_solution_t *out, int32_t *needed)
{
    if (from == NULL || to == NULL || out == NULL || min_radius < DRIVE_MIN_RADIUS_MIN ||
        min_radius > DRIVE_MIN_RADIUS_MAX)
        return DRIVE_ERR_PARAM;

    /* The heading change (reverse travel turns both directions of travel by half a turn). */
    int32_t dl = (int32_t)(to->heading - from->heading);
    if (dl > (int32_t)FX_ANGLE_QUARTER || dl < -(int32_t)FX_ANGLE_QUARTER)
        return DRIVE_ERR_HEADING;

    /* D and its scale 2^k: |dx|, |dy| <= 4 * 2^k m (Q16: 2^(18 + k)), -5 <= k <= 4. */
    int32_t dx = (int32_t)((uint32_t)to->x - (uint32_t)from->x);
    int32_t dy = (int32_t)((uint32_t)to->y - (uint32_t)from->y);
    if (((to->x ^ from->x) & (to->x ^ dx)) < 0 || ((to->y ^ from->y) & (to->y ^ dy)) < 0)
        return DRIVE_ERR_TOO_FAR; /* the difference overflows: over 32768 m */
    uint32_t mx = drive_abs32(dx), my = drive_abs32(dy), m = mx > my ? mx : my;
    if (m > (uint32_t)DRIVE_MAX_DIST)
        return DRIVE_ERR_TOO_FAR;
    uint8_t sh = 13; /* 8 - k: L24 = Q16 * 2^sh */
    for (uint32_t lim = (uint32_t)1 << 13; m > lim; lim <<= 1)
        sh--;

    /* E in the u frame: p along u, q to its left. */
    int32_t v[SV_NSLOTS];
    v[SV_DX] = (int32_t)((uint32_t)dx << sh);
    v[SV_DY] = (int32_t)((uint32_t)dy << sh);
    v[SV_DL] = dl;
    v[SV_ETA] = dl / 2;
    drive_rot(&v[SV_P], &v[SV_DX],
              from->heading + (reverse ? FX_ANGLE_HALF : 0u) + (fx_angle_t)v[SV_ETA]);

    /* Mirror image: solve a heading change to the left (or none, target on the left). */
    bool mirror = v[SV_ETA] < 0 || (v[SV_ETA] == 0 && v[SV_Q] < 0);
    if (mirror) {
        v[SV_ETA] = -v[SV_ETA];
        v[SV_Q] = -v[SV_Q];
        v[SV_DL] = -dl;
    }
    drive_vm_run(v, drive_p_canon);
    if (v[SV_PP] <= 0)
        return DRIVE_ERR_BEHIND;
    if (sh == 4 && v[SV_E2] > (1l << 28))
        return DRIVE_ERR_TOO_FAR; /* |D| > 64 m */
    if (sh == 13 && v[SV_E2] < (1l << 22))
        return DRIVE_ERR_TOO_CLOSE; /* |D| < 1/64 m */

    drive_case_t kase;
    if (dl < STRAIGHT_ANGLE && dl > -STRAIGHT_ANGLE && v[SV_AQ] <= ((int32_t)1 << sh)) {
        /* Straight case: two halves along A. */
        kase = DRIVE_CASE_STRAIGHT;
        drive_vm_run(v, drive_p_halves);
        v[SV_K0] = v[SV_W0] = v[SV_K1] = v[SV_W1] = 0;
        v[SV_L0] = unscale(v[SV_T0], sh);
        v[SV_L1] = unscale(v[SV_T1], sh);
    } else {
        /* A5 = p sin(eta) - |q| cos(eta) = Lc sin(eta) > 0 when an arc and a straight fit
         * (rotation and translation the same way, eta > beta), and then the arc's radius
         * Lc / (2 sin eta) >= rmin when A5 >= 2 sin^2(eta) rmin: a cheap filter before the
         * exact test in line() (the seed's order: case 4/5 first, then its fallback, the
         * double arc). rs = rmin sin(eta) in L24. */
        int32_t rs;
        if (v[SV_A5] > 0 && v[SV_S] > 0 &&
            fx_mul_shift(min_radius, v[SV_S], (uint8_t)(30 - sh), &rs) && rs < INT32_MAX / 2 &&
            v[SV_A5] >= fx_mul_q30(rs * 2, v[SV_S]) && line(v, sh, min_radius)) {
            kase = v[SV_Q] >= 0 ? DRIVE_CASE_4 : DRIVE_CASE_5;
        } else {
            drive_status_t st = double_arc(v, sh, min_radius, needed);
            if (st != DRIVE_OK)
                return st;
            /* For q < 0, p sin(eta) - |q| cos(eta) is T = A x D: >= 0 same side (case 2). */
            kase = v[SV_Q] >= 0 ? DRIVE_CASE_1 : (v[SV_A5] >= 0 ? DRIVE_CASE_2 : DRIVE_CASE_3);
        }
    }

    /* Back to the real world: mirror, reverse. The sweeps are heading changes of the vehicle
     * (equal to those of the direction of travel); the curvature is the steering's, so
     * reverse travel mirrors it. */
    if (mirror) {
        v[SV_W0] = (int32_t)(0u - (uint32_t)v[SV_W0]);
        v[SV_W1] = (int32_t)(0u - (uint32_t)v[SV_W1]);
    }
    if (mirror != reverse) {
        v[SV_K0] = -v[SV_K0];
        v[SV_K1] = -v[SV_K1];
    }
    out->kase = kase;
    for (uint8_t i = 0; i < 2u; i++) {
        out->seg[i].curvature = v[SV_K0 + 3 * i];
        out->seg[i].length = v[SV_L0 + 3 * i];
        out->seg[i].sweep = (fx_angle_t)v[SV_W0 + 3 * i];
    }
    return DRIVE_OK;
}
#endif

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

/* clang-format off */
/* drive_pose_advance()'s programs. The heading change and its half (D28, H28: radians Q28) as
 * binary angles: r * 8 / pi = 2 r + r (8 / pi - 2), error below 1.5 LSB, wrapping. */
const uint8_t drive_p_pa_angles[] = {
    DRIVE_HALF(PV_H28, PV_D28),
    DRIVE_MULK(PV_T, PV_H28, DRIVE_K_RAD), DRIVE_SHL(PV_X, PV_H28, 1), DRIVE_ADD(PV_HALF, PV_X, PV_T),
    DRIVE_MULK(PV_T, PV_D28, DRIVE_K_RAD), DRIVE_SHL(PV_X, PV_D28, 1), DRIVE_ADD(PV_DANG, PV_X, PV_T),
    DRIVE_END};

/* sin x / x of the half change, |x| < 0.2 rad, as a series. */
const uint8_t drive_p_pa_sox[] = {
    DRIVE_SHL(PV_X, PV_H28, 2),       DRIVE_POLY(PV_RATIO, PV_X, DRIVE_K_SOX),
    DRIVE_END};

/* The chord dist * ratio in the direction of travel + half the change. */
const uint8_t drive_p_pa_chord[] = {
    DRIVE_MUL(PV_CH, PV_DIST, PV_RATIO),
    DRIVE_ADD(PV_ANG, PV_HEAD, PV_HALF), DRIVE_NEG(PV_ANG, PV_ANG), DRIVE_ROT(PV_XY, PV_CH, PV_ANG),
    DRIVE_END};
/* clang-format on */

#ifndef DRIVE_ASM /* MSP430: msp430/solve.S, the same steps */
drive_pose_t drive_pose_advance(const drive_pose_t *pose, int32_t curvature, fx_q16_t dist,
                                bool reverse)
{
    drive_pose_t r = *pose;
    if (dist <= 0)
        return r;
    int32_t v[PV_NSLOTS];
    v[PV_DIST] = dist;
    v[PV_ZERO] = 0;
    v[PV_HEAD] = (int32_t)(pose->heading + (reverse ? FX_ANGLE_HALF : 0u));
    /* Heading change delta = dist * curvature (negated when reversing), radians Q28. */
    if (!fx_mul_shift(dist, curvature, 16, &v[PV_D28]))
        v[PV_D28] = curvature >= 0 ? INT32_MAX : -INT32_MAX;
    if (reverse)
        v[PV_D28] = -v[PV_D28];
    drive_vm_run(v, drive_p_pa_angles);
    /* Chord: dist * sin(delta/2) / (delta/2), along the direction of travel + delta/2. */
    if (drive_abs32(v[PV_H28]) < (uint32_t)HALF_CHANGE_SERIES)
        drive_vm_run(v, drive_p_pa_sox);
    else /* sin x / x in Q30: negative beyond half a turn (the chord points back) */
        (void)fx_div_shift(fx_sin((fx_angle_t)v[PV_HALF]), v[PV_H28], 28, &v[PV_RATIO]);
    drive_vm_run(v, drive_p_pa_chord);
    r.x += v[PV_XY];
    r.y += v[PV_XY1];
    r.heading += (fx_angle_t)v[PV_DANG];
    return r;
}
#endif
