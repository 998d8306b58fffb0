/*
 * mission.h - a scenario turned into what the boards are told before a run (the base
 * station's download): the main board's map, path, vehicle and travel configuration, the nav
 * board's vehicle, sensors and initial vector; and the nominal path that cross_track_m is
 * measured against (docs/interfaces.md: the chain of double arcs the drive routine's solver gives
 * between consecutive prescribed poses, the start first, computed once from them).
 */
#ifndef SIM_MISSION_H
#define SIM_MISSION_H

#include <stddef.h>

#include "main_board.h"
#include "nav_board.h"
#include "sim/path.h"
#include "sim/scenario.h"

typedef struct {
    main_board_config_t main; /* kept by reference by the main board, with what it points to */
    nav_board_config_t nav;
    optical_xy_t beacons[OPTICAL_MAX_BEACONS];
    optical_refl_t refl[OPTICAL_MAX_BEACONS];
    uint32_t dk[OPTICAL_MAX_BEACONS];
    optical_xy8_t beacons8[OPTICAL_MAX_BEACONS];
    drive_path_point_t points[MAIN_BOARD_MAX_PATH];
    main_pursuit_config_t pursuit; /* mode pursuit: main.pursuit points here */
    sim_path_t nominal;
} sim_mission_t;

/**
 * Build the download of @p sc into @p m (which must outlive the run). Returns 0, or -1 with a
 * message naming the offending key and value in @p err: more path points or beacons than the
 * main board holds, beacons it cannot map (two of them coincide), a prescribed pose the solver
 * cannot reach from the previous one with the vehicle's minimum radius; in mode pursuit,
 * parameters the pursuit refuses (docs/pursuit.md).
 */
int sim_mission_build(sim_mission_t *m, const sim_scenario_t *sc, char *err, size_t errlen);

#endif
