/*
 * optical_tri.S - MSP430 version of optical_tri_core (fastmath.c holds the portable C that
 * defines the result; this performs the very same integer steps, and tests/vectors/
 * optical_vectors.c checks it bit for bit on both worlds). Conventions as optical_fast.S.
 *
 * Products: prodr gives a b - (a mod 2^16)(b mod 2^16) (three 16 x 16 products, the low
 * word of the result 0), prodx the exact a b; both signed, from the unsigned products of the
 * two's-complement words corrected modulo 2^64. 64-bit values live in R11:R10:R9:R8 (or,
 * with the low word 0, in three words). Interrupts are held off around each pair of
 * products (at most about 110 cycles).
 */
    .set MPY,   0x0130
    .set OP2,   0x0138
    .set RESLO, 0x013a
    .set RESHI, 0x013c

/* frame (R4 = optical_work.u.sv.frame: static, the stack stays small; not reentrant) */
    .set W_FRAME, 350
    .set F_N,    0          ; n[12], 48 bytes
    .set F_PA,   48         ; group: the four products, 3 words each
    .set F_PB,   54
    .set F_PC,   60
    .set F_PD,   66
    .set F_GA,   72         ; group: a, b, s, c
    .set F_GB,   76
    .set F_GS,   80
    .set F_GC,   84
    .set F_SX,   48         ; pairs (after the groups): sums x, y (3 words each)
    .set F_SY,   54
    .set F_WX,   60         ; W~
    .set F_WY,   64
    .set F_X,    68         ; cross / 2^30
    .set F_T,    72         ; the quotient, signed
    .set F_SA,   76         ; sX, sY
    .set F_SB,   80
    .set F_E,    84         ; the exponent e
    .set F_V,    88         ; v, sc, out
    .set F_SC,   90
    .set F_OUT,  92
    .set F_SIZE, 94

/*
 * R13:R12 = a, R15:R14 = b -> R11:R10:R9:R8 = a b (prodx) or a b - al bl (prodr, R8 = 0).
 * Interrupts must be off.
 */
    .section .text.optical_prod,"ax",@progbits
prodx:
    mov     r12, &MPY               ; al bl
    mov     r14, &OP2
    mov     &RESLO, r8
    mov     &RESHI, r9
    mov     r15, &OP2               ; al bh
    add     &RESLO, r9
    mov     &RESHI, r10
    adc     r10
    jmp     1f
prodr:
    clr     r8
    mov     r12, &MPY               ; al bh
    mov     r15, &OP2
    mov     &RESLO, r9
    mov     &RESHI, r10
1:  clr     r11
    mov     r13, &MPY               ; ah bl
    mov     r14, &OP2
    add     &RESLO, r9
    addc    &RESHI, r10
    adc     r11
    mov     r15, &OP2               ; ah bh
    add     &RESLO, r10
    addc    &RESHI, r11
    tst     r13                     ; a < 0: - b 2^32
    jge     2f
    sub     r14, r10
    subc    r15, r11
2:  tst     r15                     ; b < 0: - a 2^32
    jge     3f
    sub     r12, r10
    subc    r13, r11
3:  ret

/* R11:R10:R9 (bits 16..63) -> R13:R12 = floor((v + 2^29) / 2^30). */
rnd30:
    add     #0x2000, r9
    adc     r10
    adc     r11
    rla     r9
    rlc     r10
    rlc     r11
    rla     r9
    rlc     r10
    rlc     r11
    mov     r10, r12
    mov     r11, r13
    ret

/*
 * Load a 32-bit value: R12 = pointer -> R13:R12. (ld2: R14 = pointer -> R15:R14.)
 */
ld1:
    mov     2(r12), r13
    mov     @r12, r12
    ret
ld2:
    mov     2(r14), r15
    mov     @r14, r14
    ret

/*
 * dot: R11:R10:R9 = prodr(*R5, *R6) -/+ prodr(*R7, *R8') ... see dotsub below.
 * dotsub: R13:R12 = rnd30(prodr(*R5, *R6) - prodr(*R7, *R15)); dotadd: + instead.
 * R5, R6, R7 and the pointer in R15 preserved. Clobbers R8..R15 (R12, R13 the result).
 */
