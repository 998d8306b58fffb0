/*
 * gnav_dl.S - MSP430 version of the dl handler: gnav_on_delta_l(), the arc closing
 * gnav_close_arc() (seed situations 1 and 3) and the deficit it needs. The portable C in
 * gnav.c (gnav_on_delta_l, gnav_close_arc, deficit, publish) defines the results; this
 * performs the very same integer steps, which tests/vectors/groundnav_vectors.c checks bit
 * for bit. The compiler needs about twice the cycles for the same steps on this CPU (32- and
 * 64-bit arithmetic without ADDC chains), which would not leave the worst case, a closing
 * through the HAL shim, under 1,000 cycles.
 *
 * Field offsets of gnav_t (include/groundnav/gnav.h) are checked at compile time by
 * _Static_assert in gnav.c. Registers as clang calls (TI EABI): R12 = the gnav_t; R4..R10
 * are preserved, R11..R15 clobbered. The 16 x 16 multiplier (MPY 0x130, MPYS 0x132, OP2
 * 0x138, RESLO 0x13A, RESHI 0x13C) is used with interrupts held off (POP SR restores them),
 * as the compiler's multiply helpers do; the instruction after DINT does not touch it.
 */
    .set MPY,   0x0130
    .set MPYS,  0x0132
    .set OP2,   0x0138
    .set RESLO, 0x013a
    .set RESHI, 0x013c

    .set OFF_X, 0
    .set OFF_Y, 8
    .set OFF_XP, 16
    .set OFF_YP, 24
    .set OFF_INC10, 40
    .set OFF_INC11, 44
    .set OFF_N_LO, 48
    .set OFF_N_HI, 50
    .set OFF_NQ, 52
    .set OFF_N_P, 54
    .set OFF_RHO_P, 56
    .set OFF_X_P, 58
    .set OFF_G_P, 60
    .set OFF_RESID, 62
    .set OFF_D15_C, 66
    .set OFF_D15_S, 68
    .set OFF_PENDING, 74
    .set OFF_DC_DUE, 76
    .set OFF_RHO_DUE, 77
    .set OFF_NXT_C, 80
    .set OFF_NXT_S, 84
    .set OFF_N15_C, 88
    .set OFF_N15_S, 90
    .set OFF_CELL, 102
    .set OFF_CELL_INT, 104
    .set OFF_H_P, 106
    .set OFF_H_FIRST, 108
    .set OFF_H_LAST, 110
    .set OFF_VERSION, 112
    .set OFF_STOP_LO, 70
    .set OFF_STOP_HI, 72
    .set OFF_REVERSE, 75
    .set OFF_STOP_ARMED, 78
    .set OFF_STOP, 79
    .set OFF_HEADING, 92
    .set OFF_IVAL, 114
    .set OFF_HDIR, 118
    .set OFF_HRATE, 116
    .set OFF_PUB_SEQ, 120
    .set OFF_PUB, 122
    .set PUB_SIZE, 28
    .set OFF_STOP_FN, 178
    .set OFF_STOP_CTX, 180
    .set OFF_M_Q16, 200
    .set OFF_M_Q11, 204
    .set OFF_N0, 206
    .set OFF_TAB_END, 208
    .set OFF_TAB_E, 214
    .set OFF_TAB_RHO, 342
    .set OFF_CLOSINGS, 406

    .set RECIP_LO, 33

/* Sign extension of the word in \src into \dst: 0 or 0xffff. */
    .macro SEXT src, dst
    mov     \src, \dst
    rla     \dst
    subc    \dst, \dst
    inv     \dst
    .endm

/*
 * deficit: R13:R12 = me (>= n0), R10 = g -> R15:R14 = E(me), pulses Q16. Table below
 * tab_end (sets rho_p, clears rho_due); beyond, x = M / me from the reciprocal table (Q16),
 * g(x) interpolated (Q17), E = M g (and x_p, g_p, rho_due = 1). Clobbers R11..R15.
 */
    .section .text.gnav_deficit_asm,"ax",@progbits
    .type gnav_deficit_asm,@function
gnav_deficit_asm:
    tst     r13
    jnz     .Lbig
    cmp     OFF_TAB_END(r10), r12
    jhs     .Lbig
    sub     OFF_N0(r10), r12        ; i
    rla     r12                     ; 2 i
    mov     r10, r11
    add     r12, r11
    mov     OFF_TAB_RHO(r11), OFF_RHO_P(r10)
    clr.b   OFF_RHO_DUE(r10)
    add     r12, r11                ; g + 4 i
    mov     OFF_TAB_E(r11), r14
    mov     OFF_TAB_E+2(r11), r15
    ret
