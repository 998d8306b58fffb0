/*
 * optical_fast.S - MSP430 versions of the two hot helpers of firmware/optical (fastmath.c
 * holds the portable C that defines the results; these perform the very same integer steps,
 * and tests/vectors/optical_vectors.c checks them bit for bit on both worlds).
 *
 * Registers as clang emits calls (TI EABI): 32-bit arguments in R13:R12 and R15:R14 (R12 the
 * low word), further ones on the stack; results in R12 (16 bits) or R13:R12; R11..R15 may be
 * clobbered, R4..R10 are preserved. The 16 x 16 hardware multiplier (MPY 0x130, OP2 0x138,
 * RESLO 0x13A, RESHI 0x13C) is used with interrupts held off (SR saved, restored by POP SR),
 * as the compiler's and fx's multiply helpers do; the instruction after DINT never touches
 * it. Loops avoid the constant-generator immediates, which mspdebug's simulator charges like
 * memory operands (see firmware/fx/msp430/fx_trig.S).
 */
    .set MPY,   0x0130
    .set OP2,   0x0138
    .set RESLO, 0x013a
    .set RESHI, 0x013c

/*
 * uint16_t optical_angle16(int32_t dx, int32_t dy): R13:R12 = dx, R15:R14 = dy -> R12.
 * Steps of optical_angle16() in fastmath.c: magnitudes, swapped so that ay <= ax (flag),
 * both shifted right until ax < 2^15, q = floor(2^15 ay / ax) by restoring division (15
 * steps, the quotient behind a sentinel bit whose carry-out ends the loop), q = (q + 1) >> 1,
 * a = T[q >> 8] + ((T[(q >> 8) + 1] - T[q >> 8]) (q & 255) + 128) >> 8, unfolded.
 * Flags in R10: 0x100 dx < 0, 0x200 dy < 0, 0x400 swapped.
 */
    .section .text.optical_angle16,"ax",@progbits
    .global optical_angle16
    .type optical_angle16,@function
optical_angle16:
    push    r10
    clr     r10
    tst     r13
    jge     1f
    inv     r12
    inv     r13
    add     #1, r12
    adc     r13
    bis     #0x100, r10
1:  tst     r15
    jge     2f
    inv     r14
    inv     r15
    add     #1, r14
    adc     r15
    bis     #0x200, r10
2:  cmp     r13, r15                ; ay > ax: swap
    jlo     4f
    jne     3f
    cmp     r14, r12
    jhs     4f
3:  mov     r12, r11
    mov     r14, r12
    mov     r11, r14
    mov     r13, r11
    mov     r15, r13
    mov     r11, r15
    bis     #0x400, r10
4:  tst     r13                     ; ax >= 2^16: shift both right until the high word is 0
    jz      6f
    clrc                            ; (ax may be 2^31: a logical shift first)
    rrc     r13
    rrc     r12
    clrc
    rrc     r15
    rrc     r14
5:  tst     r13
    jz      6f
    rra     r13
    rrc     r12
    rra     r15
    rrc     r14
    jmp     5b
6:  tst     r12                     ; ax >= 2^15: once more
    jge     7f
    clrc
    rrc     r12
    clrc
    rrc     r14
7:  tst     r12
    jz      zero
    cmp     r12, r14                ; ay == ax: 45 degrees
    jlo     8f
    mov     #8192, r12
    jmp     unfold
8:  mov     #2, r13                 ; quotient behind a sentinel: 15 steps
9:  rla     r14
    cmp     r12, r14
    jlo     10f
    sub     r12, r14                ; C = 1: quotient bit 1
10: rlc     r13
    jnc     9b
    add     #1, r13                 ; q = (q + 1) >> 1 (no carry: C = 0 for the RRC)
    rrc     r13
    mov     r13, r11                ; i = q >> 8, table offset 2i
    swpb    r11
    mov.b   r11, r11
    rla     r11
    mov     optical_atan_tab(r11), r12
    mov.b   r13, r13                ; f = q & 255
    tst     r13
    jz      unfold
    mov     optical_atan_tab+2(r11), r15
    sub     r12, r15                ; T[i+1] - T[i]
    push    r2
    dint
    mov     r12, r14
    mov     r15, &MPY
    mov     r13, &OP2
    mov     &RESLO, r15
    pop     r2
    add     #128, r15
    swpb    r15
    mov.b   r15, r15
    add     r15, r14
    mov     r14, r12
