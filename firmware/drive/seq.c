/*
 * seq.c - the travel state table (drive_seq.h) and the delta-S pulse counter.
 */
#include <stddef.h>

#include "drive/drive_seq.h"
#include "hal/edge.h"
#include "hal/irq.h"

#include "drive_internal.h"
#include "seq_table.h"

#ifdef DRIVE_ASM /* msp430/seq.S works with these numbers */
#include "msp430/layout.h"
#include "solve_frame.h"
_Static_assert(offsetof(drive_pose_t, heading) == POSE_HEADING &&
                   offsetof(drive_board_t, min_radius) == BOARD_MIN_R &&
                   offsetof(drive_path_t, pts) == PATH_PTS && offsetof(drive_path_t, n) == PATH_N &&
                   offsetof(drive_path_t, start) == PATH_START &&
                   offsetof(drive_path_t, cfg.nominal_radius) == PATH_NOMINAL &&
                   offsetof(drive_path_t, cfg.reverse) == PATH_REVERSE &&
                   offsetof(drive_path_t, board) == PATH_BOARD &&
                   offsetof(drive_path_t, ready) == PATH_READY &&
                   offsetof(drive_path_t, bad_leg) == PATH_BAD_LEG &&
                   offsetof(drive_path_t, bad_sub) == PATH_BAD_SUB &&
                   offsetof(drive_path_t, bad_why) == PATH_BAD_WHY &&
                   offsetof(drive_path_t, cache_leg) == PATH_CACHE_LEG &&
                   offsetof(drive_path_t, cache) == PATH_CACHE &&
                   offsetof(drive_path_t, cache.seg[0].length) == PATH_CACHE + 6 &&
                   sizeof(drive_path_point_t) == 18 && offsetof(drive_path_point_t, speed) == 12 &&
                   offsetof(drive_path_point_t, nsub) == 16 && sizeof(drive_path_config_t) == 10 &&
                   offsetof(drive_path_config_t, spacing) == 4 &&
                   offsetof(drive_path_config_t, reverse) == 8 &&
                   offsetof(drive_cmd_t, pulses) == CMD_PULSES && sizeof(drive_cmd_t) == CMD_SIZE,
               "layout.h: poses, paths, commands");
_Static_assert(offsetof(drive_seq_t, cfg.mode) == SEQ_MODE &&
                   offsetof(drive_seq_t, cfg.load_ms) == SEQ_LOAD_MS &&
                   offsetof(drive_seq_t, cfg.settle_ms) == SEQ_SETTLE_MS &&
                   offsetof(drive_seq_t, cfg.stop_speed) == SEQ_STOP_SPD &&
                   offsetof(drive_seq_t, cfg.advance) == SEQ_ADVANCE &&
                   offsetof(drive_seq_t, cfg.max_fix_failures) == SEQ_MAX_FIX &&
                   offsetof(drive_seq_t, path) == SEQ_PATH &&
                   offsetof(drive_seq_t, state) == SEQ_STATE &&
                   offsetof(drive_seq_t, target) == SEQ_TARGET &&
                   offsetof(drive_seq_t, loaded) == SEQ_LOADED &&
                   offsetof(drive_seq_t, pending) == SEQ_PENDING &&
                   offsetof(drive_seq_t, pending_last) == SEQ_PEND_LAST &&
                   offsetof(drive_seq_t, loaded_last) == SEQ_LOAD_LAST &&
                   offsetof(drive_seq_t, pulses_seen) == SEQ_SEEN &&
                   offsetof(drive_seq_t, fix_failures) == SEQ_FIXFAIL &&
                   offsetof(drive_seq_t, solve_status) == SEQ_STATUS &&
                   offsetof(drive_seq_t, ignored) == SEQ_IGNORED &&
                   offsetof(drive_seq_t, underruns) == SEQ_UNDERRUNS &&
                   offsetof(drive_seq_t, loads) == SEQ_LOADS,
               "layout.h: drive_seq_t");
