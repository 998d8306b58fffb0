/*
 * kcheck_demo.S - kcheck_demo_mac (kcheck_demo.h) on the 16 x 16 hardware multiplier, with
 * interrupts held off while it is in use. R12 = acc, R13 = a, R14 = b -> R13:R12 = a * b.
 * The fields of kcheck_demo_acc_t: kcheck_demo_offsets.h, generated from kcheck_demo_offsets.c.
 */
#include "kcheck_demo_offsets.h"

    .set MPYS,  0x0132
    .set OP2,   0x0138
    .set RESLO, 0x013a
    .set RESHI, 0x013c

    .section .text.kcheck_demo_mac,"ax",@progbits
    .global kcheck_demo_mac
    .type kcheck_demo_mac,@function
kcheck_demo_mac:
    push    r2
    dint
    nop
    mov     r13, &MPYS
    mov     r14, &OP2
    mov     &RESLO, r14
    mov     &RESHI, r15
    pop     r2
    add     r14, KCHECK_DEMO_SUM(r12)
    addc    r15, KCHECK_DEMO_SUM+2(r12)
    add     #1, KCHECK_DEMO_CALLS(r12)
    mov     r14, r12
    mov     r15, r13
    ret
    .size kcheck_demo_mac, .-kcheck_demo_mac
