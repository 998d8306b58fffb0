/*
 * solve.c - the double-arc solver (drive.h; derivations in docs/drive.md, section 2).
 *
 * The problem is solved in the frame of the mean heading u = A rotated by eta = (B - A) / 2,
 * where the target E = (p, q) (p along u, q to the left of u). In that frame every case has
 * a closed form:
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
 */
#include <stddef.h>

#include "drive/drive.h"
#include "drive_math.h"

/* Straight case (the seed's THRESH test): a heading change below 2^12 binary-angle LSB
 * (6e-6 rad, 3.4e-4 degrees) and a lateral offset of at most one Q16 LSB (15 um): the two
 * straight halves then land within 0.4 mm at 64 m. */
#define STRAIGHT_ANGLE 4096
/* Half-sweeps (binary angles) that choose how the arc lengths are computed (double arc). */
#define TAU_TINY       20506958  /* 0.03 rad */
#define TAU_SMALL      136713055 /* 0.2 rad */

#define PI_4_Q30 843314857l /* pi / 4, Q30 */
#define TINY_Q30 431210l    /* pi^2 / 24576, Q30: the arc factor of binary angles scaled by 32 */

/* Series coefficients (drive_series()): x / sin x and 1 / cos x for |x| <= 0.2 rad. */
static const int32_t x_over_sin[3] = {178956971l, 20878313l, 2201455l}; /* 1/6, 7/360, 31/15120 */
static const int32_t secant[3] = {536870912l, 223696213l, 90969793l};   /* 1/2, 5/24, 61/720 */

/* The canonical problem: heading change 2 eta >= 0 to the left, lengths in L24. */
typedef struct {
    uint8_t sh;             /* the scale: L24 = Q16 * 2^sh                           */
    int32_t p, q;           /* the target E in the frame of the mean heading u        */
    int32_t eta;            /* half the heading change, binary angle, 0..quarter / 2  */
    int32_t dl;             /* the heading change B - A, binary angle                 */
    fx_q30_t s, c;          /* sin eta, cos eta                                       */
    int32_t aq;             /* |q|                                                    */
    int32_t pc, qs;         /* p cos eta, q sin eta                                   */
    int32_t pp;             /* P = A . D = p cos eta - q sin eta                      */
    int32_t e2;             /* |E|^2, Q24 of (2^k m)^2                                */
    int32_t sp, cq;         /* p sin eta, |q| cos eta                                 */
    int32_t a5;             /* p sin eta - |q| cos eta (T = A x D when q < 0)         */
    drive_segment_t seg[2]; /* the answer, turning to the left                        */
} canon_t;

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
    case DRIVE_ERR_TURN:
        return "turn over 90 degrees: no corner of the nominal radius fits between the poses "
               "(the target must lie inside the turn; a U-turn needs two radii across)";
    }
    return "unknown status";
}

/* L24 -> Q16: round(x / 2^sh) for x >= 0. */
static int32_t unscale(int32_t x, uint8_t sh)
{
    return (x + ((int32_t)1 << (sh - 1))) >> sh;
}

/* The canonical problem's parameters from p, q, eta. */
static void parameters(canon_t *k)
{
    fx_sincos((fx_angle_t)k->eta, &k->s, &k->c);
    k->aq = (int32_t)drive_abs32(k->q);
    k->pc = fx_mul_q30(k->p, k->c);
    k->qs = fx_mul_q30(k->q, k->s);
    k->pp = k->pc - k->qs;
    /* |E|^2: (8p)^2 / 2^30 = p^2 / 2^24 (|8p| < 2^30, as |p| < 6 * 2^24) */
    k->e2 = fx_mul_q30(k->p * 8, k->p * 8) + fx_mul_q30(k->q * 8, k->q * 8);
    k->sp = fx_mul_q30(k->p, k->s);
    k->cq = fx_mul_q30(k->aq, k->c);
    k->a5 = k->sp - k->cq;
}

/* Cases 4 and 5: an arc and a straight, when the arc's radius (as driven) is >= rmin.
 * Straight l = |q| / sin(eta); the arc's chord Lc = p - l cos(eta) lies along u. The straight
 * next to the arc can be long: the arc's heading change is made exact in the units it is
 * driven in (length rounded up to Q16, curvature = sweep / length, never above the true one,
 * and that curvature checked against the minimum radius). Sets k->seg. */
