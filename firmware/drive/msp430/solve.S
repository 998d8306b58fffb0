/*
 * solve.S - MSP430 version of drive_solve() (solve.c holds the portable C that defines the
 * results). The formulas are the very programs of solve.c, run by drive_vm_run on the same
 * frame (solve_frame.h); what is here are the decisions between them and the few fx calls
 * with a shift or a failure to look at, step for step as in solve.c, which
 * tests/vectors/drive_vectors.c checks bit for bit.
 *
 * Registers as clang emits calls (TI EABI; see vm.S). Kept across the calls: R9 the frame,
 * R10 the scale sh (L24 = Q16 * 2^sh, 4..13), R6 up = 2^sh, R5:R4 the minimum radius, R8
 * bit 0 mirror image, bit 1 reverse travel, R7 the case.
 */
#include "../drive_internal.h"
#include "../solve_frame.h"
#include "layout.h"

/* Slot s's low and high word. (LLVM's MSP430 assembler silently drops an instruction whose
 * indexed operand starts with a parenthesis: these must not.) */
#define V(s)  4 * (s)(r9)
#define VH(s) 4 * (s) + 2(r9)

    .set FRAME, 4 + SV_NSLOTS * 4   /* 0(SP): outgoing stack arguments, then the slots */
    .set ARG, SV_NSLOTS * 4 + 16    /* from R9: reverse, out, needed (the caller's) */

    .macro RUN prog
    mov     r9, r12
    mov     #\prog, r13
    call    #drive_vm_run
    .endm

    /* fx_div_shift / fx_mul_shift's stack arguments: the shift (register or #n) and the
     * address of slot s for the result. */
    .macro ARGS shift, s
    mov     \shift, 0(r1)
    mov     r9, r11
    add     #(\s)*4, r11
    mov     r11, 2(r1)
    .endm

    .macro LD s, lo, hi
    mov     V(\s), \lo
    mov     VH(\s), \hi
    .endm

    .macro ST lo, hi, s
    mov     \lo, V(\s)
    mov     \hi, VH(\s)
    .endm

    .macro NEG32 lo, hi
    inv     \lo
    inv     \hi
    inc     \lo
    adc     \hi
    .endm

/*
 * drive_status_t drive_solve(const drive_pose_t *from, const drive_pose_t *to,
 *     fx_q16_t min_radius, bool reverse, drive_solution_t *out, int32_t *needed):
 * R12 = from, R13 = to, R15:R14 = min_radius, reverse, out and needed on the stack.
 */
    .section .text.drive_solve,"ax",@progbits
    .global drive_solve
    .type drive_solve,@function
drive_solve:
    push    r10
    push    r9
    push    r8
    push    r7
    push    r6
    push    r5
    push    r4
    sub     #FRAME, r1
    mov     r1, r9
    add     #4, r9
    tst     r12                     ; NULL pointers, the minimum radius out of range
    jz      e_param
    tst     r13
    jz      e_param
    tst     ARG+2(r9)
    jz      e_param
    mov     r14, r4
    mov     r15, r5
    tst     r5
    jn      e_param
    jnz     1f
    cmp     #LO(DRIVE_MIN_RADIUS_MIN_Q16), r4
    jlo     e_param
1:  cmp     #HI(DRIVE_MIN_RADIUS_MAX_Q16), r5
    jlo     2f
    jne     e_param
    tst     r4
    jnz     e_param
2:  clr     r8
    tst.b   ARG(r9)
    jz      3f
    mov     #2, r8
3:  mov     8(r13), r14             ; dl = B - A, within a quarter turn
    mov     10(r13), r15
    sub     8(r12), r14
    subc    10(r12), r15
    ST      r14, r15, SV_DL
    cmp     #0x4000, r15
    jl      4f
    jne     e_heading
    tst     r14
    jnz     e_heading
    jmp     5f
4:  cmp     #0xC000, r15
    jl      e_heading
5:  tst     r15                     ; eta = dl / 2, toward zero
    jge     6f
    inc     r14
    adc     r15
