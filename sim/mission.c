/*
 * mission.c - a scenario turned into the boards' download and the nominal path (see
 * mission.h).
 */
#include "sim/mission.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "drive/drive.h"
#include "drive/drive_path.h"
#include "fx/fx_host.h"
#include "hal/uart.h"
#include "mission/mission.h"
#include "sim/canbus.h"

static fx_q16_t q16(double v)
{
    return fx_q16_from_double(v);
}

static drive_pose_t dpose(double x, double y, double th)
{
    drive_pose_t p = {q16(x), q16(y), fx_angle_from_rad(th)};
    return p;
}

static int build_nominal(sim_mission_t *m, const sim_scenario_t *sc, char *err, size_t errlen)
{
    const main_board_config_t *mc = &m->main;
    drive_pose_t from = mc->start;
    sim_pose_t s0 = {sc->start_x, sc->start_y, sc->start_heading};
    m->nominal.n = 0;
    for (size_t i = 0; i < sc->n_path; i++) {
        /* The board's nominal leg: a turn over 90 degrees is two double arcs through the pose
         * path preparation inserts (drive_leg_solve()). */
        drive_pose_t to = mc->path[i].pose;
        drive_leg_t leg;
        drive_status_t st =
            drive_leg_solve(&from, &to, mc->path_cfg.nominal_radius, mc->path_cfg.reverse, &leg);
        if (st != DRIVE_OK) {
            snprintf(err, errlen,
                     "path[%zu]: no double arc from the previous point: %s (min_radius_m %.3f)", i,
                     drive_status_text(st), sc->min_radius);
            return -1;
        }
        for (int k = 0; k < 2 * leg.parts; k++) {
            const drive_segment_t *g = &leg.sol[k / 2].seg[k % 2];
            double len = fx_q16_to_double(g->length);
            if (len <= 0)
                continue;
            double kap = (double)g->curvature / (double)(1l << DRIVE_CURV_SHIFT);
            /* Each leg starts at its prescribed pose (the solver lands within 0.05 mm). */
            if (k == 0 || m->nominal.n == 0)
                sim_path_append_from(&m->nominal, s0, kap, len, mc->path_cfg.reverse);
            else
                sim_path_append(&m->nominal, s0, kap, len, mc->path_cfg.reverse);
        }
        from = to;
        s0 = (sim_pose_t){sc->path[i].x, sc->path[i].y, sc->path[i].heading};
    }
    return 0;
}

/* Mode pursuit: the main board's pursuit parameters, checked as it will check them. */
static int build_pursuit(sim_mission_t *m, const sim_scenario_t *sc, char *err, size_t errlen)
{
    const sim_pursuit_t *pu = &sc->pursuit;
    const sim_position_source_t *src = &sc->src;
    if (src->baud != HAL_UART_BAUD_9600 && src->baud != HAL_UART_BAUD_115200) {
        snprintf(err, errlen, "position_source.baud: %u: the serial line runs at 9600 or 115200",
                 src->baud);
        return -1;
    }
    for (size_t i = 0; i < src->n_outages; i++)
        if (src->outage[i].to < src->outage[i].from) {
            snprintf(err, errlen, "position_source.outages[%zu].to_s: %g is before from_s (%g)", i,
                     src->outage[i].to, src->outage[i].from);
            return -1;
        }
    if (pu->slow_after > 0 && pu->stop_after <= pu->slow_after) {
        snprintf(err, errlen, "pursuit.stop_after_s: %g is not after slow_after_s (%g)",
                 pu->stop_after, pu->slow_after);
        return -1;
    }
    if (pu->speed > pu->max_speed) {
        snprintf(err, errlen, "pursuit.speed_mps: %g is above max_speed_mps (%g)", pu->speed,
                 pu->max_speed);
        return -1;
    }
    if (pu->heading == SIM_PURSUIT_HEADING_RECEIVERS && src->n_receivers != 2) {
        snprintf(err, errlen,
                 "pursuit.heading: \"receivers\" needs two position_source.receivers (%zu given)",
                 src->n_receivers);
        return -1;
    }
    main_pursuit_config_t *pc = &m->pursuit;
    pursuit_config_t *law = &pc->law;
    law->speed = q16(pu->speed);
    law->max_speed = q16(pu->max_speed);
    law->k = q16(pu->k);
    law->activation_ms = (uint16_t)lround(fmin(pu->activation * 1000.0, 65535.0));
    law->threshold = q16(pu->threshold_pct / 100.0);
    law->max_steer = fx_angle_from_rad(atan(sc->wheelbase / sc->min_radius));
    law->slow_after_ms = (uint16_t)lround(pu->slow_after * 1000.0);
    law->stop_after_ms = (uint16_t)lround(pu->stop_after * 1000.0);
    law->regulate = pu->regulate;
    if (src->n_receivers == 2) {
        double dx = src->receiver[0].x - src->receiver[1].x,
               dy = src->receiver[0].y - src->receiver[1].y;
        law->pair_sep = q16(hypot(dx, dy));
        law->pair_angle = fx_angle_from_rad(atan2(dy, dx));
    }
    law->pair_tol = q16(pu->pair_tol);
    pc->rx.min_update_mm = (uint16_t)lround(pu->min_update * 1000.0);
    pc->rx.max_speed_mm_s = (uint16_t)lround(pu->max_speed * 1000.0);
    pc->baud = src->baud;
    pc->receivers = src->n_receivers == 2 ? 2u : 1u;
    pc->heading = pu->heading == SIM_PURSUIT_HEADING_RECEIVERS ? MAIN_HEADING_RECEIVERS
                  : pu->heading == SIM_PURSUIT_HEADING_NAV     ? MAIN_HEADING_NAV
                                                               : MAIN_HEADING_POSITIONS;
    if (!pursuit_config_ok(law)) {
        snprintf(err, errlen, "pursuit: parameters the main board refuses (docs/pursuit.md)");
        return -1;
    }
    /* every goal point apart from the one before (the start first) */
    double px = sc->start_x, py = sc->start_y;
    for (size_t i = 0; i < sc->n_path; i++) {
        if (hypot(sc->path[i].x - px, sc->path[i].y - py) < 1.0 / 256) {
            snprintf(err, errlen,
                     "path[%zu]: (%g, %g) is the goal point before it: pursuit needs segments "
                     "of 4 mm or more",
                     i, sc->path[i].x, sc->path[i].y);
            return -1;
        }
        px = sc->path[i].x;
        py = sc->path[i].y;
    }
    m->main.pursuit = pc;
    return 0;
}

