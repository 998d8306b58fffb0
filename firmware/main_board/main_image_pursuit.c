/*
 * main_image_pursuit.c - the built-in mission of the pursuit image (main_board_pursuit.elf;
 * see main_image.h), generated from sim/scenarios/seed002_straight_pursuit.json by
 * tools/gen_mission.py: seed 002's straight path, its pursuit parameters and one position
 * receiver on USCI_A1. The beacon map, the goniometer and the double-arc travel's settings are
 * the beacon image's: pursuit mode reads none of them.
 */
#include "main_image.h"
#include "mission/mission.h"
#include "mission_builtin.h"

/* RAM: the configuration's points are writable (the beacon travel prepares them in place). */
static drive_path_point_t path[MISSION_N_PATH] = MISSION_PATH;

static const main_pursuit_config_t pursuit = {
    .law = MISSION_PURSUIT_LAW,
    .rx = MISSION_POSRX_CONFIG,
    .baud = MISSION_POSRX_BAUD,
    .receivers = 1u,
    .heading = MISSION_PURSUIT_HEADING,
};

const main_board_config_t main_image_cfg = {
    .path = path,
    .n_path = MISSION_N_PATH,
    .start = MISSION_START,
    .board = DRIVE_BOARD_SEED_WITH(MISSION_WHEELBASE, MISSION_MIN_RADIUS),
    .link = MISSION_LINK_CONFIG(LINKMSG_NODE_MAIN),
    .pursuit = &pursuit,
};

const char main_image_banner[] = "cyclopion main board: " MISSION_NAME "\r\n";

const char main_image_no_link[] =
    "CAN controller does not answer: no board link (pursuit goes on without it)\r\n";