6:  rra     r15
    rrc     r14
    ST      r14, r15, SV_ETA
    add     8(r12), r14             ; u = A + eta (the direction of travel), to T0
    addc    10(r12), r15
    bit     #2, r8
    jz      7f
    xor     #0x8000, r15
7:  ST      r14, r15, SV_T0
    clr     r7                      ; D, each difference checked for overflow
1:  mov     r13, r10                ; &to->x, &to->y
    add     r7, r10
    mov     r12, r6                 ; &from->x, &from->y
    add     r7, r6
    mov     @r10, r14
    mov     2(r10), r15
    sub     @r6, r14
    subc    2(r6), r15
    mov     r9, r11                 ; DX, DY
    add     r7, r11
    mov     r14, 0(r11)
    mov     r15, 2(r11)
    mov     2(r10), r11
    xor     2(r6), r11
    xor     2(r10), r15
    and     r11, r15
    jn      e_far
    add     #4, r7
    cmp     #8, r7
    jne     1b
    mov     #SV_DX*4, r11           ; m = max(|dx|, |dy|) <= 64 m
    call    #absmax
    cmp     #HI(DRIVE_MAX_DIST_Q16), r15
    jlo     8f
    jne     e_far
    tst     r14
    jnz     e_far
8:  mov     #13, r10                ; the scale: sh = 13, lim = 2^13; while m > lim: lim
    mov     #0x2000, r6             ; doubles, sh and up = 2^sh go down
    mov     #0x2000, r12
    clr     r13
9:  cmp     r13, r15
    jlo     11f
    jne     10f
    cmp     r14, r12
    jhs     11f
10: rla     r12
    rlc     r13
    dec     r10
    rra     r6
    jmp     9b
11: LD      SV_DX, r12, r13         ; D in L24
    LD      SV_DY, r14, r15
    mov     r10, r11
12: rla     r12
    rlc     r13
    rla     r14
    rlc     r15
    dec     r11
    jnz     12b
    ST      r12, r13, SV_DX
    ST      r14, r15, SV_DY
    mov     r9, r12                 ; E in the u frame
    add     #SV_P*4, r12
    mov     r9, r13
    LD      SV_T0, r14, r15
    call    #drive_rot
    tst     VH(SV_ETA)              ; mirror image: eta < 0 or (eta = 0 and q < 0)
    jn      13f
    jnz     14f
    tst     V(SV_ETA)
    jnz     14f
    tst     VH(SV_Q)
    jge     14f
13: bis     #1, r8
    mov     #SV_ETA*4, r11
    call    #negv
    mov     #SV_Q*4, r11
    call    #negv
    mov     #SV_DL*4, r11
    call    #negv
14: RUN     drive_p_canon
    tst     VH(SV_PP)               ; P <= 0: behind
    jn      e_behind
    jnz     15f
    tst     V(SV_PP)
    jz      e_behind
15: cmp     #4, r10                 ; |D| > 64 m
    jne     16f
    cmp     #0x1000, VH(SV_E2)
    jlo     16f
    jne     e_far
    tst     V(SV_E2)
    jnz     e_far
16: cmp     #13, r10                ; |D| < 1/64 m
    jne     17f
    cmp     #0x40, VH(SV_E2)
    jlo     e_close

/* The straight case: |dl| < STRAIGHT_ANGLE and |q| <= one Q16 LSB. */
17: LD      SV_DL, r12, r13
    tst     r13
    jge     18f
    NEG32   r12, r13
18: tst     r13
    jnz     filter
    cmp     #STRAIGHT_ANGLE, r12
    jhs     filter
    tst     VH(SV_AQ)
    jnz     filter
    cmp     V(SV_AQ), r6
    jlo     filter
    call    #clear_out
    clr     r7
    RUN     drive_p_halves          ; the two halves of P
    mov     #SV_T0*4, r11
    mov     #SV_L0*4, r14
    call    #usc
    mov     #SV_T1*4, r11
    mov     #SV_L1*4, r14
    call    #usc

