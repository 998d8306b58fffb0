/*
 * gnav_arith.S - MSP430 versions of gnav_add64 and gnav_mac64 (gnav_arith.h; the portable
 * C in gnav_arith.c defines the results, tests/vectors/groundnav_vectors.c checks the two
 * bit for bit).
 *
 * Registers as clang emits the calls (TI EABI): R12 = the pointer, then the 32-bit v in
 * R14:R13 (R13 the low word), or the 16-bit a, b in R13, R14.
 * R11..R15 may be clobbered. The hardware multiplier (MPYS 0x132, OP2 0x138, RESLO 0x13A,
 * RESHI 0x13C) is used with interrupts held off (SR saved on the stack, restored by POP SR),
 * as the compiler's multiply helpers do; the instruction after DINT does not touch it.
 */
    .set MPYS,  0x0132
    .set OP2,   0x0138
    .set RESLO, 0x013a
    .set RESHI, 0x013c

/* void gnav_add64(int64_t *acc, int32_t v): *acc += v, 4 words with carries. */
    .section .text.gnav_add64,"ax",@progbits
    .global gnav_add64
    .type gnav_add64,@function
gnav_add64:
    mov     r14, r15                ; sign extension of v: 0 or 0xffff
    rla     r15
    subc    r15, r15
    inv     r15
    add     r13, 0(r12)
    addc    r14, 2(r12)
    addc    r15, 4(r12)
    addc    r15, 6(r12)
    ret
    .size gnav_add64, .-gnav_add64

/* void gnav_mac64(int64_t *acc, int16_t a, int16_t b): *acc += a * b (signed 16 x 16). */
    .section .text.gnav_mac64,"ax",@progbits
    .global gnav_mac64
    .type gnav_mac64,@function
gnav_mac64:
    push    r2
    dint
    mov     r13, r15                ; (not the multiplier: DINT acts one instruction late)
    mov     r15, &MPYS
    mov     r14, &OP2
    mov     &RESLO, r14
    mov     &RESHI, r15
    pop     r2
    mov     r15, r13                ; sign extension of the product
    rla     r13
    subc    r13, r13
    inv     r13
    add     r14, 0(r12)
    addc    r15, 2(r12)
    addc    r13, 4(r12)
    addc    r13, 6(r12)
    ret
    .size gnav_mac64, .-gnav_mac64
