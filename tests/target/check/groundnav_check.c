/*
 * groundnav_check.c - the check-mode wrappers of the groundnav kernels (docs/kernels.md,
 * kernel_check.h): the C twin runs on a copy of what the kernel writes (the accumulators, or
 * the whole gnav_t), which is compared with the assembly's afterwards.
 */
#include "gnav_arith.h"
#include "kernel_check.h"

void __real_gnav_add64x2(int64_t *xy, const int32_t *v);
void __wrap_gnav_add64x2(int64_t *xy, const int32_t *v);
void gnav_add64x2_c(int64_t *xy, const int32_t *v);
void __real_gnav_sub64x2(int64_t *xy, const int32_t *v);
void __wrap_gnav_sub64x2(int64_t *xy, const int32_t *v);
void gnav_sub64x2_c(int64_t *xy, const int32_t *v);
void __real_gnav_chord(gnav_t *g, int32_t e, const int32_t *step);
void __wrap_gnav_chord(gnav_t *g, int32_t e, const int32_t *step);
void gnav_chord_c(gnav_t *g, int32_t e, const int32_t *step);
void __real_gnav_arc(gnav_t *g, uint16_t half, const int32_t *step);
void __wrap_gnav_arc(gnav_t *g, uint16_t half, const int32_t *step);
void gnav_arc_c(gnav_t *g, uint16_t half, const int32_t *step);

/* add64x2 and sub64x2: the two accumulators before the call and the step are the inputs. */
static void pair(const char *name, kcheck_stat_t *st, void (*real)(int64_t *, const int32_t *),
                 void (*twin_fn)(int64_t *, const int32_t *), int64_t *xy, const int32_t *v)
{
    const uint32_t in[] = {(uint32_t)((uint64_t)xy[0] >> 32),
                           (uint32_t)xy[0],
                           (uint32_t)((uint64_t)xy[1] >> 32),
                           (uint32_t)xy[1],
                           (uint32_t)v[0],
                           (uint32_t)v[1]};
    int64_t copy[2] = {xy[0], xy[1]};
    KCHECK_RUN(st, real(xy, v), twin_fn(copy, v));
    kcheck_bytes(name, "x_hi,x_lo,y_hi,y_lo,v0,v1", in, 6, xy, copy, sizeof copy);
}

void __wrap_gnav_add64x2(int64_t *xy, const int32_t *v)
{
    static kcheck_stat_t st = KCHECK_STAT("gnav_add64x2");
    pair("gnav_add64x2", &st, __real_gnav_add64x2, gnav_add64x2_c, xy, v);
}

void __wrap_gnav_sub64x2(int64_t *xy, const int32_t *v)
{
    static kcheck_stat_t st = KCHECK_STAT("gnav_sub64x2");
    pair("gnav_sub64x2", &st, __real_gnav_sub64x2, gnav_sub64x2_c, xy, v);
}

/* The twin's copy of the whole state (the handlers do not nest: one is enough), and where a
 * pointer into the state (step: one of g's inc) points in the copy. */
static gnav_t twin;

static const int32_t *in_twin(const gnav_t *g, const int32_t *p)
{
    return (const int32_t *)((const char *)&twin + ((const char *)p - (const char *)g));
}

/* The inputs of a closing kernel: its argument and what it reads of g before the call. */
#define CLOSING_INPUTS(arg)                                                                        \
    const uint32_t in[] = {(uint32_t)(arg),                                                        \
                           (uint32_t)step[0],                                                      \
                           (uint32_t)step[1],                                                      \
                           ((uint32_t)(uint16_t)g->n_hi << 16) | g->n_lo,                          \
                           g->n_p,                                                                 \
                           g->rho_p,                                                               \
                           (uint32_t)g->resid,                                                     \
                           g->reverse}
#define CLOSING_NAMES ",step0,step1,n,n_p,rho_p,resid,reverse"

void __wrap_gnav_chord(gnav_t *g, int32_t e, const int32_t *step)
{
    static kcheck_stat_t st = KCHECK_STAT("gnav_chord");
    CLOSING_INPUTS(e);
    twin = *g;
    const int32_t *step_c = in_twin(g, step);
    KCHECK_RUN(&st, __real_gnav_chord(g, e, step), gnav_chord_c(&twin, e, step_c));
    kcheck_bytes("gnav_chord", "e" CLOSING_NAMES, in, 8, g, &twin, sizeof twin);
}

void __wrap_gnav_arc(gnav_t *g, uint16_t half, const int32_t *step)
{
    static kcheck_stat_t st = KCHECK_STAT("gnav_arc");
    CLOSING_INPUTS(half);
    twin = *g;
    const int32_t *step_c = in_twin(g, step);
    KCHECK_RUN(&st, __real_gnav_arc(g, half, step), gnav_arc_c(&twin, half, step_c));
    kcheck_bytes("gnav_arc", "half" CLOSING_NAMES, in, 8, g, &twin, sizeof twin);
}
