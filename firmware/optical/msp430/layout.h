/*
 * layout.h - what the optical module's MSP430 assembly needs of the C side as plain numbers:
 * the hardware multiplier's registers, the offsets of the structures it reads and writes
 * (MSP430 layout: 2-byte pointers and enums, int32 aligned to 2), their sizes and the status
 * codes it returns. fastmath.c checks every one against the C definitions when it is compiled
 * for the MSP430. Plain numbers only: LLVM's MSP430 assembler misreads an indexed operand
 * that starts with '(' (a parenthesised macro in front of "(rN)").
 */
#ifndef OPTICAL_MSP430_LAYOUT_H
#define OPTICAL_MSP430_LAYOUT_H

/* The 16 x 16 hardware multiplier (MSP430F249). */
#define MPY    0x0130
#define MPYS   0x0132
#define MACS   0x0136
#define OP2    0x0138
#define RESLO  0x013a
#define RESHI  0x013c
#define SUMEXT 0x013e

/* optical_work_t (fastmath.h), the work area optical_work */
#define OW            optical_work
#define OW_B          0
#define OW_X          2
#define OW_Y          6
#define OW_HEAD       10
#define OW_EPS8       12
#define OW_LEVER8     14
#define OW_AMAX8      16
#define OW_GATE8      18
#define OW_NB         20
#define OW_N          21
#define OW_NC         22
#define OW_M          23
#define OW_TH         24
#define OW_LEV        54
#define OW_WE         84
#define OW_SM         174
#define OW_BSTART     189
#define OW_ORD        205
#define OW_WCHK       220
#define OW_POS        235
/* its union u: .id (identification) */
#define OW_PSI        250
#define OW_E          314
#define OW_G          378
#define OW_BM         442
#define OW_CAND       474
/* .sv (solving): the identified angles, the triangulation kernels' frame (at least
 * OW_FRAME_SIZE bytes), optical_triangulate's offsets, sines and cosines, solution */
#define OW_ANG        250
#define OW_FRAME      350
#define OW_FRAME_SIZE 110
#define OW_SV_V       460
#define OW_SV_SC      476
#define OW_SV_TS      492
/* after the union: the compiled map and its origin */
#define OW_B8         554
#define OW_OX         556
#define OW_OY         560

/* the match codes of optical_work_t.sm / .bm (OPTICAL_NONE, _MULTI, _DROPPED: NONE as -1,
 * the constant generator's, whose low byte it is), OPTICAL_MARGIN, OPTICAL_MAX_CAND */
#define MATCH_NONE    -1
#define MATCH_MULTI   0xfe
#define MATCH_DROPPED 0xfd
#define MARGIN        6
#define MAX_CAND      40

/* optical_tsol_t (fastmath.h) */
#define TSOL_OFF 0
#define TSOL_W   8
#define TSOL_L   16
#define TSOL_R   28
#define TSOL_X   32

/* optical_xy_t, optical_pose_t, optical_sighting_t, optical_map_t (optical.h) */
#define XY_X         0
#define XY_Y         4
#define XY_SIZE      8
#define POSE_X       0
#define POSE_Y       4
#define POSE_HEADING 8
#define POSE_SIZE    12
#define SIGHT_ANGLE  0
#define SIGHT_WIDTH  4
#define SIGHT_SIZE   6
#define MAP_B        0
#define MAP_N        2

/* optical_config_t (optical.h) */
#define CFG_DIAMETER 0
#define CFG_FLAT     4
#define CFG_WIN_POS  10
#define CFG_DIST_TOL 30
#define CFG_DIST_REL 34
#define CFG_JUMP_MAX 38
#define CFG_TURN_MAX 42

/* optical_width_t (fastmath.h) */
#define WD_DK    0
#define WD_X     4
#define WD_Y     8
#define WD_EPS8  12
#define WD_TOL8  14
#define WD_REL16 16
#define WD_FLAT  18

/* optical_tri_t, optical_fix_t (optical.h); ident holds MAX_SIGHTINGS bytes; the map at most
 * MAX_BEACONS beacons */
#define TRI_POSE      0
#define TRI_QUALITY   12
#define FIX_POSE      0
#define FIX_QUALITY   12
#define FIX_IDENT     16
#define FIX_N_IDENT   34
#define FIX_WIDENED   35
#define MAX_SIGHTINGS 15
#define MAX_BEACONS   32

/* optical_status_t */
#define E_DEGENERATE 4
#define E_SINGULAR   5
#define E_JUMP       6
#define E_TURN       7
#define E_DISAGREE   8

#endif
