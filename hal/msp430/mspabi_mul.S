/*
 * mspabi_mul.S - 16- and 32-bit multiplies on the 16 x 16 hardware multiplier (MPY at
 * 0x130, MPYS 0x132, MAC 0x134, OP2 0x138, RESLO 0x13A, RESHI 0x13C).
 * Interrupts are held off while the multiplier is in use (SR saved on the stack, restored by
 * POP SR), so an ISR that multiplies cannot corrupt the multiply it interrupted.
 */
    .set MPY,   0x0130
    .set MPYS,  0x0132
    .set MAC,   0x0134
    .set OP2,   0x0138
    .set RESLO, 0x013a
    .set RESHI, 0x013c

/* int16_t __mspabi_mpyi_hw(int16_t a /R12/, int16_t b /R13/) -> R12 */
    .section .text.__mspabi_mpyi_hw,"ax",@progbits
    .global __mspabi_mpyi_hw
    .type __mspabi_mpyi_hw,@function
__mspabi_mpyi_hw:
    push    r2
    dint
    nop
    mov     r12, &MPY
    mov     r13, &OP2
    mov     &RESLO, r12
    pop     r2
    ret

/*
 * int32_t __mspabi_mpyl_hw(int32_t a /R12:R13/, int32_t b /R14:R15/) -> R12:R13
 * Operands that fit 16 bits (unsigned, or signed) take one multiply; the general case takes
 * three: al*bl plus the low words of the cross products al*bh + ah*bl in the high word.
 */
    .section .text.__mspabi_mpyl_hw,"ax",@progbits
    .global __mspabi_mpyl_hw
    .type __mspabi_mpyl_hw,@function
__mspabi_mpyl_hw:
    push    r2
    dint
    nop
    mov     r13, r11
    bis     r15, r11                ; (BIS leaves the flags alone)
    tst     r11
    jnz     1f
    mov     r12, &MPY               ; both high words zero: unsigned 16 x 16
    jmp     3f
1:  mov     r12, r11                ; r11 = sign extension of al
    rla     r11
    subc    r11, r11
    inv     r11
    cmp     r11, r13
    jne     2f
    mov     r14, r11                ; r11 = sign extension of bl
    rla     r11
    subc    r11, r11
    inv     r11
    cmp     r11, r15
    jne     2f
    mov     r12, &MPYS              ; both fit 16 bits signed
3:  mov     r14, &OP2
    mov     &RESLO, r12
    mov     &RESHI, r13
    pop     r2
    ret
2:  mov     r12, &MPY               ; al * bh
    mov     r15, &OP2
    mov     r13, &MAC               ; + ah * bl
    mov     r14, &OP2
    mov     &RESLO, r13             ; cross products, low word
    mov     r12, &MPY               ; al * bl
    mov     r14, &OP2
    mov     &RESLO, r12
    add     &RESHI, r13
    pop     r2
    ret
