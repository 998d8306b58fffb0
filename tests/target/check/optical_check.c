/*
 * optical_check.c - the check-mode wrappers of the optical kernels (kernel_check.h,
 * docs/kernels.md): optical_scan, optical_angle16, optical_tri_core and optical_tri_quality,
 * each run as its assembly and as its C twin (scan_k.c, tri_k.c) on every
 * call, every output compared.
 */
#include <stdbool.h>
#include <stdint.h>

#include "kernel_check.h"
#include "optical/fastmath.h"

uint8_t __real_optical_scan(int16_t mid, uint16_t half);
uint8_t __wrap_optical_scan(int16_t mid, uint16_t half);
uint8_t optical_scan_c(int16_t mid, uint16_t half);
uint16_t __real_optical_angle16(int32_t dx, int32_t dy);
uint16_t __wrap_optical_angle16(int32_t dx, int32_t dy);
uint16_t optical_angle16_c(int32_t dx, int32_t dy);
int8_t __real_optical_tri_core(int32_t v[4], const int32_t sc[4], optical_tsol_t *out);
int8_t __wrap_optical_tri_core(int32_t v[4], const int32_t sc[4], optical_tsol_t *out);
int8_t optical_tri_core_c(int32_t v[4], const int32_t sc[4], optical_tsol_t *out);
uint32_t __real_optical_tri_quality(const int32_t v[4], const optical_tsol_t *s);
uint32_t __wrap_optical_tri_quality(const int32_t v[4], const optical_tsol_t *s);
uint32_t optical_tri_quality_c(const int32_t v[4], const optical_tsol_t *s);

/* The work area before the call, and as each side left it. */
static optical_work_t before, after_asm, after_c;

/*
 * What optical_scan's contract leaves open (fastmath.h), cleared in a copy so that the rest
 * compares byte for byte: psi and g of a gated beacon (e = 0), g standing (lever8 = 0: not
 * stored), we of a sighting without a single match.
 */
static void scan_settle(optical_work_t *w)
{
    for (uint8_t k = 0; k < w->nb && k < OPTICAL_MAX_BEACONS; k++) {
        if (w->u.id.e[k] == 0)
            w->u.id.psi[k] = 0;
        if (w->u.id.e[k] == 0 || w->lever8 == 0)
            w->u.id.g[k] = 0;
    }
    for (uint8_t j = 0; j < w->n && j < OPTICAL_MAX_SIGHTINGS; j++)
        if (w->sm[j] >= OPTICAL_DROPPED)
            w->we[j] = 0;
}

/*
 * The scan reads and writes the work area: the assembly runs on it, the C twin on the state
 * from before, then the two results are compared and the assembly's is put back. Calls of
 * more than 8,000 assembly cycles are compared but not timed (the C twin's could pass the
 * 16-bit counter's 65,535).
 */
uint8_t __wrap_optical_scan(int16_t mid, uint16_t half)
{
    static kcheck_stat_t st = KCHECK_STAT("optical_scan");
    kcheck_register(&st);
    const optical_work_t *w = &optical_work;
    const uint32_t in[] = {(uint32_t)(int32_t)mid,
                           half,
                           w->nb,
                           w->n,
                           (uint32_t)w->x,
                           (uint32_t)w->y,
                           w->head,
                           ((uint32_t)w->eps8 << 16) | w->lever8,
                           ((uint32_t)w->amax8 << 16) | w->gate8};
    const char *names = "mid,half,nb,n,x,y,head,eps8:lever8,amax8:gate8";
    before = optical_work;
    uint16_t t0 = cy_bench_now();
    uint8_t r_asm = __real_optical_scan(mid, half);
    uint16_t t1 = cy_bench_now();
    after_asm = optical_work;
    optical_work = before;
    uint16_t t2 = cy_bench_now();
    uint8_t r_c = optical_scan_c(mid, half);
    uint16_t t3 = cy_bench_now();
    uint16_t c_asm = (uint16_t)(t1 - t0 - cy_bench_overhead);
    if (c_asm <= 8000u) {
        kcheck_add(&st.asm_cycles, c_asm);
        kcheck_add(&st.c_cycles, (uint16_t)(t3 - t2 - cy_bench_overhead));
    }
    after_c = optical_work;
    optical_work = after_asm;
    const uint32_t oa[] = {r_asm}, oc[] = {r_c};
    kcheck_words("optical_scan", names, in, 9, oa, oc, 1);
    scan_settle(&after_asm);
    scan_settle(&after_c);
    kcheck_bytes("optical_scan", names, in, 9, &after_asm, &after_c, sizeof after_c);
    return r_asm;
}

