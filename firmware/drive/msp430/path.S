/*
 * path.S - MSP430 versions of path.c's functions (path.c holds the portable C that defines
 * the results: the same calls and decisions, step for step), checked bit for bit by
 * tests/vectors/drive_vectors.c. Registers as in vm.S; structure offsets from layout.h.
 */
#include "../solve_frame.h"
#include "layout.h"

/*
 * R12 = &path->pts[R12] (R11 = the path): leg * 18 = leg * 16 + leg * 2. Clobbers R13 only.
 */
    .section .text.drive_path_helpers,"ax",@progbits
point_of:
    rla     r12
    mov     r12, r13
    rla     r12
    rla     r12
    rla     r12
    add     r13, r12
    add     PATH_PTS(r11), r12
    ret

/* R12 = the start of leg R12 (R11 = the path): &path->start or &path->pts[leg - 1].pose.
 * Clobbers R13 only. */
start_of:
    tst.b   r12
    jnz     1f
    mov     r11, r12
    add     #PATH_START, r12
    ret
1:  dec     r12
    jmp     point_of

/*
 * drive_status_t drive_path_leg(drive_path_t *path, uint8_t leg, const drive_solution_t **sol):
 * R12 = path, R13 = leg, R14 = sol. The leg's nominal solution, cached.
 */
    .section .text.drive_path_leg,"ax",@progbits
    .global drive_path_leg
    .type drive_path_leg,@function
drive_path_leg:
    push    r10
    push    r9
    push    r8
    sub     #6, r1
    mov     #DRIVE_ERR_PARAM_N, r15
    tst     r12
    jz      3f
    mov.b   r13, r9                 ; leg
    cmp.b   PATH_N(r12), r9
    jhs     3f
    mov     r12, r10
    mov     r14, r8
    cmp     r9, PATH_CACHE_LEG(r10)
    jeq     2f
    mov     #-1, PATH_CACHE_LEG(r10)
    mov.b   PATH_REVERSE(r10), 0(r1) ; drive_solve(start of leg, &pts[leg].pose, nominal,
    clr.b   1(r1)                   ;   reverse, &cache, NULL)
    mov     r10, r12
    add     #PATH_CACHE, r12
    mov     r12, 2(r1)
    clr     4(r1)
    mov     r10, r11
    mov     r9, r12
    call    #start_of
    mov     r12, r15
    mov     r9, r12
    call    #point_of
    mov     r12, r13
    mov     r15, r12
    mov     PATH_NOMINAL(r10), r14
    mov     PATH_NOMINAL+2(r10), r15
    call    #drive_solve
    mov     r12, r15
    tst     r12
    jnz     3f
    mov     r9, PATH_CACHE_LEG(r10)
2:  mov     r10, r12
    add     #PATH_CACHE, r12
    mov     r12, 0(r8)
    clr     r15
3:  mov     r15, r12
    add     #6, r1
    pop     r8
    pop     r9
    pop     r10
    ret

/*
 * secondary(): R12 = path, R13 = the start of the leg, R14 = its point, R15 = sub, the result's
 * address on the stack. At sub / nsub of the cached nominal solution, the point itself for
 * sub >= nsub. R10 = path, R9 = the segment, R8 = the point, R7 = out.
 */
    .set SC_P, 6                    /* the pose on the way; 0(SP): outgoing arguments */
    .set SC_FRAC, 18
    .set SC_FRAME, 22

    .section .text.drive_path_secondary,"ax",@progbits
secondary:
    push    r10
    push    r9
    push    r8
    push    r7
    push    r6
    sub     #SC_FRAME, r1
    mov     r12, r10
    mov     r14, r8
    mov     SC_FRAME+12(r1), r7     ; out
    mov     r10, r9
    add     #PATH_CACHE+2, r9       ; &cache.seg[0]
    mov.b   16(r8), r14             ; nsub
    cmp.b   r14, r15
    jlo     1f
    mov     r8, r13                 ; the point itself
    jmp     3f
1:  mov     r13, r6                 ; the start
    clr     SC_FRAC(r1)             ; frac = sub / nsub, Q30
    clr     SC_FRAC+2(r1)
    mov     #30, 0(r1)
    mov     r1, r12
    add     #SC_FRAC, r12
    mov     r12, 2(r1)
    mov     r15, r12
    clr     r13
    clr     r15
    call    #fx_div_shift
    mov     4(r9), r12              ; t = (s0 + s1) frac
    mov     6(r9), r13
    add     16(r9), r12
    addc    18(r9), r13
    mov     SC_FRAC(r1), r14
    mov     SC_FRAC+2(r1), r15
    call    #fx_mul_q30
    mov     r12, r14                ; t in R15:R14
    mov     r13, r15
    mov     r1, r13                 ; p = the start
    add     #SC_P, r13
    mov     #6, r11
