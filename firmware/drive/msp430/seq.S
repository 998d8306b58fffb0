/*
 * seq.S - MSP430 version of drive_seq_step() and its pick() (seq.c holds the portable C that
 * defines the results: the same table, guards, calls and decisions, step for step), checked
 * bit for bit by tests/vectors/drive_vectors.c. Registers as in vm.S; structure offsets from
 * layout.h.
 */
#include "../seq_table.h"
#include "../solve_frame.h"
#include "layout.h"

/* pick()'s frame: outgoing stack arguments, the target and its speed, along()'s vectors, the
 * solution. */
    .set PK_TP, 6
    .set PK_SPD, 18
    .set PK_D, 22
    .set PK_R, 30
    .set PK_SOL, 38
    .set PK_FRAME, 64

/*
 * uint8_t pick(drive_seq_t *seq, const drive_pose_t *pose): R12 = seq, R13 = pose -> R12 =
 * PICK_*. R10 = seq, R9 = pose, R8 = tries left, R7 = last, R6 = the path.
 */
    .section .text.drive_seq_pick,"ax",@progbits
pick:
    push    r10
    push    r9
    push    r8
    push    r7
    push    r6
    sub     #PK_FRAME, r1
    mov     r12, r10
    mov     r13, r9
    mov     SEQ_PATH(r10), r6
    mov     #4, r8
pk_loop:
    mov     SEQ_TARGET(r10), 0(r1)  ; drive_path_target(path, target, &tp, &speed)
    mov     r6, r12
    mov     r1, r13
    add     #PK_TP, r13
    mov     r1, r14
    add     #PK_SPD, r14
    call    #drive_path_target
    tst     r12
    jz      1f
    mov     r12, SEQ_STATUS(r10)
    jmp     pk_failed
1:  mov     SEQ_TARGET(r10), 0(r1)  ; last = drive_path_is_last(path, target)
    mov     r6, r12
    call    #drive_path_is_last
    mov.b   r12, r7
    tst.b   r7
    jnz     pk_solve
    cmp     #MODE_FULL, SEQ_MODE(r10)
    jne     pk_solve
    mov     PK_TP(r1), r12          ; along(): (target - pose) rotated by -(its direction)
    mov     PK_TP+2(r1), r13
    sub     @r9, r12
    subc    2(r9), r13
    mov     r12, PK_D(r1)
    mov     r13, PK_D+2(r1)
    mov     PK_TP+4(r1), r12
    mov     PK_TP+6(r1), r13
    sub     4(r9), r12
    subc    6(r9), r13
    mov     r12, PK_D+4(r1)
    mov     r13, PK_D+6(r1)
    mov     PK_TP+POSE_HEADING(r1), r14
    mov     PK_TP+POSE_HEADING+2(r1), r15
    tst.b   PATH_REVERSE(r6)
    jz      2f
    xor     #0x8000, r15
2:  mov     r1, r12
    add     #PK_R, r12
    mov     r1, r13
    add     #PK_D, r13
    call    #drive_rot
    mov     PK_R(r1), r12           ; nearer than advance: the next target
    mov     PK_R+2(r1), r13
    sub     SEQ_ADVANCE(r10), r12
    subc    SEQ_ADVANCE+2(r10), r13
    jl      pk_next
pk_solve:
    mov.b   PATH_REVERSE(r6), r12   ; drive_solve(pose, &tp, min_radius, rev, &sol, NULL)
    mov     r12, 0(r1)
    mov     r1, r12
    add     #PK_SOL, r12
    mov     r12, 2(r1)
    clr     4(r1)
    mov     PATH_BOARD(r6), r11
    mov     BOARD_MIN_R(r11), r14
    mov     BOARD_MIN_R+2(r11), r15
    mov     r9, r12
    mov     r1, r13
    add     #PK_TP, r13
    call    #drive_solve
    tst     r12
    jnz     3f
    mov.b   PATH_REVERSE(r6), r12   ; drive_cmd_build(&sol, board, speed, rev, &pending)
    mov     r12, 0(r1)
    mov     r10, r12
    add     #SEQ_PENDING, r12
    mov     r12, 2(r1)
    mov     r1, r12
    add     #PK_SOL, r12
    mov     PATH_BOARD(r6), r13
    mov     PK_SPD(r1), r14
    mov     PK_SPD+2(r1), r15
    call    #drive_cmd_build
3:  mov     r12, SEQ_STATUS(r10)
    cmp     #DRIVE_ERR_TOO_CLOSE_N, r12 ; reached: too close, behind, or nothing to drive
    jeq     4f
    cmp     #DRIVE_ERR_BEHIND_N, r12
    jeq     4f
    tst     r12
    jnz     5f                      ; failed
    tst.b   SEQ_PENDING+CMD_PULSES(r10)
    jz      4f
    mov.b   r7, SEQ_PEND_LAST(r10)  ; solved
    mov     #PICK_SOLVED, r12
    jmp     pk_ret