dotsub:
    push    r15
    push    r2
    dint
    mov     r7, r12
    call    #ld1
    mov     r15, r14
    call    #ld2
    call    #prodr
    push    r9                      ; the second product
    push    r10
    push    r11
    mov     r5, r12
    call    #ld1
    mov     r6, r14
    call    #ld2
    call    #prodr
    sub     4(r1), r9
    subc    2(r1), r10
    subc    0(r1), r11
    jmp     1f
dotadd:
    push    r15
    push    r2
    dint
    mov     r7, r12
    call    #ld1
    mov     r15, r14
    call    #ld2
    call    #prodr
    push    r9
    push    r10
    push    r11
    mov     r5, r12
    call    #ld1
    mov     r6, r14
    call    #ld2
    call    #prodr
    add     4(r1), r9
    addc    2(r1), r10
    addc    0(r1), r11
1:  add     #6, r1
    pop     r2
    pop     r15
    jmp     rnd30

/*
 * Group (group() in fastmath.c): a, b, s, c at F_GA.. -> n0 at @R14, n1 at @R15:
 * n0 = (as - bc, bs + ac), n1 = (-as - bc, ac - bs).
 */
group:
    push    r14
    push    r15
    push    r2
    dint
    mov     F_GA(r4), r12           ; A = a s
    mov     F_GA+2(r4), r13
    mov     F_GS(r4), r14
    mov     F_GS+2(r4), r15
    call    #prodr
    mov     r9, F_PA(r4)
    mov     r10, F_PA+2(r4)
    mov     r11, F_PA+4(r4)
    mov     F_GC(r4), r14           ; D = a c
    mov     F_GC+2(r4), r15
    call    #prodr
    mov     r9, F_PD(r4)
    mov     r10, F_PD+2(r4)
    mov     r11, F_PD+4(r4)
    pop     r2
    push    r2
    dint
    mov     F_GB(r4), r12           ; B = b c
    mov     F_GB+2(r4), r13
    call    #prodr
    mov     r9, F_PB(r4)
    mov     r10, F_PB+2(r4)
    mov     r11, F_PB+4(r4)
    mov     F_GS(r4), r14           ; C = b s
    mov     F_GS+2(r4), r15
    call    #prodr
    pop     r2
    mov     r9, F_PC(r4)
    mov     r10, F_PC+2(r4)
    mov     r11, F_PC+4(r4)
    add     F_PD(r4), r9            ; n0.y = C + D
    addc    F_PD+2(r4), r10
    addc    F_PD+4(r4), r11
    call    #rnd30
    mov     2(r1), r14
    mov     r12, 4(r14)
    mov     r13, 6(r14)
    mov     F_PD(r4), r9            ; n1.y = D - C
    mov     F_PD+2(r4), r10
    mov     F_PD+4(r4), r11
    sub     F_PC(r4), r9
    subc    F_PC+2(r4), r10
    subc    F_PC+4(r4), r11
    call    #rnd30
    mov     @r1, r14
    mov     r12, 4(r14)
    mov     r13, 6(r14)
    mov     F_PA(r4), r9            ; n0.x = A - B
    mov     F_PA+2(r4), r10
    mov     F_PA+4(r4), r11
    sub     F_PB(r4), r9
    subc    F_PB+2(r4), r10
    subc    F_PB+4(r4), r11
    call    #rnd30
    mov     2(r1), r14
    mov     r12, 0(r14)
    mov     r13, 2(r14)
    clr     r9                      ; n1.x = -A - B
    clr     r10
    clr     r11
    sub     F_PA(r4), r9
    subc    F_PA+2(r4), r10
    subc    F_PA+4(r4), r11
    sub     F_PB(r4), r9
    subc    F_PB+2(r4), r10
    subc    F_PB+4(r4), r11
    call    #rnd30
    pop     r14
    mov     r12, 0(r14)
    mov     r13, 2(r14)
    incd    r1
    ret

/* floor halving of R13:R12 */
half:
    rra     r13
    rrc     r12
    ret

