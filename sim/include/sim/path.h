/*
 * path.h - the nominal path: a chain of circular arcs and straights (double precision),
 * and the distance of a point to it (the cross-track error of docs/interfaces.md).
 */
#ifndef SIM_PATH_H
#define SIM_PATH_H

#include <stddef.h>

#include "sim/motion.h"

#define SIM_MAX_PIECES 4096

typedef struct {
    double x0, y0, th0; /* start of the piece: rear-axle position and heading */
    double kappa;       /* curvature, 1/m, left positive (0 = straight) */
    double length;      /* rear-axle path length, m (>= 0); travelled backwards if reverse */
    int reverse;        /* 1 when the vehicle drives this piece backwards */
} sim_piece_t;

typedef struct {
    sim_piece_t piece[SIM_MAX_PIECES];
    size_t n;
} sim_path_t;

/** Append a piece that starts where the path ends (or at @p start for the first). Returns 0
 * or -1 when the path is full. */
int sim_path_append(sim_path_t *p, sim_pose_t start, double kappa, double length, int reverse);

/** Append a piece that starts at @p start whatever the path's end. Returns 0 or -1 (full). */
int sim_path_append_from(sim_path_t *p, sim_pose_t start, double kappa, double length, int reverse);

/** The pose at the end of a piece. */
sim_pose_t sim_piece_end(const sim_piece_t *pc);

/** The pose at the end of the whole path (the start pose of an empty path is undefined). */
sim_pose_t sim_path_end(const sim_path_t *p);

/** min(@p best, @p d) for numbers that are not NaN: @p d only when smaller (fmin() without
 * its call). */
static inline double sim_path_least(double best, double d)
{
    return d < best ? d : best;
}

/** Shortest distance from (x, y) to the piece, m (INFINITY for a NaN point). */
double sim_piece_distance(const sim_piece_t *pc, double x, double y);

/** What sim_piece_distance() works out from the piece alone (its end, its line or arc). */
typedef struct {
    double ex, ey;            /* the end, m */
    double ux, uy;            /* a straight piece: its direction of travel */
    double cx, cy, r, a0, sw; /* an arc: centre, m; signed radius, m; start angle, signed sweep */
    double ecos, esin;        /* an arc: cos and sin of a0 + sw (the end's direction) */
} sim_piece_geom_t;

/** Fill @p g for @p pc (once per piece: the trigonometry of sim_piece_distance()). */
void sim_piece_geom(const sim_piece_t *pc, sim_piece_geom_t *g);

/**
 * min(@p best, sim_piece_distance(@p pc, @p x, @p y)), m, from @p pc's geometry @p g
 * (sim_piece_geom()): bit for bit the same number, with less work when @p best is small (a
 * part of the piece that cannot come closer than @p best is not measured exactly). @p best:
 * m, >= 0 or INFINITY. A NaN point leaves @p best.
 */
double sim_piece_geom_nearer(const sim_piece_t *pc, const sim_piece_geom_t *g, double x, double y,
                             double best);

/**
 * Is |hypot(vx, vy) - @p r|, as double arithmetic rounds it, certainly >= @p best, m, for a
 * point at squared distance @p v2 = vx^2 + vy^2 (m^2) from a centre? @p r >= 0 is the radius
 * of a circle about the centre, m (0: the distance to the centre itself). 1 when the
 * squares decide it with a relative margin of 1e-12, else 0 (also for @p best below 1e-60 m,
 * where subnormal squares could mislead).
 */
int sim_path_ring_beyond(double v2, double r, double best);

/**
 * Where the vector v = (@p vx, @p vy) points relative to the wedge swept counter-clockwise
 * from p = (@p px, @p py) to q = (@p qx, @p qy) (a wedge of at most half a turn, give or take
 * rounding): 1 inside, -1 outside, each by more than 1e-9 rad of angle; 0 when nearer a side
 * than that, or when a squared length is outside [1e-60, 1e60] (any unit, the same for all).
 */
int sim_path_in_wedge(double px, double py, double qx, double qy, double vx, double vy);

/** The piece's bounding box {xmin, ymin, xmax, ymax}, m, with a micrometre of slack. */
void sim_piece_bounds(const sim_piece_t *pc, double box[4]);

/** Shortest distance from (x, y) to the path, m (the minimum over its pieces); INFINITY for an
 * empty path. */
double sim_path_distance(const sim_path_t *p, double x, double y);

/** Total length, m. */
double sim_path_length(const sim_path_t *p);

#endif