4:  tst.b   r7                      ; reached: the last point is arrived at
    jz      pk_next
    mov     #PICK_ARRIVED, r12
    jmp     pk_ret
5:  tst.b   r7                      ; failed: at the last point that is the end
    jnz     pk_failed
pk_next:
    mov     SEQ_TARGET(r10), 0(r1)  ; target = drive_path_next(path, target)
    mov     r10, r12
    add     #SEQ_TARGET, r12
    mov     r6, r13
    call    #drive_path_next
    dec     r8
    jnz     pk_loop
pk_failed:
    mov     #PICK_FAILED, r12
pk_ret:
    add     #PK_FRAME, r1
    pop     r6
    pop     r7
    pop     r8
    pop     r9
    pop     r10
    ret

/*
 * void drive_seq_step(drive_seq_t *seq, const drive_seq_event_t *ev, drive_seq_out_t *out):
 * R12 = seq, R13 = ev, R14 = out. R10 = seq, R9 = ev (later the actions), R8 = out, R7 =
 * what pick() found (later the row), R6 = the guards that hold, R5 = the event, R4 = the
 * state.
 */
    .section .text.drive_seq_step,"ax",@progbits
    .global drive_seq_step
    .type drive_seq_step,@function
drive_seq_step:
    push    r10
    push    r9
    push    r8
    push    r7
    push    r6
    push    r5
    push    r4
    sub     #2, r1                  ; an outgoing stack argument
    mov     r12, r10
    mov     r13, r9
    mov     r14, r8
    mov     r8, r11                 ; *out = 0
    mov     #OUT_SIZE / 2, r12
1:  clr     0(r11)
    incd    r11
    dec     r12
    jnz     1b
    clr     r7                      ; PICK_NONE
    mov     @r9, r5
    mov     SEQ_STATE(r10), r4
    cmp     #EVT_POSE, r5           ; pose in full/start or full/predict, fix in simple/fix
    jne     2f
    cmp     #ST_F_START, r4
    jeq     3f
    cmp     #ST_F_PREDICT, r4
    jeq     3f
    jmp     4f
2:  cmp     #EVT_FIX_READY, r5
    jne     4f
    cmp     #ST_S_FIX, r4
    jne     4f
3:  mov     r10, r12
    mov     r9, r13
    add     #EV_POSE, r13
    call    #pick
    mov     r12, r7
4:  cmp     #EVT_DELTA_S, r5        ; the counters the event moves
    jne     5f
    cmp.b   #255, SEQ_SEEN(r10)
    jeq     5f
    inc.b   SEQ_SEEN(r10)
5:  cmp     #EVT_FIX_FAILED, r5
    jne     6f
    cmp.b   #255, SEQ_FIXFAIL(r10)
    jeq     7f
    inc.b   SEQ_FIXFAIL(r10)
    jmp     7f
6:  cmp     #EVT_FIX_READY, r5
    jne     7f
    clr.b   SEQ_FIXFAIL(r10)

/* The guards that hold, a bit each. */
7:  mov     #1 << G_ANY, r6
    mov     SEQ_PATH(r10), r11
    tst.b   PATH_READY(r11)
    jnz     8f
    bis     #1 << G_NOT_READY, r6
    jmp     10f
8:  cmp     #MODE_FULL, SEQ_MODE(r10)
    jne     9f
    bis     #1 << G_FULL, r6
    jmp     10f
9:  bis     #1 << G_SIMPLIFIED, r6
10: cmp     #PICK_ARRIVED, r7
    jne     11f
    bis     #1 << G_ARRIVED, r6
11: cmp     #PICK_SOLVED, r7
    jne     13f
    tst.b   SEQ_PEND_LAST(r10)
    jz      12f
    bis     #1 << G_SOLVED_LAST, r6
    jmp     13f
12: bis     #1 << G_SOLVED, r6
13: cmp     #PICK_FAILED, r7
    jne     14f
    bis     #1 << G_FAILED, r6
14: tst.b   SEQ_PEND_LAST(r10)
    jz      15f
    bis     #1 << G_PENDING_LAST, r6
15: cmp.b   SEQ_LOADED+CMD_PULSES(r10), SEQ_SEEN(r10)
    jhs     16f
    bis     #1 << G_PULSE_MORE, r6  ; seen < pulses
    jmp     17f
16: jne     17f
    bis     #1 << G_PULSE_FINAL, r6 ; seen == pulses
    tst.b   SEQ_LOAD_LAST(r10)
    jz      18f
    bis     #1 << G_FINAL_LAST, r6
