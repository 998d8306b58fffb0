/*
 * solve_frame.h - the frames of drive_solve() and drive_pose_advance() (solve.c,
 * msp430/solve.S) and the numbers the C and the assembly share: the solver's thresholds, and
 * drive.h's limits and status codes as plain numbers (solve.c checks them against drive.h).
 * The assembly reads it too: only #defines outside the __ASSEMBLER__ guard.
 *
 * drive_solve()'s slots are int32 values of the canonical problem (heading change 2 eta >= 0
 * to the left, target E = (p, q) in the frame of the mean heading u), lengths in L24. Pairs
 * that an instruction writes or reads together are adjacent; slots whose values are dead by
 * then are shared (noted).
 */
#ifndef DRIVE_SOLVE_FRAME_H
#define DRIVE_SOLVE_FRAME_H

/* The result, as two drive_segment_t: curvature, length (Q16), sweep. */
#define SV_K0     0 /* also DX: D, L24 (the first rotation's input)          */
#define SV_L0     1 /* also DY                                               */
#define SV_W0     2
#define SV_K1     3
#define SV_L1     4
#define SV_W1     5
#define SV_DX     0
#define SV_DY     1
/* The canonical problem. */
#define SV_P      6 /* E in the u frame                                     */
#define SV_Q      7
#define SV_ETA    8  /* binary angle, 0 <= eta <= quarter / 2                */
#define SV_S      9  /* sin eta                                              */
#define SV_C      10 /* cos eta                                              */
#define SV_AQ     11 /* |q|                                                  */
#define SV_SP     12 /* p sin eta (with AQ: the input of W's rotation)       */
#define SV_PC     13 /* p cos eta                                            */
#define SV_QS     14 /* q sin eta                                            */
#define SV_PP     15 /* P = A . D = p cos eta - q sin eta                    */
#define SV_E2     16 /* |E|^2, L24 m^2                                       */
#define SV_CQ     17 /* |q| cos eta                                          */
#define SV_A5     18 /* p sin eta - |q| cos eta                              */
#define SV_KC     19 /* the first arc's curvature, Q4.28 /m (canonical sign)  */
#define SV_ARCQ   20 /* cases 4, 5: the arc, Q16 (KC, ARCQ, DL: a segment)  */
#define SV_DL     21 /* the heading change B - A (canonical sign)            */
#define SV_T0     22 /* temporaries                                          */
#define SV_T1     23
#define SV_T2     24
#define SV_T3     25
/* Cases 4, 5 (an arc and a straight). */
#define SV_E30    26 /* eta, radians Q30                                     */
#define SV_L      27 /* the straight                                         */
#define SV_LC     28 /* the arc's chord along u                              */
#define SV_ARC    29 /* the arc                                              */
#define SV_INVS   30 /* 1 / sin eta, Q4.28                                   */
/* Cases 1, 2, 3 (the double arc), sharing the slots of cases 4, 5. */
#define SV_Z      26 /* angle of (|q|, p sin eta)                            */
#define SV_W      27 /* its length (WJ: the rotation's other output)         */
#define SV_WJ     28
#define SV_X      29 /* W + |q| cos eta                                      */
#define SV_R20    30 /* radius, L20                                          */
#define SV_RS     31 /* sigma rho                                            */
#define SV_JX2    32 /* p + 2 sigma rho                                      */
#define SV_KX2    33 /* p - 2 sigma rho                                      */
#define SV_G      34 /* gamma, the angle of the junction J                   */
#define SV_TAU0   35 /* half-sweeps                                          */
#define SV_TAU1   36
#define SV_A0     37 /* (32 tau)^2 / 2^30                                    */
#define SV_A1     38
#define SV_LEN0   39 /* the arcs, L24                                        */
#define SV_LEN1   40
#define SV_NSLOTS 41

/* drive_pose_advance()'s frame. */
#define PV_D28             0 /* the heading change, radians Q28                       */
#define PV_H28             1 /* its half                                              */
#define PV_HALF            2 /* the half as a binary angle                            */
#define PV_DANG            3 /* the change as a binary angle                          */
#define PV_T               4 /* temporaries                                           */
#define PV_X               5
#define PV_RATIO           6 /* sin(half) / half, Q30                                 */
#define PV_DIST            7 /* the distance, Q16                                     */
#define PV_CH              8 /* the chord (with ZERO: the rotation's input)           */
#define PV_ZERO            9
#define PV_XY              10 /* the chord as a vector                                 */
#define PV_XY1             11
#define PV_ANG             12 /* minus its direction                                   */
#define PV_HEAD            13 /* the direction of travel                               */
#define PV_NSLOTS          14
#define HALF_CHANGE_SERIES 53687091 /* 0.2 rad, Q28: sin x / x as a series below it */

/* Straight case (the seed's THRESH test): a heading change below 2^12 binary-angle LSB
 * (6e-6 rad, 3.4e-4 degrees) and a lateral offset of at most one Q16 LSB (15 um): the two
 * straight halves then land within 0.4 mm at 64 m. */
#define STRAIGHT_ANGLE 4096
/* Half-sweeps (binary angles) bounding the ways of getting arc lengths (double arc). */
#define TAU_TINY       20506958  /* 0.03 rad */
#define TAU_SMALL      136713055 /* 0.2 rad */

/* drive.h's limits and status codes as plain numbers for the assembly (solve.c checks that
 * they agree). */
#define DRIVE_MIN_RADIUS_MIN_Q16 0x2000   /* 0.125 m */
#define DRIVE_MIN_RADIUS_MAX_Q16 0x640000 /* 100 m */
#define DRIVE_MAX_DIST_Q16       0x400000 /* 64 m */
#define DRIVE_ERR_PARAM_N        1
#define DRIVE_ERR_TOO_CLOSE_N    2
#define DRIVE_ERR_TOO_FAR_N      3
#define DRIVE_ERR_BEHIND_N       4
#define DRIVE_ERR_HEADING_N      5
#define DRIVE_ERR_RADIUS_N       6
#define DRIVE_ERR_SWEEP_N        7
#define DRIVE_ERR_RANGE_N        8
#define DRIVE_ERR_PATH_N         9

#ifndef __ASSEMBLER__
#include <stdint.h>

/* The programs on these frames (solve.c; drive_internal.h), run by the C and the assembly. */
extern const uint8_t drive_p_canon[];
extern const uint8_t drive_p_line_small[];
extern const uint8_t drive_p_line_big[];
extern const uint8_t drive_p_x[];
extern const uint8_t drive_p_junction[];
extern const uint8_t drive_p_da_tail[];
extern const uint8_t drive_p_halves[];
extern const uint8_t drive_p_len_tiny[];
extern const uint8_t drive_p_len_small[];
extern const uint8_t drive_p_len_radius[];
extern const uint8_t drive_p_pa_angles[];
extern const uint8_t drive_p_pa_sox[];
extern const uint8_t drive_p_pa_chord[];
#endif

#endif