unfold:
    bit     #0x400, r10
    jz      11f
    mov     #16384, r11
    sub     r12, r11
    mov     r11, r12
11: bit     #0x100, r10
    jz      12f
    mov     #32768, r11
    sub     r12, r11
    mov     r11, r12
12: bit     #0x200, r10
    jz      13f
    inv     r12
    add     #1, r12
13: pop     r10
    ret
zero:
    clr     r12
    pop     r10
    ret

/*
 * int32_t optical_dot2(int32_t a, int32_t b, int32_t c, int32_t d): R13:R12 = a,
 * R15:R14 = b, c and d on the stack -> R13:R12 = floor((a b + c d + 2^29) / 2^30).
 * Each product is the unsigned 64-bit product of the two's-complement words, corrected
 * modulo 2^64 (a < 0: b from the high half; b < 0: a from the high half); their sum is
 * exact modulo 2^64, so the result is exact whenever it fits 32 bits (the caller's part).
 * The sum W3:W2:W1:W0 lives in R9:R8:R7:R6. Interrupts are held off for about 100 cycles.
 */
    .section .text.optical_dot2,"ax",@progbits
    .global optical_dot2
    .type optical_dot2,@function
optical_dot2:
    push    r9
    push    r8
    push    r7
    push    r6
    push    r2                      ; c at 12(SP), d at 16(SP) from here
    dint
    mov     r13, r11
    mov     r12, &MPY               ; a_lo b_lo
    mov     r14, &OP2
    mov     &RESLO, r6
    mov     &RESHI, r7
    mov     r15, &OP2               ; a_lo b_hi
    add     &RESLO, r7
    mov     &RESHI, r8
    adc     r8
    mov     r11, &MPY               ; a_hi b_lo
    mov     r14, &OP2
    add     &RESLO, r7
    addc    &RESHI, r8
    clr     r9
    adc     r9
    mov     r15, &OP2               ; a_hi b_hi
    add     &RESLO, r8
    addc    &RESHI, r9
    tst     r13                     ; a < 0: W3:W2 -= b
    jge     1f
    sub     r14, r8
    subc    r15, r9
1:  tst     r15                     ; b < 0: W3:W2 -= a
    jge     2f
    sub     r12, r8
    subc    r13, r9
2:  mov     12(r1), r12             ; c
    mov     14(r1), r13
    mov     16(r1), r14             ; d
    mov     18(r1), r15
    mov     r12, &MPY               ; c_lo d_lo
    mov     r14, &OP2
    add     &RESLO, r6
    addc    &RESHI, r7
    adc     r8
    adc     r9
    mov     r15, &OP2               ; c_lo d_hi
    add     &RESLO, r7
    addc    &RESHI, r8
    adc     r9
    mov     r13, &MPY               ; c_hi d_lo
    mov     r14, &OP2
    add     &RESLO, r7
    addc    &RESHI, r8
    adc     r9
    mov     r15, &OP2               ; c_hi d_hi
    add     &RESLO, r8
    addc    &RESHI, r9
    pop     r2
    tst     r13                     ; c < 0: W3:W2 -= d
    jge     3f
    sub     r14, r8
    subc    r15, r9
3:  tst     r15                     ; d < 0: W3:W2 -= c
    jge     4f
    sub     r12, r8
    subc    r13, r9
4:  add     #0x2000, r7             ; + 2^29
    adc     r8
    adc     r9
    rla     r7                      ; >> 30: W3:W2:W1 << 2, the result W3:W2
    rlc     r8
    rlc     r9
    rla     r7
    rlc     r8
    rlc     r9
    mov     r8, r12
    mov     r9, r13
    pop     r6
    pop     r7
    pop     r8
    pop     r9
    ret
