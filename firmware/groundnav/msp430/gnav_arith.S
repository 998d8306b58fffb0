/*
 * gnav_arith.S - the groundnav kernels (gnav_arith.h, docs/kernels.md): the dl handler's step
 * gnav_add64x2 / gnav_sub64x2, and the numeric parts of an arc's closing, the chord's
 * correction gnav_chord and, with the arc's deficit first, gnav_arc, as ADDC chains and the
 * hardware multiplier. Their C twins (gnav_arith_k.c) define the results; the check images compare
 * every call. The control logic around them is C (gnav_dr.c, gnav_arc.c).
 *
 * Registers as clang emits the calls (TI EABI): R12 = the first argument (a pointer), a
 * 32-bit second argument in R14:R13, a 32-bit result in R13:R12. R11..R15 may be clobbered,
 * R4..R10 are preserved. The fields of gnav_t and the reciprocal table's range come from
 * gnav_offsets.h, generated from the C headers (msp430/gnav_offsets.c).
 * The hardware multiplier (MPY 0x130, MPYS 0x132, OP2 0x138, RESLO 0x13A, RESHI 0x13C) is
 * used with interrupts held off (SR saved on the stack, restored by POP SR), as the
 * compiler's multiply helpers do; the instruction after DINT does not touch it.
 */
#include "gnav_offsets.h"

    .set MPY,   0x0130
    .set MPYS,  0x0132
    .set OP2,   0x0138
    .set RESLO, 0x013a
    .set RESHI, 0x013c

/* void gnav_add64x2(int64_t *xy, const int32_t *v): xy[0] += v[0], xy[1] += v[1]. */
    .section .text.gnav_add64x2,"ax",@progbits
    .global gnav_add64x2
    .type gnav_add64x2,@function
gnav_add64x2:
    mov     @r13+, r14              ; v[0]
    mov     @r13+, r15
    mov     r15, r11                ; its sign extension: 0 or 0xffff
    rla     r11
    subc    r11, r11
    inv     r11
    add     r14, 0(r12)
    addc    r15, 2(r12)
    addc    r11, 4(r12)
    addc    r11, 6(r12)
    mov     @r13+, r14              ; v[1]
    mov     @r13, r15
    mov     r15, r11
    rla     r11
    subc    r11, r11
    inv     r11
    add     r14, 8(r12)
    addc    r15, 10(r12)
    addc    r11, 12(r12)
    addc    r11, 14(r12)
    ret
    .size gnav_add64x2, .-gnav_add64x2

/* void gnav_sub64x2(int64_t *xy, const int32_t *v): xy[0] -= v[0], xy[1] -= v[1]. */
    .section .text.gnav_sub64x2,"ax",@progbits
    .global gnav_sub64x2
    .type gnav_sub64x2,@function
gnav_sub64x2:
    mov     @r13+, r14
    mov     @r13+, r15
    mov     r15, r11
    rla     r11
    subc    r11, r11
    inv     r11
    sub     r14, 0(r12)
    subc    r15, 2(r12)
    subc    r11, 4(r12)
    subc    r11, 6(r12)
    mov     @r13+, r14
    mov     @r13, r15
    mov     r15, r11
    rla     r11
    subc    r11, r11
    inv     r11
    sub     r14, 8(r12)
    subc    r15, 10(r12)
    subc    r11, 12(r12)
    subc    r11, 14(r12)
    ret
    .size gnav_sub64x2, .-gnav_sub64x2

/* Sign extension of the word in \src into \dst: 0 or 0xffff. */
    .macro SEXT src, dst
    mov     \src, \dst
    rla     \dst
    subc    \dst, \dst
    inv     \dst
    .endm

/* The tiers of the reciprocal below assume its table ends at 2^10. */
    .if GNAV_RECIP_HI_ != 1024
    .error "deficit_core: the reciprocal tiers are written for GNAV_RECIP_HI = 1024"
    .endif

/*
 * deficit_core (local): R10 = g, R13:R12 = m (>= n0) -> R15:R14 = E(m), pulses Q16; the
 * deficit's steps of gnav_arc() in gnav_arith_k.c: the table below tab_end (sets rho_p,
 * clears rho_due); beyond, x = M / m from the reciprocal table (Q16; m rounded to 2^4, 2^8,
 * 2^12 in tiers 1..3), g(x) interpolated (Q17), E = M g (and x_p, g_p, rho_due = 1).
 * Clobbers R11..R15.
 */
    .section .text.gnav_chord,"ax",@progbits
    .type deficit_core,@function
