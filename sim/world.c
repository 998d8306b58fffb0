/*
 * world.c - line of sight in the simulated building.
 */
#include "sim/world.h"

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
    return true;
}