static bool arc_and_straight(canon_t *k, fx_q16_t rmin)
{
    int32_t eta30 = fx_mul_q30(k->eta, DRIVE_PI_2_Q30); /* eta, radians Q30 */
    int32_t l, lc, arc;
    if (k->eta < TAU_SMALL) {
        /* l = |q| / sin eta; arc = Lc (eta / sin eta) as a series */
        if (!fx_div_shift(k->aq, k->s, 30, &l))
            return false;
        lc = k->p - fx_mul_q30(l, k->c);
        arc = fx_mul_q30(lc, drive_series(eta30, x_over_sin));
    } else {
        /* 1 / sin eta (Q4.28, <= 5.1); l = |q| / sin eta; arc = 2 eta r = 2 eta Lc / (2 sin eta) */
        int32_t inv_s;
        (void)fx_div_shift(FX_Q30_ONE, k->s, 28, &inv_s);
        l = fx_mul_q30(k->aq * 4, inv_s);
        lc = k->p - fx_mul_q30(l, k->c);
        arc = fx_mul_q30(fx_mul_q30(lc * 2, inv_s), eta30 * 2);
    }
    if (lc <= 0 || arc <= 0)
        return false;
    drive_segment_t a;
    a.length = (arc + ((int32_t)1 << k->sh) - 1) >> k->sh; /* Q16, rounded up */
    a.sweep = (fx_angle_t)k->dl;
    if (!fx_div_shift(eta30, a.length, 15, &a.curvature) ||
        fx_mul_q16(a.curvature, rmin) > DRIVE_CURV_ONE)
        return false;
    /* The arc first (case 4, q >= 0) or second (case 5), the straight the other. */
    drive_segment_t str = {0, unscale(l, k->sh), 0};
    k->seg[0] = k->q >= 0 ? a : str;
    k->seg[1] = k->q >= 0 ? str : a;
    return true;
}

/* The two arc lengths of a double arc (L24) from the half-sweeps tau0 (O to J) and tau1 (J
 * to E), the doubled junction's x (jx2 = p + 2 sigma rho, kx2 = p - 2 sigma rho) and the
 * radius r20 (L20). From the radius, s = 2 |tau| r, unless the radius is large: an error d in
 * tau (fx_atan2: 1.3e-6 rad) costs 2 r d, so below |tau| = 0.03 rad (r > 16 |E|: at most
 * 190 m for legs up to 8 m) and, for longer legs (k >= 2), for radii over 256 m below
 * 0.2 rad, they come from the chords: chord * sec(chord angle) * tau / sin(tau). Arc 1 runs
 * from O to J (chord angle -tau1, half-sweep tau0), arc 2 from J to E (chord angle tau0,
 * half-sweep tau1). */
static void arc_lengths(const canon_t *k, int32_t tau0, int32_t tau1, int32_t jx2, int32_t kx2,
                        int32_t r20, int32_t len[2])
{
    uint32_t t0 = drive_abs32(tau0), t1 = drive_abs32(tau1), big = t0 > t1 ? t0 : t1;
    if (big < (uint32_t)TAU_TINY) {
        /* With a' = (32 tau)^2 / 2^30 (tau^2 = a' pi^2 / 4096 in Q30) the factor is
         * 1 + g^2/2 + tau^2/6 = 1 + (a' + 3 b') pi^2 / 24576, fourth-order terms below 3e-7.
         * chord * (1 + f) is computed as chord + chord * f: the same rounding, as f >= 0. */
        int32_t a0 = fx_mul_q30(tau0 * 32, tau0 * 32), a1 = fx_mul_q30(tau1 * 32, tau1 * 32);
        int32_t f0 = fx_mul_q30(a0 + 3 * a1, TINY_Q30), f1 = fx_mul_q30(3 * a0 + a1, TINY_Q30);
        len[0] = jx2 / 2 + fx_mul_q30(jx2 / 2, f0);
        len[1] = kx2 / 2 + fx_mul_q30(kx2 / 2, f1);
    } else if (k->sh <= 6 && big < (uint32_t)TAU_SMALL && r20 >= ((int32_t)1 << (20 + k->sh))) {
        /* Long legs with a large radius: the same with sixth-order series. */
        int32_t x0 = fx_mul_q30(tau0, DRIVE_PI_2_Q30), x1 = fx_mul_q30(tau1, DRIVE_PI_2_Q30);
        len[0] =
            fx_mul_q30(fx_mul_q30(jx2 / 2, drive_series(x1, secant)), drive_series(x0, x_over_sin));
        len[1] =
            fx_mul_q30(fx_mul_q30(kx2 / 2, drive_series(x0, secant)), drive_series(x1, x_over_sin));
    } else {
        /* 2 |tau| r = |tau (binary)| pi r / 2^30 with r <= |E| / (2 sin 0.03) < 95 * 2^k m:
         * rp = pi r / 4 (L24, < 2^31), s = fx_mul_q30(rp, |tau|) * 4. */
        int32_t rp = fx_mul_q30(r20 * 16, PI_4_Q30);
        len[0] = fx_mul_q30(rp, (int32_t)t0) * 4;
        len[1] = fx_mul_q30(rp, (int32_t)t1) * 4;
    }
}