/*
 * Pair (pair() in fastmath.c): R5 = nX, R6 = nY (pointers into F_N), sX, sY at F_SA, F_SB ->
 * R13:R12 = the point's x, R15:R14 its y (relative to the common beacon), carry clear; carry
 * set when the circles (nearly) coincide.
 */
pair:
    push    r5
    push    r6
    ; W = sX nY - sY nX (componentwise): dotsub with (nY, sX) - (nX, sY)
    mov     r5, r7                  ; second product: *R7 = nX0, *R15 = sY
    mov     r6, r5                  ; first: *R5 = nY0, *R6 = sX
    mov     r4, r6
    add     #F_SA, r6
    mov     r4, r15
    add     #F_SB, r15
    call    #dotsub
    mov     r12, F_WX(r4)
    mov     r13, F_WX+2(r4)
    add     #4, r5                  ; nY1, nX1
    add     #4, r7
    call    #dotsub
    mov     r12, F_WY(r4)
    mov     r13, F_WY+2(r4)
    ; x = nY0 nX1 - nY1 nX0: R5 = nY1 now
    sub     #4, r5                  ; nY0
    mov     r7, r6                  ; nX1
    mov     r5, r7
    add     #4, r7                  ; nY1
    mov     r6, r15
    sub     #4, r15                 ; nX0
    call    #dotsub
    mov     r12, F_X(r4)
    mov     r13, F_X+2(r4)
    ; m = |wx| | |wy|; normalise to [2^28, 2^29)
    mov     #2, F_E(r4)
    mov     F_WX(r4), r12
    mov     F_WX+2(r4), r13
    mov     F_WY(r4), r14
    mov     F_WY+2(r4), r15
    mov     r13, r8                 ; |wx|
    mov     r12, r9
    tst     r8
    jge     1f
    inv     r8
    inv     r9
    add     #1, r9
    adc     r8
1:  mov     r15, r10                ; |wy|
    mov     r14, r11
    tst     r10
    jge     2f
    inv     r10
    inv     r11
    add     #1, r11
    adc     r10
2:  bis     r10, r8                 ; m = R8:R9
    bis     r11, r9
    tst     r8
    jnz     3f
    tst     r9
    jnz     3f
    setc                            ; W = 0
    jmp     pair_out
3:  cmp     #0x1000, r8             ; m < 2^28: double
    jhs     4f
    rla     r9
    rlc     r8
    rla     r12
    rlc     r13
    rla     r14
    rlc     r15
    add     #1, F_E(r4)
    jmp     3b
4:  cmp     #0x2000, r8             ; m >= 2^29: halve (floor)
    jlo     5f
    rra     r8
    rrc     r9
    rra     r13
    rrc     r12
    rra     r15
    rrc     r14
    sub     #1, F_E(r4)
    jmp     4b
5:  mov     r12, F_WX(r4)
    mov     r13, F_WX+2(r4)
    mov     r14, F_WY(r4)
    mov     r15, F_WY+2(r4)
    ; d = rnd30(wx wx + wy wy)
    mov     r4, r5
    add     #F_WX, r5
    mov     r5, r6
    mov     r4, r7
    add     #F_WY, r7
    mov     r7, r15
    call    #dotadd                 ; d = R13:R12
    ; t = floor((|x| 2^28 + d / 2) / d): 31 quotient bits. R = |x| >> 3, then the bits of
    ; F = (|x| << 29) | ((d >> 1) << 1), from the top.
    mov     F_X(r4), r14
    mov     F_X+2(r4), r15
    tst     r15
    jge     6f
    inv     r14
    inv     r15
    add     #1, r14
    adc     r15
6:  mov     r15, r11                ; F_hi = (|x| << 13) | (d >> 17 ...): build F in R9:R8
    mov     r14, r10
    mov     r12, r8                 ; (d >> 1) << 1 = d & ~1
    bic     #1, r8
    mov     r13, r9
    and     #0x1fff, r9             ; d < 2^29: bits 16..28
    mov     r14, r7                 ; |x| bits 2..0 -> F bits 31..29
    swpb    r7
    rla     r7
    rla     r7
    rla     r7
    rla     r7
    rla     r7
    and     #0xe000, r7
    bis     r7, r9
    clrc                            ; R = |x| >> 3
    rrc     r11
    rrc     r10
    rra     r11
    rrc     r10
    rra     r11
    rrc     r10
    mov     #31, r7