.Lbig:
    /* the reciprocal's index (R14) and the rounding/shift of the product, by range */
    tst     r13
    jnz     .Lt2
    cmp     #1024, r12
    jhs     .Lt1
    mov     r12, r14                ; tier 0: me itself
    mov     #0, r11                 ; t = 0
    jmp     .Lrecip
.Lt1:
    cmp     #16384, r12
    jhs     .Lt2
    mov     r12, r14                ; tier 1: (me + 8) >> 4 (me < 2^14: no carry out)
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
    mov     r12, r14                ; tier 2: (me + 128) >> 8
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
    mov     r12, r14                ; tier 3: (me + 2048) >> 12
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
    cmp     #1024, r14
    jlo     .Lrecip
    mov     #1023, r14
.Lrecip:
    sub     #RECIP_LO, r14
    rla     r14
    push    r2
    dint
    mov     gnav_recip(r14), r14    ; (not the multiplier right after DINT)
    mov     OFF_M_Q11(r10), &MPY
    mov     r14, &OP2
    mov     &RESLO, r12
    mov     &RESHI, r13
    pop     r2
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
    mov     r12, OFF_X_P(r10)
    mov     r12, r14
    swpb    r14
    and     #0xff, r14              ; i
    rla     r14
    mov     gnav_g(r14), r15        ; G[i]
    mov     gnav_g+2(r14), r13
    sub     r15, r13                ; G[i+1] - G[i] (>= 0)
    and     #0xff, r12              ; f
    push    r2
    dint
    mov     r13, r14                ; (not the multiplier right after DINT)
    mov     r14, &MPY
    mov     r12, &OP2
    mov     &RESLO, r12             ; (diff f + 128) >> 8: diff < 2^9, f < 2^8
    mov     &RESHI, r13
    pop     r2
    add     #128, r12
    adc     r13
    swpb    r12
    and     #0xff, r12
    swpb    r13                     ; r13 < 2: its low byte lands in the high byte
    bis     r13, r12
    add     r12, r15                ; g (Q17)
    mov     r15, OFF_G_P(r10)
    mov.b   #1, OFF_RHO_DUE(r10)
    /* E = (M_hi g + (M_lo g >> 16) + 1) >> 1, M = m_q16 */
    push    r2
    dint
    mov     r15, r11                ; (not the multiplier right after DINT)
    mov     OFF_M_Q16+2(r10), &MPY
    mov     r11, &OP2
    mov     &RESLO, r14
    mov     &RESHI, r15
    mov     OFF_M_Q16(r10), &MPY
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
    .size gnav_deficit_asm, .-gnav_deficit_asm

/* void gnav_close_arc(gnav_t *g): see gnav.c. */
    .section .text.gnav_close_arc,"ax",@progbits
    .global gnav_close_arc
    .type gnav_close_arc,@function
gnav_close_arc:
    push    r10
    push    r9
    push    r8
    push    r7
    push    r6
    push    r5
    push    r4
    mov     r12, r10
    /* m = |n| in R9:R8, R7 = 1 when n < 0 */
    mov     OFF_N_LO(r10), r8
    mov     OFF_N_HI(r10), r9
    clr     r7
    tst     r9
    jge     1f
    inv     r8
    inv     r9
    add     #1, r8
    adc     r9
    mov     #1, r7
1:  /* k = |h_first - h_p| in R6 */
    mov     OFF_H_FIRST(r10), r6
    sub     OFF_H_P(r10), r6
    tst     r6                      ; the sign of the wrapped difference
    jge     2f
    inv     r6
    add     #1, r6
2:  /* nc = min(m, n_p) */
    mov     OFF_N_P(r10), r13
    tst     r9
    jnz     3f
    cmp     r13, r8
    jhs     3f
    mov     r8, r13
3:  /* dprov = 2 nc rho_p (Q16) in R5:R4 */
    push    r2
    dint
    mov     OFF_RHO_P(r10), r14     ; (not the multiplier right after DINT)
    mov     r13, &MPY
    mov     r14, &OP2
    mov     &RESLO, r4
    mov     &RESHI, r5
    pop     r2
    rla     r4
    rlc     r5
    /* n_p of the next interval in R11: min(m, 32000) */
    mov     #32000, r11
    tst     r9
    jnz     31f
    cmp     r11, r8
    jhs     31f
    mov     r8, r11