/* Cases 1, 2 and 3: a double arc of equal radii, first turn sigma = sign(q).
 * X = sqrt(q^2 + (p sin eta)^2) + |q| cos eta, curvature 2 X / |E|^2, radius r = |E|^2 / (2 X),
 * rho = r sin(eta), junction 2J = (p + 2 sigma rho, q), half-sweeps gamma + eta and -gamma
 * with gamma the angle of J. Sets k->seg. */
static drive_status_t double_arc(canon_t *k, fx_q16_t rmin, int32_t *needed)
{
    /* W = hypot(|q|, p sin eta) as a projection on its own direction (cheaper than the 64-bit
     * square root; exact but for the rounding of the two products). */
    fx_angle_t z = fx_atan2(k->sp, k->aq);
    fx_q30_t sz, cz;
    fx_sincos(z, &sz, &cz);
    int32_t x = fx_mul_q30(k->aq, cz) + fx_mul_q30(k->sp, sz) + k->cq;
    int32_t curv;
    bool fits = fx_div_shift(x, k->e2, (uint8_t)(21 + k->sh), &curv);
    if (!fits || fx_mul_q16(curv, rmin) > DRIVE_CURV_ONE) {
        if (needed != NULL)
            *needed = fits ? curv : INT32_MAX;
        return DRIVE_ERR_RADIUS;
    }
    /* The radius (L20: fits below 2048 * 2^k m), rho = r sin eta (L24). */
    int32_t r20, rho = 0;
    if (!fx_div_shift(k->e2, x, 19, &r20)) {
        r20 = INT32_MAX; /* as large as it gets, for the choice of lengths */
        (void)fx_div_shift(fx_mul_q30(k->e2, k->s), x, 23, &rho);
    } else if (r20 < (1l << 27)) {
        rho = fx_mul_q30(r20 * 16, k->s);
    } else {
        rho = fx_mul_q30(r20, k->s) * 16;
    }
    /* rho <= p/2 whenever |q| sin(eta) <= p cos(eta) (always for sigma > 0, as P > 0): J
     * cannot pass E (sigma > 0) or fall behind O (sigma < 0). When q and p sin(eta) are a few
     * LSB, rho is known only roughly and may overshoot; moving J along u keeps it on the locus
     * of junctions to within (q / |E|) |d rho| < 1 LSB, so the clamp costs nothing and keeps
     * both chords forward. */
    if ((k->q >= 0 || k->pc + k->qs >= 0) && rho > k->p / 2)
        rho = k->p / 2;
    if (k->q < 0)
        rho = -rho; /* sigma rho */
    int32_t jx2 = k->p + 2 * rho, kx2 = k->p - 2 * rho;
    fx_angle_t gamma = fx_atan2(k->q, jx2);
    int32_t tau0 = (int32_t)(gamma + (fx_angle_t)k->eta), tau1 = (int32_t)(0u - gamma);
    if (k->q < 0 && tau0 > 0)
        return DRIVE_ERR_SWEEP;
    int32_t len[2];
    arc_lengths(k, tau0, tau1, jx2, kx2, r20, len);
    if (len[0] < 0 || len[1] < 0)
        return DRIVE_ERR_SWEEP;
    if (k->q < 0)
        curv = -curv;
    k->seg[0].curvature = curv;
    k->seg[0].length = unscale(len[0], k->sh);
    k->seg[0].sweep = (fx_angle_t)tau0 * 2u;
    k->seg[1].curvature = -curv;
    k->seg[1].length = unscale(len[1], k->sh);
    k->seg[1].sweep = (fx_angle_t)k->dl - k->seg[0].sweep;
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
    canon_t k;
    k.sh = 13; /* 8 - k */
    for (uint32_t lim = (uint32_t)1 << 13; m > lim; lim <<= 1)
        k.sh--;

    /* E in the u frame: p along u, q to its left. */
    k.dl = dl;
    k.eta = dl / 2;
    drive_to_frame((int32_t)((uint32_t)dx << k.sh), (int32_t)((uint32_t)dy << k.sh),
                   from->heading + (reverse ? FX_ANGLE_HALF : 0u) + (fx_angle_t)k.eta, &k.p, &k.q);

    /* Mirror image: solve a heading change to the left (or none, target on the left). */
    bool mirror = k.eta < 0 || (k.eta == 0 && k.q < 0);
    if (mirror) {
        k.eta = -k.eta;
        k.q = -k.q;
        k.dl = -dl;
    }
    parameters(&k);
    if (k.pp <= 0)
        return DRIVE_ERR_BEHIND;
    if (k.sh == 4 && k.e2 > (1l << 28))
        return DRIVE_ERR_TOO_FAR; /* |D| > 64 m */
    if (k.sh == 13 && k.e2 < (1l << 22))
        return DRIVE_ERR_TOO_CLOSE; /* |D| < 1/64 m */

    if (dl < STRAIGHT_ANGLE && dl > -STRAIGHT_ANGLE && k.aq <= ((int32_t)1 << k.sh)) {
        /* Straight case: two halves of P along A. */
        out->kase = DRIVE_CASE_STRAIGHT;
        k.seg[0] = (drive_segment_t){0, unscale(k.pp / 2, k.sh), 0};
        k.seg[1] = (drive_segment_t){0, unscale(k.pp - k.pp / 2, k.sh), 0};
    } else {
        /* A5 = p sin(eta) - |q| cos(eta) = Lc sin(eta) > 0 when an arc and a straight fit
         * (rotation and translation the same way, eta > beta), and then the arc's radius
         * Lc / (2 sin eta) >= rmin when A5 >= 2 sin^2(eta) rmin: a cheap filter before the
         * exact test in arc_and_straight() (the seed's order: case 4/5 first, then its
         * fallback, the double arc). rs = rmin sin(eta) in L24. */
        int32_t rs;
        if (k.a5 > 0 && k.s > 0 && fx_mul_shift(min_radius, k.s, (uint8_t)(30 - k.sh), &rs) &&
            rs < INT32_MAX / 2 && k.a5 >= fx_mul_q30(rs * 2, k.s) &&
            arc_and_straight(&k, min_radius)) {
            out->kase = k.q >= 0 ? DRIVE_CASE_4 : DRIVE_CASE_5;
        } else {
            drive_status_t st = double_arc(&k, min_radius, needed);
            if (st != DRIVE_OK)
                return st;
            /* For q < 0, p sin(eta) - |q| cos(eta) is T = A x D: >= 0 same side (case 2). */
            out->kase = k.q >= 0 ? DRIVE_CASE_1 : (k.a5 >= 0 ? DRIVE_CASE_2 : DRIVE_CASE_3);
        }
    }

    /* Back to the real world: mirror, reverse. The sweeps are heading changes of the vehicle
     * (equal to those of the direction of travel); the curvature is the steering's, so
     * reverse travel mirrors it. */
    for (uint8_t i = 0; i < 2u; i++) {
        out->seg[i] = k.seg[i];
        if (mirror)
            out->seg[i].sweep = 0u - out->seg[i].sweep;
        if (mirror != reverse)
            out->seg[i].curvature = -out->seg[i].curvature;
    }
    return DRIVE_OK;
}