/* Back to the real world: mirror (sweeps and curvatures), reverse (curvatures). */
output:
    bit     #1, r8
    jz      50f
    mov     #SV_W0*4, r11
    call    #negv2
50: mov     r8, r11                 ; mirror != reverse: R8 is 1 or 2
    inc     r11
    bit     #2, r11
    jz      51f
    mov     #SV_K0*4, r11
    call    #negv2
51: mov     ARG+2(r9), r11
    mov     r7, 0(r11)
    incd    r11
    mov     r9, r14
    mov     #12, r15
    call    #copyw
    clr     r12
    jmp     exit
/* The refusals and the way out (mid-function: within reach of every jump). */
e_param:
    mov     #DRIVE_ERR_PARAM_N, r12
    jmp     exit
e_close:
    mov     #DRIVE_ERR_TOO_CLOSE_N, r12
    jmp     exit
e_far:
    mov     #DRIVE_ERR_TOO_FAR_N, r12
    jmp     exit
e_behind:
    mov     #DRIVE_ERR_BEHIND_N, r12
    jmp     exit
e_heading:
    mov     #DRIVE_ERR_HEADING_N, r12
    jmp     exit
e_radius:
    mov     #DRIVE_ERR_RADIUS_N, r12
    jmp     exit
e_sweep:
    mov     #DRIVE_ERR_SWEEP_N, r12
exit:
    add     #FRAME, r1
    pop     r4
    pop     r5
    pop     r6
    pop     r7
    pop     r8
    pop     r9
    pop     r10
    ret

/* Cases 4, 5 when the cheap filter lets them: A5 > 0, sin eta > 0, and A5 >= 2 rs sin eta
 * with rs = rmin sin eta in L24 below INT32_MAX / 2 (fx_mul_q30(rmin << sh, sin eta) when the
 * shift fits, else fx_mul_shift(rmin, sin eta, 30 - sh): the same value). */
filter:
    tst     VH(SV_A5)
    jn      darc
    jnz     19f
    tst     V(SV_A5)
    jz      darc
19: tst     VH(SV_S)
    jnz     20f
    tst     V(SV_S)
    jz      darc
20: mov     r4, r12
    mov     r5, r13
    mov     r10, r11
21: rla     r12
    rlc     r13
    jn      22f
    dec     r11
    jnz     21b
    LD      SV_S, r14, r15
    call    #fx_mul_q30
    jmp     23f
22: mov     #30, r11
    sub     r10, r11
    ARGS    r11, SV_T0
    mov     r4, r12
    mov     r5, r13
    LD      SV_S, r14, r15
    call    #fx_mul_shift
    tst.b   r12
    jz      darc
    LD      SV_T0, r12, r13
23: cmp     #0x3FFF, r13
    jlo     24f
    jne     darc
    cmp     #-1, r12
    jeq     darc
24: rla     r12
    rlc     r13
    LD      SV_S, r14, r15
    call    #fx_mul_q30
    LD      SV_A5, r14, r15
    sub     r12, r14
    subc    r13, r15
    jl      darc

/* line() of solve.c: the straight l, the arc from its chord, rounded up to Q16, its
 * curvature checked against the minimum radius. */
    cmp     #HI(TAU_SMALL), VH(SV_ETA)
    jlo     25f
    jne     26f
    cmp     #LO(TAU_SMALL), V(SV_ETA)
    jhs     26f
25: ARGS    #30, SV_L
    LD      SV_AQ, r12, r13
    LD      SV_S, r14, r15
    call    #fx_div_shift
    tst.b   r12
    jz      darc
    mov     #drive_p_line_small, r13
    jmp     27f
26: ARGS    #28, SV_INVS
    clr     r12
    mov     #0x4000, r13
    LD      SV_S, r14, r15
    call    #fx_div_shift
    mov     #drive_p_line_big, r13
