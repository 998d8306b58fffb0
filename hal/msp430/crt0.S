/*
 * crt0.S - reset entry of every MSP430 image.
 * Holds the watchdog before anything else (it would reset the part after 32768 SMCLK
 * cycles), sets the stack to the top of RAM, lets cy_crt_init copy .data and clear .bss,
 * runs main and, should main return, stops the CPU for good in cy_halt.
 */
    .section .text.cy_reset,"ax",@progbits
    .global cy_reset
    .type cy_reset,@function
cy_reset:
    mov.w   #0x5a80, &0x0120        ; WDTCTL = WDTPW | WDTHOLD
    mov.w   #__stack_top, r1
    call    #cy_crt_init
    call    #main
    .global cy_halt
    .type cy_halt,@function
cy_halt:
    dint
    nop
    bis.w   #0x00f0, r2             ; CPUOFF | OSCOFF | SCG0 | SCG1: LPM4
    jmp     cy_halt