2:  mov     @r6+, r12
    mov     r12, 0(r13)
    incd    r13
    dec     r11
    jnz     2b
    mov     4(r9), r12              ; t > s0: along the first segment, then the second
    mov     6(r9), r13
    sub     r14, r12
    subc    r15, r13
    jge     4f
    mov     r14, r6                 ; t - s0 kept in R6 and SC_FRAC
    mov     r15, SC_FRAC(r1)
    sub     4(r9), r6
    subc    6(r9), SC_FRAC(r1)
    mov     4(r9), 0(r1)            ; p = advance(p, k0, s0)
    mov     6(r9), 2(r1)
    mov.b   PATH_REVERSE(r10), 4(r1)
    clr.b   5(r1)
    mov     r1, r12
    add     #SC_P, r12
    mov     r12, r13
    mov     @r9, r14
    mov     2(r9), r15
    call    #drive_pose_advance
    mov     r6, r14
    mov     SC_FRAC(r1), r15
    add     #12, r9
4:  mov     r14, 0(r1)              ; *out = advance(p, k, t)
    mov     r15, 2(r1)
    mov.b   PATH_REVERSE(r10), 4(r1)
    clr.b   5(r1)
    mov     r7, r12
    mov     r1, r13
    add     #SC_P, r13
    mov     @r9, r14
    mov     2(r9), r15
    call    #drive_pose_advance
    jmp     5f
3:  mov     #6, r11                 ; *out = *R13
6:  mov     @r13+, r12
    mov     r12, 0(r7)
    incd    r7
    dec     r11
    jnz     6b
5:  add     #SC_FRAME, r1
    pop     r6
    pop     r7
    pop     r8
    pop     r9
    pop     r10
    ret

/*
 * drive_status_t drive_path_target(drive_path_t *path, drive_path_cursor_t cur,
 *     drive_pose_t *pose, fx_q16_t *speed): R12 = path, cur on the stack, R13 = pose,
 * R14 = speed.
 */
    .section .text.drive_path_target,"ax",@progbits
    .global drive_path_target
    .type drive_path_target,@function
drive_path_target:
    push    r10
    push    r9
    push    r8
    push    r7
    sub     #2, r1                  ; the stack argument of secondary() / sol
    mov     #DRIVE_ERR_PARAM_N, r15
    tst     r12
    jz      1f
    tst.b   PATH_READY(r12)
    jz      1f
    mov     r12, r10
    mov     r13, r8
    mov     r14, r7
    mov.b   12(r1), r9              ; cur.leg
    cmp.b   PATH_N(r10), r9
    jhs     1f
    tst.b   13(r1)                  ; cur.sub in 1..nsub
    jz      1f
    mov     r10, r11
    mov     r9, r12
    call    #point_of
    cmp.b   13(r1), 16(r12)
    jlo     1f
    mov     r10, r12                ; drive_path_leg(path, leg, &sol)
    mov     r9, r13
    mov     r1, r14
    call    #drive_path_leg
    mov     r12, r15
    tst     r12
    jnz     1f
    mov     r8, 0(r1)               ; secondary(path, start, pt, sub, pose)
    mov     r10, r11
    mov     r9, r12
    call    #start_of
    push    r12
    mov     r9, r12
    call    #point_of
    mov     r12, r14
    pop     r13
    mov     r14, r9
    mov.b   13(r1), r15
    mov     r10, r12
    call    #secondary
    mov     12(r9), 0(r7)           ; *speed
    mov     14(r9), 2(r7)
    clr     r15
1:  mov     r15, r12
    add     #2, r1
    pop     r7
    pop     r8
    pop     r9
    pop     r10
    ret

/* drive_path_cursor_t drive_path_first(const drive_path_t *path): {0, 1} to R12. */
    .section .text.drive_path_first,"ax",@progbits
    .global drive_path_first
    .type drive_path_first,@function
drive_path_first:
    mov     #0x0100, 0(r12)
    ret

/*
 * bool drive_path_is_last(const drive_path_t *path, drive_path_cursor_t cur): R12 = path,
 * cur at 2(SP). leg + 1 >= n and sub >= nsub.
 */
    .section .text.drive_path_is_last,"ax",@progbits
    .global drive_path_is_last
    .type drive_path_is_last,@function
drive_path_is_last:
    mov     r12, r11
    mov.b   2(r1), r12
    inc     r12
    mov.b   PATH_N(r11), r13
    cmp     r13, r12
    jlo     1f
    dec     r12
    call    #point_of
    cmp.b   16(r12), 3(r1)
    jlo     1f
    mov     #1, r12
    ret
