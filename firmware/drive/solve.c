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

/* Straight case (the seed's THRESH test): a heading change below 2^12 binary-angle LSB
 * (6e-6 rad, 3.4e-4 degrees) and a lateral offset of at most one Q16 LSB (15 um): the two
 * straight halves then land within 0.4 mm at 64 m. */
#define STRAIGHT_ANGLE 4096l
/* Half-sweeps (binary angles) bounding the ways of getting arc lengths (double_arc()). */
#define TAU_TINY       20506958l  /* 0.03 rad */
#define TAU_SMALL      136713055l /* 0.2 rad */

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

/* The canonical problem: heading change 2 eta >= 0 to the left, target E = (p, q) in the frame
 * of the mean heading u, lengths in L24 (Q24 of 2^k m). Powers of two of the scale are kept
 * as numbers (variable shifts are slow loops on the MSP430). */
typedef struct {
    int32_t p, q, aq;   /* L24; aq = |q| */
    int32_t eta;        /* binary angle, 0 <= eta <= quarter / 2 */
    fx_q30_t s, c;      /* sin eta, cos eta */
    int32_t pc, qs;     /* p cos eta, q sin eta */
    int32_t sp, cq;     /* p sin eta, |q| cos eta */
    int32_t e2;         /* |E|^2, L24 m^2 */
    int8_t k;           /* scale 2^k m, -5..4 */
    int32_t up;         /* 2^(8 - k): one Q16 LSB in L24 */
    int32_t down;       /* 2^(22 + k): L24 -> Q16 is fx_mul_q30(v, down) */
    fx_q16_t rmin;      /* metres Q16 */
    drive_case_t kase;  /* result: case */
    int32_t curv;       /* result: first arc's curvature, Q4.28 /m, canonical sign */
    int32_t len0, len1; /* result: lengths, L24 (case 4/5: the arc's already in Q16) */
    int32_t arc_q16;    /* case 4/5: the arc's length, Q16 m */
    fx_angle_t sweep0;  /* result: first segment's heading change (double arc), canonical */
} canon_t;

/* Cases 4 and 5: an arc and a straight, when the arc's radius (as driven) is >= rmin.
 * Straight l = |q| / sin(eta); the arc's chord Lc = p - l cos(eta) lies along u. */
static bool arc_and_straight(canon_t *z)
{
    int32_t l, lc, arc;
    int32_t eta30 = drive_angle_to_rad_q30(z->eta);
    if (z->eta < TAU_SMALL) {
        if (!fx_div_shift(z->aq, z->s, 30, &l))
            return false;
        lc = z->p - fx_mul_q30(l, z->c);
        arc = fx_mul_q30(lc, drive_x_over_sin_small(eta30));
    } else {
        int32_t inv_s; /* 1 / sin(eta) <= 5.1, Q4.28 */
        (void)fx_div_shift(FX_Q30_ONE, z->s, 28, &inv_s);
        l = fx_mul_q30(z->aq * 4, inv_s);
        lc = z->p - fx_mul_q30(l, z->c);
        arc = fx_mul_q30(fx_mul_q30(lc * 2, inv_s), eta30 * 2); /* 2 eta r */
    }
    if (lc <= 0 || arc <= 0)
        return false;
    /* The straight next to the arc can be long: make the arc's heading change exact in the
     * units it is driven in. Length rounded up, curvature = sweep / length (never above the
     * true one), and that curvature checked against the minimum radius. */
    int32_t arc_q16 = fx_mul_q30(arc, z->down);
    if (arc_q16 * z->up < arc)
        arc_q16++;
    if (!fx_div_shift(eta30, arc_q16, 15, &z->curv) ||
        fx_mul_q16(z->curv, z->rmin) > DRIVE_CURV_ONE)
        return false;
    z->arc_q16 = arc_q16;
    if (z->q >= 0) {
        z->kase = DRIVE_CASE_4;
        z->len1 = l;
        z->sweep0 = (fx_angle_t)z->eta * 2u;
    } else {
        z->kase = DRIVE_CASE_5;
        z->len0 = l;
    }
    return true;
}

