/*
 * nmi.S - the entry of the NMI (the RST/NMI pin in NMI mode: the nav board's coordinate
 * request). Accepting the NMI clears NMIIE; SLAU144 (non-maskable interrupts) allows setting
 * it inside the handler only as the last instruction before RETI, or NMIs nest and grow the
 * stack. C cannot place that instruction after the epilogue's register pops, so this entry
 * saves the registers a C function may clobber (R11-R15, TI's EABI), runs
 * hal_isr_nmi_body() (hal/msp430/edge.c: clear NMIIFG, call the portable handler),
 * restores them and re-enables NMIIE right before RETI. A request that arrived meanwhile
 * (NMIIFG set again) is then taken on top of this frame's 4 bytes (PC, SR) alone: one level,
 * which tools/stack_bound.py counts (docs/stack.md).
 */
#include "f2618.h"
#include "hal/pinmap.h"

    .global CY_VECTOR_SYMBOL(HAL_VEC_NMI)
    .set CY_VECTOR_SYMBOL(HAL_VEC_NMI), hal_isr_nmi

    .section .text.hal_isr_nmi,"ax",@progbits
    .global hal_isr_nmi
    .type hal_isr_nmi,@function
hal_isr_nmi:
    push    r15
    push    r14
    push    r13
    push    r12
    push    r11
    call    #hal_isr_nmi_body
    pop     r11
    pop     r12
    pop     r13
    pop     r14
    pop     r15
    bis.b   #NMIIE, &IE1
    reti
    .size hal_isr_nmi, .-hal_isr_nmi