7:  rla     r8                      ; next dividend bit into R
    rlc     r9
    rlc     r10
    rlc     r11
    sub     r12, r10                ; R -= d
    subc    r13, r11
    jnc     8f
    bis     #1, r8                  ; quotient bit (F's vacated bit 0)
    sub     #1, r7
    jnz     7b
    jmp     9f
8:  add     r12, r10                ; borrow: restore
    addc    r13, r11
    sub     #1, r7
    jnz     7b
9:  tst     F_X+2(r4)               ; t with the sign of x
    jge     10f
    inv     r8
    inv     r9
    add     #1, r8
    adc     r9
10: mov     r8, F_T(r4)
    mov     r9, F_T+2(r4)
    ; px = rnd30(t (-wy)), py = rnd30(t wx): exact products
    push    r2
    dint
    mov     F_WY(r4), r14
    mov     F_WY+2(r4), r15
    inv     r14
    inv     r15
    add     #1, r14
    adc     r15
    mov     r8, r12
    mov     r9, r13
    call    #prodx
    call    #rnd30
    mov     r12, r5
    mov     r13, r6
    mov     F_T(r4), r12
    mov     F_T+2(r4), r13
    mov     F_WX(r4), r14
    mov     F_WX+2(r4), r15
    call    #prodx
    pop     r2
    call    #rnd30                  ; py = R13:R12, px = R6:R5
    mov     r12, r14
    mov     r13, r15
    mov     r5, r12
    mov     r6, r13
11: tst     F_E(r4)                 ; P 2^e, refused beyond 2^30
    jz      13f
    mov     r12, r9                 ; |px|
    mov     r13, r8
    tst     r8
    jge     12f
    inv     r8
    inv     r9
    add     #1, r9
    adc     r8
12: mov     r14, r11                ; |py|
    mov     r15, r10
    tst     r10
    jge     14f
    inv     r10
    inv     r11
    add     #1, r11
    adc     r10
14: bis     r10, r8
    cmp     #0x2000, r8
    jhs     pair_out                ; carry set: coincide
    rla     r12
    rlc     r13
    rla     r14
    rlc     r15
    sub     #1, F_E(r4)
    jmp     11b
13: clrc
pair_out:
    pop     r6
    pop     r5
    ret

/* Add R13:R12 (sign-extended) to the 48-bit sum at @R10. Clobbers R8. */
add48:
    clr     r8
    tst     r13
    jge     1f
    mov     #-1, r8
1:  add     r12, 0(r10)
    addc    r13, 2(r10)
    addc    r8, 4(r10)
    ret

/* Copy *R12 (32 bits) to @R13 (R14 = 1: negated). */
copy32:
    mov     @r12, r15
    mov     2(r12), r12
    tst     r14
    jz      1f
    inv     r15
    inv     r12
    add     #1, r15
    adc     r12
1:  mov     r15, 0(r13)
    mov     r12, 2(r13)
    ret

/* The group's arguments: a = *R5, b = *R6 (or b - a, c, d as below), s = *R7, c = *R9
 * (negated when R14 = 1) -> F_GA..F_GC; then the group into @R10 (n0), @R11 (n1). */
group_at:
    mov     r5, r12
    mov     r4, r13
    add     #F_GA, r13
    push    r14
    clr     r14
    call    #copy32
    mov     r6, r12
    mov     r4, r13
    add     #F_GB, r13
    call    #copy32
    mov     r7, r12
    mov     r4, r13
    add     #F_GS, r13
    call    #copy32
    pop     r14
    mov     r9, r12
    mov     r4, r13
    add     #F_GC, r13
    call    #copy32
    mov     r10, r14
    mov     r11, r15
    jmp     group

/* A pair: sX = *R7, sY = *R9, nX at F_N + R10, nY at F_N + R11; the point added to the sums.
 * Carry set when the circles coincide. */
