/*
 * main_msp430.c - reset-to-main-loop of the nav board image, with its built-in mission
 * (generated from sim/scenarios/table_6_1_1987_full.json by tools/gen_mission.py): the
 * vehicle of seed 000 at the start of the thesis's Table 6-1 run; it asks for a stop after
 * MISSION_BLIND_DISTANCE without an optical fix (the scenario's blind_distance_m, which the
 * main board's travel sequence watches too).
 */
#include "hal/console.h"
#include "hal/cpu.h"
#include "hal/fault.h"
#include "hal/irq.h"
#include "mission/mission.h"
#include "mission_builtin.h"
#include "nav_board.h"

static const nav_board_config_t config = {
    {MISSION_WHEELBASE, MISSION_DL_Q40, MISSION_GYRO_STEP_Q48, MISSION_BLIND_DISTANCE},
    MISSION_START,
    MISSION_LINK_CONFIG(LINKMSG_NODE_NAV),
};
int main(void)
{
    hal_cpu_init();
    if (nav_board_init(&config) != 0)
        hal_fault(HAL_FAULT_BAD_ARGUMENT);
    hal_console_puts("cyclopion nav board\r\n");
    nav_board_stats_t st;
    nav_board_stats(&st);
    if (st.can_error != 0)
        hal_console_puts("CAN controller does not answer: no board link\r\n");
    hal_irq_enable();
    for (;;) {
        nav_board_poll();
        hal_cpu_idle();
    }
}