int sim_mission_build(sim_mission_t *m, const sim_scenario_t *sc, char *err, size_t errlen)
{
    memset(m, 0, sizeof *m);
    if (sc->n_path > MAIN_BOARD_MAX_PATH) {
        snprintf(err, errlen, "path: %zu points, the main board holds at most %d", sc->n_path,
                 MAIN_BOARD_MAX_PATH);
        return -1;
    }
    if (sc->world.n_beacons > OPTICAL_MAX_BEACONS) {
        snprintf(err, errlen, "beacons: %zu, the main board's map holds at most %d",
                 sc->world.n_beacons, OPTICAL_MAX_BEACONS);
        return -1;
    }
    main_board_config_t *mc = &m->main;
    for (size_t i = 0; i < sc->world.n_beacons; i++) {
        m->beacons[i].x = q16(sc->world.beacon[i].x);
        m->beacons[i].y = q16(sc->world.beacon[i].y);
        m->refl[i].d = q16(sc->world.beacon[i].diameter);
        m->refl[i].flat = sc->world.beacon[i].kind == SIM_BEACON_KIND_FLAT;
    }
    uint8_t bad[2];
    int8_t st = optical_map_compile(&mc->map, m->beacons, m->refl, (uint8_t)sc->world.n_beacons,
                                    m->beacons8, m->dk, bad);
    if (st == OPTICAL_E_DEGENERATE) {
        snprintf(err, errlen,
                 "beacons[%u] and beacons[%u] coincide: the main board's map refuses "
                 "them",
                 bad[0], bad[1]);
        return -1;
    }
    if (st != OPTICAL_OK) {
        snprintf(err, errlen,
                 "beacons: %zu of them; the main board needs 3..%d within +-128 m of one "
                 "point (a site of at most 256 m by 256 m)",
                 sc->world.n_beacons, OPTICAL_MAX_BEACONS);
        return -1;
    }
    for (size_t i = 0; i < sc->n_path; i++) {
        m->points[i].pose = dpose(sc->path[i].x, sc->path[i].y, sc->path[i].heading);
        m->points[i].speed = q16(sc->path[i].speed);
        m->points[i].nsub = 0;
    }
    mc->path = m->points;
    mc->n_path = (uint8_t)sc->n_path;
    mc->start = dpose(sc->start_x, sc->start_y, sc->start_heading);
    drive_board_t seed_board = DRIVE_BOARD_SEED;
    mc->board = seed_board;
    mc->board.wheelbase = q16(sc->wheelbase);
    mc->board.min_radius = q16(sc->min_radius);
    mc->path_cfg = (drive_path_config_t)MISSION_PATH_CONFIG(q16(sc->min_radius));
    /* The blind distance: one value for both boards (the sequencer's and the nav board's G6). */
    fx_q16_t blind = q16(sc->blind_distance);
    mc->seq_cfg = (drive_seq_config_t)MISSION_SEQ_CONFIG(
        sc->mode == SIM_SCENARIO_MODE_FULL ? DRIVE_MODE_FULL : DRIVE_MODE_SIMPLIFIED, blind);
    mc->counts_per_turn = (uint16_t)sc->counts;
    optical_config_default(&mc->optical);
    /* the sighting's error bounds of this goniometer and gyro */
    fx_angle_t noise = fx_angle_from_rad(sc->gonio_noise), step = fx_angle_from_rad(sc->gyro_step);
    mc->optical.bearing_err = OPTICAL_BEARING_ERR(noise);
    mc->optical.bearing_err_moving = OPTICAL_BEARING_ERR_MOVING(noise, step);

    if (build_nominal(m, sc, err, errlen))
        return -1;
    if (sc->mode == SIM_SCENARIO_MODE_PURSUIT && build_pursuit(m, sc, err, errlen))
        return -1;

    gnav_config_t *g = &m->nav.gnav;
    g->wheelbase = q16(sc->wheelbase);
    g->dl_q40 = (uint32_t)llround(sc->dl * 1099511627776.0);
    g->gyro_step_q48 = (uint64_t)llround(sc->gyro_step / (2 * M_PI) * 281474976710656.0);
    g->stop_distance = blind;
    m->nav.start.x = q16(sc->start_x + sc->start_err_x);
    m->nav.start.y = q16(sc->start_y + sc->start_err_y);
    m->nav.start.heading = fx_angle_from_rad(sc->start_heading + sc->start_err_heading);
    mc->link = sim_canbus_link_config(sc, LINKMSG_NODE_MAIN);
    m->nav.link = sim_canbus_link_config(sc, LINKMSG_NODE_NAV);
    return 0;
}
