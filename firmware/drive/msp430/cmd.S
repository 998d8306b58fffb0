/*
 * cmd.S - MSP430 version of drive_cmd_build() (cmd.c holds the portable C that defines the
 * results: the same fx calls and decisions, step for step, with drive_steer_byte() worked in:
 * the byte of alpha >= 0 is 128 -/+ ((alpha + 2^22) >> 23) for a left/right turn).
 * tests/vectors/drive_vectors.c checks the two bit for bit. Registers as in vm.S.
 */
#include "../solve_frame.h"

    /* The frame: outgoing stack arguments at 0(SP), then the command being built, |k| of the
     * angle in hand, the speed, the front/rear ratio sec and the counts. */
    .set CMD, 4
    .set KABS, 18
    .set SPEED, 22
    .set SEC, 26
    .set CNT, 30
    .set CFRAME, 34
    .set CARG, CFRAME + 16          /* reverse, then cmd (the caller's) */
    .set STEER_LIMIT_HI, 0x3FC0     /* 127.5 * 2^23: 89.6 degrees */

/*
 * drive_status_t drive_cmd_build(const drive_solution_t *sol, const drive_board_t *board,
 *     fx_q16_t speed_mps, bool reverse, drive_cmd_t *cmd): R12 = sol, R13 = board,
 * R15:R14 = speed_mps, reverse and cmd on the stack. R10 walks the segments, R9 = board,
 * R8 = the segment's index, R7:R6 = alpha of |k|, R5:R4 = the wheelbase.
 */
    .section .text.drive_cmd_build,"ax",@progbits
    .global drive_cmd_build
    .type drive_cmd_build,@function
drive_cmd_build:
    push    r10
    push    r9
    push    r8
    push    r7
    push    r6
    push    r5
    push    r4
    sub     #CFRAME, r1
    tst     r12                     ; NULL pointers, the wheelbase within 0.05..4 m,
    jz      c_param                 ; counts_per_m > 0
    tst     r13
    jz      c_param
    tst     CARG+2(r1)
    jz      c_param
    mov     r12, r10
    incd    r10                     ; &sol->seg[0]
    mov     r13, r9
    mov     r14, SPEED(r1)
    mov     r15, SPEED+2(r1)
    mov     @r9, r4
    mov     2(r9), r5
    tst     r5
    jn      c_param
    jnz     1f
    cmp     #3276, r4               ; FX_Q16_ONE / 20
    jlo     c_param
1:  cmp     #4, r5
    jlo     2f
    jne     c_param
    tst     r4
    jnz     c_param
2:  tst     10(r9)
    jn      c_param
    jnz     3f
    tst     8(r9)
    jz      c_param
3:  clr     KABS(r1)
    clr     KABS+2(r1)
    clr     r8
seg:
    mov     @r10, r12               ; |k|
    mov     2(r10), r13
    tst     r13
    jge     4f
    inv     r12
    inv     r13
    inc     r12
    adc     r13
4:  tst     r12
    jnz     5f
    tst     r13
    jnz     5f
    clr     r6                      ; a straight: alpha 0, the counts as they are
    clr     r7
    clr     SEC(r1)
    clr     SEC+2(r1)
    clr     KABS(r1)
    clr     KABS+2(r1)
    jmp     7f
5:  cmp     KABS(r1), r12           ; the magnitude in hand: alpha and sec as they are
    jne     6f
    cmp     KABS+2(r1), r13
    jeq     7f
6:  mov     r12, KABS(r1)           ; lk = L |k|, alpha = atan(lk), sec = hypot(1, lk)
    mov     r13, KABS+2(r1)
    mov     r4, r14
    mov     r5, r15
    call    #fx_mul_q16
    mov     r12, SEC(r1)
    mov     r13, SEC+2(r1)
    clr     r14
    mov     #0x1000, r15
    call    #fx_atan_ratio
    mov     r12, r6
    mov     r13, r7
    mov     SEC(r1), r14
    mov     SEC+2(r1), r15
    clr     r12
    mov     #0x1000, r13
    call    #fx_hypot
    tst     r13                     ; over INT32_MAX: no Q4.28
    jn      c_range
    mov     r12, SEC(r1)
    mov     r13, SEC+2(r1)
7:  cmp     #STEER_LIMIT_HI, r7     ; the steering byte
    jhs     c_range
    mov     r7, r14
    add     #0x40, r14
    mov     #7, r11
8:  rra     r14
    dec     r11
    jnz     8b
    mov     r6, r12
    mov     r7, r13
    mov     #128, r15
    tst     2(r10)
    jge     9f
    inv     r12                     ; a right turn: -alpha, 128 + counts
    inv     r13
    inc     r12
    adc     r13
    add     r14, r15
    jmp     10f
