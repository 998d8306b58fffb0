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