1:  clr     r12
    ret

/*
 * drive_path_cursor_t drive_path_next(const drive_path_t *path, drive_path_cursor_t cur):
 * R12 = the result's address, R13 = path, cur at 2(SP). Unchanged at the last point; else
 * the next secondary point, or the first of the next leg.
 */
    .section .text.drive_path_next,"ax",@progbits
    .global drive_path_next
    .type drive_path_next,@function
drive_path_next:
    push    r10
    push    r9
    mov     r12, r10                ; the result
    mov     r13, r9                 ; the path
    mov     6(r1), r12              ; the cursor (leg, sub), also the result so far
    mov     r12, 0(r10)
    push    r12                     ; drive_path_is_last(path, cur)
    mov     r9, r12
    call    #drive_path_is_last
    add     #2, r1
    tst.b   r12
    jnz     2f
    mov     r9, r11                 ; sub < nsub: the next sub
    mov.b   0(r10), r12
    call    #point_of
    cmp.b   16(r12), 1(r10)
    jhs     1f
    inc.b   1(r10)
    jmp     2f
1:  inc.b   0(r10)                  ; the next leg
    mov.b   #1, 1(r10)
2:  mov     r10, r12
    pop     r9
    pop     r10
    ret

/*
 * drive_status_t drive_path_prepare(drive_path_t *path, const drive_pose_t *start,
 *     drive_path_point_t *pts, uint8_t n, const drive_path_config_t *cfg,
 *     const drive_board_t *board): R12 = path, R13 = start, R14 = pts, R15 = n, cfg and board
 * on the stack. R10 = path, R9 = the point, R8 = the leg's start, R7 = leg, R6 = sub,
 * R5 = cfg, R4 = board.
 */
    .set PR_SOL, 6                  /* drive_path_leg()'s answer; 0(SP): outgoing arguments */
    .set PR_CNT, 8
    .set PR_A, 10
    .set PR_B, 22
    .set PR_PIECE, 34
    .set PR_CMD, 60
    .set PR_FRAME, 74
    .set PR_ARG, PR_FRAME + 16      /* cfg, board (the caller's) */

    .section .text.drive_path_prepare,"ax",@progbits
    .global drive_path_prepare
    .type drive_path_prepare,@function
drive_path_prepare:
    push    r10
    push    r9
    push    r8
    push    r7
    push    r6
    push    r5
    push    r4
    sub     #PR_FRAME, r1
    tst     r12
    jz      1f
    mov     r12, r10
    mov     r14, PATH_PTS(r10)
    mov.b   r15, PATH_N(r10)
    mov     #-1, PATH_CACHE_LEG(r10)
    mov     PR_ARG+2(r1), r4
    mov     r4, PATH_BOARD(r10)
    mov     PR_ARG(r1), r5
    clr     r7                      ; leg 0, sub 0 for the refusals below
    clr     r6
    tst     r13                     ; NULL pointers
    jz      pr_param
    tst     r14
    jz      pr_param
    tst     r5
    jz      pr_param
    tst     r4
    jz      pr_param
    jmp     2f
1:  mov     #DRIVE_ERR_PARAM_N, r15 ; no path
    jmp     pr_ret
2:  mov     r10, r12                ; path->start = *start, path->cfg = *cfg
    add     #PATH_START, r12
    mov     #6, r11
    call    #copyw
    mov     r5, r13
    mov     #5, r11
    call    #copyw
    mov.b   PATH_N(r10), r12        ; 1 <= n <= 254
    dec.b   r12
    cmp.b   #254, r12
    jhs     pr_param
    mov     @r5, r12                ; board's minimum <= nominal <= 100 m
    mov     2(r5), r13
    sub     BOARD_MIN_R(r4), r12
    subc    BOARD_MIN_R+2(r4), r13
    jl      pr_param
    cmp     #HI(DRIVE_MIN_RADIUS_MAX_Q16), 2(r5)
    jl      1f
    jne     pr_param
    tst     0(r5)
    jnz     pr_param
1:  tst     BOARD_MIN_R+2(r4)       ; board's minimum >= 0.125 m
    jn      pr_param
    jnz     2f
    cmp     #LO(DRIVE_MIN_RADIUS_MIN_Q16), BOARD_MIN_R(r4)
    jlo     pr_param
2:  tst     6(r5)                   ; 0.05 m <= spacing <= 8 m
    jn      pr_param
    jnz     3f
    cmp     #3276, 4(r5)
    jlo     pr_param
3:  cmp     #8, 6(r5)
    jl      4f
    jne     pr_param
    tst     4(r5)
    jnz     pr_param
