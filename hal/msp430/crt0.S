/*
 * crt0.S - reset entry of every MSP430 image.
 * Holds the watchdog before anything else (it would reset the part after 32768 SMCLK
 * cycles), sets the stack to the top of RAM, lets cy_crt_init copy .data and clear .bss,
 * runs main and, should main return, lets the console's last bytes out (hal_console_flush)
 * and stops the CPU for good in cy_halt.
 */
#include "f2618.h"

    .section .text.cy_reset,"ax",@progbits
    .global cy_reset
    .type cy_reset,@function
cy_reset:
    mov.w   #WDTPW|WDTHOLD, &WDTCTL
    mov.w   #__stack_top, r1
    call    #cy_crt_init
    call    #main
    call    #hal_console_flush
    .global cy_halt
    .type cy_halt,@function
cy_halt:
    dint
    nop
    bis.w   #SR_CPUOFF|SR_OSCOFF|SR_SCG0|SR_SCG1, r2 ; LPM4: every clock off
    jmp     cy_halt