_Static_assert(offsetof(drive_seq_out_t, actions) == OUT_ACTIONS &&
                   offsetof(drive_seq_out_t, cmd) == OUT_CMD &&
                   offsetof(drive_seq_out_t, speed) == OUT_SPEED &&
                   offsetof(drive_seq_out_t, timer_ms) == OUT_TIMER &&
                   offsetof(drive_seq_out_t, pose_ms) == OUT_POSE_MS &&
                   offsetof(drive_seq_out_t, fault) == OUT_FAULT &&
                   offsetof(drive_seq_out_t, status) == OUT_STATUS &&
                   sizeof(drive_seq_out_t) == OUT_SIZE &&
                   offsetof(drive_seq_event_t, pose) == EV_POSE &&
                   sizeof(drive_seq_row_t) == ROW_SIZE,
               "layout.h: events, outputs, rows");
_Static_assert(ST_F_START == DRIVE_ST_F_START && ST_F_PREDICT == DRIVE_ST_F_PREDICT &&
                   ST_S_FIX == DRIVE_ST_S_FIX && ST_ANY == DRIVE_ST_ANY &&
                   EVT_FIX_READY == DRIVE_EVT_FIX_READY && EVT_FIX_FAILED == DRIVE_EVT_FIX_FAILED &&
                   EVT_POSE == DRIVE_EVT_POSE && EVT_DELTA_S == DRIVE_EVT_DELTA_S &&
                   MODE_FULL == DRIVE_MODE_FULL && FAULT_NOT_READY == DRIVE_FAULT_NOT_READY &&
                   FAULT_SOLVE == DRIVE_FAULT_SOLVE && FAULT_FIXES == DRIVE_FAULT_FIXES,
               "layout.h: states, events, faults");
_Static_assert(ACT_REQUEST_POSE == DRIVE_ACT_REQUEST_POSE && ACT_LOAD == DRIVE_ACT_LOAD &&
                   ACT_SET_SPEED == DRIVE_ACT_SET_SPEED && ACT_TIMER == DRIVE_ACT_TIMER &&
                   ACT_FAULT == DRIVE_ACT_FAULT && DRIVE_ERR_TOO_CLOSE_N == DRIVE_ERR_TOO_CLOSE &&
                   DRIVE_ERR_BEHIND_N == DRIVE_ERR_BEHIND && DRIVE_ERR_PATH_N == DRIVE_ERR_PATH,
               "layout.h: actions");
#endif

#define ROW(st, ev, g, nx, act)                                                                    \
    {                                                                                              \
        (uint8_t)(st), (uint8_t)(ev), (uint8_t)(g), (uint8_t)(nx), (act)                           \
    }