18: tst.b   SEQ_PEND_LAST(r10)
    jz      17f
    bis     #1 << G_FINAL_PLAST, r6
17: cmp.b   SEQ_FIXFAIL(r10), SEQ_MAX_FIX(r10)
    jhs     19f
    bis     #1 << G_FIX_GIVE_UP, r6
    jmp     20f
19: bis     #1 << G_FIX_RETRY, r6

/* The first row of the state (or any state) and the event whose guard holds. */
20: mov     #drive_seq_rows, r7
21: cmp.b   @r7, r4
    jeq     22f
    cmp.b   #ST_ANY, 0(r7)
    jne     23f
22: cmp.b   1(r7), r5
    jne     23f
    mov.b   2(r7), r12
    mov     r6, r13
    tst     r12
    jz      24f
25: rra     r13
    dec     r12
    jnz     25b
24: bit     #1, r13
    jnz     found
23: add     #ROW_SIZE, r7
    cmp     #drive_seq_rows + DRIVE_SEQ_ROWS * ROW_SIZE, r7
    jlo     21b
    cmp     #-1, SEQ_IGNORED(r10)   ; no row: ignored
    jeq     step_ret
    inc     SEQ_IGNORED(r10)
    jmp     step_ret

/* Its actions. */
found:
    mov     4(r7), r9
    bit     #ACT_LOAD, r9
    jz      26f
    mov     r10, r12                ; loaded = pending, and to out->cmd
    add     #SEQ_PENDING, r12
    mov     r10, r13
    add     #SEQ_LOADED, r13
    mov     r8, r11
    add     #OUT_CMD, r11
    mov     #CMD_SIZE / 2, r14
27: mov     @r12+, r15
    mov     r15, 0(r13)
    mov     r15, 0(r11)
    incd    r13
    incd    r11
    dec     r14
    jnz     27b
    mov.b   SEQ_PEND_LAST(r10), SEQ_LOAD_LAST(r10)
    clr.b   SEQ_SEEN(r10)
    inc     SEQ_LOADS(r10)
26: bit     #ACT_SET_SPEED, r9
    jz      28f
    mov     SEQ_PATH(r10), r11      ; drive_speed_counts(stop_speed, rev, board, &out->speed)
    mov     r8, r12
    add     #OUT_SPEED, r12
    mov     r12, 0(r1)
    mov     SEQ_STOP_SPD(r10), r12
    mov     SEQ_STOP_SPD+2(r10), r13
    mov.b   PATH_REVERSE(r11), r14
    mov     PATH_BOARD(r11), r15
    call    #drive_speed_counts
28: bit     #X_TIMER_SETTLE | X_TIMER_LOAD, r9
    jz      29f
    bis     #ACT_TIMER, r9
    mov     SEQ_SETTLE_MS(r10), OUT_TIMER(r8)
    bit     #X_TIMER_LOAD, r9
    jz      29f
    mov     SEQ_LOAD_MS(r10), OUT_TIMER(r8)
29: bit     #X_POSE_PREDICT, r9
    jz      30f
    bis     #ACT_REQUEST_POSE, r9
    mov     SEQ_LOAD_MS(r10), OUT_POSE_MS(r8)
30: bit     #X_UNDERRUN, r9
    jz      31f
    cmp     #-1, SEQ_UNDERRUNS(r10)
    jeq     31f
    inc     SEQ_UNDERRUNS(r10)
31: bit     #X_NEXT_TARGET, r9
    jz      32f
    mov     SEQ_TARGET(r10), 0(r1)  ; target = drive_path_next(path, target)
    mov     r10, r12
    add     #SEQ_TARGET, r12
    mov     SEQ_PATH(r10), r13
    call    #drive_path_next
32: bit     #ACT_FAULT, r9
    jz      33f
    mov     #FAULT_NOT_READY, r12   ; fault by the guard: not ready, fixes, else the solve
    cmp.b   #G_NOT_READY, 2(r7)
    jeq     34f
    mov     #FAULT_FIXES, r12
    cmp.b   #G_FIX_GIVE_UP, 2(r7)
    jeq     34f
    mov     #FAULT_SOLVE, r12
34: mov     r12, OUT_FAULT(r8)
    mov     SEQ_STATUS(r10), OUT_STATUS(r8)
33: and     #PUBLIC_ACTIONS, r9
    mov     r9, OUT_ACTIONS(r8)
    cmp.b   #SAME, 3(r7)
    jeq     step_ret
    mov.b   3(r7), SEQ_STATE(r10)
    clr.b   SEQ_STATE+1(r10)
step_ret:
    add     #2, r1
    pop     r4
    pop     r5
    pop     r6
    pop     r7
    pop     r8
    pop     r9
    pop     r10
    ret