9:  sub     r14, r15
10: mov     r1, r11
    add     r8, r11
    mov.b   r15, CMD(r11)           ; steer[i]
    add     r8, r11
    add     r8, r11
    add     r8, r11
    mov     r12, CMD+6(r11)         ; alpha[i]
    mov     r13, CMD+8(r11)
    mov     4(r10), r12             ; counts = s counts_per_m (sec / 2^28)
    mov     6(r10), r13
    mov     8(r9), r14
    mov     10(r9), r15
    call    #fx_mul_q16
    tst     SEC(r1)
    jnz     11f
    tst     SEC+2(r1)
    jz      12f
11: mov     r12, CNT(r1)
    mov     r13, CNT+2(r1)
    mov     #28, 0(r1)
    mov     r1, r11
    add     #CNT, r11
    mov     r11, 2(r1)
    mov     SEC(r1), r14
    mov     SEC+2(r1), r15
    call    #fx_mul_shift
    tst.b   r12
    jz      c_range
    mov     CNT(r1), r12
    mov     CNT+2(r1), r13
12: cmp     #0x00FF, r13            ; >= 255.5 counts: over the byte
    jlo     13f
    jne     c_range
    cmp     #0x8000, r12
    jhs     c_range
13: add     #0x8000, r12            ; rounded
    adc     r13
    mov     r1, r11
    add     r8, r11
    mov.b   r13, CMD+2(r11)         ; arc[i]
    add     #12, r10
    inc     r8
    cmp     #2, r8
    jne     seg
    mov     SPEED(r1), r12          ; the speed byte
    mov     SPEED+2(r1), r13
    mov.b   CARG(r1), r14
    mov     r9, r15
    mov     r1, r11
    add     #CMD+4, r11
    mov     r11, 0(r1)
    call    #drive_speed_counts
    tst     r12
    jnz     c_exit
    mov     #2, r14                 ; D7: short arcs
    cmp.b   16(r9), CMD+2(r1)
    jhs     14f
    clr.b   CMD+2(r1)
    dec     r14
14: cmp.b   16(r9), CMD+3(r1)
    jhs     15f
    dec     r14
15: mov.b   r14, CMD+5(r1)
    mov     CARG+2(r1), r11         ; *cmd = c
    mov     r1, r14
    add     #CMD, r14
    mov     #7, r15
16: mov     @r14+, r12
    mov     r12, 0(r11)
    incd    r11
    dec     r15
    jnz     16b
    clr     r12
c_exit:
    add     #CFRAME, r1
    pop     r4
    pop     r5
    pop     r6
    pop     r7
    pop     r8
    pop     r9
    pop     r10
    ret
c_param:
    mov     #DRIVE_ERR_PARAM_N, r12
    jmp     c_exit
c_range:
    mov     #DRIVE_ERR_RANGE_N, r12
    jmp     c_exit

/*
 * drive_status_t drive_speed_counts(fx_q16_t speed_mps, bool reverse,
 *     const drive_board_t *board, int8_t *out): R13:R12 = speed_mps, R14 = reverse,
 * R15 = board, out on the stack. round(v / speed_lsb), negated for reverse travel.
 */
    .section .text.drive_speed_counts,"ax",@progbits
    .global drive_speed_counts
    .type drive_speed_counts,@function
drive_speed_counts:
    push    r10
    sub     #8, r1                  ; outgoing arguments, then the counts at 4(SP)
    mov.b   r14, r10
    tst     r15                     ; a board with speed_lsb > 0, a speed >= 0
    jz      3f
    tst     14(r15)
    jn      3f
    jnz     1f
    tst     12(r15)
    jz      3f
1:  tst     r13
    jn      3f
    clr     0(r1)                   ; fx_div_shift(speed, lsb, 0, &counts)
    mov     r1, r14
    add     #4, r14
    mov     r14, 2(r1)
    mov     12(r15), r14
    mov     14(r15), r15
    call    #fx_div_shift
    mov     #DRIVE_ERR_RANGE_N, r14 ; over 127 counts
    tst.b   r12
    jz      4f
    tst     6(r1)
    jnz     4f
    mov     4(r1), r12
    cmp     #128, r12
    jhs     4f
    tst.b   r10
    jz      2f
    inv     r12
    inc     r12
2:  mov     12(r1), r13
    mov.b   r12, 0(r13)
    clr     r14
    jmp     4f
3:  mov     #DRIVE_ERR_PARAM_N, r14
4:  mov     r14, r12
    add     #8, r1
    pop     r10
    ret