pair_at:
    mov     r7, r12
    mov     r4, r13
    add     #F_SA, r13
    clr     r14
    call    #copy32
    mov     r9, r12
    mov     r4, r13
    add     #F_SB, r13
    call    #copy32
    mov     r4, r5
    add     #F_N, r5
    add     r10, r5
    mov     r4, r6
    add     #F_N, r6
    add     r11, r6
    call    #pair
    jc      1f
    mov     r4, r10
    add     #F_SY, r10
    push    r12
    push    r13
    mov     r14, r12
    mov     r15, r13
    call    #add48
    pop     r13
    pop     r12
    sub     #F_SY-F_SX, r10
    call    #add48
    clrc
1:  ret

/* The mean of one coordinate: the 48-bit sum at @R10 -> R13:R12 = 2 rnd30(prodr(floor(sum
 * / 2), 2^30 / 3)). */
mean:
    mov     4(r10), r11
    mov     2(r10), r13
    mov     @r10, r12
    rra     r11
    rrc     r13
    rrc     r12
    mov     #0x5555, r14            ; 357913941 = 0x15555555
    mov     #0x1555, r15
    push    r2
    dint
    call    #prodr
    pop     r2
    call    #rnd30
    rla     r12
    rlc     r13
    ret

/*
 * bool optical_tri_core(const int32_t v[4], const int32_t sc[6], int32_t out[2]):
 * R12 = v, R13 = sc, R14 = out -> R12 = 1, or 0 when a pair of circles coincides.
 */
    .section .text.optical_tri_core,"ax",@progbits
    .global optical_tri_core
    .type optical_tri_core,@function
optical_tri_core:
    push    r10
    push    r9
    push    r8
    push    r7
    push    r6
    push    r5
    push    r4
    mov     #optical_work+W_FRAME, r4
    mov     r12, F_V(r4)
    mov     r13, F_SC(r4)
    mov     r14, F_OUT(r4)
    ; A: (v0, v1, s1, -c1) -> n[0], n[4]
    mov     r12, r5
    mov     r12, r6
    add     #4, r6
    mov     r13, r7
    mov     r13, r9
    add     #4, r9
    mov     #1, r14
    mov     r4, r10
    add     #F_N, r10
    mov     r10, r11
    add     #16, r11
    call    #group_at
    ; B: (v2, v3, s2, c2) -> n[2], n[8]
    mov     F_V(r4), r5
    add     #8, r5
    mov     r5, r6
    add     #4, r6
    mov     F_SC(r4), r7
    add     #8, r7
    mov     r7, r9
    add     #4, r9
    clr     r14
    mov     r4, r10
    add     #F_N+8, r10
    mov     r4, r11
    add     #F_N+32, r11
    call    #group_at
    ; C: (v2 - v0, v3 - v1, s3, c3) -> n[6], n[10]; q built in F_SX.. (free until the sums)
    mov     F_V(r4), r12
    mov     8(r12), r13
    mov     10(r12), r14
    sub     @r12, r13
    subc    2(r12), r14
    mov     r13, F_SX(r4)
    mov     r14, F_SX+2(r4)
    mov     12(r12), r13
    mov     14(r12), r14
    sub     4(r12), r13
    subc    6(r12), r14
    mov     r13, F_SX+4(r4)
    mov     r14, F_SX+6(r4)
    mov     r4, r5
    add     #F_SX, r5
    mov     r5, r6
    add     #4, r6
    mov     F_SC(r4), r7
    add     #16, r7
    mov     r7, r9
    add     #4, r9
    clr     r14
    mov     r4, r10
    add     #F_N+24, r10
    mov     r4, r11
    add     #F_N+40, r11
    call    #group_at
    ; the sums start with the origins of pairs AC (B1) and BC (B3): v0 + v2, v1 + v3
    clr     F_SX(r4)
    clr     F_SX+2(r4)
    clr     F_SX+4(r4)
    clr     F_SY(r4)
    clr     F_SY+2(r4)
    clr     F_SY+4(r4)
    mov     F_V(r4), r5
    mov     r4, r10
    add     #F_SX, r10
    mov     @r5, r12
    mov     2(r5), r13
    call    #add48
    mov     8(r5), r12
    mov     10(r5), r13
    call    #add48
    add     #F_SY-F_SX, r10
    mov     4(r5), r12
    mov     6(r5), r13
    call    #add48
    mov     12(r5), r12
    mov     14(r5), r13
    call    #add48
    ; AB at B2: n[0], n[2], s1, s2
    mov     F_SC(r4), r7
    mov     r7, r9
    add     #8, r9
    clr     r10
    mov     #8, r11
    call    #pair_at
    jc      fail
    ; AC at B1: n[4], n[6], s1, s3
    mov     F_SC(r4), r7
    mov     r7, r9
    add     #16, r9
    mov     #16, r10
    mov     #24, r11
    call    #pair_at
    jc      fail
    ; BC at B3: n[8], n[10], s2, s3
    mov     F_SC(r4), r7
    add     #8, r7
    mov     r7, r9
    add     #8, r9
    mov     #32, r10
    mov     #40, r11
    call    #pair_at
    jc      fail
    mov     r4, r10
    add     #F_SX, r10
    call    #mean
    mov     F_OUT(r4), r5
    mov     r12, 0(r5)
    mov     r13, 2(r5)
    mov     r4, r10
    add     #F_SY, r10
    call    #mean
    mov     r12, 4(r5)
    mov     r13, 6(r5)
    mov     #1, r12
    jmp     out