31: clr     r14                     ; e = 0 in R15:R14
    clr     r15
    tst     r6
    jnz     4f
    /* k = 0: the turn reversed inside one cell; the curvature went on over at most 2 n_p
     * pulses: e = 2 min(m, 2 n_p) rho_p; kept when m <= 2 n_p, else straightened */
    mov     OFF_N_P(r10), r13
    rla     r13                     ; n2 = 2 n_p (< 2^16)
    mov     r13, r12
    tst     r9
    jnz     32f
    cmp     r13, r8
    jhs     32f
    mov     r8, r12                 ; min(m, n2)
32: push    r2
    dint
    mov     OFF_RHO_P(r10), r15     ; (not the multiplier right after DINT)
    mov     r12, &MPY
    mov     r15, &OP2
    mov     &RESLO, r14
    mov     &RESHI, r15
    pop     r2
    rla     r14
    rlc     r15
    tst     r9                      ; m <= n2: the curvature goes on
    jnz     33f
    cmp     r8, r13                 ; n2 - m
    jlo     33f
    mov     OFF_N_P(r10), r11
    jmp     34f
33: clr     r11
    clr     OFF_RHO_P(r10)
34: clr.b   OFF_RHO_DUE(r10)
    add     #1, OFF_CLOSINGS+8(r10)
    adc     OFF_CLOSINGS+10(r10)
    jmp     .Lapply
4:  /* me = m, or 2 m for the first edge after init (k = 1), saturating at 2^31 */
    mov     r8, r12
    mov     r9, r13
    cmp     #1, r6
    jne     5f
    cmp     #0x4000, r13
    jlo     41f
    clr     r12
    mov     #0x8000, r13
    jmp     5f
41: rla     r12
    rlc     r13
5:  tst     r13
    jnz     .Ldef
    cmp     OFF_N0(r10), r12
    jhs     .Ldef
    /* situation 1: too few pulses for the heading change, back to P */
    mov     OFF_XP(r10), OFF_X(r10)
    mov     OFF_XP+2(r10), OFF_X+2(r10)
    mov     OFF_XP+4(r10), OFF_X+4(r10)
    mov     OFF_XP+6(r10), OFF_X+6(r10)
    mov     OFF_YP(r10), OFF_Y(r10)
    mov     OFF_YP+2(r10), OFF_Y+2(r10)
    mov     OFF_YP+4(r10), OFF_Y+4(r10)
    mov     OFF_YP+6(r10), OFF_Y+6(r10)
    mov     #32767, OFF_RHO_P(r10)
    clr.b   OFF_RHO_DUE(r10)
    add     #1, OFF_CLOSINGS(r10)
    adc     OFF_CLOSINGS+2(r10)
    jmp     .Lnp
.Ldef:
    push    r11
    call    #gnav_deficit_asm
    pop     r11
    cmp     #1, r6
    jne     6f
    add     #1, r14                 ; half a step: (E + 1) >> 1
    adc     r15
    rra     r15
    rrc     r14
6:  add     #1, OFF_CLOSINGS+4(r10)
    adc     OFF_CLOSINGS+6(r10)
.Lapply:
    /* delta = +-(dprov - e) + resid in R5:R4 */
    sub     r14, r4
    subc    r15, r5
    tst     r7
    jz      7f
    inv     r4
    inv     r5
    add     #1, r4
    adc     r5
7:  add     OFF_RESID(r10), r4
    addc    OFF_RESID+2(r10), r5
    /* d10 = (delta + 32) >> 6, clamped to +-32767, in R12 */
    mov     r4, r12
    mov     r5, r13
    add     #32, r12
    adc     r13
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
    rra     r13
    rrc     r12
    tst     r13
    jn      71f
    jnz     72f
    cmp     #0x8000, r12
    jlo     73f
72: mov     #32767, r12
    jmp     73f
71: cmp     #-1, r13
    jne     74f
    cmp     #0x8001, r12
    jhs     73f
