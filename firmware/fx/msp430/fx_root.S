/*
 * fx_root.S - MSP430 versions of fx_sqrt32, fx_sqrt64 and fx_hypot (firmware/fx/fx_root.c
 * holds the portable C; both
 * are exact, tests/vectors/fx_vectors.c checks them bit for bit and every root boundary on
 * the target). Conventions as in fx_trig.S; no multiplier, no table.
 */

/*
 * uint16_t fx_sqrt32(uint32_t x): R13:R12 = x -> R12 = floor(sqrt(x)).
 * Digit by digit as fx_sqrt32() of fx_root.c: the remainder x (R13:R12), the root so far r
 * (R11:R10) and one = 4^j, j = 15..0 (R15): t = r + one; r >>= 1; x >= t: x -= t, r += one.
 * Before step j, r = q 4^(j+1) (q the root's bits above j), so t = r + one and r / 2 + one
 * are plain ORs, never a carry. For j >= 8 (one in the high word) r and t have zero low
 * words: those eight steps need the high words only. Constant time, about 230 cycles.
 */
    .section .text.fx_sqrt32,"ax",@progbits
    .global fx_sqrt32
    .type fx_sqrt32,@function
fx_sqrt32:
    push    r10
    clr     r11
    mov     #0x4000, r15            ; one = 2^30 (high word)
1:  mov     r11, r14                ; t = r + one (high words)
    add     r15, r14
    rra     r11                     ; r >>= 1 (a multiple of 4 here)
    cmp     r14, r13                ; x >= t: x_hi >= t_hi (t_lo = 0)
    jlo     2f
    sub     r14, r13
    add     r15, r11                ; r += one
2:  rra     r15
    rra     r15
    jnz     1b
    clr     r10                     ; r = R11:R10 from here
    mov     #0x4000, r15            ; one = 2^14 (low word)
3:  mov     r10, r14                ; t = r + one: R11:R14
    add     r15, r14
    sub     r14, r12                ; x - t
    subc    r11, r13
    jc      4f
    add     r14, r12                ; x < t: restore
    addc    r11, r13
    rra     r11
    rrc     r10
    jmp     5f
4:  rra     r11                     ; x >= t: r = r / 2 + one
    rrc     r10
    add     r15, r10
5:  rra     r15
    rra     r15
    jnz     3b
    mov     r10, r12
    pop     r10
    ret

/*
 * The 64-bit root core, local convention: R15:R14:R13:R12 = x -> R7:R11 = floor(sqrt(x)),
 * R14:R13:R12 = the remainder x - root^2 (<= 2 root, 33 bits), R15 = 0; R8, R9, R10 are
 * clobbered (R8 = 0 at the end). The steps of fx_sqrt64() in fx_root.c, one = 4^j for
 * j = 31..0 in R10, t in R9. Before step j, r = q 4^(j+1) < 2^(j+33) (q the root's bits
 * above j) and the remainder is below 2^(j+34), so each group of eight steps needs only
 * some words: j >= 24 the top word of r and x (r in R11); j >= 16 words 3:2 (R11:R8);
 * j >= 8 r in words 2:1 (R8:R7), x in words 3:2:1; then r in words 2:1:0 (R8:R7:R11),
 * x in words 2:1:0. t = r + one and r / 2 + one never carry (as in fx_sqrt32); r >>= 1 is
 * RRA on the top word where that is below 2^15, RRC after CLRC for j = 15..8.
 */
    .section .text.sqrt64_core,"ax",@progbits
    .type sqrt64_core,@function
sqrt64_core:
    clr     r11
    mov     #0x4000, r10            ; j = 31..24: one in word 3
1:  mov     r11, r9
    add     r10, r9
    rra     r11
    cmp     r9, r15
    jlo     2f
    sub     r9, r15
    add     r10, r11
2:  rra     r10
    rra     r10
    jnz     1b
    clr     r8                      ; j = 23..16: r = R11:R8, one in word 2
    mov     #0x4000, r10