fail:
    clr     r12
out:
    pop     r4
    pop     r5
    pop     r6
    pop     r7
    pop     r8
    pop     r9
    pop     r10
    ret

/*
 * Cut the six 32-bit values at @R12 into the 16-bit array @R13 by the common floor shift s
 * that brings them all below 2^14 (to15() in fastmath.c) -> R12 = s. Clobbers R8..R11, R14,
 * R15.
 */
    .section .text.optical_quality_parts,"ax",@progbits
to15:
    clr     r8                      ; m = OR of the magnitudes' high words, R9 the low words
    clr     r9
    mov     #6, r11
    mov     r12, r10
1:  mov     @r10, r14
    mov     2(r10), r15
    add     #4, r10
    tst     r15
    jge     2f
    inv     r14
    inv     r15
    add     #1, r14
    adc     r15
2:  bis     r14, r9
    bis     r15, r8
    dec     r11
    jnz     1b
    clr     r11                     ; s: bit length of m - 14
3:  cmp     #0x0100, r8             ; m >= 2^24: a whole byte
    jlo     31f
    swpb    r9                      ; m >>= 8
    mov.b   r9, r9
    swpb    r8
    mov     r8, r10
    and     #0xff00, r10
    bis     r10, r9
    mov.b   r8, r8
    add     #8, r11
    jmp     3b
31: tst     r8
    jz      4f
    clrc
    rrc     r8
    rrc     r9
    inc     r11
    jmp     31b
4:  cmp     #0x4000, r9
    jlo     5f
    clrc
    rrc     r9
    inc     r11
    jmp     4b
5:  ; each value: floor(v / 2^s) as 16 bits, by the case of s chosen once
    mov     r11, r8                 ; s (the result)
    mov     #6, r10
    tst     r11
    jz      20f
    cmp     #16, r11
    jhs     30f
    mov     #1, r9                  ; 0 < s < 16: M = 2^(16 - s)
    mov     #16, r15
    sub     r11, r15
10: rla     r9
    dec     r15
    jnz     10b
11: mov     @r12+, r14              ; lo
    mov     @r12+, r15              ; hi
    push    r2
    dint
    nop
    mov     r14, &MPY               ; floor((lo M) / 2^16) + hi M, mod 2^16
    mov     r9, &OP2
    mov     &RESHI, r14
    mov     r15, &MPY
    mov     r9, &OP2
    add     &RESLO, r14
    pop     r2
    mov     r14, 0(r13)
    incd    r13
    dec     r10
    jnz     11b
    jmp     40f
20: mov     @r12, 0(r13)            ; s = 0: the low word
    add     #4, r12
    incd    r13
    dec     r10
    jnz     20b
    jmp     40f
