/*
 * main_msp430.c - reset-to-main-loop of the nav board image. The built-in configuration is
 * the Cyclopion vehicle of seed 000 (wheelbase 30 in, odometer pulse 0.01 in, gyro step 0.25
 * degrees) standing at the first point of the thesis's Table 6-1 run (36 in, 142 in, 270
 * degrees); it stops after 5 m without an optical fix.
 */
#include "hal/console.h"
#include "hal/cpu.h"
#include "hal/fault.h"
#include "hal/irq.h"
#include "nav_board.h"

static const nav_board_config_t config = {
    {49938l /* 0.762 m */, 279275970ul /* 0.254 mm * 2^40 */,
     195468235376ull /* 0.25 degrees: 2^48 / 1440 turns */, 327680l /* 5 m */},
    {59926l /* 0.9144 m */, 236375l /* 3.6068 m */, 0xC0000000ul /* 270 degrees */},
};

int main(void)
{
    hal_cpu_init();
    if (nav_board_init(&config) != 0)
        hal_fault(HAL_FAULT_BAD_ARGUMENT);
    hal_console_puts("cyclopion nav board\r\n");
    hal_irq_enable();
    for (;;) {
        nav_board_poll();
        hal_cpu_idle();
    }
}
