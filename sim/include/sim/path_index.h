/*
 * path_index.h - the distance from a point to the nominal path (docs/interfaces.md's cross_track_m:
 * the minimum over every piece of the path), at a cost that does not grow with the path's
 * length. The pieces are filed in a uniform grid of square cells by their bounding boxes; a
 * query visits the cells in rings around the point and stops when no unvisited cell can hold
 * a piece closer than the best found, so the answer is exactly sim_path_distance()'s. Pieces
 * that repeat an earlier one exactly (a route driven several times) are filed once. A point
 * outside the grid falls back to examining every piece.
 */
#ifndef SIM_PATH_INDEX_H
#define SIM_PATH_INDEX_H

#include <stddef.h>
#include <stdint.h>

#include "sim/path.h"

typedef struct {
    const sim_path_t *path;
    double x0, y0;      /* corner of cell (0, 0), m */
    double cell;        /* cell side, m */
    int nx, ny;         /* cells */
    uint32_t *first;    /* nx * ny + 1 offsets into items (cell k: items[first[k]..first[k+1])) */
    uint32_t *items;    /* piece numbers */
    uint32_t *distinct; /* the pieces that repeat no earlier one */
    size_t n_distinct;
    sim_piece_geom_t *geom; /* per piece: its geometry (the distinct pieces' filled) */
    uint32_t *seen;         /* per piece: the last query that examined it */
    uint32_t query;
    uint32_t nearest; /* the distinct piece nearest at the last query (piece 0 at first) */
    /* work counters (deterministic): queries answered, pieces examined */
    uint64_t queries, examined;
} sim_path_index_t;

/**
 * Index @p p (kept by reference: it must not change while indexed). Returns 0, or -1 when
 * memory runs out. An empty path gives an index whose distance is INFINITY.
 */
int sim_path_index_build(sim_path_index_t *ix, const sim_path_t *p);

/** Shortest distance from (x, y) to the path, m: equal to sim_path_distance(). */
double sim_path_index_distance(sim_path_index_t *ix, double x, double y);

/** Release the index's memory. */
void sim_path_index_free(sim_path_index_t *ix);

#endif
