/*
 * fx_arith.S - the arithmetic kernels (docs/kernels.md): fx_umul64, fx_udiv32_16,
 * fx_mul_q30, fx_mul_q16 and fx_div_shift. Their C twins are firmware/fx/fx_arith_k.c (the
 * results are exact, so both agree by definition; the check images compare every call).
 * Conventions and the multiplier as in fx_trig.S. Calls between these kernels go to local
 * labels, so that a check image's wrappers see only the calls from outside.
 */
    .set MPY,   0x0130
    .set OP2,   0x0138
    .set RESLO, 0x013a
    .set RESHI, 0x013c

/*
 * uint64_t fx_umul64(uint32_t a, uint32_t b): R13:R12 = a, R15:R14 = b -> R15:R14:R13:R12.
 * Four 16 x 16 products; the first operand register keeps a word for two of them.
 * Interrupts are held off for 60 cycles.
 */
    .section .text.fx_umul64,"ax",@progbits
    .global fx_umul64
    .type fx_umul64,@function
fx_umul64:
.Lumul64:
    push    r10
    push    r2
    dint
    mov     r13, r11                ; a_hi
    mov     r12, &MPY               ; a_lo b_lo
    mov     r14, &OP2
    mov     &RESLO, r12             ; word 0
    mov     &RESHI, r13             ; word 1 so far
    mov     r15, &OP2               ; a_lo b_hi
    add     &RESLO, r13
    mov     &RESHI, r10
    adc     r10                     ; word 2 so far (no carry out: < 2^32)
    mov     r11, &MPY               ; a_hi b_lo
    mov     r14, &OP2
    add     &RESLO, r13
    addc    &RESHI, r10
    clr     r14
    adc     r14                     ; word 3 so far
    mov     r15, &OP2               ; a_hi b_hi
    add     &RESLO, r10
    addc    &RESHI, r14
    mov     r14, r15
    mov     r10, r14
    pop     r2
    pop     r10
    ret

/*
 * The 64/32 division core (fx_udiv64_32() of fx_arith.c), local convention:
 * R15:R14 = hi, R13:R12 = lo, R11:R10 = d (hi < d <= 2^31) -> R13:R12 = the quotient
 * floor((hi 2^32 + lo) / d), R15:R14 = the remainder; R9 is clobbered.
 * Restoring division, 32 steps: the remainder R15:R14 (< d <= 2^31, so doubled it still
 * fits) doubles with the next dividend bit (from R13, then from R12), d is subtracted and
 * added back on a borrow. The quotient collects in R9 behind a sentinel bit whose carry-out
 * ends each 16-step half. When hi = 0 and lo >> 16 < d the first half is skipped.
 */
    .section .text.udiv64_core,"ax",@progbits
    .type udiv64_core,@function
udiv64_core:
    tst     r15                     ; hi = 0 and lo >> 16 < d: the first half gives 0
    jnz     9f
    tst     r14
    jnz     9f
    tst     r11
    jnz     10f
    cmp     r10, r13
    jhs     9f
10: mov     r13, r14                ; remainder lo >> 16, quotient high word 0
    clr     r9
    jmp     4f
9:  mov     #1, r9                  ; quotient bits 31..16 from the dividend bits of R13
1:  rla     r13
    rlc     r14
    rlc     r15
    sub     r10, r14
    subc    r11, r15
    jc      2f                      ; no borrow: quotient bit 1
    add     r10, r14                ; restore, quotient bit 0
    addc    r11, r15
    rla     r9
    jnc     1b
    jmp     4f
2:  rlc     r9
    jnc     1b
4:  mov     r9, r13                 ; quotient high word (R13 is used up)
    mov     #1, r9                  ; quotient bits 15..0 from the dividend bits of R12
5:  rla     r12
    rlc     r14
    rlc     r15
    sub     r10, r14
    subc    r11, r15
    jc      6f
    add     r10, r14
    addc    r11, r15
    rla     r9
    jnc     5b
    jmp     8f
6:  rlc     r9
    jnc     5b
8:  mov     r9, r12
    ret

/*
 * bool fx_div_shift(int32_t num, int32_t den, uint8_t shift, int32_t *out): R13:R12 = num,
 * R15:R14 = den, 2(SP) = shift, 4(SP) = out -> R12 = 1 and *out = num 2^shift / den
 * rounded to nearest (ties away from zero), or R12 = 0 (den = 0 or the quotient does not
 * fit int32). Steps of fx_div_shift() in fx_arith_k.c: the magnitudes n, d; n = 0 gives 0;
 * shift >= 64 fails; the dividend n 2^shift as hi:lo by shl64 (for shift > 32 as
 * n 2^(shift-32), failing if that does not fit 32 bits); hi >= d fails; the division core;
 * + 1 when the remainder is at least d - remainder; the sign. Frame: R10, R9, R8, R7
 * pushed; R8 = shift, R7 = out, R9 bit 15 = the sign of the result, R11:R10 = d.
 */
    .section .text.fx_div_shift,"ax",@progbits
    .global fx_div_shift
    .type fx_div_shift,@function
