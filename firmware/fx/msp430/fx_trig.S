/*
 * fx_trig.S - the trigonometry kernels (docs/kernels.md): fx_sin, fx_cos and the
 * first-quadrant arctangent fx_atan_q1. Their C twins (firmware/fx/fx_trig_k.c) define the
 * results; these perform the very same integer steps, which the check images compare call
 * by call.
 *
 * Registers as clang emits calls (TI EABI): 32-bit arguments in R13:R12 and R15:R14 (high
 * word first here: R12 is the low word), 32-bit result in R13:R12; R11..R15 may be
 * clobbered, R4..R10 are preserved.
 *
 * Cycle counts are what mspdebug's simulator counts (tools/msp430sim.py, the cycle report):
 * it charges the constant-generator immediates #1, #2, #4, #8 and #-1 like memory operands
 * (INC is 3 cycles there, CLRC 3, DINT 2), so these are avoided in the loops.
 *
 * The 16 x 16 hardware multiplier (MPY 0x130, OP2 0x138, RESLO 0x13A, RESHI 0x13C) is used
 * with interrupts held off (SR saved on the stack, restored by POP SR), as the compiler's
 * multiply helpers do, so an interrupt that multiplies cannot corrupt a product here. The
 * instruction after DINT never touches the multiplier (DINT takes effect one instruction
 * late).
 */
    .set MPY,   0x0130
    .set OP2,   0x0138
    .set RESLO, 0x013a
    .set RESHI, 0x013c

/*
 * fx_q30_t fx_cos(fx_angle_t a) = fx_sin(a + quarter turn); falls through into fx_sin.
 * fx_q30_t fx_sin(fx_angle_t a): R13:R12 = a -> R13:R12. Steps of sin_q1() in fx_trig.c:
 *   x = a mod quarter (mirrored in odd quadrants: 2^30 - x), xr = x + 64, i = xr >> 23,
 *   u = (xr >> 7) mod 2^16, e = T[i+1] - T[i] + 2 ((G[i] ((2^16 - u) mod 2^16)) >> 16),
 *   s = T[i] + ((e u) >> 16), negated in the lower half turn.
 * The body is assembled twice (SIN_BODY), for the upper and the lower half turn, so that
 * the sign needs no register. Interrupts are held off for 58 cycles.
 */
    .macro SIN_BODY
    bit     #0x4000, r13            ; odd quadrant: xr = (2^30 - 1 - x) + 65
    jz      1f
    inv     r12
    inv     r13
    and     #0x3fff, r13
    add     #65, r12
    adc     r13
    jmp     2f
1:  and     #0x3fff, r13            ; even quadrant: xr = x + 64
    add     #64, r12
    adc     r13
2:  rla     r12                     ; xr << 1: i = high byte of R13,
    rlc     r13                     ; u = low byte of R13 : high byte of R12
    swpb    r13
    mov.b   r13, r14                ; i
    xor     r14, r13                ; (u >> 8) << 8
    swpb    r12
    mov.b   r12, r12
    bis     r12, r13                ; u
    rla     r14                     ; 2i
    push    r2
    dint
    clr     r11
    mov     fx_sin_corr(r14), &MPY  ; G[i] (2^16 - u)
    sub     r13, r11
    mov     r11, &OP2
    rla     r14                     ; 4i
    mov     fx_sin_tab+4(r14), r12  ; D = T[i+1] - T[i]
    mov     fx_sin_tab+6(r14), r15
    sub     fx_sin_tab(r14), r12
    subc    fx_sin_tab+2(r14), r15
    mov     &RESHI, r11             ; + 2 ((G (2^16 - u)) >> 16), 17 bits
    rla     r11
    adc     r15
    add     r11, r12
    adc     r15                     ; e = R15:R12
    mov     r13, &MPY               ; (e u) >> 16 = e_hi u + ((e_lo u) >> 16)
    mov     r12, &OP2
    mov     &RESHI, r12
    mov     r15, &OP2
    add     &RESLO, r12
    mov     &RESHI, r13
    adc     r13
    pop     r2
    add     fx_sin_tab(r14), r12    ; + T[i]
    addc    fx_sin_tab+2(r14), r13
    .endm

    .section .text.fx_sin,"ax",@progbits
    .global fx_cos
    .type fx_cos,@function
    .global fx_sin
    .type fx_sin,@function
fx_cos:
    add     #0x4000, r13
fx_sin:
    tst     r13
    jn      3f
    SIN_BODY
    ret
3:  SIN_BODY
    clr     r14                     ; lower half turn: negate
    sub     r12, r14
    clr     r15
    subc    r13, r15
    mov     r14, r12
    mov     r15, r13
    ret

