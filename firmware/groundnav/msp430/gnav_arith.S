/*
 * gnav_arith.S - the groundnav kernels (gnav_arith.h, docs/kernels.md): gnav_add64x2,
 * gnav_sub64x2 and gnav_mac64, the dl handler's 64-bit accumulations as ADDC/SUBC chains.
 * Their C twins (gnav_arith_k.c) define the results; the check images compare every call.
 *
 * Registers as clang emits the calls (TI EABI): R12 = the first pointer, R13 the second
 * pointer or the 16-bit a, R14 the 16-bit b. R11..R15 may be clobbered.
 * The hardware multiplier (MPYS 0x132, OP2 0x138, RESLO 0x13A,
 * RESHI 0x13C) is used with interrupts held off (SR saved on the stack, restored by POP SR),
 * as the compiler's multiply helpers do; the instruction after DINT does not touch it.
 */
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