fx_div_shift:
    push    r10
    push    r9
    push    r8
    push    r7
    mov.b   10(r1), r8
    mov     12(r1), r7
    mov     r14, r10                ; den = 0 fails
    bis     r15, r10
    tst     r10
    jz      .Ldiv_fail
    mov     r13, r9                 ; sign
    xor     r15, r9
    mov     r14, r10                ; d = |den|
    mov     r15, r11
    tst     r11
    jge     2f
    inv     r10
    inv     r11
    add     #1, r10
    adc     r11
2:  tst     r13                     ; n = |num|
    jge     3f
    inv     r12
    inv     r13
    add     #1, r12
    adc     r13
3:  mov     r12, r14                ; n = 0: 0
    bis     r13, r14
    tst     r14
    jz      .Ldiv_store
    cmp     #64, r8
    jhs     .Ldiv_fail
    clr     r14
    clr     r15
    push    r11                     ; d across shl64 (it clobbers R11)
    push    r10
    mov     r8, r10                 ; n 2^shift, or n 2^(shift - 32) for shift > 32
    cmp     #33, r8
    jlo     4f
    sub     #32, r10
4:  push    r10
    call    #shl64
    pop     r10
    pop     r10
    pop     r11
    cmp     #33, r8
    jlo     5f
    tst     r15                     ; shift > 32: n 2^(shift - 32) must fit 32 bits;
    jnz     .Ldiv_fail              ; it is hi, and lo = 0
    tst     r14
    jnz     .Ldiv_fail
    mov     r12, r14
    mov     r13, r15
    clr     r12
    clr     r13
5:  cmp     r11, r15                ; hi >= d fails
    jlo     6f
    jne     .Ldiv_fail
    cmp     r10, r14
    jhs     .Ldiv_fail
6:  mov     r9, r8                  ; the sign across the core (it clobbers R9)
    call    #udiv64_core            ; R13:R12 = q, R15:R14 = remainder
    mov     r8, r9
    sub     r14, r10                ; remainder >= d - remainder: q + 1
    subc    r15, r11
    cmp     r11, r15
    jlo     .Ldiv_store
    jne     7f
    cmp     r10, r14
    jlo     .Ldiv_store
7:  add     #1, r12
    adc     r13
    jc      .Ldiv_fail              ; 2^32
.Ldiv_store:
    br      #fx_store
.Ldiv_fail:
    br      #fx_fail

/*
 * Tail of fx_div_shift (plain labels, not functions: it jumps here with its frame pushed):
 * R13:R12 = the magnitude m,
 * R9 bit 15 = the sign -> *out = +-m and R12 = 1 when it fits int32 (m <= 2^31 - 1, or
 * 2^31 for a negative result), else R12 = 0 (fx_fail); pops the frame.
 */
fx_store:
    tst     r9
    jn      1f
    tst     r13                     ; positive: m <= 2^31 - 1
    jn      fx_fail
    jmp     3f
1:  cmp     #0x8000, r13            ; negative: m <= 2^31
    jlo     2f
    jne     fx_fail
    tst     r12
    jnz     fx_fail
2:  inv     r12
    inv     r13
    add     #1, r12
    adc     r13
3:  mov     r12, 0(r7)
    mov     r13, 2(r7)
    mov     #1, r12
    jmp     4f
fx_fail:
    clr     r12
4:  pop     r7
    pop     r8
    pop     r9
    pop     r10
    ret


/*
 * uint16_t fx_udiv32_16(uint32_t n, uint16_t d, uint16_t *rem): R13:R12 = n, R14 = d,
 * R15 = rem -> R12 = floor(n / d), *rem the remainder; (n >> 16) < d. 16 steps as above,
 * the remainder in R13 (a carry out of it: 17 bits, certainly >= d).
 */
    .section .text.fx_udiv32_16,"ax",@progbits
    .global fx_udiv32_16
    .type fx_udiv32_16,@function
fx_udiv32_16:
    mov     #1, r11
1:  rla     r12
    rlc     r13
    jc      3f
    cmp     r14, r13
    jlo     2f
    sub     r14, r13                ; C = 1: quotient bit 1
2:  rlc     r11
    jnc     1b
    mov     r13, 0(r15)
    mov     r11, r12
    ret
3:  sub     r14, r13
    setc
    rlc     r11
    jnc     1b
    mov     r13, 0(r15)
    mov     r11, r12
    ret

