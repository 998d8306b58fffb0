/*
 * main_msp430.c - reset-to-main-loop of the main board image, with its built-in mission
 * (generated from sim/scenarios/table_6_1_1987_full.json by tools/gen_mission.py: the
 * thesis's Table 6-1 path and our nine beacons). The run starts at once; a board in a vehicle
 * would wait for the operator's go.
 */
#include "hal/console.h"
#include "hal/cpu.h"
#include "hal/fault.h"
#include "hal/irq.h"
#include "main_board.h"
#include "mission/mission.h"
#include "mission_builtin.h"

static const optical_xy_t beacons[MISSION_N_BEACONS] = MISSION_BEACONS;
static const optical_xy8_t beacons8[MISSION_N_BEACONS] = MISSION_BEACONS8;
static const uint32_t reflectors_dk[MISSION_N_BEACONS] = MISSION_DK;
/* RAM: the board prepares the points in place. */
static drive_path_point_t path[MISSION_N_PATH] = MISSION_PATH;

/* The download, a constant in flash (the board keeps it by reference). */
static const main_board_config_t cfg = {
    .map = {beacons, MISSION_N_BEACONS, beacons8, MISSION_ORIGIN_X, MISSION_ORIGIN_Y, reflectors_dk,
            MISSION_DKMIN},
    .path = path,
    .n_path = MISSION_N_PATH,
    .start = MISSION_START,
    .board = DRIVE_BOARD_SEED_WITH(MISSION_WHEELBASE, MISSION_MIN_RADIUS),
    .path_cfg = MISSION_PATH_CONFIG(MISSION_MIN_RADIUS),
    .seq_cfg = MISSION_SEQ_CONFIG(MISSION_FULL_TRAVEL ? DRIVE_MODE_FULL : DRIVE_MODE_SIMPLIFIED,
                                  MISSION_BLIND_DISTANCE),
    .counts_per_turn = MISSION_COUNTS,
    .optical = OPTICAL_CONFIG(MISSION_GONIO_NOISE, MISSION_GYRO_STEP),
    .link = MISSION_LINK_CONFIG(LINKMSG_NODE_MAIN),
};

int main(void)
{
    hal_cpu_init();
    if (main_board_init(&cfg) != DRIVE_OK)
        hal_fault(HAL_FAULT_BAD_ARGUMENT);
    hal_console_puts("cyclopion main board: " MISSION_NAME "\r\n");
    main_board_stats_t st;
    main_board_stats(&st);
    if (st.can_error != 0)
        hal_console_puts("CAN controller does not answer: no board link, no travel\r\n");
    hal_irq_enable();
    main_board_start();
    for (;;) {
        main_board_poll();
        hal_cpu_idle();
    }
}
