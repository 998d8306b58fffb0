/*
 * main_msp430.c - reset-to-main-loop of the nav board image.
 */
#include "hal/console.h"
#include "hal/cpu.h"
#include "hal/irq.h"
#include "nav_board.h"

int main(void)
{
    hal_cpu_init();
    nav_board_init();
    hal_console_puts("cyclopion nav board\r\n");
    hal_irq_enable();
    for (;;) {
        nav_board_poll();
        hal_cpu_idle();
    }
}
