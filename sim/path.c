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
    *g = (sim_piece_geom_t){e.x, e.y, 0, 0, 0, 0, 0, 0, 0};
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
}

double sim_piece_geom_distance(const sim_piece_t *pc, const sim_piece_geom_t *g, double x, double y)
{
    double to_end = hypot(x - g->ex, y - g->ey), to_start = hypot(x - pc->x0, y - pc->y0);
    double best = fmin(to_start, to_end);
    if (fabs(pc->kappa) < 1e-12) {
        /* Segment from start to end. */
        double s = (x - pc->x0) * g->ux + (y - pc->y0) * g->uy;
        if (s > 0.0 && s < pc->length)
            best = fmin(best, fabs(-(x - pc->x0) * g->uy + (y - pc->y0) * g->ux));
        return best;
    }
    arc_t arc = {g->cx, g->cy, g->r, g->a0, g->sw};
    if (arc_covers(&arc, atan2(y - arc.cy, x - arc.cx)))
        best = fmin(best, fabs(hypot(x - arc.cx, y - arc.cy) - fabs(arc.r)));
    return best;
}

double sim_piece_distance(const sim_piece_t *pc, double x, double y)
{
    sim_piece_geom_t g;
    sim_piece_geom(pc, &g);
    return sim_piece_geom_distance(pc, &g, x, y);
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
