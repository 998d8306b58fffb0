/*
 * main_msp430.c - reset-to-main-loop of the main board image.
 */
#include "hal/console.h"
#include "hal/cpu.h"
#include "hal/irq.h"
#include "main_board.h"

int main(void)
{
    hal_cpu_init();
    main_board_init();
    hal_console_puts("cyclopion main board\r\n");
    hal_irq_enable();
    for (;;) {
        main_board_poll();
        hal_cpu_idle();
    }
}
