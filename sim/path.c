/*
 * path.c - the nominal path and the distance to it (see path.h).
 */
#include "sim/path.h"

#include <math.h>

sim_pose_t sim_piece_end(const sim_piece_t *pc)
{
    double d = pc->reverse ? -pc->length : pc->length;
    sim_segment_t seg;
    seg.t0 = 0.0;
    seg.p0 = (sim_pose_t){pc->x0, pc->y0, pc->th0};
    seg.kappa = pc->kappa;
    seg.v = d;
    seg.front_per_rear = 1.0;
    seg.front0 = 0.0;
    seg.decel = 0.0;
    return sim_segment_pose(&seg, 1.0);
}

int sim_path_append_from(sim_path_t *p, sim_pose_t start, double kappa, double length, int reverse)
{
    if (p->n >= SIM_MAX_PIECES)
        return -1;
    sim_piece_t *pc = &p->piece[p->n++];
    pc->x0 = start.x;
    pc->y0 = start.y;
    pc->th0 = start.th;
    pc->kappa = kappa;
    pc->length = length;
    pc->reverse = reverse;
    return 0;
}

int sim_path_append(sim_path_t *p, sim_pose_t start, double kappa, double length, int reverse)
{
    sim_pose_t s = p->n ? sim_piece_end(&p->piece[p->n - 1]) : start;
    return sim_path_append_from(p, s, kappa, length, reverse);
}

sim_pose_t sim_path_end(const sim_path_t *p)
{
    return sim_piece_end(&p->piece[p->n - 1]);
}

double sim_path_length(const sim_path_t *p)
{
    double s = 0.0;
    for (size_t i = 0; i < p->n; i++)
        s += p->piece[i].length;
    return s;
}

/* Arc geometry: centre, radius (signed like 1 / kappa), start angle, signed sweep. */
typedef struct {
    double cx, cy, r, a0, sweep;
} arc_t;

static arc_t arc_of(const sim_piece_t *pc)
{
    arc_t a;
    double dir = pc->reverse ? -1.0 : 1.0;
    /* Centre on the left of the heading for kappa > 0 (right for < 0). */
    a.r = 1.0 / pc->kappa;
    a.cx = pc->x0 - a.r * sin(pc->th0);
    a.cy = pc->y0 + a.r * cos(pc->th0);
    a.a0 = atan2(pc->y0 - a.cy, pc->x0 - a.cx);
    a.sweep = pc->kappa * pc->length * dir; /* signed angle swept around the centre */
    return a;
}

/* Is direction @p a (rad, from the centre) within the arc's swept angle? */
static int arc_covers(const arc_t *arc, double a)
{
    double rel = remainder(a - arc->a0, 2.0 * M_PI);
    return arc->sweep >= 0.0 ? (rel >= 0.0 ? rel <= arc->sweep : rel + 2.0 * M_PI <= arc->sweep)
                             : (rel <= 0.0 ? rel >= arc->sweep : rel - 2.0 * M_PI >= arc->sweep);
}