/* clang-format off */
const drive_seq_row_t drive_seq_rows[DRIVE_SEQ_ROWS] = {
    /* start */
    ROW(DRIVE_ST_IDLE,         DRIVE_EVT_START,      G_NOT_READY,    DRIVE_ST_FAULT,        DRIVE_ACT_FAULT),
    ROW(DRIVE_ST_IDLE,         DRIVE_EVT_START,      G_FULL,         DRIVE_ST_F_START,      DRIVE_ACT_REQUEST_POSE | DRIVE_ACT_INDEX_ON),
    ROW(DRIVE_ST_IDLE,         DRIVE_EVT_START,      G_SIMPLIFIED,   DRIVE_ST_S_SKIP_INDEX, DRIVE_ACT_INDEX_ON),
    /* full travel: the first double arc starts the run */
    ROW(DRIVE_ST_F_START,      DRIVE_EVT_POSE,       G_ARRIVED,      DRIVE_ST_DONE,         DRIVE_ACT_STOP | DRIVE_ACT_DONE),
    ROW(DRIVE_ST_F_START,      DRIVE_EVT_POSE,       G_SOLVED_LAST,  DRIVE_ST_F_STOP1,      DRIVE_ACT_LOAD),
    ROW(DRIVE_ST_F_START,      DRIVE_EVT_POSE,       G_SOLVED,       DRIVE_ST_F_SETTLE,     DRIVE_ACT_LOAD | X_TIMER_SETTLE),
    ROW(DRIVE_ST_F_START,      DRIVE_EVT_POSE,       G_FAILED,       DRIVE_ST_FAULT,        DRIVE_ACT_STOP | DRIVE_ACT_FAULT),
    /* full travel: settle, fix at the index pulse, correct, predict, next target, load */
    ROW(DRIVE_ST_F_SETTLE,     DRIVE_EVT_TIMER,      G_ANY,          DRIVE_ST_F_WAIT_INDEX, 0),
    ROW(DRIVE_ST_F_WAIT_INDEX, DRIVE_EVT_INDEX,      G_ANY,          DRIVE_ST_F_FIX,        DRIVE_ACT_REQUEST_FIX),
    ROW(DRIVE_ST_F_FIX,        DRIVE_EVT_FIX_READY,  G_ANY,          DRIVE_ST_F_PREDICT,    DRIVE_ACT_CORRECT_NAV | X_POSE_PREDICT),
    ROW(DRIVE_ST_F_FIX,        DRIVE_EVT_FIX_FAILED, G_FIX_RETRY,    DRIVE_ST_F_PREDICT,    X_POSE_PREDICT),
    ROW(DRIVE_ST_F_FIX,        DRIVE_EVT_FIX_FAILED, G_FIX_GIVE_UP,  DRIVE_ST_FAULT,        DRIVE_ACT_STOP | DRIVE_ACT_FAULT),
    ROW(DRIVE_ST_F_PREDICT,    DRIVE_EVT_POSE,       G_ARRIVED,      DRIVE_ST_DONE,         DRIVE_ACT_STOP | DRIVE_ACT_DONE),
    ROW(DRIVE_ST_F_PREDICT,    DRIVE_EVT_POSE,       G_SOLVED_LAST,  DRIVE_ST_F_LOAD,       X_TIMER_LOAD),
    ROW(DRIVE_ST_F_PREDICT,    DRIVE_EVT_POSE,       G_SOLVED,       DRIVE_ST_F_LOAD,       X_TIMER_LOAD),
    ROW(DRIVE_ST_F_PREDICT,    DRIVE_EVT_POSE,       G_FAILED,       DRIVE_ST_FAULT,        DRIVE_ACT_STOP | DRIVE_ACT_FAULT),
    ROW(DRIVE_ST_F_LOAD,       DRIVE_EVT_TIMER,      G_PENDING_LAST, DRIVE_ST_F_STOP1,      DRIVE_ACT_LOAD),
    ROW(DRIVE_ST_F_LOAD,       DRIVE_EVT_TIMER,      G_ANY,          DRIVE_ST_F_SETTLE,     DRIVE_ACT_LOAD | X_TIMER_SETTLE),
    /* D1: the loaded double arc ends; the next one is ready: load it now */
    ROW(DRIVE_ST_F_LOAD,       DRIVE_EVT_DELTA_S,    G_FINAL_PLAST,  DRIVE_ST_F_STOP1,      DRIVE_ACT_LOAD),
    ROW(DRIVE_ST_F_LOAD,       DRIVE_EVT_DELTA_S,    G_PULSE_FINAL,  DRIVE_ST_F_SETTLE,     DRIVE_ACT_LOAD | X_TIMER_SETTLE),
    /* ... or it is not ready yet: the drive board stops at the end, the next load restarts */
    ROW(DRIVE_ST_F_SETTLE,     DRIVE_EVT_DELTA_S,    G_PULSE_FINAL,  SAME,                  X_UNDERRUN),
    ROW(DRIVE_ST_F_WAIT_INDEX, DRIVE_EVT_DELTA_S,    G_PULSE_FINAL,  SAME,                  X_UNDERRUN),
    ROW(DRIVE_ST_F_FIX,        DRIVE_EVT_DELTA_S,    G_PULSE_FINAL,  SAME,                  X_UNDERRUN),
    ROW(DRIVE_ST_F_PREDICT,    DRIVE_EVT_DELTA_S,    G_PULSE_FINAL,  SAME,                  X_UNDERRUN),
    /* full travel: the stopping routine */
    ROW(DRIVE_ST_F_STOP1,      DRIVE_EVT_DELTA_S,    G_PULSE_FINAL,  DRIVE_ST_DONE,         DRIVE_ACT_STOP | DRIVE_ACT_DONE),
    ROW(DRIVE_ST_F_STOP1,      DRIVE_EVT_DELTA_S,    G_PULSE_MORE,   DRIVE_ST_F_STOP2,      DRIVE_ACT_SET_SPEED),
    ROW(DRIVE_ST_F_STOP2,      DRIVE_EVT_DELTA_S,    G_PULSE_FINAL,  DRIVE_ST_DONE,         DRIVE_ACT_STOP | DRIVE_ACT_DONE),
    /* simplified travel */
    ROW(DRIVE_ST_S_SKIP_INDEX, DRIVE_EVT_INDEX,      G_ANY,          DRIVE_ST_S_WAIT_INDEX, 0),
    ROW(DRIVE_ST_S_WAIT_INDEX, DRIVE_EVT_INDEX,      G_ANY,          DRIVE_ST_S_FIX,        DRIVE_ACT_REQUEST_FIX | DRIVE_ACT_INDEX_OFF),
    ROW(DRIVE_ST_S_FIX,        DRIVE_EVT_FIX_READY,  G_ARRIVED,      DRIVE_ST_DONE,         DRIVE_ACT_DONE),
    ROW(DRIVE_ST_S_FIX,        DRIVE_EVT_FIX_READY,  G_SOLVED_LAST,  DRIVE_ST_S_ARC1,       DRIVE_ACT_LOAD),
    ROW(DRIVE_ST_S_FIX,        DRIVE_EVT_FIX_READY,  G_SOLVED,       DRIVE_ST_S_ARC1,       DRIVE_ACT_LOAD),
    ROW(DRIVE_ST_S_FIX,        DRIVE_EVT_FIX_READY,  G_FAILED,       DRIVE_ST_FAULT,        DRIVE_ACT_STOP | DRIVE_ACT_FAULT),
    ROW(DRIVE_ST_S_FIX,        DRIVE_EVT_FIX_FAILED, G_FIX_RETRY,    DRIVE_ST_S_SKIP_INDEX, DRIVE_ACT_INDEX_ON),
    ROW(DRIVE_ST_S_FIX,        DRIVE_EVT_FIX_FAILED, G_FIX_GIVE_UP,  DRIVE_ST_FAULT,        DRIVE_ACT_FAULT),
    ROW(DRIVE_ST_S_ARC1,       DRIVE_EVT_DELTA_S,    G_FINAL_LAST,   DRIVE_ST_DONE,         DRIVE_ACT_STOP | DRIVE_ACT_DONE),
    ROW(DRIVE_ST_S_ARC1,       DRIVE_EVT_DELTA_S,    G_PULSE_FINAL,  DRIVE_ST_S_SKIP_INDEX, DRIVE_ACT_STOP | DRIVE_ACT_INDEX_ON | X_NEXT_TARGET),
    ROW(DRIVE_ST_S_ARC1,       DRIVE_EVT_DELTA_S,    G_PULSE_MORE,   DRIVE_ST_S_ARC2,       0),
    ROW(DRIVE_ST_S_ARC2,       DRIVE_EVT_DELTA_S,    G_FINAL_LAST,   DRIVE_ST_DONE,         DRIVE_ACT_STOP | DRIVE_ACT_DONE),
    ROW(DRIVE_ST_S_ARC2,       DRIVE_EVT_DELTA_S,    G_PULSE_FINAL,  DRIVE_ST_S_SKIP_INDEX, DRIVE_ACT_STOP | DRIVE_ACT_INDEX_ON | X_NEXT_TARGET),
    /* expected pulses of the loaded double arc that need no action */
    ROW(DRIVE_ST_ANY,          DRIVE_EVT_DELTA_S,    G_PULSE_MORE,   SAME,                  0),
    /* stop request */
    ROW(DRIVE_ST_ANY,          DRIVE_EVT_STOP,       G_ANY,          DRIVE_ST_DONE,         DRIVE_ACT_STOP | DRIVE_ACT_DONE),
};
/* clang-format on */