3:  mov     r8, r9
    add     r10, r9
    sub     r9, r14
    subc    r11, r15
    jc      4f
    add     r9, r14
    addc    r11, r15
    rra     r11
    rrc     r8
    jmp     5f
4:  rra     r11
    rrc     r8
    add     r10, r8
5:  rra     r10
    rra     r10
    jnz     3b
    clr     r7                      ; j = 15..8: r = R8:R7 (R11 is 0), one in word 1
    mov     #0x4000, r10
6:  mov     r7, r9
    add     r10, r9
    sub     r9, r13
    subc    r8, r14
    sbc     r15
    jc      7f
    add     r9, r13
    addc    r8, r14
    adc     r15
    clrc                            ; r >>= 1 (R8 may have bit 15 set here)
    rrc     r8
    rrc     r7
    jmp     8f
7:  clrc
    rrc     r8
    rrc     r7
    add     r10, r7
8:  rra     r10
    rra     r10
    jnz     6b
    mov     #0x4000, r10            ; j = 7..0: r = R8:R7:R11, one in word 0
9:  mov     r11, r9
    add     r10, r9
    sub     r9, r12
    subc    r7, r13
    subc    r8, r14
    jc      10f
    add     r9, r12
    addc    r7, r13
    addc    r8, r14
    rra     r8
    rrc     r7
    rrc     r11
    jmp     11f
10: rra     r8
    rrc     r7
    rrc     r11
    add     r10, r11
11: rra     r10
    rra     r10
    jnz     9b
    ret

/* uint32_t fx_sqrt64(uint64_t x): R15:R14:R13:R12 = x -> R13:R12 = floor(sqrt(x)). */
    .section .text.fx_sqrt64,"ax",@progbits
    .global fx_sqrt64
    .type fx_sqrt64,@function
fx_sqrt64:
    push    r10
    push    r9
    push    r8
    push    r7
    call    #sqrt64_core
    mov     r11, r12
    mov     r7, r13
    pop     r7
    pop     r8
    pop     r9
    pop     r10
    ret

/*
 * uint32_t fx_hypot(int32_t x, int32_t y): R13:R12 = x, R15:R14 = y -> R13:R12 =
 * sqrt(x^2 + y^2) rounded to nearest: n = |x|^2 + |y|^2 (fx_umul64), its root r and
 * remainder n - r^2 from the core, r + 1 when the remainder exceeds r (fx_hypot() of
 * fx_root.c).
 */
    .section .text.fx_hypot,"ax",@progbits
    .global fx_hypot
    .type fx_hypot,@function
fx_hypot:
    push    r10
    push    r9
    push    r8
    push    r7
    tst     r15                     ; |y| -> R7:R8 (fx_umul64 keeps R4..R10)
    jge     1f
    inv     r14
    inv     r15
    add     #1, r14
    adc     r15
1:  mov     r14, r8
    mov     r15, r7
    tst     r13                     ; |x|
    jge     2f
    inv     r12
    inv     r13
    add     #1, r12
    adc     r13
2:  mov     r12, r14
    mov     r13, r15
    call    #fx_umul64              ; x^2 on the stack
    push    r15
    push    r14
    push    r13
    push    r12
    mov     r8, r12
    mov     r7, r13
    mov     r8, r14
    mov     r7, r15
    call    #fx_umul64              ; + y^2 (<= 2^63: no carry out)
    add     @r1+, r12
    addc    @r1+, r13
    addc    @r1+, r14
    addc    @r1+, r15
    call    #sqrt64_core
    tst     r14                     ; remainder > r: r + 1
    jnz     3f
    cmp     r13, r7
    jlo     3f
    jne     4f
    cmp     r12, r11
    jhs     4f
3:  add     #1, r11
    adc     r7
4:  mov     r11, r12
    mov     r7, r13
    pop     r7
    pop     r8
    pop     r9
    pop     r10
    ret