74: mov     #-32767, r12
73: /* resid = delta - 64 d10 */
    mov     r12, r14
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
    mov     r4, OFF_RESID(r10)
    mov     r5, OFF_RESID+2(r10)
    /* x += d10 d15_c, y += d10 d15_s (Q10 x Q15 = Q25) */
    push    r2
    dint
    mov     OFF_D15_C(r10), r14     ; (not the multiplier right after DINT)
    mov     r12, &MPYS
    mov     r14, &OP2
    mov     &RESLO, r14
    mov     &RESHI, r15
    mov     r12, &MPYS
    mov     OFF_D15_S(r10), &OP2
    mov     &RESLO, r4
    mov     &RESHI, r5
    pop     r2
    SEXT    r15, r13
    add     r14, OFF_X(r10)
    addc    r15, OFF_X+2(r10)
    addc    r13, OFF_X+4(r10)
    addc    r13, OFF_X+6(r10)
    SEXT    r5, r13
    add     r4, OFF_Y(r10)
    addc    r5, OFF_Y+2(r10)
    addc    r13, OFF_Y+4(r10)
    addc    r13, OFF_Y+6(r10)
    /* P = the closed point */
    mov     OFF_X(r10), OFF_XP(r10)
    mov     OFF_X+2(r10), OFF_XP+2(r10)
    mov     OFF_X+4(r10), OFF_XP+4(r10)
    mov     OFF_X+6(r10), OFF_XP+6(r10)
    mov     OFF_Y(r10), OFF_YP(r10)
    mov     OFF_Y+2(r10), OFF_YP+2(r10)
    mov     OFF_Y+4(r10), OFF_YP+4(r10)
    mov     OFF_Y+6(r10), OFF_YP+6(r10)
.Lnp:
    mov     r11, OFF_N_P(r10)
    /* more edges inside this pulse: zero-length intervals */
    mov     OFF_H_LAST(r10), r13
    cmp     OFF_H_FIRST(r10), r13
    jeq     9f
    clr     OFF_N_P(r10)
    clr.b   OFF_RHO_DUE(r10)
    add     #1, OFF_CLOSINGS+12(r10)
    adc     OFF_CLOSINGS+14(r10)
9:  /* the next interval */
    mov     r13, OFF_H_P(r10)
    clr     OFF_N_LO(r10)
    clr     OFF_N_HI(r10)
    clr     OFF_NQ(r10)
    mov     OFF_CELL(r10), OFF_CELL_INT(r10)
    mov     OFF_NXT_C(r10), OFF_INC10(r10)
    mov     OFF_NXT_C+2(r10), OFF_INC10+2(r10)
    mov     OFF_NXT_S(r10), OFF_INC11(r10)
    mov     OFF_NXT_S+2(r10), OFF_INC11+2(r10)
    mov     OFF_N15_C(r10), OFF_D15_C(r10)
    mov     OFF_N15_S(r10), OFF_D15_S(r10)
    clr.b   OFF_PENDING(r10)
    mov.b   #1, OFF_DC_DUE(r10)
    add     #1, OFF_VERSION(r10)
    pop     r4
    pop     r5
    pop     r6
    pop     r7
    pop     r8
    pop     r9
    pop     r10
    ret
    .size gnav_close_arc, .-gnav_close_arc

/*
 * void gnav_on_delta_l(void *g): one odometer pulse. The step (curved for the first n_p
 * pulses away from P), the closing when a gyro edge came, the stop countdown, and the
 * published pose (the free slot filled, then the sequence bumped with one store).
 */
    .section .text.gnav_on_delta_l,"ax",@progbits
    .global gnav_on_delta_l
    .type gnav_on_delta_l,@function
gnav_on_delta_l:
    push    r10
    mov     r12, r10
    tst.b   OFF_DC_DUE(r10)
    jz      1f
    tst.b   OFF_PENDING(r10)        ; closing at the interval's first pulse: no curved part
    jz      0f
    clr     OFF_N_P(r10)
    jmp     1f
0:  call    #gnav_finish_interval   ; R12 = g
1:  mov     OFF_NQ(r10), r12        ; q
    mov     r10, r14
    add     #32, r14                ; &inc[0]
    tst.b   OFF_REVERSE(r10)
    jnz     .Lback
    /* forwards: m = q >= 0 ? q : ~q; q += 1 (saturating); n += 1; x, y += inc[m >= n_p] */
    mov     r12, r13
    tst     r12
    jge     2f
    inv     r13
2:  cmp     #32767, r12
    jeq     3f
    add     #1, OFF_NQ(r10)
