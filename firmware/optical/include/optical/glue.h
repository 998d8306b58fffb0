/*
 * optical/glue.h - the loops of optical_fix()'s C glue (fix.c) that run once per sighting on
 * every fix: the standing preparation, the bucket index, the identification's both-ways
 * uniqueness with its O5 width checks, and the gather of the identified. On the MSP430 they
 * are assembly (msp430/optical_glue.S, OPTICAL_ASM); fix.c holds the portable C that defines
 * every result, and tests/vectors/optical_vectors.c compares both worlds bit for bit.
 *
 * They work on optical_work (optical/fastmath.h), whose fields fix.c describes; sm[j] holds a
 * beacon (below OPTICAL_MAX_BEACONS) or NONE, MULTI, DROPPED (the assembly tells them apart by
 * the sign bit).
 */
#ifndef OPTICAL_GLUE_H
#define OPTICAL_GLUE_H

#include <stdbool.h>
#include <stdint.h>

#include "optical/fastmath.h"
#include "optical/optical.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * optical_fix()'s argument check and its work area and O5 arguments from its inputs: false
 * (nothing written) when @p map is NULL, map->n lies outside [3, OPTICAL_MAX_BEACONS] or
 * approx's x or y outside (-OPTICAL_COORD_LIMIT, OPTICAL_COORD_LIMIT); else true and: b, nb
 * from @p map; x, y and head = (heading + 2^15) >> 16 from @p approx; amax8 = eps8 =
 * min(m8 + 2, 0xFFFF) with m8 = min(ceil(window_pos / 2^8), 0xFFFF) (2^-8 m), lever8 = 0 (as
 * standing); @p wd: dk = (beacon_diameter 10430 mod 2^32) >> 8, x, y as approx, eps8 = m8,
 * tol8 = min(dist_tol >> 8, 0xFFFF), rel16 = min(dist_rel, 0xFFFF) (both as uint32), flat =
 * beacon_flat.
 */
bool optical_setup(const optical_map_t *map, const optical_config_t *cfg,
                   const optical_pose_t *approx, optical_width_t *wd);

/**
 * optical_fix()'s result before any check: ident all -1, n_ident = widened = 0 (pose and
 * quality are written once the outcome is known).
 */
void optical_fix_init(optical_fix_t *out);

/**
 * The standing preparation (no latched poses): sightings @p s[0..n) (n = optical_work.n) by
 * rounded 16-bit angle t = (angle + 2^15) >> 16 into th[], ascending (insertion: equal angles
 * keep their input order), ord[j] the input index of th[j]; the bucket index
 * (optical_buckets); and O4's marks as optical_drop(@p s, @p wmin). Returns the sightings kept.
 */
uint8_t optical_sort(const optical_sighting_t *s, uint16_t wmin);

/**
 * The bucket index of the sorted th[0..n): bstart[b] = the first j with th[j] >> 12 >= b, 0
 * when there is none (b = 0..15).
 */
void optical_buckets(void);

/**
 * The both-ways uniqueness of fix.c's unique() without the overlapping-window rule: every
 * sorted sighting j whose match k = sm[j] is a beacon (below OPTICAL_DROPPED) is kept when
 * bm[k] = j and its width fits (O5: optical_width_ok(@p wd, &b[k], s[ord[j]].width), asked
 * once per (j, k): wchk[j] caches k, bit 7 set for a misfit); otherwise sm[j] becomes
 * OPTICAL_NONE. With @p lohi non-NULL, every kept match narrows [lohi[0], lohi[1]] (heading
 * offsets, 2^-16 turn, signed): off = th[j] - psi[k], e = we[j]; lohi[0] = off - e when
 * off > lohi[0] and off - lohi[0] > e (16 bits, unsigned), lohi[1] = off + e when
 * off < lohi[1] and lohi[1] - off > e. Returns the kept.
 */
int8_t optical_unique(const optical_width_t *wd, const optical_sighting_t *s, int16_t *lohi);

/**
 * The identified: every sorted sighting j with sm[j] below OPTICAL_DROPPED, in order, into
 * pos[0..m), its angle s[ord[j]].angle into u.sv.ang[0..m) and its beacon into the result's
 * @p ident[ord[j]] = sm[j] (the others left alone); m into optical_work.m.
 */
void optical_gather(const optical_sighting_t *s, int8_t *ident);

/**
 * O6's plausibility of the fix @p p against the approximate pose @p ap: OPTICAL_E_JUMP when
 * the distance exceeds cfg->jump_max (jx = |dx|, jy = |dy| unsigned 32-bit: jx > jump_max or
 * jy > jump_max - jx, and fx_hypot(dx, dy) > jump_max), else OPTICAL_E_TURN when
 * |heading - ap heading| (as int32, magnitude unsigned) exceeds cfg->turn_max, else OPTICAL_OK.
 */
int8_t optical_jump(const optical_pose_t *p, const optical_pose_t *ap, const optical_config_t *cfg);

/**
 * O6's residuals: of the identified positions i = 0..m-1 other than @p t3[0..2] (each below
 * 16), the first CHECK_MAX (4) in order: beacon k = sm[pos[i]] seen from the fix @p p, res =
 * optical_angle16(b[k] - p) - a16(p->heading) - a16(u.sv.ang[i]) (16 bits; a16(a) = (a +
 * 2^15) >> 16). Returns OPTICAL_E_DISAGREE at the first with |res| > @p tol (2^-16 turn),
 * else OPTICAL_OK.
 */
int8_t optical_resid(const optical_pose_t *p, const uint8_t t3[3], uint16_t tol);

#ifdef __cplusplus
}
#endif

#endif
