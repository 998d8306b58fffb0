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
#include "mission_builtin.h"

static const optical_xy_t beacons[MISSION_N_BEACONS] = MISSION_BEACONS;
/* RAM: the board prepares the points in place. */
static drive_path_point_t path[MISSION_N_PATH] = MISSION_PATH;

/* The download, on a stack frame that is gone before the main loop runs (main_board_init
 * copies what it keeps). */
static __attribute__((noinline)) void setup(void)
{
    main_board_config_t cfg = {0};
    cfg.beacons = beacons;
    cfg.n_beacons = MISSION_N_BEACONS;
    cfg.path = path;
    cfg.n_path = MISSION_N_PATH;
    cfg.start = (drive_pose_t)MISSION_START;
    cfg.board = (drive_board_t)DRIVE_BOARD_SEED;
    cfg.board.wheelbase = MISSION_WHEELBASE;
    cfg.board.min_radius = MISSION_MIN_RADIUS;
    cfg.path_cfg.nominal_radius = MISSION_MIN_RADIUS;
    cfg.path_cfg.spacing = 52429l; /* 0.8 m: the double-arc length */
    cfg.path_cfg.reverse = false;
    cfg.seq_cfg.mode = MISSION_FULL_TRAVEL ? DRIVE_MODE_FULL : DRIVE_MODE_SIMPLIFIED;
    cfg.seq_cfg.load_ms = 35;
    cfg.seq_cfg.settle_ms = 50;
    cfg.seq_cfg.stop_speed = 9830l; /* 0.15 m/s */
    cfg.seq_cfg.advance = 26214l;   /* 0.4 m */
    cfg.seq_cfg.max_fix_failures = 3;
    cfg.counts_per_turn = MISSION_COUNTS;
    optical_config_default(&cfg.optical);
    cfg.optical.beacon_diameter = MISSION_BEACON_DIAMETER;
    if (main_board_init(&cfg) != DRIVE_OK)
        hal_fault(HAL_FAULT_BAD_ARGUMENT);
}

int main(void)
{
    hal_cpu_init();
    setup();
    hal_console_puts("cyclopion main board: " MISSION_NAME "\r\n");
    hal_irq_enable();
    main_board_start();
    for (;;) {
        main_board_poll();
        hal_cpu_idle();
    }
}