/* A pure function: the return values compared. */
uint16_t __wrap_optical_angle16(int32_t dx, int32_t dy)
{
    static kcheck_stat_t st = KCHECK_STAT("optical_angle16");
    const uint32_t in[] = {(uint32_t)dx, (uint32_t)dy};
    uint16_t r_asm, r_c;
    KCHECK_RUN(&st, r_asm = __real_optical_angle16(dx, dy), r_c = optical_angle16_c(dx, dy));
    const uint32_t oa[] = {r_asm}, oc[] = {r_c};
    kcheck_words("optical_angle16", "dx,dy", in, 2, oa, oc, 1);
    return r_asm;
}

/* The solution's fields as words (its padding is nobody's). */
static void tsol_words(const optical_tsol_t *s, uint32_t out[10])
{
    out[0] = (uint32_t)s->off[0];
    out[1] = (uint32_t)s->off[1];
    out[2] = (uint32_t)s->w[0];
    out[3] = (uint32_t)s->w[1];
    out[4] = (uint32_t)s->l[0];
    out[5] = (uint32_t)s->l[1];
    out[6] = (uint32_t)s->l[2];
    out[7] = s->r;
    out[8] = (uint32_t)(int32_t)s->x;
}

/* The core scales v in place and writes *out on OPTICAL_OK (the assembly keeps an
 * intermediate in out->l[1] on its way: out is compared only then). */
int8_t __wrap_optical_tri_core(int32_t v[4], const int32_t sc[4], optical_tsol_t *out)
{
    static kcheck_stat_t st = KCHECK_STAT("optical_tri_core");
    const uint32_t in[] = {(uint32_t)v[0],  (uint32_t)v[1],  (uint32_t)v[2],  (uint32_t)v[3],
                           (uint32_t)sc[0], (uint32_t)sc[1], (uint32_t)sc[2], (uint32_t)sc[3]};
    const char *names = "v0,v1,v2,v3,s1,c1,s2,c2";
    int32_t v_c[4] = {v[0], v[1], v[2], v[3]};
    optical_tsol_t out_c = *out;
    int8_t r_asm, r_c;
    KCHECK_RUN(&st, r_asm = __real_optical_tri_core(v, sc, out),
               r_c = optical_tri_core_c(v_c, sc, &out_c));
    uint32_t oa[4 + 9 + 1], oc[4 + 9 + 1];
    for (uint8_t i = 0; i < 4; i++) {
        oa[i] = (uint32_t)v[i];
        oc[i] = (uint32_t)v_c[i];
    }
    uint8_t n = 4;
    if (r_asm == OPTICAL_OK && r_c == OPTICAL_OK) {
        tsol_words(out, &oa[4]);
        tsol_words(&out_c, &oc[4]);
        n = 13;
    }
    oa[n] = (uint32_t)(int32_t)r_asm;
    oc[n] = (uint32_t)(int32_t)r_c;
    kcheck_words("optical_tri_core", names, in, 8, oa, oc, (uint8_t)(n + 1u));
    return r_asm;
}

uint32_t __wrap_optical_tri_quality(const int32_t v[4], const optical_tsol_t *s)
{
    static kcheck_stat_t st = KCHECK_STAT("optical_tri_quality");
    uint32_t in[4 + 9];
    for (uint8_t i = 0; i < 4; i++)
        in[i] = (uint32_t)v[i];
    tsol_words(s, &in[4]);
    uint32_t r_asm, r_c;
    KCHECK_RUN(&st, r_asm = __real_optical_tri_quality(v, s), r_c = optical_tri_quality_c(v, s));
    const uint32_t oa[] = {r_asm}, oc[] = {r_c};
    kcheck_words("optical_tri_quality", "v0,v1,v2,v3,off0,off1,w0,w1,l0,l1,l2,r,x", in, 13, oa, oc,
                 1);
    return r_asm;
}