const drive_seq_row_t *drive_seq_table(uint16_t *n)
{
    *n = (uint16_t)(DRIVE_SEQ_ROWS);
    return drive_seq_rows;
}

const char *drive_seq_state_name(drive_state_t st)
{
    static const char *const names[DRIVE_ST_COUNT] = {"idle",
                                                      "full/start",
                                                      "full/settle",
                                                      "full/wait-index",
                                                      "full/fix",
                                                      "full/predict",
                                                      "full/load",
                                                      "full/stop1",
                                                      "full/stop2",
                                                      "simple/skip-index",
                                                      "simple/wait-index",
                                                      "simple/fix",
                                                      "simple/arc1",
                                                      "simple/arc2",
                                                      "done",
                                                      "fault"};
    return (unsigned)st < DRIVE_ST_COUNT ? names[st] : "?";
}

void drive_seq_init(drive_seq_t *seq, drive_path_t *path, const drive_seq_config_t *cfg)
{
    *seq = (drive_seq_t){0}; /* idle, nothing loaded or pending, no counts */
    seq->cfg = *cfg;
    seq->path = path;
    seq->target = drive_path_first(path);
}

#ifndef DRIVE_ASM /* MSP430: msp430/seq.S, the same steps */
/* Distance from @p pose to @p target along the target's direction of travel, Q16 m. */
static int32_t along(const drive_pose_t *pose, const drive_pose_t *target, bool reverse)
{
    int32_t d[2] = {target->x - pose->x, target->y - pose->y}, r[2];
    drive_rot(r, d, target->heading + (reverse ? FX_ANGLE_HALF : 0u));
    return r[0];
}