30: sub     #16, r11                ; s >= 16: the high word >> (s - 16)
32: mov     2(r12), r14
    add     #4, r12
    mov     r11, r15
    tst     r15
    jz      34f
33: rra     r14
    dec     r15
    jnz     33b
34: mov     r14, 0(r13)
    incd    r13
    dec     r10
    jnz     32b
40: mov     r8, r12
    ret

/* R13 = pointer to (x, y) 16-bit -> R15:R14 = x^2 + y^2 (interrupts off). */
sq2:
    mov     @r13, &0x0132           ; MPYS
    mov     @r13, &OP2
    mov     2(r13), &0x0136         ; MACS
    mov     2(r13), &OP2
    add     #4, r13
    mov     &RESLO, r14
    mov     &RESHI, r15
    ret

/* R15:R14 >> 14 (< 2^29: 15 bits) -> R14. */
sh14:
    rla     r14
    rlc     r15
    rla     r14
    rlc     r15
    mov     r15, r14
    ret

/*
 * void optical_quality_parts(const int32_t v[4], const int32_t c[2], const int32_t sc[6],
 * optical_qparts_t *out): R12 = v, R13 = c, R14 = sc, R15 = out.
 * Frame: 0..23 the chords (6 x 32), 24..47 the ranges, 48..59 the chords cut (6 x 16),
 * 60..71 the ranges cut, 72..83 the squares (6 x 32: c12, c23, c31, q1, q2, q3 - reusing
 * 0..23), sc, out pointers at 84, 86.
 */
    .global optical_quality_parts
    .type optical_quality_parts,@function
optical_quality_parts:
    push    r10
    push    r9
    push    r8
    push    r7
    push    r6
    push    r5
    push    r4
    mov     #optical_work+W_FRAME, r4
    mov     r14, 84(r4)
    mov     r15, 86(r4)
    ; chords: b1, b3, b3 - b1
    mov     @r12, 0(r4)
    mov     2(r12), 2(r4)
    mov     4(r12), 4(r4)
    mov     6(r12), 6(r4)
    mov     8(r12), 8(r4)
    mov     10(r12), 10(r4)
    mov     12(r12), 12(r4)
    mov     14(r12), 14(r4)
    mov     8(r12), r8
    mov     10(r12), r9
    sub     @r12, r8
    subc    2(r12), r9
    mov     r8, 16(r4)
    mov     r9, 18(r4)
    mov     12(r12), r8
    mov     14(r12), r9
    sub     4(r12), r8
    subc    6(r12), r9
    mov     r8, 20(r4)
    mov     r9, 22(r4)
    ; ranges: b1 - c, c, b3 - c
    mov     @r12, r8
    mov     2(r12), r9
    sub     @r13, r8
    subc    2(r13), r9
    mov     r8, 24(r4)
    mov     r9, 26(r4)
    mov     4(r12), r8
    mov     6(r12), r9
    sub     4(r13), r8
    subc    6(r13), r9
    mov     r8, 28(r4)
    mov     r9, 30(r4)
    mov     @r13, 32(r4)
    mov     2(r13), 34(r4)
    mov     4(r13), 36(r4)
    mov     6(r13), 38(r4)
    mov     8(r12), r8
    mov     10(r12), r9
    sub     @r13, r8
    subc    2(r13), r9
    mov     r8, 40(r4)
    mov     r9, 42(r4)
    mov     12(r12), r8
    mov     14(r12), r9
    sub     4(r13), r8
    subc    6(r13), r9
    mov     r8, 44(r4)
    mov     r9, 46(r4)
    mov     r4, r12                 ; cut both groups
    mov     r4, r13
    add     #48, r13
    call    #to15
    mov     86(r4), r15
    mov.b   r12, 6(r15)             ; sc
    mov     r4, r12
    add     #24, r12
    mov     r4, r13
    add     #60, r13
    call    #to15
    ; the six squares into 0..23 (c12 c23 c31 q1 q2 q3)
    mov     r4, r13
    add     #48, r13
    mov     r4, r10
    mov     #6, r11
    push    r2
    dint
