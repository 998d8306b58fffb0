/*
 * mspabi_div64.S - 64-bit divide and remainder entry points with the EABI's special
 * register convention (SLAA534): dividend in R8..R11, divisor in R12..R15 (low word first),
 * result in R12..R15. Each shim passes them on to the C implementation in mspabi.c with the
 * ordinary convention (first operand in R12..R15, second on the stack, low word lowest).
 * R4..R10 are preserved by the C function; R11 is clobbered as in any call.
 */
    .macro CY_DIV64 name, impl
    .section .text.\name,"ax",@progbits
    .global \name
    .type \name,@function
\name:
    push    r15
    push    r14
    push    r13
    push    r12
    mov     r8, r12
    mov     r9, r13
    mov     r10, r14
    mov     r11, r15
    call    #\impl
    add     #8, r1
    ret
    .endm

    CY_DIV64 __mspabi_divlli, cy_mspabi_divlli
    CY_DIV64 __mspabi_remlli, cy_mspabi_remlli
    CY_DIV64 __mspabi_divull, cy_mspabi_divull
    CY_DIV64 __mspabi_remull, cy_mspabi_remull