/*
 * From @p pose: skip targets nearer than cfg.advance along their direction (full travel),
 * solve toward the target, and on failure (or nothing left to drive) move on to the next
 * point; the last point reached with nothing to drive means arrived.
 */
static uint8_t pick(drive_seq_t *seq, const drive_pose_t *pose)
{
    drive_path_t *path = seq->path;
    bool rev = path->cfg.reverse;
    for (uint8_t tries = 0; tries < 4u; tries++) {
        drive_pose_t tp;
        fx_q16_t speed;
        drive_status_t st = drive_path_target(path, seq->target, &tp, &speed);
        if (st != DRIVE_OK) {
            seq->solve_status = st;
            return PICK_FAILED;
        }
        bool last = drive_path_is_last(path, seq->target);
        if (last || seq->cfg.mode != DRIVE_MODE_FULL || along(pose, &tp, rev) >= seq->cfg.advance) {
            drive_solution_t sol;
            st = drive_solve(pose, &tp, path->board->min_radius, rev, &sol, NULL);
            if (st == DRIVE_OK)
                st = drive_cmd_build(&sol, path->board, speed, rev, &seq->pending);
            seq->solve_status = st;
            bool reached = st == DRIVE_ERR_TOO_CLOSE || st == DRIVE_ERR_BEHIND ||
                           (st == DRIVE_OK && seq->pending.pulses == 0);
            if (st == DRIVE_OK && !reached) {
                seq->pending_last = last;
                return PICK_SOLVED;
            }
            if (last)
                return reached ? PICK_ARRIVED : PICK_FAILED;
        }
        seq->target = drive_path_next(path, seq->target);
    }
    return PICK_FAILED;
}

/* The guards that hold (bit G_*) in the state the event left. */
static uint16_t guards(const drive_seq_t *seq, uint8_t picked)
{
    uint16_t g = 1u << G_ANY;
    if (!seq->path->ready)
        g |= 1u << G_NOT_READY;
    else
        g |= seq->cfg.mode == DRIVE_MODE_FULL ? 1u << G_FULL : 1u << G_SIMPLIFIED;
    if (picked == PICK_ARRIVED)
        g |= 1u << G_ARRIVED;
    if (picked == PICK_SOLVED)
        g |= seq->pending_last ? 1u << G_SOLVED_LAST : 1u << G_SOLVED;
    if (picked == PICK_FAILED)
        g |= 1u << G_FAILED;
    if (seq->pending_last)
        g |= 1u << G_PENDING_LAST;
    if (seq->pulses_seen < seq->loaded.pulses)
        g |= 1u << G_PULSE_MORE;
    if (seq->pulses_seen == seq->loaded.pulses) {
        g |= 1u << G_PULSE_FINAL;
        if (seq->loaded_last)
            g |= 1u << G_FINAL_LAST;
        if (seq->pending_last)
            g |= 1u << G_FINAL_PLAST;
    }
    g |= seq->fix_failures <= seq->cfg.max_fix_failures ? 1u << G_FIX_RETRY : 1u << G_FIX_GIVE_UP;
    return g;
}