4:  mov     r10, r8                 ; the legs
    add     #PATH_START, r8
    mov     PATH_PTS(r10), r9
leg:
    cmp.b   PATH_N(r10), r7
    jhs     pr_ready
    clr     r6
    mov     r1, r12                 ; drive_speed_counts(speed, reverse, board, &counts)
    add     #PR_CNT, r12
    mov     r12, 0(r1)
    mov     12(r9), r12
    mov     14(r9), r13
    mov.b   8(r5), r14
    mov     r4, r15
    call    #drive_speed_counts
    mov     r12, r15
    tst     r12
    jnz     pr_refuse
    mov     #DRIVE_ERR_PARAM_N, r15 ; a speed that rounds to a stop
    tst.b   PR_CNT(r1)
    jz      pr_refuse
    mov     r10, r12                ; drive_path_leg(path, leg, &sol)
    mov     r7, r13
    mov     r1, r14
    add     #PR_SOL, r14
    call    #drive_path_leg
    mov     r12, r15
    tst     r12
    jnz     pr_refuse
    mov     PR_SOL(r1), r11         ; nsub = ceil((s0 + s1) / spacing), at least 1
    mov     6(r11), r12
    mov     8(r11), r13
    add     18(r11), r12
    addc    20(r11), r13
    add     4(r5), r12
    addc    6(r5), r13
    sub     #1, r12
    subc    #0, r13
    mov     4(r5), r14
    mov     6(r5), r15
    call    #__mspabi_divul
    mov     #DRIVE_ERR_PATH_N, r15
    tst     r13
    jnz     pr_refuse
    cmp     #256, r12
    jhs     pr_refuse
    tst     r12
    jnz     5f
    inc     r12
5:  mov.b   r12, 16(r9)
    mov     r1, r12                 ; a = the leg's start
    add     #PR_A, r12
    mov     r8, r13
    mov     #6, r11
    call    #copyw
piece:
    inc     r6
    cmp.b   r6, 16(r9)
    jlo     6f
    mov     r1, r12                 ; b = secondary(path, start, pt, sub)
    add     #PR_B, r12
    mov     r12, 0(r1)
    mov     r10, r12
    mov     r8, r13
    mov     r9, r14
    mov     r6, r15
    call    #secondary
    mov.b   8(r5), 0(r1)            ; drive_solve(&a, &b, min_radius, reverse, &piece, NULL)
    clr.b   1(r1)
    mov     r1, r12
    add     #PR_PIECE, r12
    mov     r12, 2(r1)
    clr     4(r1)
    mov     r1, r12
    add     #PR_A, r12
    mov     r1, r13
    add     #PR_B, r13
    mov     BOARD_MIN_R(r4), r14
    mov     BOARD_MIN_R+2(r4), r15
    call    #drive_solve
    mov     r12, r15
    tst     r12
    jnz     pr_refuse
    mov.b   8(r5), 0(r1)            ; drive_cmd_build(&piece, board, speed, reverse, &cmd)
    clr.b   1(r1)
    mov     r1, r12
    add     #PR_CMD, r12
    mov     r12, 2(r1)
    mov     r1, r12
    add     #PR_PIECE, r12
    mov     r4, r13
    mov     12(r9), r14
    mov     14(r9), r15
    call    #drive_cmd_build
    mov     r12, r15
    tst     r12
    jnz     pr_refuse
    mov     r1, r12                 ; a = b
    add     #PR_A, r12
    mov     r1, r13
    add     #PR_B, r13
    mov     #6, r11
    call    #copyw
    jmp     piece
6:  mov     r9, r8                  ; the next leg starts at this point
    add     #18, r9
    inc     r7
    jmp     leg
pr_ready:
    mov.b   #1, PATH_READY(r10)
    clr     PATH_BAD_WHY(r10)
    clr     r15
    jmp     pr_ret
pr_param:
    mov     #DRIVE_ERR_PARAM_N, r15
pr_refuse:
    clr.b   PATH_READY(r10)         ; reject(): not ready, where and why
    mov.b   r7, PATH_BAD_LEG(r10)
    mov.b   r6, PATH_BAD_SUB(r10)
    mov     r15, PATH_BAD_WHY(r10)
pr_ret:
    mov     r15, r12
    add     #PR_FRAME, r1
    pop     r4
    pop     r5
    pop     r6
    pop     r7
    pop     r8
    pop     r9
    pop     r10
    ret

/* R11 words from R13 to R12 (both advanced). */
copyw:
    mov     @r13+, r14
    mov     r14, 0(r12)
    incd    r12
    dec     r11
    jnz     copyw
    ret