void sim_piece_geom(const sim_piece_t *pc, sim_piece_geom_t *g)
{
    sim_pose_t e = sim_piece_end(pc);
    double dir = pc->reverse ? -1.0 : 1.0;
    *g = (sim_piece_geom_t){e.x, e.y, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    if (fabs(pc->kappa) < 1e-12) {
        g->ux = cos(pc->th0) * dir;
        g->uy = sin(pc->th0) * dir;
        return;
    }
    arc_t arc = arc_of(pc);
    g->cx = arc.cx;
    g->cy = arc.cy;
    g->r = arc.r;
    g->a0 = arc.a0;
    g->sw = arc.sweep;
    g->ecos = cos(arc.a0 + arc.sweep);
    g->esin = sin(arc.a0 + arc.sweep);
}

/* Below this, m (or m^2 for squares), the rounding arguments of the shortcuts need care with
 * subnormal numbers: the shortcuts stand aside. Above 1e60 products could overflow. */
#define SMALL 1e-60
#define LARGE 1e60

/* Relative slack of the squared comparisons in ring_beyond(): far above double rounding. */
#define SLACK 1e-12

/* sin^2 of the angular margin of in_wedge(): 1e-9 rad, far above the rounding of atan2(). */
#define SIDE2 1e-18

int sim_path_ring_beyond(double v2, double r, double best)
{
    if (!(best >= SMALL))
        return 0;
    double out = r + best;
    if (v2 > out * out * (1.0 + SLACK))
        return 1;
    double in = r - best;
    return in >= SMALL && v2 < in * in * (1.0 - SLACK);
}

int sim_path_in_wedge(double px, double py, double qx, double qy, double vx, double vy)
{
    double p2 = px * px + py * py, q2 = qx * qx + qy * qy, v2 = vx * vx + vy * vy;
    if (!(p2 >= SMALL && p2 <= LARGE && q2 >= SMALL && q2 <= LARGE && v2 >= SMALL && v2 <= LARGE))
        return 0;
    double a = px * vy - py * vx; /* |p| |v| sin(angle from p to v) */
    double b = vx * qy - vy * qx; /* |v| |q| sin(angle from v to q) */
    double ma = SIDE2 * p2 * v2, mb = SIDE2 * v2 * q2;
    if (a > 0.0 && b > 0.0 && a * a > ma && b * b > mb)
        return 1;
    if ((a < 0.0 && a * a > ma) || (b < 0.0 && b * b > mb))
        return -1;
    return 0;
}

/*
 * arc_covers(arc, atan2(vy, vx)) for the arc of @p g starting at radius vector (px, py) (its
 * start minus its centre, m) and the point's radius vector (vx, vy), m, decided by cross
 * products: 1 covered, -1 not, 0 too close to a boundary to tell (the caller asks
 * arc_covers()). A sweep of at most half a turn is the covered wedge from the start to the
 * end direction (clockwise sweeps: from the end to the start); a longer one leaves the
 * uncovered wedge the other way round; a whole turn or more is left to arc_covers().
 */
static int arc_side(const sim_piece_geom_t *g, double px, double py, double vx, double vy)
{
    double sw = g->sw, ex = g->ecos, ey = g->esin;
    if (sw >= 0.0 && sw <= M_PI)
        return sim_path_in_wedge(px, py, ex, ey, vx, vy);
    if (sw > M_PI && sw < 2.0 * M_PI)
        return -sim_path_in_wedge(ex, ey, px, py, vx, vy);
    if (sw < 0.0 && sw >= -M_PI)
        return sim_path_in_wedge(ex, ey, px, py, vx, vy);
    if (sw < -M_PI && sw > -2.0 * M_PI)
        return -sim_path_in_wedge(px, py, ex, ey, vx, vy);
    return 0;
}

/* min(best, the distance to the point (x, y) - (dx, dy)): hypot() only when it can win. */
static double nearer_point(double best, double dx, double dy)
{
    if (sim_path_ring_beyond(dx * dx + dy * dy, 0.0, best))
        return best;
    return sim_path_least(best, hypot(dx, dy));
}

double sim_piece_geom_nearer(const sim_piece_t *pc, const sim_piece_geom_t *g, double x, double y,
                             double best)
{
    if (fabs(pc->kappa) < 1e-12) {
        /* Segment from start to end. */
        double s = (x - pc->x0) * g->ux + (y - pc->y0) * g->uy;
        if (s > 0.0 && s < pc->length)
            best = sim_path_least(best, fabs(-(x - pc->x0) * g->uy + (y - pc->y0) * g->ux));
    } else {
        /* The arc's inside: the distance to its circle where the arc covers the direction. */
        double vx = x - g->cx, vy = y - g->cy;
        if (!sim_path_ring_beyond(vx * vx + vy * vy, fabs(g->r), best)) {
            int side = arc_side(g, pc->x0 - g->cx, pc->y0 - g->cy, vx, vy);
            arc_t arc = {g->cx, g->cy, g->r, g->a0, g->sw};
            if (side > 0 || (side == 0 && arc_covers(&arc, atan2(vy, vx))))
                best = sim_path_least(best, fabs(hypot(vx, vy) - fabs(g->r)));
        }
    }
    best = nearer_point(best, x - pc->x0, y - pc->y0);
    return nearer_point(best, x - g->ex, y - g->ey);
}

double sim_piece_distance(const sim_piece_t *pc, double x, double y)
{
    sim_piece_geom_t g;
    sim_piece_geom(pc, &g);
    return sim_piece_geom_nearer(pc, &g, x, y, INFINITY);
}

void sim_piece_bounds(const sim_piece_t *pc, double box[4])
{
    sim_pose_t e = sim_piece_end(pc);
    box[0] = fmin(pc->x0, e.x);
    box[1] = fmin(pc->y0, e.y);
    box[2] = fmax(pc->x0, e.x);
    box[3] = fmax(pc->y0, e.y);
    if (fabs(pc->kappa) >= 1e-12) {
        /* The circle's extreme points in x and y that the arc passes. */
        arc_t arc = arc_of(pc);
        double r = fabs(arc.r);
        for (int k = 0; k < 4; k++) {
            double a = k * 0.5 * M_PI;
            if (!arc_covers(&arc, remainder(a, 2.0 * M_PI)))
                continue;
            double px = arc.cx + r * cos(a), py = arc.cy + r * sin(a);
            box[0] = fmin(box[0], px);
            box[1] = fmin(box[1], py);
            box[2] = fmax(box[2], px);
            box[3] = fmax(box[3], py);
        }
    }
    /* Rounding of the pose and trig evaluations: a micrometre of slack. */
    for (int k = 0; k < 4; k++)
        box[k] += (k < 2 ? -1.0 : 1.0) * (1e-6 + 1e-12 * fabs(box[k]));
}

double sim_path_distance(const sim_path_t *p, double x, double y)
{
    double best = INFINITY;
    for (size_t i = 0; i < p->n; i++)
        best = fmin(best, sim_piece_distance(&p->piece[i], x, y));
    return best;
}
