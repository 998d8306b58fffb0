/*
 * path_index.c - nearest piece of the nominal path through a uniform grid (see path_index.h).
 */
#include "sim/path_index.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CELL      1.0       /* m: the cell side, doubled until the grid is small enough */
#define MAX_CELLS (1 << 20) /* cells at most */

static int same_piece(const sim_piece_t *a, const sim_piece_t *b)
{
    return a->x0 == b->x0 && a->y0 == b->y0 && a->th0 == b->th0 && a->kappa == b->kappa &&
           a->length == b->length && a->reverse == b->reverse;
}

/* Cells [i0, i1] x [j0, j1] that the box covers, clipped to the grid. */
static void cell_span(const sim_path_index_t *ix, const double box[4], int span[4])
{
    span[0] = (int)floor((box[0] - ix->x0) / ix->cell);
    span[1] = (int)floor((box[1] - ix->y0) / ix->cell);
    span[2] = (int)floor((box[2] - ix->x0) / ix->cell);
    span[3] = (int)floor((box[3] - ix->y0) / ix->cell);
    span[0] = span[0] < 0 ? 0 : span[0];
    span[1] = span[1] < 0 ? 0 : span[1];
    span[2] = span[2] >= ix->nx ? ix->nx - 1 : span[2];
    span[3] = span[3] >= ix->ny ? ix->ny - 1 : span[3];
}

int sim_path_index_build(sim_path_index_t *ix, const sim_path_t *p)
{
    memset(ix, 0, sizeof *ix);
    ix->path = p;
    size_t n = p->n;
    ix->distinct = malloc((n ? n : 1) * sizeof *ix->distinct);
    ix->seen = calloc(n ? n : 1, sizeof *ix->seen);
    ix->geom = malloc((n ? n : 1) * sizeof *ix->geom);
    double(*box)[4] = malloc((n ? n : 1) * sizeof *box);
    if (!ix->distinct || !ix->seen || !ix->geom || !box) {
        free(box);
        sim_path_index_free(ix);
        return -1;
    }
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t i = 0; i < n; i++) {
        size_t k = 0;
        while (k < ix->n_distinct && !same_piece(&p->piece[ix->distinct[k]], &p->piece[i]))
            k++;
        if (k < ix->n_distinct)
            continue; /* the same piece again: it cannot change a minimum */
        ix->distinct[ix->n_distinct++] = (uint32_t)i;
        sim_piece_geom(&p->piece[i], &ix->geom[i]);
        sim_piece_bounds(&p->piece[i], box[i]);
        for (int c = 0; c < 2; c++) {
            lo[c] = fmin(lo[c], box[i][c]);
            hi[c] = fmax(hi[c], box[i][c + 2]);
        }
    }
    if (ix->n_distinct == 0) {
        free(box);
        return 0;
    }
    /* One cell of margin around the pieces: a vehicle slightly off the path stays inside. */
    ix->cell = CELL;
    for (;;) {
        double w = hi[0] - lo[0] + 2 * ix->cell, h = hi[1] - lo[1] + 2 * ix->cell;
        ix->nx = (int)ceil(w / ix->cell);
        ix->ny = (int)ceil(h / ix->cell);
        if ((double)ix->nx * ix->ny <= MAX_CELLS)
            break;
        ix->cell *= 2;
    }
    ix->x0 = lo[0] - ix->cell;
    ix->y0 = lo[1] - ix->cell;
    size_t cells = (size_t)ix->nx * (size_t)ix->ny;
    ix->first = calloc(cells + 1, sizeof *ix->first);
    if (!ix->first) {
        free(box);
        sim_path_index_free(ix);
        return -1;
    }
    /* Two passes: count the pieces per cell, then file them. */
    for (int pass = 0; pass < 2; pass++) {
        for (size_t k = 0; k < ix->n_distinct; k++) {
            uint32_t i = ix->distinct[k];
            int s[4];
            cell_span(ix, box[i], s);
            for (int cy = s[1]; cy <= s[3]; cy++)
                for (int cx = s[0]; cx <= s[2]; cx++) {
                    size_t c = (size_t)cy * (size_t)ix->nx + (size_t)cx;
                    if (pass == 0)
                        ix->first[c + 1]++;
                    else
                        ix->items[ix->first[c + 1]++] = i;
                }
        }
        if (pass == 0) {
            for (size_t c = 0; c < cells; c++)
                ix->first[c + 1] += ix->first[c];
            ix->items = malloc((ix->first[cells] ? ix->first[cells] : 1) * sizeof *ix->items);
            if (!ix->items) {
                free(box);
                sim_path_index_free(ix);
                return -1;
            }
            /* Fill from each cell's start: first[c + 1] runs from first[c] to its end. */
            memmove(ix->first + 1, ix->first, cells * sizeof *ix->first);
            ix->first[0] = 0;
        }
    }
    free(box);
    return 0;
}

