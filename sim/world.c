/*
 * world.c - the simulated building: overlapping beacons, line of sight.
 */
#include "sim/world.h"

#include <math.h>

bool sim_world_coincident(const sim_world_t *w, size_t *i, size_t *j)
{
    for (size_t a = 0; a < w->n_beacons; a++)
        for (size_t b = a + 1; b < w->n_beacons; b++) {
            const sim_beacon_t *p = &w->beacon[a], *q = &w->beacon[b];
            if (hypot(p->x - q->x, p->y - q->y) < 0.5 * (p->diameter + q->diameter)) {
                *i = a;
                *j = b;
                return true;
            }
        }
    return false;
}

/* Signed area of the triangle (a, b, c): > 0 when c is left of a->b. */
static double orient(double ax, double ay, double bx, double by, double cx, double cy)
{
    return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

bool sim_world_visible(const sim_world_t *w, double ax, double ay, double bx, double by)
{
    for (size_t i = 0; i < w->n_occluders; i++) {
        const sim_occluder_t *o = &w->occluder[i];
        double d1 = orient(ax, ay, bx, by, o->x1, o->y1);
        double d2 = orient(ax, ay, bx, by, o->x2, o->y2);
        double d3 = orient(o->x1, o->y1, o->x2, o->y2, ax, ay);
        double d4 = orient(o->x1, o->y1, o->x2, o->y2, bx, by);
        if (((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)))
            return false;
    }
    double dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy;
    for (size_t i = 0; i < w->n_pillars; i++) {
        const sim_pillar_t *c = &w->pillar[i];
        /* The point of the segment nearest to the centre. */
        double u = len2 > 0 ? ((c->x - ax) * dx + (c->y - ay) * dy) / len2 : 0.0;
        u = u < 0 ? 0 : u > 1 ? 1 : u;
        double r = 0.5 * c->diameter;
        if (hypot(ax + u * dx - c->x, ay + u * dy - c->y) < r)
            return false;
    }
    return true;
}

/* |(x, y)|: sqrt without hypot()'s care for overflow (the margins below dwarf its rounding). */
static double norm2d(double x, double y)
{
    return sqrt(x * x + y * y);
}

/* -1, 0 or +1: the sign of @p v when its magnitude exceeds @p margin, else 0 (too close). */
static int sure_sign(double v, double margin)
{
    return v > margin ? 1 : v < -margin ? -1 : 0;
}

/*
 * For a viewpoint p within r of c, sim_world_visible()'s orientations are linear in p:
 *   orient(p, B, a) = (B - c) x (a - B) + (c - p) x (a - B), the second term at most r |a - B|;
 *   orient(a1, a2, p) = (a2 - a1) x (c - a1) + (a2 - a1) x (p - c), at most r |a2 - a1|.
 * A sign is sure for the whole disk when the first term exceeds that bound plus a margin far
 * above the rounding of either computation (a few 1e-16 of the distances squared, s^2).
 */
sim_sight_t sim_world_sight(const sim_world_t *w, double cx, double cy, double r, double bx,
                            double by)
{
    double ux = bx - cx, uy = by - cy; /* B - c */
    double reach = norm2d(ux, uy) + r; /* every viewpoint is within this of B */
    bool clear = true;
    for (size_t i = 0; i < w->n_occluders; i++) {
        const sim_occluder_t *o = &w->occluder[i];
        double ax = o->x1 - bx, ay = o->y1 - by, qx = o->x2 - bx, qy = o->y2 - by; /* - B */
        double la = norm2d(ax, ay), lq = norm2d(qx, qy), ell = norm2d(o->x2 - o->x1, o->y2 - o->y1);
        double s = fmax(reach, fmax(la, lq)), tol = 1e-9 * s * s;
        /* The wall's ends against the line of sight (d1, d2), the viewpoint and B against
         * the wall's line (d3, d4). */
        int s1 = sure_sign(ux * ay - uy * ax, r * la + tol);
        int s2 = sure_sign(ux * qy - uy * qx, r * lq + tol);
        int s3 = sure_sign(orient(o->x1, o->y1, o->x2, o->y2, cx, cy), r * ell + tol);
        int s4 = sure_sign(orient(o->x1, o->y1, o->x2, o->y2, bx, by), tol);
        if (s1 && s2 && s1 != s2 && s3 && s4 && s3 != s4)
            return SIM_SIGHT_BLOCKED;
        if (!((s1 && s1 == s2) || (s3 && s3 == s4)))
            clear = false;
    }
    double len2 = ux * ux + uy * uy;
    for (size_t i = 0; clear && i < w->n_pillars; i++) {
        const sim_pillar_t *c = &w->pillar[i];
        /* Each line of sight lies within r of the one from the centre c. */
        double u = len2 > 0 ? ((c->x - cx) * ux + (c->y - cy) * uy) / len2 : 0.0;
        u = u < 0 ? 0 : u > 1 ? 1 : u;
        double d = norm2d(cx + u * ux - c->x, cy + u * uy - c->y);
        if (!(d - r - 0.5 * c->diameter > 1e-9 * (reach + norm2d(c->x - bx, c->y - by))))
            clear = false;
    }
    return clear ? SIM_SIGHT_CLEAR : SIM_SIGHT_UNSURE;
}
