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

/** Shortest distance from (x, y) to the piece, m. */
double sim_piece_distance(const sim_piece_t *pc, double x, double y);

/** What sim_piece_distance() works out from the piece alone (its end, its line or arc). */
typedef struct {
    double ex, ey;            /* the end, m */
    double ux, uy;            /* a straight piece: its direction of travel */
    double cx, cy, r, a0, sw; /* an arc: centre, m; signed radius, m; start angle, signed sweep */
} sim_piece_geom_t;

/** Fill @p g for @p pc (once per piece: the trigonometry of sim_piece_distance()). */
void sim_piece_geom(const sim_piece_t *pc, sim_piece_geom_t *g);

/** sim_piece_distance() from @p pc's geometry @p g (sim_piece_geom()): the same number. */
double sim_piece_geom_distance(const sim_piece_t *pc, const sim_piece_geom_t *g, double x,
                               double y);

/** The piece's bounding box {xmin, ymin, xmax, ymax}, m, with a micrometre of slack. */
void sim_piece_bounds(const sim_piece_t *pc, double box[4]);

/** Shortest distance from (x, y) to the path, m (the minimum over its pieces); INFINITY for an
 * empty path. */
double sim_path_distance(const sim_path_t *p, double x, double y);

/** Total length, m. */
double sim_path_length(const sim_path_t *p);

#endif