11: call    #sq2
    mov     r14, 0(r10)
    mov     r15, 2(r10)
    add     #4, r10
    dec     r11
    jnz     11b
    ; num2 = c12' q3' + c23' q1' + c31' q2' (the squares >> 14)
    mov     0(r4), r14
    mov     2(r4), r15
    call    #sh14
    mov     r14, &MPY
    mov     20(r4), r14
    mov     22(r4), r15
    call    #sh14
    mov     r14, &OP2
    mov     4(r4), r14
    mov     6(r4), r15
    call    #sh14
    mov     r14, &0x0134            ; MAC
    mov     12(r4), r14
    mov     14(r4), r15
    call    #sh14
    mov     r14, &OP2
    mov     8(r4), r14
    mov     10(r4), r15
    call    #sh14
    mov     r14, &0x0134
    mov     16(r4), r14
    mov     18(r4), r15
    call    #sh14
    mov     r14, &OP2
    mov     &RESLO, r12
    mov     &RESHI, r13
    pop     r2
    call    #fx_sqrt32
    mov     86(r4), r15
    mov     r12, 4(r15)             ; num
    mov     12(r4), r12             ; r1, r2, r3
    mov     14(r4), r13
    call    #fx_sqrt32
    mov     r12, r5
    mov     16(r4), r12
    mov     18(r4), r13
    call    #fx_sqrt32
    mov     r12, r6
    mov     20(r4), r12
    mov     22(r4), r13
    call    #fx_sqrt32
    ; den = r3 s1 + r1 s2 - r2 s3 (the sines' high words)
    mov     84(r4), r14
    push    r2
    dint
    mov     2(r14), r15             ; (spacer)
    mov     r12, &0x0132            ; MPYS r3 s1
    mov     r15, &OP2
    mov     r5, &0x0136             ; MACS r1 s2
    mov     10(r14), &OP2
    mov     18(r14), r15            ; MACS r2 (-s3)
    inv     r15
    inc     r15
    mov     r6, &0x0136
    mov     r15, &OP2
    mov     &RESLO, r12
    mov     &RESHI, r13
    pop     r2
    tst     r13
    jge     12f
    inv     r12
    inv     r13
    add     #1, r12
    adc     r13
12: mov     86(r4), r15
    mov     r12, 0(r15)
    mov     r13, 2(r15)
    pop     r4
    pop     r5
    pop     r6
    pop     r7
    pop     r8
    pop     r9
    pop     r10
    ret

/*
 * uint32_t optical_shl32(uint32_t v, uint8_t n): R13:R12 = v, R14 = n (< 32) -> v 2^n
 * (whole bytes first, then bit by bit).
 */
    .section .text.optical_shl32,"ax",@progbits
    .global optical_shl32
    .type optical_shl32,@function
optical_shl32:
1:  cmp.b   #8, r14
    jlo     2f
    swpb    r12                     ; (hi:lo) << 8
    mov.b   r12, r15
    and     #0xff00, r12
    swpb    r13
    and     #0xff00, r13
    bis     r15, r13
    sub.b   #8, r14
    jmp     1b
2:  tst.b   r14
    jz      3f
4:  rla     r12
    rlc     r13
    sub.b   #1, r14
    jnz     4b
3:  ret

/*
 * int32_t optical_asr32(int32_t v, uint8_t n): R13:R12 = v, R14 = n (< 32) -> floor(v / 2^n)
 * (whole bytes first, then bit by bit).
 */
    .section .text.optical_asr32,"ax",@progbits
    .global optical_asr32
    .type optical_asr32,@function
optical_asr32:
1:  cmp.b   #8, r14
    jlo     2f
    swpb    r12                     ; (hi:lo) >> 8, the sign extended
    mov.b   r12, r12
    swpb    r13
    mov     r13, r15
    and     #0xff00, r15
    bis     r15, r12
    sxt     r13
    sub.b   #8, r14
    jmp     1b
2:  tst.b   r14
    jz      3f
4:  rra     r13
    rrc     r12
    sub.b   #1, r14
    jnz     4b
3:  ret