/* For |tau|, |g| < 0.03 rad, from the squares of the binary angles scaled by 32
 * (a' = (32 tau)^2 / 2^30, so that tau^2 = a' pi^2 / 4096 in Q30): sec(g) tau / sin(tau) =
 * 1 + g^2/2 + tau^2/6 + O(4) = 1 + (a' + 3 b') pi^2 / 24576; the fourth-order terms stay
 * below 3e-7. */
#define PI2_OVER_24576_Q30 431210l

static int32_t chord_factor_tiny(int32_t a, int32_t b)
{
    return (int32_t)(FX_Q30_ONE + fx_mul_q30(a + 3 * b, PI2_OVER_24576_Q30));
}

/* Cases 1, 2 and 3: a double arc of equal radii, first turn sigma = sign(q).
 * X = sqrt(q^2 + (p sin eta)^2) + |q| cos eta, curvature 2 X / |E|^2, radius r = |E|^2 / (2 X),
 * rho = r sin(eta), junction 2J = (p + 2 sigma rho, q), half-sweeps gamma + eta and -gamma
 * with gamma the angle of J. */
static drive_status_t double_arc(canon_t *z, int32_t *needed)
{
    int32_t sigma = z->q >= 0 ? 1 : -1;
    /* W = hypot(q, p sin eta) as a projection on its own direction (cheaper than the 64-bit
     * square root on the MSP430; exact but for the rounding of the two products). */
    fx_q30_t zs, zc;
    fx_sincos(fx_atan2(z->sp, z->aq), &zs, &zc);
    int32_t x = fx_mul_q30(z->aq, zc) + fx_mul_q30(z->sp, zs) + z->cq;
    bool fits = fx_div_shift(x, z->e2, (uint8_t)(29 - z->k), &z->curv);
    if (!fits || fx_mul_q16(z->curv, z->rmin) > DRIVE_CURV_ONE) {
        if (needed != NULL)
            *needed = fits ? z->curv : INT32_MAX;
        return DRIVE_ERR_RADIUS;
    }
    int32_t r20, rho; /* radius L20 (fits below 2048 * 2^k m), rho L24 */
    bool have_r = fx_div_shift(z->e2, x, 19, &r20);
    if (!have_r)
        (void)fx_div_shift(fx_mul_q30(z->e2, z->s), x, 23, &rho);
    else if (r20 < (1l << 27))
        rho = fx_mul_q30(r20 * 16, z->s);
    else
        rho = fx_mul_q30(r20, z->s) * 16;
    /* rho <= p/2 whenever |q| sin(eta) <= p cos(eta) (always for sigma > 0, as P > 0): J
     * cannot pass E (sigma > 0) or fall behind O (sigma < 0). When q and p sin(eta) are a few
     * LSB, rho is known only roughly and may overshoot; moving J along u keeps it on the locus
     * of junctions to within (q / |E|) |d rho| < 1 LSB, so the clamp costs nothing and keeps
     * both chords forward. */
    if ((sigma > 0 || z->pc + z->qs >= 0) && rho > z->p / 2)
        rho = z->p / 2;
    int32_t jx2 = z->p + 2 * sigma * rho, kx2 = z->p - 2 * sigma * rho;
    int32_t gamma = (int32_t)fx_atan2(z->q, jx2);
    int32_t tau0 = gamma + z->eta, tau1 = -gamma;
    if (sigma < 0 && tau0 > 0)
        return DRIVE_ERR_SWEEP;
    uint32_t big = drive_abs32(tau0) > drive_abs32(tau1) ? drive_abs32(tau0) : drive_abs32(tau1);
    /* Lengths. From the radius, s = 2 |tau| r, unless the radius is large: an error d in tau
     * (fx_atan2: 1.3e-6 rad) costs 2 r d, so below |tau| = 0.03 rad (r > 16 |E|: at most
     * 190 m for legs up to 8 m) and, for longer legs, for radii over 256 m below 0.2 rad, they
     * come from the chords: arc 1 from O to J at angle gamma = -tau1 from u, arc 2 from J to
     * E at gamma + eta = tau0: s = (chord along u) sec(chord angle) tau / sin(tau), as series
     * in the angles. */
    if (big < (uint32_t)TAU_TINY) {
        int32_t a0 = fx_mul_q30(tau0 * 32, tau0 * 32), a1 = fx_mul_q30(tau1 * 32, tau1 * 32);
        z->len0 = fx_mul_q30(jx2 / 2, chord_factor_tiny(a0, a1));
        z->len1 = fx_mul_q30(kx2 / 2, chord_factor_tiny(a1, a0));
    } else if (z->k >= 2 && big < (uint32_t)TAU_SMALL &&
               (!have_r || r20 >= ((int32_t)1 << (28 - z->k)))) {
        int32_t t0 = drive_angle_to_rad_q30(tau0), t1 = drive_angle_to_rad_q30(tau1);
        z->len0 = fx_mul_q30(fx_mul_q30(jx2 / 2, drive_sec_small(t1)), drive_x_over_sin_small(t0));
        z->len1 = fx_mul_q30(fx_mul_q30(kx2 / 2, drive_sec_small(t0)), drive_x_over_sin_small(t1));
    } else {
        /* r <= |E| / (2 sin 0.03) < 95 * 2^k m here. 2 |tau| r = |tau (binary)| pi r / 2^30:
         * rp = pi r / 4 (L24), s = fx_mul_q30(rp, |tau|) * 4. */
        int32_t rp = fx_mul_q30(r20 * 16, 843314857l); /* pi / 4, Q30 */
        z->len0 = fx_mul_q30(rp, (int32_t)drive_abs32(tau0)) * 4;
        z->len1 = fx_mul_q30(rp, (int32_t)drive_abs32(tau1)) * 4;
    }
    if (z->len0 < 0 || z->len1 < 0)
        return DRIVE_ERR_SWEEP;
    /* For q < 0, p sin(eta) - |q| cos(eta) is T = A x D: >= 0 same side (case 2). */
    z->kase = sigma > 0 ? DRIVE_CASE_1 : (z->sp - z->cq >= 0 ? DRIVE_CASE_2 : DRIVE_CASE_3);
    z->curv *= sigma;
    z->sweep0 = (fx_angle_t)tau0 * 2u;
    return DRIVE_OK;
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
    canon_t z;
    z.eta = dl / 2;
    z.rmin = min_radius;

    /* D and its scale 2^k: |dx|, |dy| <= 4 * 2^k m (Q16: 2^(18 + k)), -5 <= k <= 4. */
    int32_t dx = (int32_t)((uint32_t)to->x - (uint32_t)from->x);
    int32_t dy = (int32_t)((uint32_t)to->y - (uint32_t)from->y);
    if (((to->x ^ from->x) & (to->x ^ dx)) < 0 || ((to->y ^ from->y) & (to->y ^ dy)) < 0)
        return DRIVE_ERR_TOO_FAR; /* the difference overflows: over 32768 m */
    uint32_t mx = drive_abs32(dx), my = drive_abs32(dy), m = mx > my ? mx : my;
    if (m > (uint32_t)DRIVE_MAX_DIST)
        return DRIVE_ERR_TOO_FAR;
    uint32_t lim = (uint32_t)1 << 13;
    z.k = -5;
    z.up = (int32_t)1 << 13;
    z.down = (int32_t)1 << 17;
    int32_t rlim = INT32_MAX >> 13; /* INT32_MAX / up */
    while (m > lim) {
        lim <<= 1;
        z.up >>= 1;
        z.down <<= 1;
        rlim = (rlim << 1) | 1;
        z.k++;
    }

    /* E in the u frame: p along u, q to its left. */
    fx_q30_t cu, su;
    fx_sincos(a1 + (fx_angle_t)z.eta, &su, &cu);
    dx *= z.up; /* L24, |.| <= 2^26 */
    dy *= z.up;
    z.p = fx_mul_q30(dx, cu) + fx_mul_q30(dy, su);
    z.q = fx_mul_q30(dy, cu) - fx_mul_q30(dx, su);

    /* Mirror image: solve a heading change to the left (or none, target on the left). */
    bool mirror = z.eta < 0 || (z.eta == 0 && z.q < 0);
    if (mirror) {
        z.eta = -z.eta;
        z.q = -z.q;
    }
    fx_sincos((fx_angle_t)z.eta, &z.s, &z.c);
    z.aq = z.q < 0 ? -z.q : z.q;

    /* P = A . D > 0: the target is ahead. */
    z.pc = fx_mul_q30(z.p, z.c);
    z.qs = fx_mul_q30(z.q, z.s);
    int32_t pp = z.pc - z.qs;
    if (pp <= 0)
        return DRIVE_ERR_BEHIND;
    z.e2 = fx_mul_q30(z.p * 8, z.p * 8) + fx_mul_q30(z.q * 8, z.q * 8);
    if (z.k == 4 && z.e2 > (1l << 28))
        return DRIVE_ERR_TOO_FAR; /* |D| > 64 m */
    if (z.k == -5 && z.e2 < (1l << 22))
        return DRIVE_ERR_TOO_CLOSE; /* |D| < 1/64 m */
    z.curv = 0;
    z.sweep0 = 0;
    z.arc_q16 = 0;

    if (dl < STRAIGHT_ANGLE && dl > -STRAIGHT_ANGLE && z.aq <= z.up) {
        /* Straight case: two halves along A. */
        z.kase = DRIVE_CASE_STRAIGHT;
        z.len0 = pp / 2;
        z.len1 = pp - z.len0;
    } else {
        /* A5 = p sin(eta) - |q| cos(eta) = Lc sin(eta) > 0 when an arc and a straight fit
         * (rotation and translation the same way, eta > beta), and then the arc's radius
         * Lc / (2 sin eta) >= rmin when A5 >= 2 sin^2(eta) rmin: a cheap filter before the
         * exact test in arc_and_straight() (the seed's order: case 4/5 first, then its
         * fallback, the double arc). */
        z.sp = fx_mul_q30(z.p, z.s);
        z.cq = fx_mul_q30(z.aq, z.c);
        int32_t a5 = z.sp - z.cq, rs = INT32_MAX; /* rmin sin(eta), L24 */
        if (a5 > 0 && z.s > 0) {
            if (min_radius <= rlim)
                rs = fx_mul_q30(min_radius * z.up, z.s);
            else if (!fx_mul_shift(min_radius, z.s, (uint8_t)(22 + z.k), &rs))
                rs = INT32_MAX;
        }
        bool line = rs < INT32_MAX / 2 && a5 >= fx_mul_q30(rs * 2, z.s) && arc_and_straight(&z);
        if (!line) {
            drive_status_t st = double_arc(&z, needed);
            if (st != DRIVE_OK)
                return st;
        }
    }

    /* Back to the real world: mirror, reverse, units. The sweeps are heading changes of the
     * vehicle (equal to those of the direction of travel); the curvature is the steering's,
     * so reverse travel mirrors it. */
    int32_t curv = mirror ? -z.curv : z.curv;
    fx_angle_t sweep0 = mirror ? 0u - z.sweep0 : z.sweep0;
    int32_t steer = reverse ? -curv : curv;
    drive_segment_t *s0 = &out->seg[0], *s1 = &out->seg[1];
    out->kase = z.kase;
    switch (z.kase) {
    case DRIVE_CASE_STRAIGHT:
        s0->length = fx_mul_q30(z.len0, z.down);
        s1->length = fx_mul_q30(z.len1, z.down);
        s0->curvature = s1->curvature = 0;
        s0->sweep = s1->sweep = 0;
        break;
    case DRIVE_CASE_4:
        s0->length = z.arc_q16;
        s1->length = fx_mul_q30(z.len1, z.down);
        s0->curvature = steer;
        s0->sweep = (fx_angle_t)dl;
        s1->curvature = 0;
        s1->sweep = 0;
        break;
    case DRIVE_CASE_5:
        s0->length = fx_mul_q30(z.len0, z.down);
        s1->length = z.arc_q16;
        s0->curvature = 0;
        s0->sweep = 0;
        s1->curvature = steer;
        s1->sweep = (fx_angle_t)dl;
        break;
    default:
        s0->length = fx_mul_q30(z.len0, z.down);
        s1->length = fx_mul_q30(z.len1, z.down);
        s0->curvature = steer;
        s0->sweep = sweep0;
        s1->curvature = -steer;
        s1->sweep = (fx_angle_t)dl - sweep0;
        break;
    }
    return DRIVE_OK;
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
    if (drive_abs32((int32_t)half) < (uint32_t)TAU_SMALL) {
        ratio = drive_sin_over_x_small(drive_angle_to_rad_q28((int32_t)half) * 4);
    } else {
        /* sin x / x in Q30: negative beyond half a turn (the chord points back) */
        (void)fx_div_shift(fx_sin(half), half28, 28, &ratio);
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
