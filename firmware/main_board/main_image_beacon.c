/*
 * main_image_beacon.c - the built-in mission of the beacon image (main_board.elf; see
 * main_image.h), generated from sim/scenarios/table_6_1_1987_full.json by tools/gen_mission.py:
 * the thesis's Table 6-1 path and our nine beacons.
 */
#include "main_image.h"
#include "mission/mission.h"
#include "mission_builtin.h"

static const optical_xy_t beacons[MISSION_N_BEACONS] = MISSION_BEACONS;
static const optical_xy8_t beacons8[MISSION_N_BEACONS] = MISSION_BEACONS8;
static const uint32_t reflectors_dk[MISSION_N_BEACONS] = MISSION_DK;
/* RAM: the board prepares the points in place. */
static drive_path_point_t path[MISSION_N_PATH] = MISSION_PATH;

const main_board_config_t main_image_cfg = {
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

const char main_image_banner[] = "cyclopion main board: " MISSION_NAME "\r\n";

const char main_image_no_link[] = "CAN controller does not answer: no board link, no travel\r\n";