deficit_core:
    tst     r13
    jnz     .Lbig
    cmp     GNAV_TAB_END(r10), r12
    jhs     .Lbig
    sub     GNAV_N0(r10), r12       ; i
    rla     r12                     ; 2 i
    mov     r10, r11
    add     r12, r11
    mov     GNAV_TAB_RHO(r11), GNAV_RHO_P(r10)
    clr.b   GNAV_RHO_DUE(r10)
    add     r12, r11                ; g + 4 i
    mov     GNAV_TAB_E(r11), r14
    mov     GNAV_TAB_E+2(r11), r15
    ret
.Lbig:
    /* the reciprocal's index (R14) and the rounding/shift of the product, by range; the
     * multiplier is used up to E with interrupts held off throughout (one section) */
    push    r2
    dint
    tst     r13                     ; (not the multiplier right after DINT)
    jnz     .Lt2
    cmp     #GNAV_RECIP_HI_, r12
    jhs     .Lt1
    mov     r12, r14                ; tier 0: m itself
    mov     #0, r11                 ; t = 0
    jmp     .Lrecip
.Lt1:
    cmp     #16384, r12
    jhs     .Lt2
    mov     r12, r14                ; tier 1: (m + 8) >> 4 (m < 2^14: no carry out)
    add     #8, r14
    rra     r14
    rra     r14
    rra     r14
    rra     r14
    mov     #1, r11
    jmp     .Lclamp
.Lt2:
    cmp     #4, r13
    jhs     .Lt3
    mov     r12, r14                ; tier 2: (m + 128) >> 8
    mov     r13, r15
    add     #128, r14
    adc     r15
    swpb    r14
    and     #0xff, r14
    swpb    r15
    bis     r15, r14                ; r15 < 4: its low byte lands in the high byte
    mov     #2, r11
    jmp     .Lclamp
.Lt3:
    cmp     #64, r13
    jhs     .Lzero
    mov     r12, r14                ; tier 3: (m + 2048) >> 12
    mov     r13, r15
    add     #2048, r14
    adc     r15
    swpb    r14
    and     #0xff, r14              ; (v >> 8) low byte
    swpb    r15
    bis     r15, r14                ; v >> 8 (r15 < 64 before the swap)
    rra     r14
    rra     r14
    rra     r14
    rra     r14
    and     #0x0fff, r14
    mov     #3, r11
.Lclamp:
    cmp     #GNAV_RECIP_HI_, r14
    jlo     .Lrecip
    mov     #GNAV_RECIP_HI_-1, r14
.Lrecip:
    sub     #GNAV_RECIP_LO_, r14
    rla     r14
    mov     gnav_recip(r14), r14
    mov     GNAV_M_Q11(r10), &MPY
    mov     r14, &OP2
    mov     &RESLO, r12
    mov     &RESHI, r13
    /* x = (p + 2^(15 + 4t)) >> (16 + 4t) */
    tst     r11
    jnz     .Lx1
    add     #0x8000, r12
    adc     r13
    mov     r13, r12
    jmp     .Lg
.Lx1:
    cmp     #2, r11
    jhs     .Lx2
    add     #8, r13                 ; tier 1: + 2^19, >> 20
    rra     r13
    rra     r13
    rra     r13
    rra     r13
    and     #0x0fff, r13
    mov     r13, r12
    jmp     .Lg
.Lx2:
    jne     .Lx3
    add     #0x80, r13              ; tier 2: + 2^23, >> 24
    swpb    r13
    and     #0xff, r13
    mov     r13, r12
    jmp     .Lg
.Lx3:
    add     #0x800, r13             ; tier 3: + 2^27, >> 28
    swpb    r13
    and     #0xff, r13
    rra     r13
    rra     r13
    rra     r13
    rra     r13
    and     #0x0f, r13
    mov     r13, r12
    jmp     .Lg
.Lzero:
    clr     r12
