/*
 * seq_table.h - the state table's guards and internal actions (seq.c, msp430/seq.S); only
 * #defines outside the __ASSEMBLER__ guard.
 */
#ifndef DRIVE_SEQ_TABLE_H
#define DRIVE_SEQ_TABLE_H

/* Guards: conditions a row needs besides its state and event (bit numbers of a mask). */
#define G_ANY          0
#define G_FULL         1  /* START: full travel, path ready                         */
#define G_SIMPLIFIED   2  /* START: simplified travel, path ready                   */
#define G_NOT_READY    3  /* START: the path is not ready                           */
#define G_ARRIVED      4  /* pose/fix: the last point is reached, nothing to drive  */
#define G_SOLVED_LAST  5  /* pose/fix: a double arc to the last point is ready      */
#define G_SOLVED       6  /* pose/fix: a double arc to a point before it is ready   */
#define G_FAILED       7  /* pose/fix: no double arc (or command) to the target     */
#define G_PULSE_MORE   8  /* delta-S: more pulses of the loaded double arc to come  */
#define G_PULSE_FINAL  9  /* delta-S: the last pulse of the loaded double arc       */
#define G_FINAL_LAST   10 /* delta-S: ... and it was driving to the last point      */
#define G_FINAL_PLAST  11 /* delta-S: final pulse; the pending double arc is last   */
#define G_PENDING_LAST 12 /* timer: the pending double arc goes to the last point   */
#define G_FIX_RETRY    13 /* fix failed: still within the tolerated failures        */
#define G_FIX_GIVE_UP  14 /* fix failed: too many in a row                          */

/* Internal actions, translated by the step (above the public DRIVE_ACT_* bits). */
#define X_TIMER_SETTLE 0x1000 /* DRIVE_ACT_TIMER with settle_ms   */
#define X_TIMER_LOAD   0x2000 /* DRIVE_ACT_TIMER with load_ms     */
#define X_POSE_PREDICT 0x4000 /* DRIVE_ACT_REQUEST_POSE at load_ms */
#define X_NEXT_TARGET  0x8000 /* advance to the next path point    */
#define X_UNDERRUN     0x0800 /* count a double arc that ran out   */
#define PUBLIC_ACTIONS 0x07FF

#define SAME 0xFE /* next state: unchanged */

/* Outcome of picking a target and solving toward it. */
#define PICK_NONE    0
#define PICK_ARRIVED 1
#define PICK_SOLVED  2
#define PICK_FAILED  3

/* Rows of the table. */
#define DRIVE_SEQ_ROWS 42

#ifndef __ASSEMBLER__
#include "drive/drive_seq.h"

/* The table (seq.c), read by the C and the assembly step. */
extern const drive_seq_row_t drive_seq_rows[DRIVE_SEQ_ROWS];
#endif

#endif