/*
 * fx_angle_t fx_atan_q1(uint32_t ay, uint32_t ax) (fx_internal.h): R13:R12 = ay,
 * R15:R14 = ax (both <= 2^31, not both 0) -> R13:R12 = the angle of (ax, ay) in
 * [0, quarter]. Steps of fx_atan_q1() in fx_trig_k.c: swap so that ay <= ax (bit 0 of R11),
 * octant_ratio() (both halved when ax >= 2^30; turned by 45 degrees when ay > ax - ay: bit
 * 1 of R11), q = floor(num 2^24 / den) by restoring division (24 steps; den <= 2^31, so the
 * doubled remainder fits 32 bits), t = A[i] + (A[i+1] - A[i]) u / 2^16 with i = q >> 16,
 * u = q mod 2^16, then unfolded: turned t = 2^29 - t, swapped t = 2^30 - t.
 * Each quotient register starts with a sentinel bit whose carry-out ends its loop.
 */
    .section .text.fx_atan_q1,"ax",@progbits
    .global fx_atan_q1
    .type fx_atan_q1,@function
fx_atan_q1:
    push    r10
    push    r9
    clr     r11
    cmp     r13, r15                ; ay > ax: swap (bit 0)
    jlo     1f
    jne     2f
    cmp     r12, r14
    jhs     2f
1:  mov     r12, r10
    mov     r14, r12
    mov     r10, r14
    mov     r13, r10
    mov     r15, r13
    mov     r10, r15
    bis     #1, r11
2:  bit     #0xc000, r15            ; ax >= 2^30: both halved
    jz      3f
    clrc
    rrc     r15
    rrc     r14
    clrc
    rrc     r13
    rrc     r12
3:  mov     r14, r9                 ; rest = ax - ay -> R10:R9
    mov     r15, r10
    sub     r12, r9
    subc    r13, r10
    cmp     r10, r13                ; turned = ay > rest
    jlo     4f
    jne     5f
    cmp     r9, r12
    jlo     4f
    jeq     4f
5:  bis     #2, r11                 ; turned: num = rest, den = ax + ay
    add     r12, r14
    addc    r13, r15
    jmp     6f
4:  mov     r12, r9                 ; not turned: num = ay, den = ax
    mov     r13, r10
6:  mov     #0x0100, r13            ; quotient bits 23..16 (sentinel at bit 8)
7:  rla     r9                      ; remainder doubled
    rlc     r10
    sub     r14, r9
    subc    r15, r10
    jc      8f                      ; no borrow: quotient bit 1
    add     r14, r9                 ; restore, quotient bit 0
    addc    r15, r10
    rla     r13
    jnc     7b
    jmp     9f
8:  rlc     r13
    jnc     7b
9:  mov     #1, r12                 ; quotient bits 15..0 (sentinel at bit 0)
10: rla     r9
    rlc     r10
    sub     r14, r9
    subc    r15, r10
    jc      11f
    add     r14, r9
    addc    r15, r10
    rla     r12
    jnc     10b
    jmp     12f
11: rlc     r12
    jnc     10b
12: rla     r13                     ; i = q >> 16 (<= 128): 4i
    rla     r13
    mov     fx_atan_tab+4(r13), r14 ; d = A[i+1] - A[i] (< 2^22)
    mov     fx_atan_tab+6(r13), r15
    sub     fx_atan_tab(r13), r14
    subc    fx_atan_tab+2(r13), r15
    push    r2
    dint
    mov     fx_atan_tab(r13), r9    ; A[i]
    mov     r12, &MPY               ; (d u) >> 16 = d_hi u + ((d_lo u) >> 16)
    mov     r14, &OP2
    mov     &RESHI, r14
    mov     r15, &OP2
    add     &RESLO, r14
    mov     &RESHI, r15
    adc     r15
    pop     r2
    mov     fx_atan_tab+2(r13), r13
    add     r9, r14
    addc    r15, r13                ; t = R13:R14
    bit     #2, r11                 ; turned: t = 2^29 - t
    jz      13f
    clr     r12
    sub     r14, r12
    mov     #0x2000, r10
    subc    r13, r10
    mov     r12, r14
    mov     r10, r13
13: bit     #1, r11                 ; swapped: t = 2^30 - t
    jz      14f
    clr     r12
    sub     r14, r12
    mov     #0x4000, r10
    subc    r13, r10
    mov     r12, r14
    mov     r10, r13
14: mov     r14, r12
    pop     r9
    pop     r10
    ret