.Lg:
    /* g = G[i] + ((G[i+1] - G[i]) f + 128) >> 8, i = x >> 8, f = x & 255; R12 = x */
    mov     r12, GNAV_X_P(r10)
    mov     r12, r14
    swpb    r14
    and     #0xff, r14              ; i
    rla     r14
    mov     gnav_g(r14), r15        ; G[i]
    mov     gnav_g+2(r14), r13
    sub     r15, r13                ; G[i+1] - G[i] (>= 0)
    and     #0xff, r12              ; f
    mov     r13, &MPY
    mov     r12, &OP2
    mov     &RESLO, r12             ; (diff f + 128) >> 8: diff < 2^9, f < 2^8
    mov     &RESHI, r13
    add     #128, r12
    adc     r13
    swpb    r12
    and     #0xff, r12
    swpb    r13                     ; r13 < 2: its low byte lands in the high byte
    bis     r13, r12
    add     r12, r15                ; g (Q17)
    mov     r15, GNAV_G_P(r10)
    mov.b   #1, GNAV_RHO_DUE(r10)
    /* E = (M_hi g + (M_lo g >> 16) + 1) >> 1, M = m_q16 */
    mov     r15, r11
    mov     GNAV_M_Q16+2(r10), &MPY
    mov     r11, &OP2
    mov     &RESLO, r14
    mov     &RESHI, r15
    mov     GNAV_M_Q16(r10), &MPY
    mov     r11, &OP2
    mov     &RESHI, r12
    pop     r2
    add     r12, r14
    adc     r15
    add     #1, r14
    adc     r15
    clrc
    rrc     r15
    rrc     r14
    ret
    .size deficit_core, .-deficit_core

/*
 * provisional (local): R10 = g -> R13:R12 = m = |n|, the pulses since P (n = n_hi:n_lo), and
 * R5:R4 = what the provisional pose assumed of them, min(m, n_p) pulses of rho_p, pulses Q16
 * (nc 2 rho_p). Clobbers R11, R14, R15.
 */
    .section .text.gnav_chord,"ax",@progbits
    .type provisional,@function
provisional:
    mov     GNAV_N_LO(r10), r12
    mov     GNAV_N_HI(r10), r13
    tst     r13
    jge     1f
    inv     r12                     ; m = -n
    inv     r13
    add     #1, r12
    adc     r13
1:  mov     GNAV_N_P(r10), r14      ; nc = min(m, n_p)
    tst     r13
    jnz     2f
    cmp     r14, r12
    jhs     2f
    mov     r12, r14
2:  mov     GNAV_RHO_P(r10), r15
    rla     r15                     ; 2 rho_p (rho_p < 2^15)
    push    r2
    dint
    mov     r15, r11                ; (not the multiplier right after DINT)
    mov     r14, &MPY
    mov     r11, &OP2
    mov     &RESLO, r4
    mov     &RESHI, r5
    pop     r2
    ret
    .size provisional, .-provisional

/*
 * void gnav_chord(gnav_t *g, int32_t e, const int32_t *step): R12 = g, R14:R13 = e (pulses
 * Q16), R15 = step. Steps of gnav_chord() in gnav_arith_k.c (provisional, then apply):
 * delta = nc 2 rho_p - e, negated when n < 0; delta += resid; d10 = (delta + 32) >> 6 clamped
 * to +-32767; resid = delta - 64 d10 (from the low six bits when nothing was clamped);
 * x += d10 d15_c +- step[0], y += d10 d15_s +- step[1] (Q10 x Q15 = Q25; - when reverse).
 * The body (.Lapply, shared with gnav_arc): R10 = g,
 * R9 = step, R5:R4 = delta before its sign, with R10, R9, R8, R5, R4 pushed.
 */
    .global gnav_chord
    .type gnav_chord,@function
gnav_chord:
    push    r10
    push    r9
    push    r8
    push    r5
    push    r4
    mov     r12, r10
    mov     r15, r9                 ; step
    mov     r13, r8                 ; e across provisional (it clobbers R11..R15)
    push    r14
    call    #provisional            ; R5:R4 = dprov
    pop     r14
    sub     r8, r4                  ; delta = dprov - e
    subc    r14, r5
.Lapply:
    tst     GNAV_N_HI(r10)          ; backwards: negated
    jge     5f
    inv     r4
    inv     r5
    add     #1, r4
    adc     r5
5:  add     GNAV_RESID(r10), r4
    addc    GNAV_RESID+2(r10), r5
    /* v = delta + 32; d10 = v >> 6, clamped to +-32767, in R12 */
    mov     r4, r12
    mov     r5, r13
    add     #32, r12
    adc     r13
    cmp     #32, r13                ; -32 < v_hi < 32: no clamp, resid = (v & 63) - 32
    jge     6f
    cmp     #-31, r13
    jl      6f
    mov     r12, r14
    and     #63, r14
    sub     #32, r14
    mov     r14, GNAV_RESID(r10)
    SEXT    r14, r15
    mov     r15, GNAV_RESID+2(r10)
    rra     r13                     ; d10 = v >> 6 (fits 16 bits here)
    rrc     r12
    rra     r13
    rrc     r12
    rra     r13
    rrc     r12
    rra     r13
    rrc     r12
    rra     r13
    rrc     r12
    rra     r13
    rrc     r12
    jmp     8f