/*
 * shl64 (local, for fx_div_shift): R15:R14:R13:R12 = v, 2(SP) = n (n < 64) -> v << n: word
 * moves for 32 and 16, byte swaps for 8, then up to seven bit steps (the compiler's own
 * 64-bit shifts by a few bits are long sequences here).
 */
    .section .text.shl64,"ax",@progbits
    .type shl64,@function
shl64:
    mov.b   2(r1), r11
    bit     #32, r11
    jz      1f
    mov     r13, r15
    mov     r12, r14
    clr     r13
    clr     r12
1:  bit     #16, r11
    jz      2f
    mov     r14, r15
    mov     r13, r14
    mov     r12, r13
    clr     r12
2:  bit     #8, r11
    jz      3f
    swpb    r15                     ; each word: its own low byte high, the previous one's high byte low
    mov.b   r15, r11
    xor     r11, r15
    swpb    r14
    mov.b   r14, r11
    xor     r11, r14
    bis     r11, r15
    swpb    r13
    mov.b   r13, r11
    xor     r11, r13
    bis     r11, r14
    swpb    r12
    mov.b   r12, r11
    xor     r11, r12
    bis     r11, r13
    mov.b   2(r1), r11
3:  and     #7, r11
    jz      5f
4:  rla     r12
    rlc     r13
    rlc     r14
    rlc     r15
    dec     r11
    jnz     4b
5:  ret

/*
 * int32_t fx_mul_q30(int32_t a, int32_t b), fx_mul_q16(a, b): R13:R12 = a, R15:R14 = b ->
 * R13:R12 = a b / 2^30 (2^16) rounded to nearest, ties away from zero, saturated. The
 * product of the magnitudes (fx_umul64), + 2^29 (2^15), the bits 30..61 (16..47) taken, the
 * sign applied; a magnitude above 2^31 - 1 (2^31 for a negative result) saturates.
 */
    .section .text.fx_mul_q30,"ax",@progbits
    .global fx_mul_q30
    .type fx_mul_q30,@function
fx_mul_q30:
    push    r10
    push    r9
    call    #mul_magnitudes         ; R15:R14:R13:R12 = |a| |b|, R9 bit 15 = sign
    add     #0x2000, r13            ; + 2^29
    adc     r14
    adc     r15
    rla     r13                     ; bits 30..61 to R15:R14, bit 62 to the carry
    rlc     r14
    rlc     r15
    rla     r13
    rlc     r14
    rlc     r15
    jc      mul_saturate
    jmp     mul_signed

    .section .text.fx_mul_q16,"ax",@progbits
    .global fx_mul_q16
    .type fx_mul_q16,@function
fx_mul_q16:
    push    r10
    push    r9
    call    #mul_magnitudes
    add     #0x8000, r12            ; + 2^15
    adc     r13
    adc     r14
    adc     r15
    tst     r15                     ; bits 48..63 must be 0
    jnz     mul_saturate
    mov     r14, r15                ; bits 16..47 to R15:R14
    mov     r13, r14
    jmp     mul_signed

/*
 * Shared tails (R10, R9 pushed by the entry): R15:R14 = the rounded magnitude m (< 2^32),
 * R9 bit 15 = sign of the result -> R13:R12 = +-m, or the saturated value.
 */
    .section .text.mul_tails,"ax",@progbits
mul_signed:
    tst     r9
    jn      2f
    tst     r15                     ; positive: m <= 2^31 - 1
    jn      mul_saturate
    mov     r14, r12
    mov     r15, r13
    jmp     3f
2:  cmp     #0x8000, r15            ; negative: m <= 2^31
    jlo     1f
    jne     mul_saturate
    tst     r14
    jnz     mul_saturate
1:  clr     r12
    sub     r14, r12
    clr     r13
    subc    r15, r13
3:  pop     r9
    pop     r10
    ret
mul_saturate:
    mov     #-1, r12                ; INT32_MAX, or INT32_MIN for a negative result
    mov     #0x7fff, r13
    tst     r9
    jge     3b
    clr     r12
    mov     #0x8000, r13
    jmp     3b

/* R13:R12 = a, R15:R14 = b -> R15:R14:R13:R12 = |a| |b|, R9 = a_hi ^ b_hi; clobbers R10, R11. */
mul_magnitudes:
    mov     r13, r9
    xor     r15, r9
    tst     r13
    jge     1f
    clr     r10
    sub     r12, r10
    clr     r11
    subc    r13, r11
    mov     r10, r12
    mov     r11, r13
1:  tst     r15
    jge     2f
    clr     r10
    sub     r14, r10
    clr     r11
    subc    r15, r11
    mov     r10, r14
    mov     r11, r15
2:  br      #.Lumul64
