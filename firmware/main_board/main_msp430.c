/*
 * main_msp430.c - reset-to-main-loop of both main board images, each with its built-in
 * mission (main_image.h): the beacon image (main_image_beacon.c) and the pursuit image
 * (main_image_pursuit.c). The run starts at once; a board in a vehicle would wait for the
 * operator's go.
 */
#include "hal/console.h"
#include "hal/cpu.h"
#include "hal/fault.h"
#include "hal/irq.h"
#include "main_board.h"
#include "main_image.h"

int main(void)
{
    hal_cpu_init();
    if (main_board_init(&main_image_cfg) != DRIVE_OK)
        hal_fault(HAL_FAULT_BAD_ARGUMENT);
    hal_console_puts(main_image_banner);
    main_board_stats_t st;
    main_board_stats(&st);
    hal_console_puts(st.can_error != 0 ? main_image_no_link : "board link up\r\n");
    hal_irq_enable();
    main_board_start();
    for (;;) {
        main_board_poll();
        hal_cpu_idle();
    }
}