6:  rra     r13                     ; clamped: d10 = v >> 6 limited to +-32767
    rrc     r12
    rra     r13
    rrc     r12
    rra     r13
    rrc     r12
    rra     r13
    rrc     r12
    rra     r13
    rrc     r12
    rra     r13
    rrc     r12
    tst     r13
    jn      1f
    jnz     2f
    cmp     #0x8000, r12
    jlo     3f
2:  mov     #32767, r12
    jmp     3f
1:  cmp     #-1, r13
    jne     4f
    cmp     #0x8001, r12
    jhs     3f
4:  mov     #-32767, r12
3:  mov     r12, r14                ; resid = delta - 64 d10
    SEXT    r12, r15
    rla     r14
    rlc     r15
    rla     r14
    rlc     r15
    rla     r14
    rlc     r15
    rla     r14
    rlc     r15
    rla     r14
    rlc     r15
    rla     r14
    rlc     r15
    sub     r14, r4
    subc    r15, r5
    mov     r4, GNAV_RESID(r10)
    mov     r5, GNAV_RESID+2(r10)
8:  /* d10 d15_c, d10 d15_s (Q10 x Q15 = Q25) */
    push    r2
    dint
    mov     GNAV_D15_C(r10), r14    ; (not the multiplier right after DINT)
    mov     r12, &MPYS
    mov     r14, &OP2
    mov     &RESLO, r14
    mov     &RESHI, r15
    mov     r12, &MPYS
    mov     GNAV_D15_S(r10), &OP2
    mov     &RESLO, r4
    mov     &RESHI, r5
    pop     r2
    /* + the step, or - when reverse (the sums fit 32 bits) */
    tst.b   GNAV_REVERSE(r10)
    jnz     9f
    add     @r9+, r14
    addc    @r9+, r15
    add     @r9+, r4
    addc    @r9, r5
    jmp     10f
9:  sub     @r9+, r14
    subc    @r9+, r15
    sub     @r9+, r4
    subc    @r9, r5
10: SEXT    r15, r13
    add     r14, GNAV_X(r10)
    addc    r15, GNAV_X+2(r10)
    addc    r13, GNAV_X+4(r10)
    addc    r13, GNAV_X+6(r10)
    SEXT    r5, r13
    add     r4, GNAV_Y(r10)
    addc    r5, GNAV_Y+2(r10)
    addc    r13, GNAV_Y+4(r10)
    addc    r13, GNAV_Y+6(r10)
    pop     r4
    pop     r5
    pop     r8
    pop     r9
    pop     r10
    ret
    .size gnav_chord, .-gnav_chord

/*
 * void gnav_arc(gnav_t *g, uint16_t half, const int32_t *step): R12 = g, R13 = half,
 * R14 = step. Steps of gnav_arc() in gnav_arith_k.c: provisional (m and dprov, before the
 * deficit changes rho_p), the arc's deficit E of m pulses (for half, m = 2 m, 2^31 from 2^30
 * on, and E = (E + 1) >> 1), then apply delta = dprov - E (gnav_chord's body).
 */
    .global gnav_arc
    .type gnav_arc,@function
gnav_arc:
    push    r10
    push    r9
    push    r8
    push    r5
    push    r4
    mov     r12, r10
    mov     r13, r8                 ; half
    mov     r14, r9                 ; step
    call    #provisional            ; R13:R12 = m, R5:R4 = dprov
    tst     r8
    jz      2f
    cmp     #0x4000, r13            ; half: m = 2 m, or 2^31 from 2^30 on
    jlo     1f
    clr     r12
    mov     #0x8000, r13
    jmp     2f
1:  rla     r12
    rlc     r13
2:  call    #deficit_core           ; R15:R14 = E
    tst     r8
    jz      3f
    add     #1, r14                 ; half: (E + 1) >> 1 (E >= 0)
    adc     r15
    rra     r15
    rrc     r14
3:  sub     r14, r4                 ; delta = dprov - E
    subc    r15, r5
    jmp     .Lapply
    .size gnav_arc, .-gnav_arc