void drive_seq_step(drive_seq_t *seq, const drive_seq_event_t *ev, drive_seq_out_t *out)
{
    *out = (drive_seq_out_t){0}; /* no actions; DRIVE_FAULT_NONE, DRIVE_OK */

    /* Effects of the event that guards look at. */
    uint8_t picked = PICK_NONE, e = (uint8_t)ev->type, st = (uint8_t)seq->state;
    if ((e == DRIVE_EVT_POSE && (st == DRIVE_ST_F_START || st == DRIVE_ST_F_PREDICT)) ||
        (e == DRIVE_EVT_FIX_READY && st == DRIVE_ST_S_FIX))
        picked = pick(seq, &ev->pose);
    if (e == DRIVE_EVT_DELTA_S && seq->pulses_seen < 255u)
        seq->pulses_seen++;
    if (e == DRIVE_EVT_FIX_FAILED && seq->fix_failures < 255u)
        seq->fix_failures++;
    if (e == DRIVE_EVT_FIX_READY)
        seq->fix_failures = 0;

    uint16_t g = guards(seq, picked);
    const drive_seq_row_t *row = drive_seq_rows;
    while (!((row->state == st || row->state == DRIVE_ST_ANY) && row->event == e &&
             ((g >> row->guard) & 1u))) {
        if (++row == drive_seq_rows + DRIVE_SEQ_ROWS) {
            if (seq->ignored < UINT16_MAX)
                seq->ignored++;
            return;
        }
    }

    uint16_t act = row->actions;
    if (act & DRIVE_ACT_LOAD) {
        seq->loaded = seq->pending;
        seq->loaded_last = seq->pending_last;
        seq->pulses_seen = 0;
        seq->loads++;
        out->cmd = seq->loaded;
    }
    if (act & DRIVE_ACT_SET_SPEED)
        (void)drive_speed_counts(seq->cfg.stop_speed, seq->path->cfg.reverse, seq->path->board,
                                 &out->speed);
    if (act & (X_TIMER_SETTLE | X_TIMER_LOAD)) {
        act |= DRIVE_ACT_TIMER;
        out->timer_ms = (act & X_TIMER_LOAD) ? seq->cfg.load_ms : seq->cfg.settle_ms;
    }
    if (act & X_POSE_PREDICT) {
        act |= DRIVE_ACT_REQUEST_POSE;
        out->pose_ms = seq->cfg.load_ms;
    }
    if ((act & X_UNDERRUN) && seq->underruns < UINT16_MAX)
        seq->underruns++;
    if (act & X_NEXT_TARGET)
        seq->target = drive_path_next(seq->path, seq->target);
    if (act & DRIVE_ACT_FAULT) {
        out->fault = row->guard == G_NOT_READY     ? DRIVE_FAULT_NOT_READY
                     : row->guard == G_FIX_GIVE_UP ? DRIVE_FAULT_FIXES
                                                   : DRIVE_FAULT_SOLVE;
        out->status = seq->solve_status;
    }
    out->actions = (uint16_t)(act & PUBLIC_ACTIONS);
    if (row->next != SAME)
        seq->state = (drive_state_t)row->next;
}
#endif

/* ------------------------------------------------------------------ delta-S pulse (D1) */

void drive_ds_handler(void *arg)
{
    drive_ds_t *ds = arg;
    if (ds->count < UINT16_MAX)
        ds->count++;
}

int drive_ds_init(drive_ds_t *ds)
{
    ds->count = 0;
    return hal_edge_init(HAL_EDGE_DELTA_S, HAL_EDGE_RISING, drive_ds_handler, ds);
}

uint16_t drive_ds_take(drive_ds_t *ds)
{
    hal_critical_enter();
    uint16_t n = ds->count;
    ds->count = 0;
    hal_critical_exit();
    return n;
}