27: mov     r9, r12
    call    #drive_vm_run
    tst     VH(SV_LC)
    jn      darc
    jnz     28f
    tst     V(SV_LC)
    jz      darc
28: LD      SV_ARC, r12, r13
    tst     r13
    jn      darc
    jnz     29f
    tst     r12
    jz      darc
29: mov     r10, r11                ; ceil(ARC / 2^sh): the bits shifted out counted in R14
    clr     r14
30: rra     r13
    rrc     r12
    adc     r14
    dec     r11
    jnz     30b
    tst     r14
    jz      31f
    inc     r12
    adc     r13
31: ST      r12, r13, SV_ARCQ
    ARGS    #15, SV_KC
    mov     r12, r14
    mov     r13, r15
    LD      SV_E30, r12, r13
    call    #fx_div_shift
    tst.b   r12
    jz      darc
    call    #too_tight
    jnz     darc
    call    #clear_out
    LD      SV_L, r12, r13
    call    #unscale
    mov     #4, r7
    mov     #SV_K0*4, r11           ; case 4: the arc first, the straight second
    tst     VH(SV_Q)
    jge     32f
    mov     #5, r7                  ; case 5: the straight first
    ST      r12, r13, SV_L0
    mov     #SV_K1*4, r11
    jmp     33f
32: ST      r12, r13, SV_L1
33: add     r9, r11                 ; the arc: KC, ARCQ, DL
    mov     r9, r14
    add     #SV_KC*4, r14
    mov     #6, r15
    call    #copyw
    jmp     output

/* double_arc() of solve.c. */
darc:
    RUN     drive_p_x
    mov     r10, r11                ; the curvature 2 X / |E|^2
    add     #21, r11
    ARGS    r11, SV_KC
    LD      SV_X, r12, r13
    LD      SV_E2, r14, r15
    call    #fx_div_shift
    mov     #-1, r14                ; too tight: needed = the curvature, INT32_MAX if over 8
    mov     #0x7FFF, r15
    tst.b   r12
    jz      34f
    call    #too_tight
    jz      35f
    LD      SV_KC, r14, r15
34: mov     ARG+4(r9), r11
    tst     r11
    jz      e_radius
    mov     r14, 0(r11)
    mov     r15, 2(r11)
    jmp     e_radius
35: clr     V(SV_RS)                ; the radius (L20) and rho = r sin eta (L24)
    clr     VH(SV_RS)
    ARGS    #19, SV_R20
    LD      SV_E2, r12, r13
    LD      SV_X, r14, r15
    call    #fx_div_shift
    tst.b   r12
    jnz     36f
    mov     #-1, V(SV_R20)          ; no radius: R20 = INT32_MAX, rho from |E|^2 sin eta / X
    mov     #0x7FFF, VH(SV_R20)
    LD      SV_E2, r12, r13
    LD      SV_S, r14, r15
    call    #fx_mul_q30
    ARGS    #23, SV_RS
    LD      SV_X, r14, r15
    call    #fx_div_shift
    jmp     39f
36: LD      SV_R20, r12, r13
    cmp     #0x0800, r13            ; R20 >= 2^27: multiply first
    jhs     37f
    call    #shl4
    LD      SV_S, r14, r15
    call    #fx_mul_q30
    jmp     38f
37: LD      SV_S, r14, r15
    call    #fx_mul_q30
    call    #shl4
38: ST      r12, r13, SV_RS
39: LD      SV_P, r14, r15          ; the clamp: rho <= p / 2 when q >= 0 or pc + qs >= 0
    tst     r15
    jge     40f
    inc     r14
    adc     r15
40: rra     r15
    rrc     r14
    tst     VH(SV_Q)
    jge     41f
    LD      SV_PC, r12, r13
    add     V(SV_QS), r12
    addc    VH(SV_QS), r13
    jn      42f
41: mov     r14, r12
    mov     r15, r13
    sub     V(SV_RS), r12
    subc    VH(SV_RS), r13
    jge     42f
    ST      r14, r15, SV_RS
