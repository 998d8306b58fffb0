/*
 * seq.c - the travel state table (drive_seq.h).
 */
#include <stddef.h>

#include "drive/drive_seq.h"
#include "drive_math.h"

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
#define G_BLIND        15 /* pose: the last fix failed and the blind distance is up */
#define G_RUNNING      16 /* stop: the travel has not ended yet                     */

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

#define ROW(st, ev, g, nx, act)                                                                    \
    {                                                                                              \
        (uint8_t)(st), (uint8_t)(ev), (uint8_t)(g), (uint8_t)(nx), (act)                           \
    }

/* clang-format off */
static const drive_seq_row_t drive_seq_rows[] = {
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
    /* ... no fix: on dead reckoning (slower as the blind distance nears), stop at its end */
    ROW(DRIVE_ST_F_FIX,        DRIVE_EVT_FIX_FAILED, G_ANY,          DRIVE_ST_F_PREDICT,    X_POSE_PREDICT),
    ROW(DRIVE_ST_F_PREDICT,    DRIVE_EVT_POSE,       G_BLIND,        DRIVE_ST_STOPPED,      DRIVE_ACT_STOP | DRIVE_ACT_DONE),
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
    /* stop request (after the end of the travel it is ignored) */
    ROW(DRIVE_ST_ANY,          DRIVE_EVT_STOP,       G_RUNNING,      DRIVE_ST_STOPPED,      DRIVE_ACT_STOP | DRIVE_ACT_DONE),
};
/* clang-format on */
#define DRIVE_SEQ_ROWS (sizeof drive_seq_rows / sizeof drive_seq_rows[0])

const drive_seq_row_t *drive_seq_table(uint16_t *n)
{
    *n = (uint16_t)DRIVE_SEQ_ROWS;
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
                                                      "fault",
                                                      "stopped"};
    return (unsigned)st < DRIVE_ST_COUNT ? names[st] : "?";
}

void drive_seq_init(drive_seq_t *seq, drive_path_t *path, const drive_seq_config_t *cfg)
{
    *seq = (drive_seq_t){0}; /* idle, nothing loaded or pending, no counts */
    seq->cfg = *cfg;
    seq->path = path;
    seq->target = drive_path_first(path);
}

/* Distance from @p pose to @p target along the target's direction of travel, Q16 m. */
static int32_t along(const drive_pose_t *pose, const drive_pose_t *target, bool reverse)
{
    int32_t u, v;
    drive_to_frame(target->x - pose->x, target->y - pose->y,
                   target->heading + (reverse ? FX_ANGLE_HALF : 0u), &u, &v);
    return u;
}

fx_q16_t drive_blind_speed(fx_q16_t speed, fx_q16_t blind, fx_q16_t limit, fx_q16_t slowest)
{
    int32_t f = FX_Q16_ONE / 4, r; /* the factor, Q16 */
    if (limit > 0 && fx_div_shift(blind, limit, 16, &r) && r < FX_Q16_ONE)
        f = r <= FX_Q16_ONE / 4 ? FX_Q16_ONE : 5 * FX_Q16_ONE / 4 - r;
    fx_q16_t v = fx_mul_q16(speed, f), least = speed < slowest ? speed : slowest;
    return v < least ? least : v;
}

/* The travel since the last accepted fix grows by the chord from the last pose to @p pose
 * (the poses come once a revolution: the chord of a 0.5 m arc of 0.8 m radius is 1.6 % short). */
static void blind_add(drive_seq_t *seq, const drive_pose_t *pose)
{
    int32_t dx = (int32_t)((uint32_t)pose->x - (uint32_t)seq->blind_from.x);
    int32_t dy = (int32_t)((uint32_t)pose->y - (uint32_t)seq->blind_from.y);
    uint32_t d = fx_hypot(dx, dy) + (uint32_t)seq->blind;
    seq->blind = d > (uint32_t)FX_Q16_MAX ? FX_Q16_MAX : (fx_q16_t)d;
    seq->blind_from = *pose;
}

/* Solve from @p pose toward the secondary point @p cur and build its command into
 * seq->pending (the status in seq->solve_status too); *reached: nothing left to drive there
 * (too close, behind, or arcs too short for a pulse). Full travel drives slower the longer
 * it has been without a fix (drive_blind_speed()). */
static drive_status_t solve_toward(drive_seq_t *seq, const drive_pose_t *pose,
                                   drive_path_cursor_t cur, bool *reached)
{
    drive_path_t *path = seq->path;
    drive_pose_t tp;
    fx_q16_t speed;
    drive_solution_t sol;
    drive_status_t st = drive_path_target(path, cur, &tp, &speed);
    if (seq->cfg.mode == DRIVE_MODE_FULL)
        speed =
            drive_blind_speed(speed, seq->blind, seq->cfg.blind_distance, path->board->speed_lsb);
    if (st == DRIVE_OK)
        st = drive_solve(pose, &tp, path->board->min_radius, path->cfg.reverse, &sol, NULL);
    if (st == DRIVE_OK)
        st = drive_cmd_build(&sol, path->board, speed, path->cfg.reverse, &seq->pending);
    seq->solve_status = st;
    *reached = st == DRIVE_ERR_TOO_CLOSE || st == DRIVE_ERR_BEHIND ||
               (st == DRIVE_OK && seq->pending.pulses == 0);
    return st;
}

