/*
 * vm.S - MSP430 versions of drive_vm_run, drive_rot and drive_poly (drive_internal.h; the
 * portable C in vm.c defines the results: the same fx calls in the same order, so both worlds
 * agree bit for bit, which tests/vectors/drive_vectors.c checks).
 *
 * Registers as clang emits calls (TI EABI): 32-bit arguments in R13:R12 and R15:R14 (R12 the
 * low word), the rest on the stack; 32-bit results in R13:R12; R11..R15 may be clobbered,
 * R4..R10 are preserved (the fx functions preserve them too).
 */
#include "../drive_internal.h"

/*
 * void drive_vm_run(int32_t *v, const uint8_t *prog): R12 = v, R13 = prog.
 * Every instruction first has its destination's address (R8), operand a (R13:R12, its
 * address in R7) and the byte b (R14) fetched, then jumps through the table by opcode: about
 * 40 cycles per instruction besides the fx call it makes, 30 for ADD and SUB.
 */
    .section .text.drive_vm_run,"ax",@progbits
    .global drive_vm_run
    .type drive_vm_run,@function
drive_vm_run:
    push    r10
    push    r9
    push    r8
    push    r7
    mov     r12, r9                 ; the frame
    mov     r13, r10                ; the instruction pointer
next:
    mov.b   @r10+, r11              ; opcode (even)
    mov.b   @r10+, r8               ; &d
    add     r9, r8
    mov.b   @r10+, r7               ; &a, a
    add     r9, r7
    mov     @r7, r12
    mov     2(r7), r13
    mov.b   @r10+, r14              ; b
    br      vm_ops(r11)

op_add:
    add     r9, r14
    add     @r14+, r12
    addc    @r14, r13
    jmp     store
op_sub:
    add     r9, r14
    sub     @r14+, r12
    subc    @r14, r13
    jmp     store
op_abs:
    tst     r13
    jge     store
op_neg:
    inv     r12
    inv     r13
    inc     r12
    adc     r13
    jmp     store
op_half:                            ; toward zero: a negative a is raised by one first
    tst     r13
    jge     1f
    inc     r12
    adc     r13
1:  rra     r13
    rrc     r12
    jmp     store
op_shl:
    tst     r14
    jz      store
1:  rla     r12
    rlc     r13
    dec     r14
    jnz     1b
    jmp     store
op_mulk:
    add     #drive_vm_k, r14
    jmp     1f
op_mul:
    add     r9, r14
1:  mov     2(r14), r15
    mov     @r14, r14
    call    #fx_mul_q30
    jmp     store
op_poly:
    add     #drive_vm_k, r14
    call    #drive_poly
    jmp     store
op_atan2:
    add     r9, r14
    mov     2(r14), r15
    mov     @r14, r14
    call    #fx_atan2
store:
    mov     r12, 0(r8)
    mov     r13, 2(r8)
    jmp     next
op_sincos:
    mov     r8, r14
    mov     r8, r15
    add     #4, r15
    call    #fx_sincos
    jmp     next
op_rot:
    add     r9, r14
    mov     2(r14), r15
    mov     @r14, r14
    mov     r8, r12
    mov     r7, r13
    call    #drive_rot
    jmp     next
op_end:
    pop     r7
    pop     r8
    pop     r9
    pop     r10
    ret

    .section .rodata.vm_ops,"a",@progbits
    .p2align 1
vm_ops:                             ; by opcode / 2 (drive_internal.h)
    .word   op_end, op_add, op_sub, op_neg, op_abs, op_half, op_shl, op_mul, op_mulk
    .word   op_poly, op_atan2, op_sincos, op_rot
    .if DRIVE_OP_ROT != 24
    .error "vm_ops: the opcodes of drive_internal.h changed"
    .endif

/*
 * void drive_rot(int32_t out[2], const int32_t xy[2], fx_angle_t a): R12 = out, R13 = xy,
 * R15:R14 = a. out[0] = x c + y s, out[1] = y c - x s with (s, c) = fx_sincos(a).
 */
    .section .text.drive_rot,"ax",@progbits
    .global drive_rot
    .type drive_rot,@function
drive_rot:
    push    r10
    push    r9
    push    r8
    push    r7
    sub     #8, r1                  ; s at 0(SP), c at 4(SP)
    mov     r12, r10                ; out
    mov     r13, r9                 ; xy
    mov     r14, r12
    mov     r15, r13
    mov     r1, r14
    mov     r1, r15
    add     #4, r15
    call    #fx_sincos
    mov     @r9, r12                ; x c
    mov     2(r9), r13
    mov     4(r1), r14
    mov     6(r1), r15
    call    #fx_mul_q30
    mov     r12, r7
    mov     r13, r8
    mov     4(r9), r12              ; + y s
    mov     6(r9), r13
    mov     @r1, r14
    mov     2(r1), r15
    call    #fx_mul_q30
    add     r7, r12
    addc    r8, r13
    mov     r12, 0(r10)
    mov     r13, 2(r10)
    mov     4(r9), r12              ; y c
    mov     6(r9), r13
    mov     4(r1), r14
    mov     6(r1), r15
    call    #fx_mul_q30
    mov     r12, r7
    mov     r13, r8
    mov     @r9, r12                ; - x s
    mov     2(r9), r13
    mov     @r1, r14
    mov     2(r1), r15
    call    #fx_mul_q30
    sub     r12, r7
    subc    r13, r8
    mov     r7, 4(r10)
    mov     r8, 6(r10)
    add     #8, r1
    pop     r7
    pop     r8
    pop     r9
    pop     r10
    ret

/*
 * int32_t drive_poly(int32_t x, const int32_t *k): R13:R12 = x, R14 = k -> R13:R12.
 * x2 = x x; t = 0; three times t = x2 (k[i] + t) for i = 2, 1, 0; 2^30 + t. (The first step,
 * x2 (k[2] + 0), is the C version's x2 k[2].)
 */
    .section .text.drive_poly,"ax",@progbits
    .global drive_poly
    .type drive_poly,@function
drive_poly:
    push    r10
    push    r9
    push    r8
    push    r7
    mov     r14, r10
    add     #8, r10                 ; &k[2]
    mov     r12, r14
    mov     r13, r15
    call    #fx_mul_q30
    mov     r12, r8                 ; x2
    mov     r13, r9
    clr     r12
    clr     r13
    mov     #3, r7
1:  add     @r10, r12               ; k[i] + t
    addc    2(r10), r13
    mov     r12, r14
    mov     r13, r15
    mov     r8, r12
    mov     r9, r13
    call    #fx_mul_q30
    sub     #4, r10
    dec     r7
    jnz     1b
    add     #0x4000, r13            ; + 2^30
    pop     r7
    pop     r8
    pop     r9
    pop     r10
    ret
