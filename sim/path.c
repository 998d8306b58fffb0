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

static double piece_distance(const sim_piece_t *pc, double x, double y)
{
    sim_pose_t e = sim_piece_end(pc);
    double to_end = hypot(x - e.x, y - e.y), to_start = hypot(x - pc->x0, y - pc->y0);
    double best = fmin(to_start, to_end);
    double dir = pc->reverse ? -1.0 : 1.0;
    if (fabs(pc->kappa) < 1e-12) {
        /* Segment from start to end. */
        double ux = cos(pc->th0) * dir, uy = sin(pc->th0) * dir;
        double s = (x - pc->x0) * ux + (y - pc->y0) * uy;
        if (s > 0.0 && s < pc->length)
            best = fmin(best, fabs(-(x - pc->x0) * uy + (y - pc->y0) * ux));
        return best;
    }
    /* Arc: centre on the left of the heading for kappa > 0 (right for < 0). */
    double r = 1.0 / pc->kappa;
    double cx = pc->x0 - r * sin(pc->th0), cy = pc->y0 + r * cos(pc->th0);
    double a0 = atan2(pc->y0 - cy, pc->x0 - cx);
    double a = atan2(y - cy, x - cx);
    double sweep = pc->kappa * pc->length * dir; /* signed angle swept around the centre */
    double rel = remainder(a - a0, 2.0 * M_PI);
    /* Is the point's direction within the swept angle? */
    int inside = sweep >= 0.0 ? (rel >= 0.0 ? rel <= sweep : rel + 2.0 * M_PI <= sweep)
                              : (rel <= 0.0 ? rel >= sweep : rel - 2.0 * M_PI >= sweep);
    if (inside)
        best = fmin(best, fabs(hypot(x - cx, y - cy) - fabs(r)));
    return best;
}

double sim_path_distance(const sim_path_t *p, double x, double y)
{
    double best = INFINITY;
    for (size_t i = 0; i < p->n; i++)
        best = fmin(best, piece_distance(&p->piece[i], x, y));
    return best;
}