/*
 * From @p pose: skip targets nearer than cfg.advance along their direction (full travel),
 * solve toward the target, and on failure (or nothing left to drive) move on to the next
 * point; the last point reached with nothing to drive means arrived. When the target after a
 * skipped one cannot be driven to in one double arc (in a tight turn its front-wheel length
 * can exceed the drive board's byte), the skipped one is driven to instead.
 */
static uint8_t pick(drive_seq_t *seq, const drive_pose_t *pose)
{
    drive_path_t *path = seq->path;
    drive_path_cursor_t skipped = {0, 0}; /* sub 0: none */
    for (uint8_t tries = 0; tries < 4u; tries++) {
        drive_pose_t tp;
        fx_q16_t speed;
        drive_status_t st = drive_path_target(path, seq->target, &tp, &speed);
        if (st != DRIVE_OK) {
            seq->solve_status = st;
            return PICK_FAILED;
        }
        bool last = drive_path_is_last(path, seq->target), reached;
        if (!last && seq->cfg.mode == DRIVE_MODE_FULL &&
            along(pose, &tp, path->cfg.reverse) < seq->cfg.advance) {
            skipped = seq->target;
        } else if (solve_toward(seq, pose, seq->target, &reached) == DRIVE_OK && !reached) {
            seq->pending_last = last;
            return PICK_SOLVED;
        } else if (!reached && skipped.sub != 0) {
            drive_status_t why = seq->solve_status;
            seq->target = skipped;
            if (solve_toward(seq, pose, skipped, &reached) == DRIVE_OK && !reached) {
                seq->pending_last = false;
                return PICK_SOLVED;
            }
            seq->solve_status = why;
            return PICK_FAILED;
        } else if (last) {
            return reached ? PICK_ARRIVED : PICK_FAILED;
        }
        seq->target = drive_path_next(path, seq->target);
    }
    return PICK_FAILED;
}

/* The guards that hold (bit G_*) in the state the event left. */
static uint32_t guards(const drive_seq_t *seq, uint8_t picked, bool blind_out)
{
    uint32_t g = 1ul << G_ANY;
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
    if (blind_out)
        g |= 1u << G_BLIND;
    if (seq->state != DRIVE_ST_DONE && seq->state != DRIVE_ST_FAULT &&
        seq->state != DRIVE_ST_STOPPED)
        g |= 1ul << G_RUNNING;
    return g;
}

void drive_seq_step(drive_seq_t *seq, const drive_seq_event_t *ev, drive_seq_out_t *out)
{
    *out = (drive_seq_out_t){0}; /* no actions; DRIVE_FAULT_NONE, DRIVE_OK */

    /* Effects of the event that guards look at. */
    uint8_t picked = PICK_NONE, e = (uint8_t)ev->type, st = (uint8_t)seq->state;
    bool blind_out = false;
    if ((e == DRIVE_EVT_START && st == DRIVE_ST_IDLE) ||
        (e == DRIVE_EVT_FIX_READY && (st == DRIVE_ST_F_FIX || st == DRIVE_ST_S_FIX))) {
        seq->blind = 0; /* the initial vector, or an accepted fix */
        seq->blind_from = ev->pose;
    }
    if (e == DRIVE_EVT_POSE && (st == DRIVE_ST_F_START || st == DRIVE_ST_F_PREDICT)) {
        blind_add(seq, &ev->pose);
        blind_out = st == DRIVE_ST_F_PREDICT && seq->fix_failures > 0 &&
                    seq->blind >= seq->cfg.blind_distance;
    }
    if ((e == DRIVE_EVT_POSE && (st == DRIVE_ST_F_START || st == DRIVE_ST_F_PREDICT) &&
         !blind_out) ||
        (e == DRIVE_EVT_FIX_READY && st == DRIVE_ST_S_FIX))
        picked = pick(seq, &ev->pose);
    if (e == DRIVE_EVT_DELTA_S && seq->pulses_seen < 255u)
        seq->pulses_seen++;
    if (e == DRIVE_EVT_FIX_FAILED && seq->fix_failures < 255u)
        seq->fix_failures++;
    if (e == DRIVE_EVT_FIX_READY)
        seq->fix_failures = 0;

    uint32_t g = guards(seq, picked, blind_out);
    const drive_seq_row_t *row = drive_seq_rows;
    while (!((row->state == st || row->state == DRIVE_ST_ANY) && row->event == e &&
             ((g >> row->guard) & 1ul))) {
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
    if (row->next == DRIVE_ST_STOPPED) {
        seq->stop = e == DRIVE_EVT_STOP ? DRIVE_STOP_REQUEST : DRIVE_STOP_BLIND;
        out->stop = seq->stop;
    }
    out->actions = (uint16_t)(act & PUBLIC_ACTIONS);
    if (row->next != SAME)
        seq->state = (drive_state_t)row->next;
}
