/*
 * mspabi_div.S - unsigned 16- and 32-bit division for the EABI helpers (SLAA534 names,
 * clang's register use: operands in R12(:R13) and R14(:R15), result in R12(:R13)).
 *
 * Restoring shift-subtract division: the dividend shifts left into the remainder and the
 * freed low bit of the dividend register receives the quotient bit, so the dividend
 * register ends up holding the quotient. A carry out of the remainder (possible when the
 * divisor has its top bit set) means "remainder >= divisor": subtract.
 * Dividends whose high word is zero skip the first 16 steps; operands that both fit 16 bits
 * use the 16-bit loop. Division by zero: quotient all ones, remainder the dividend.
 */
    .text

/* cy_udivmod16: R12 = n, R13 = d (not 0) -> R12 = n / d, R13 = n % d. Clobbers R14, R15. */
    .section .text.cy_udivmod16,"ax",@progbits
    .global cy_udivmod16
    .type cy_udivmod16,@function
cy_udivmod16:
    clr     r14
    mov     #16, r15
1:  rla     r12
    rlc     r14
    jc      2f
    cmp     r13, r14
    jlo     3f
2:  sub     r13, r14
    bis     #1, r12
3:  dec     r15
    jnz     1b
    mov     r14, r13
    ret

/* cy_udivmod32: R12:R13 = n, R14:R15 = d (not 0) -> R12:R13 = n / d, R14:R15 = n % d. */
    .section .text.cy_udivmod32,"ax",@progbits
    .global cy_udivmod32
    .type cy_udivmod32,@function
cy_udivmod32:
    tst     r13
    jnz     5f
    tst     r15
    jnz     5f
    mov     r14, r13                ; both fit 16 bits
    call    #cy_udivmod16
    mov     r13, r14
    clr     r13
    clr     r15
    ret
5:  push    r10
    push    r9
    clr     r10                     ; remainder, low word
    clr     r11                     ; remainder, high word
    mov     #32, r9
    tst     r13
    jnz     1f
    mov     r12, r13                ; high word of n is zero: the first 16 steps are idle
    clr     r12
    mov     #16, r9
1:  rla     r12
    rlc     r13
    rlc     r10
    rlc     r11
    jc      2f
    cmp     r15, r11
    jlo     3f
    jne     2f
    cmp     r14, r10
    jlo     3f
2:  sub     r14, r10
    subc    r15, r11
    bis     #1, r12
3:  dec     r9
    jnz     1b
    mov     r10, r14
    mov     r11, r15
    pop     r9
    pop     r10
    ret

    .section .text.__mspabi_divu,"ax",@progbits
    .global __mspabi_divu
    .type __mspabi_divu,@function
__mspabi_divu:
    tst     r13
    jz      1f
    br      #cy_udivmod16
1:  mov     #-1, r12
    ret

    .section .text.__mspabi_remu,"ax",@progbits
    .global __mspabi_remu
    .type __mspabi_remu,@function
__mspabi_remu:
    tst     r13
    jz      1f
    call    #cy_udivmod16
    mov     r13, r12
1:  ret

    .section .text.__mspabi_divul,"ax",@progbits
    .global __mspabi_divul
    .type __mspabi_divul,@function
__mspabi_divul:
    tst     r14
    jnz     1f
    tst     r15
    jnz     1f
    mov     #-1, r12
    mov     #-1, r13
    ret
1:  br      #cy_udivmod32

    .section .text.__mspabi_remul,"ax",@progbits
    .global __mspabi_remul
    .type __mspabi_remul,@function
__mspabi_remul:
    tst     r14
    jnz     1f
    tst     r15
    jz      2f
1:  call    #cy_udivmod32
    mov     r14, r12
    mov     r15, r13
2:  ret

/*
 * __mspabi_divli: R13:R12 = a, R15:R14 = b (signed) -> R13:R12 = a / b truncated, as the C
 * of mspabi.c defines it: the quotient of the magnitudes, negated when the signs differ;
 * b = 0 gives INT32_MAX for a >= 0 and INT32_MIN for a < 0; INT32_MIN / -1 gives INT32_MIN.
 */
    .section .text.__mspabi_divli,"ax",@progbits
    .global __mspabi_divli
    .type __mspabi_divli,@function
__mspabi_divli:
    tst     r14
    jnz     1f
    tst     r15
    jnz     1f
    tst     r13                     ; b = 0: INT32_MAX, or INT32_MIN for a < 0
    mov     #-1, r12                ; (MOV leaves the flags alone)
    mov     #0x7fff, r13
    jge     4f
    clr     r12
    mov     #0x8000, r13
4:  ret
1:  mov     r13, r11                ; the sign of the quotient, across the division
    xor     r15, r11
    push    r11
    tst     r13
    jge     2f
    inv     r12
    inv     r13
    add     #1, r12
    adc     r13
2:  tst     r15
    jge     3f
    inv     r14
    inv     r15
    add     #1, r14
    adc     r15
3:  call    #cy_udivmod32
    pop     r11
    tst     r11
    jge     4b
    inv     r12
    inv     r13
    add     #1, r12
    adc     r13
    ret