void sim_path_index_free(sim_path_index_t *ix)
{
    free(ix->first);
    free(ix->items);
    free(ix->distinct);
    free(ix->seen);
    free(ix->geom);
    ix->first = ix->items = ix->distinct = ix->seen = NULL;
    ix->geom = NULL;
    ix->n_distinct = 0;
}

static double examine(sim_path_index_t *ix, uint32_t i, double x, double y, double best)
{
    if (ix->seen[i] == ix->query)
        return best;
    ix->seen[i] = ix->query;
    ix->examined++;
    double d = sim_piece_geom_nearer(&ix->path->piece[i], &ix->geom[i], x, y, best);
    if (d < best)
        ix->nearest = i;
    return d;
}

/* Every distinct piece: the answer for a point outside the grid. */
static double scan_all(sim_path_index_t *ix, double x, double y, double best)
{
    for (size_t k = 0; k < ix->n_distinct; k++)
        best = examine(ix, ix->distinct[k], x, y, best);
    return best;
}

double sim_path_index_distance(sim_path_index_t *ix, double x, double y)
{
    ix->queries++;
    if (ix->n_distinct == 0)
        return INFINITY;
    if (++ix->query == 0) { /* the stamps wrapped: start them afresh */
        memset(ix->seen, 0, ix->path->n * sizeof *ix->seen);
        ix->query = 1;
    }
    /* The piece nearest last time first: usually the nearest again, its distance lets the
     * other pieces be passed over cheaply (the minimum does not depend on the order). */
    double best = examine(ix, ix->nearest, x, y, INFINITY);
    double fx = (x - ix->x0) / ix->cell, fy = (y - ix->y0) / ix->cell;
    if (!(fx >= 0 && fy >= 0 && fx < ix->nx && fy < ix->ny))
        return scan_all(ix, x, y, best);
    int i0 = (int)fx, j0 = (int)fy;
    for (int k = 0;; k++) {
        /* Ring k: the cells at Chebyshev distance k from (i0, j0). */
        for (int j = j0 - k; j <= j0 + k; j++) {
            if (j < 0 || j >= ix->ny)
                continue;
            int step = (j == j0 - k || j == j0 + k) ? 1 : 2 * k;
            for (int i = i0 - k; i <= i0 + k; i += step) {
                if (i < 0 || i >= ix->nx)
                    continue;
                size_t c = (size_t)j * (size_t)ix->nx + (size_t)i;
                for (uint32_t q = ix->first[c]; q < ix->first[c + 1]; q++)
                    best = examine(ix, ix->items[q], x, y, best);
            }
        }
        /* Every unvisited cell lies outside the block of rings 0..k: no piece there is closer
         * than the block's nearest side that still has cells beyond it (a nanometre kept
         * for the rounding of the cell arithmetic). */
        double margin = INFINITY;
        if (i0 - k > 0)
            margin = sim_path_least(margin, x - (ix->x0 + (i0 - k) * ix->cell));
        if (i0 + k + 1 < ix->nx)
            margin = sim_path_least(margin, ix->x0 + (i0 + k + 1) * ix->cell - x);
        if (j0 - k > 0)
            margin = sim_path_least(margin, y - (ix->y0 + (j0 - k) * ix->cell));
        if (j0 + k + 1 < ix->ny)
            margin = sim_path_least(margin, ix->y0 + (j0 + k + 1) * ix->cell - y);
        if (margin == INFINITY || best + 1e-9 <= margin)
            return best;
    }
}