42: tst     VH(SV_Q)                ; sigma rho
    jge     43f
    mov     #SV_RS*4, r11
    call    #negv
43: RUN     drive_p_junction
    tst     VH(SV_Q)                ; first turn right and tau0 > 0: a full circle
    jge     44f
    tst     VH(SV_TAU0)
    jn      44f
    jnz     e_sweep
    tst     V(SV_TAU0)
    jnz     e_sweep
44: mov     #SV_TAU0*4, r11         ; the lengths: big = max(|tau0|, |tau1|)
    call    #absmax
    mov     #drive_p_len_tiny, r13
    cmp     #HI(TAU_TINY), r15
    jlo     46f
    jne     45f
    cmp     #LO(TAU_TINY), r14
    jlo     46f
45: mov     #drive_p_len_radius, r13
    cmp     #7, r10                 ; k < 2
    jhs     46f
    cmp     #HI(TAU_SMALL), r15
    jlo     47f
    jne     46f
    cmp     #LO(TAU_SMALL), r14
    jhs     46f
47: mov     #16, r12                ; R20 >= 2^(20 + sh): its high word >= 2^(4 + sh)
    mov     r10, r11
48: rla     r12
    dec     r11
    jnz     48b
    cmp     r12, VH(SV_R20)
    jlo     46f
    mov     #drive_p_len_small, r13
46: mov     r9, r12
    call    #drive_vm_run
    tst     VH(SV_LEN0)
    jn      e_sweep
    tst     VH(SV_LEN1)
    jn      e_sweep
    mov     #1, r7                  ; the case, the first turn's sign, the segments
    tst     VH(SV_Q)
    jge     49f
    mov     #SV_KC*4, r11
    call    #negv
    mov     #2, r7
    tst     VH(SV_A5)
    jge     49f
    mov     #3, r7
49: RUN     drive_p_da_tail
    mov     #SV_LEN0*4, r11
    mov     #SV_L0*4, r14
    call    #usc
    mov     #SV_LEN1*4, r11
    mov     #SV_L1*4, r14
    call    #usc
    br      #output

/* Helpers (R9, R10 as in drive_solve). */

/* Slot at byte offset R11 negated; negv2: and the slot three further (the next segment's). */
negv2:
    call    #negv
    add     #12, r11
negv:
    mov     r9, r15
    add     r11, r15
    inv     0(r15)
    inv     2(r15)
    inc     0(r15)
    adc     2(r15)
    ret

/* R15:R14 = max(|v|, |w|) (unsigned) of the slots at byte offsets R11 and R11 + 4. */
absmax:
    add     r9, r11
    mov     @r11+, r12
    mov     @r11+, r13
    tst     r13
    jge     1f
    NEG32   r12, r13
1:  mov     @r11+, r14
    mov     @r11, r15
    tst     r15
    jge     2f
    NEG32   r14, r15
2:  cmp     r13, r15
    jlo     3f
    jne     4f
    cmp     r12, r14
    jhs     4f
3:  mov     r12, r14
    mov     r13, r15
4:  ret

/* R13:R12 (>= 0) = round(R13:R12 / 2^sh): shifted by sh - 1, plus one, shifted by one. */
unscale:
    mov     r10, r11
    dec     r11
1:  rra     r13
    rrc     r12
    dec     r11
    jnz     1b
    inc     r12
    adc     r13
    rra     r13
    rrc     r12
    ret

/* The slot at byte offset R11 unscaled into the one at R14. */
usc:
    add     r9, r11
    mov     @r11+, r12
    mov     @r11, r13
    call    #unscale
    add     r9, r14
    mov     r12, 0(r14)
    mov     r13, 2(r14)
    ret

/* R13:R12 <<= 4. */
shl4:
    mov     #4, r11
1:  rla     r12
    rlc     r13
    dec     r11
    jnz     1b
    ret