3:  add     #1, OFF_N_LO(r10)
    adc     OFF_N_HI(r10)
    cmp     OFF_N_P(r10), r13
    jlo     4f
    add     #8, r14                 ; &inc[1]
4:  mov     @r14+, r12
    mov     @r14+, r13
    SEXT    r13, r15
    add     r12, OFF_X(r10)
    addc    r13, OFF_X+2(r10)
    addc    r15, OFF_X+4(r10)
    addc    r15, OFF_X+6(r10)
    mov     @r14+, r12
    mov     @r14, r13
    SEXT    r13, r15
    add     r12, OFF_Y(r10)
    addc    r13, OFF_Y+2(r10)
    addc    r15, OFF_Y+4(r10)
    addc    r15, OFF_Y+6(r10)
    jmp     .Lpending
.Lback:
    /* backwards: m = q > 0 ? q - 1 : -q; q -= 1 (saturating); n -= 1; x, y -= inc[m >= n_p] */
    mov     r12, r13
    tst     r12
    jge     5f
    inv     r13                     ; q < 0: -q = ~q + 1
    add     #1, r13
    jmp     6f
5:  jz      6f                      ; q = 0: m = 0
    add     #-1, r13                ; q > 0: q - 1
6:  cmp     #-32767, r12
    jeq     7f
    sub     #1, OFF_NQ(r10)
7:  sub     #1, OFF_N_LO(r10)
    subc    #0, OFF_N_HI(r10)
    cmp     OFF_N_P(r10), r13
    jlo     8f
    add     #8, r14
8:  mov     @r14+, r12
    mov     @r14+, r13
    SEXT    r13, r15
    sub     r12, OFF_X(r10)
    subc    r13, OFF_X+2(r10)
    subc    r15, OFF_X+4(r10)
    subc    r15, OFF_X+6(r10)
    mov     @r14+, r12
    mov     @r14, r13
    SEXT    r13, r15
    sub     r12, OFF_Y(r10)
    subc    r13, OFF_Y+2(r10)
    subc    r15, OFF_Y+4(r10)
    subc    r15, OFF_Y+6(r10)
.Lpending:
    tst.b   OFF_PENDING(r10)
    jz      9f
    mov     r10, r12
    call    #gnav_close_arc
9:  /* the stop countdown: 16 bits per pulse, the high word when they run out */
    sub     #1, OFF_STOP_LO(r10)
    jnz     .Lpublish
    tst.b   OFF_STOP_ARMED(r10)
    jz      .Lpublish
    tst     OFF_STOP_HI(r10)
    jz      10f
    sub     #1, OFF_STOP_HI(r10)
    jmp     .Lpublish
10: clr.b   OFF_STOP_ARMED(r10)
    mov.b   #1, OFF_STOP(r10)
    mov     OFF_STOP_FN(r10), r13
    tst     r13
    jz      .Lpublish
    mov     OFF_STOP_CTX(r10), r12
    call    r13
.Lpublish:
    mov     OFF_PUB_SEQ(r10), r12
    mov     r10, r13
    add     #OFF_PUB, r13           ; pub[0] when seq is odd
    bit     #1, r12
    jnz     11f
    add     #PUB_SIZE, r13          ; pub[1] when seq is even
11: mov     OFF_X(r10), 0(r13)
    mov     OFF_X+2(r10), 2(r13)
    mov     OFF_X+4(r10), 4(r13)
    mov     OFF_X+6(r10), 6(r13)
    mov     OFF_Y(r10), 8(r13)
    mov     OFF_Y+2(r10), 10(r13)
    mov     OFF_Y+4(r10), 12(r13)
    mov     OFF_Y+6(r10), 14(r13)
    mov     OFF_HEADING(r10), 16(r13)
    mov     OFF_HEADING+2(r10), 18(r13)
    mov     OFF_NQ(r10), 20(r13)    ; k: no edge is pending after a pulse
    mov     OFF_HRATE(r10), 22(r13) ; rate
    mov     OFF_IVAL(r10), 24(r13)  ; the interval's number
    mov.b   OFF_HDIR(r10), 26(r13)  ; its entry edge
    add     #1, r12
    mov     r12, OFF_PUB_SEQ(r10)   ; one store: the slot is published
    pop     r10
    ret
    .size gnav_on_delta_l, .-gnav_on_delta_l
