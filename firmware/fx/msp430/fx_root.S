/*
 * fx_root.S - MSP430 version of fx_sqrt32 (firmware/fx/fx_root.c holds the portable C with
 * the same steps; tests/vectors/fx_vectors.c checks both bit for bit and every root
 * boundary on the target). Conventions and the multiplier as in fx_trig.S.
 */
    .set MPY,   0x0130
    .set MPYS,  0x0132
    .set OP2,   0x0138
    .set RESLO, 0x013a
    .set RESHI, 0x013c

/*
 * The core, R13:R12 = xn in [2^30, 2^32) -> R11 = floor(sqrt(xn)), with interrupts held off
 * (the caller pops SR); \tmp is a scratch register, R13, R14 are clobbered.
 * S and R from the table row of the top byte j of xn, Newton Y = S + ((h + 6) >> 4) with
 * h = ((e >> 9) R) >> 16 and e = xn - S^2 (fx_root.c), one correction (Y^2 > xn: Y - 1).
 */
    .macro SQRT_CORE tmp
    mov     r13, r14                ; table row 4 (j - 64), j = xn >> 24
    swpb    r14
    mov.b   r14, r14
    rla     r14
    rla     r14
    push    r2
    dint
    mov     fx_sqrt_tab-256(r14), r11 ; S
    mov     r11, &MPY
    mov     r11, &OP2               ; S^2
    mov     fx_sqrt_tab-254(r14), &MPYS ; R (signed product next; RES keeps S^2)
    mov     r12, \tmp
    sub     &RESLO, \tmp
    mov     r13, r14
    subc    &RESHI, r14             ; e = xn - S^2, |e| < 2^24
    rra     r14                     ; e >> 9: bits 9..24 of e
    rrc     \tmp
    swpb    \tmp
    mov.b   \tmp, \tmp
    swpb    r14
    and     #0xff00, r14
    bis     \tmp, r14
    mov     r14, &OP2               ; h = ((e >> 9) R) >> 16
    mov     &RESHI, r14
    add     #6, r14                 ; c = (h + 6) >> 4
    rra     r14
    rra     r14
    rra     r14
    rra     r14
    add     r14, r11                ; Y = S + c
    jnz     5f
    mov     #-1, r11                ; 65536 wrapped (xn next to 2^32): 65535
5:  mov     r11, &MPY               ; Y^2 > xn: Y - 1
    mov     r11, &OP2
    sub     &RESLO, r12
    subc    &RESHI, r13
    jc      6f
    dec     r11
6:
    .endm

/*
 * uint16_t fx_sqrt32(uint32_t x): R13:R12 = x -> R12 = floor(sqrt(x)).
 * x >= 2^30 goes straight to the core. Smaller x is normalised to xn = x 4^k in [2^30, 2^32)
 * by 16, 8, 4 and 2 bits (R15 = 2k), and the core's root shifted back: Y >> k as the high
 * word of Y 2^(16-k) (fx_sqrt_pow). Interrupts are held off for up to 83 cycles.
 */
    .section .text.fx_sqrt32,"ax",@progbits
    .global fx_sqrt32
    .type fx_sqrt32,@function
fx_sqrt32:
    cmp     #0x4000, r13            ; x >= 2^30: no shift
    jlo     7f
    SQRT_CORE r15
    pop     r2
    mov     r11, r12
    ret
7:  clr     r15
    tst     r13
    jnz     1f
    tst     r12
    jz      9f                      ; sqrt(0) = 0
    mov     r12, r13                ; 16 bits
    clr     r12
    mov     #16, r15
1:  cmp     #0x0100, r13
    jhs     2f
    swpb    r13                     ; 8 bits
    swpb    r12
    mov.b   r12, r14
    xor     r14, r12
    bis     r14, r13
    add     #8, r15
2:  cmp     #0x1000, r13
    jhs     3f
    rla     r12                     ; 4 bits
    rlc     r13
    rla     r12
    rlc     r13
    rla     r12
    rlc     r13
    rla     r12
    rlc     r13
    add     #4, r15
3:  cmp     #0x4000, r13
    jhs     4f
    rla     r12                     ; 2 bits
    rlc     r13
    rla     r12
    rlc     r13
    add     #2, r15
4:  push    r10
    SQRT_CORE r10
    mov     r11, &MPY               ; Y >> k = high word of Y 2^(16-k), k >= 1
    mov     fx_sqrt_pow(r15), &OP2
    mov     &RESHI, r12
    pop     r2
    pop     r10
9:  ret