/* Z set when fx_mul_q16(KC, rmin) <= 2^28 (the radius is at least the minimum). */
too_tight:
    LD      SV_KC, r12, r13
    mov     r4, r14
    mov     r5, r15
    call    #fx_mul_q16
    cmp     #0x1000, r13
    jlo     1f
    jne     2f
    tst     r12
    jz      1f
2:  clrz
    ret
1:  setz
    ret

/* The result's six slots cleared. */
clear_out:
    mov     r9, r11
    mov     #12, r15
1:  clr     0(r11)
    incd    r11
    dec     r15
    jnz     1b
    ret

/* R15 words from R14 to R11 (R12 clobbered). */
copyw:
    mov     @r14+, r12
    mov     r12, 0(r11)
    incd    r11
    dec     r15
    jnz     copyw
    ret

/*
 * drive_pose_t drive_pose_advance(const drive_pose_t *pose, int32_t curvature, fx_q16_t dist,
 *     bool reverse): R12 = the result's address, R13 = pose, R15:R14 = curvature, dist and
 * reverse on the stack. drive_pose_advance() of solve.c, step for step, on the frame PV_*.
 */
    .set PFRAME, 4 + PV_NSLOTS * 4
    .set PARG, PV_NSLOTS * 4 + 8    /* from R9: dist, reverse (the caller's) */

    .section .text.drive_pose_advance,"ax",@progbits
    .global drive_pose_advance
    .type drive_pose_advance,@function
drive_pose_advance:
    push    r10
    push    r9
    push    r8
    sub     #PFRAME, r1
    mov     r1, r9
    add     #4, r9
    mov     r12, r10                ; r = *pose
    mov     #6, r8
1:  mov     @r13+, r11
    mov     r11, 0(r12)
    incd    r12
    dec     r8
    jnz     1b
    mov     PARG(r9), r12           ; dist <= 0: r as it is
    mov     PARG+2(r9), r13
    tst     r13
    jn      5f
    jnz     2f
    tst     r12
    jz      5f
2:  ST      r12, r13, PV_DIST
    clr     V(PV_ZERO)
    clr     VH(PV_ZERO)
    mov     8(r10), r11             ; the direction of travel
    mov     10(r10), r8
    tst.b   PARG+4(r9)
    jz      3f
    xor     #0x8000, r8
3:  ST      r11, r8, PV_HEAD
    ST      r14, r15, PV_D28        ; the change: dist * curvature, or saturated by its sign
    ARGS    #16, PV_D28
    call    #fx_mul_shift
    tst.b   r12
    jnz     4f
    mov     #-1, r12
    mov     #0x7FFF, r13
    tst     VH(PV_D28)
    jge     6f
    mov     #1, r12
    mov     #0x8000, r13
6:  ST      r12, r13, PV_D28
4:  tst.b   PARG+4(r9)              ; reversing: the change negated
    jz      7f
    mov     #PV_D28*4, r11
    call    #negv
7:  RUN     drive_p_pa_angles
    LD      PV_H28, r12, r13        ; sin x / x: the series below 0.2 rad, else a division
    tst     r13
    jge     8f
    NEG32   r12, r13
8:  cmp     #HI(HALF_CHANGE_SERIES), r13
    jlo     9f
    jne     10f
    cmp     #LO(HALF_CHANGE_SERIES), r12
    jhs     10f
9:  RUN     drive_p_pa_sox
    jmp     11f
10: LD      PV_HALF, r12, r13
    call    #fx_sin
    ARGS    #28, PV_RATIO
    LD      PV_H28, r14, r15
    call    #fx_div_shift
11: RUN     drive_p_pa_chord
    add     V(PV_XY), 0(r10)        ; r.x, r.y, r.heading
    addc    VH(PV_XY), 2(r10)
    add     V(PV_XY1), 4(r10)
    addc    VH(PV_XY1), 6(r10)
    add     V(PV_DANG), 8(r10)
    addc    VH(PV_DANG), 10(r10)
5:  mov     r10, r12
    add     #PFRAME, r1
    pop     r8
    pop     r9
    pop     r10
    ret
