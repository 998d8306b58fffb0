/*
 * telemetry.c - measurements, CSV logs, LCM messages and trace lines of a run (see
 * telemetry.h).
 */
#include "sim/telemetry.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "fx/fx_host.h"
#include "hal/pinmap.h"
#include "lcmtypes/cyclopion_drive_command_t.h"
#include "lcmtypes/cyclopion_fix_t.h"
#include "lcmtypes/cyclopion_pose_t.h"
#include "lcmtypes/cyclopion_sightings_t.h"
#include "lcmtypes/cyclopion_truth_t.h"
#include "nav_board.h"
#include "sim/clock.h"

#define DEG (M_PI / 180.0)

/* A quality in Q16 m per mrad to m per count of a 50,000-count goniometer. */
#define SIM_PER_COUNT (2.0 * M_PI / 50000.0 * 1000.0 / 65536.0)

const char *const sim_telemetry_channel[SIM_LCM_CHANNELS] = {
    "CYCLOPION_TRUTH", "CYCLOPION_POSE", "CYCLOPION_FIX", "CYCLOPION_SIGHTINGS", "CYCLOPION_DRIVE"};

/* A publish call's result (0: handed to LCM) counted for channel @p ch. */
static void published(sim_telemetry_t *tm, int ch, int rc)
{
    if (rc == 0)
        tm->lcm_published[ch]++;
    else
        tm->lcm_failed++;
}

static double wrap_deg(double d)
{
    d = fmod(d, 360.0);
    return d < 0 ? d + 360.0 : d;
}

/* ------------------------------------------------------------------ opening */

/* mkdir -p: @p dir and every missing parent. */
static int make_dirs(const char *dir, char *err, size_t errlen)
{
    char path[1024];
    if (snprintf(path, sizeof path, "%s", dir) >= (int)sizeof path) {
        snprintf(err, errlen, "--log-dir: \"%s\" is too long", dir);
        return -1;
    }
    for (char *p = path + 1;; p++) {
        if (*p != '/' && *p != '\0')
            continue;
        char c = *p;
        *p = '\0';
        struct stat st;
        if (mkdir(path, 0777) != 0 &&
            !(errno == EEXIST && stat(path, &st) == 0 && S_ISDIR(st.st_mode))) {
            if (errno == EEXIST)
                snprintf(err, errlen, "--log-dir: cannot create %s: %s is not a directory", dir,
                         path);
            else
                snprintf(err, errlen, "--log-dir: cannot create %s: %s", path, strerror(errno));
            return -1;
        }
        *p = c;
        if (c == '\0')
            return 0;
    }
}

static FILE *open_log(const char *dir, const char *name, const char *header, char *err,
                      size_t errlen)
{
    char path[1100];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    if (!f) {
        snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno));
        return NULL;
    }
    fputs(header, f);
    return f;
}

/* beacons.csv, glints.csv, walls.csv and path.csv: what does not change during the run. */
static int write_static_logs(const char *dir, const sim_scenario_t *sc, const sim_path_t *nominal,
                             char *err, size_t errlen)
{
    FILE *f = open_log(dir, "beacons.csv", "x_m,y_m,diameter_m,kind\n", err, errlen);
    if (!f)
        return -1;
    for (size_t i = 0; i < sc->world.n_beacons; i++)
        fprintf(f, "%.4f,%.4f,%.4f,%s\n", sc->world.beacon[i].x, sc->world.beacon[i].y,
                sc->world.beacon[i].diameter,
                sc->world.beacon[i].kind == SIM_BEACON_KIND_FLAT ? "flat" : "cylinder");
    fclose(f);
    f = open_log(dir, "glints.csv", "x_m,y_m,width_deg\n", err, errlen);
    if (!f)
        return -1;
    for (size_t i = 0; i < sc->world.n_spurious; i++)
        fprintf(f, "%.4f,%.4f,%.5f\n", sc->world.spurious[i].x, sc->world.spurious[i].y,
                sc->world.spurious[i].width / DEG);
    fclose(f);
    f = open_log(dir, "walls.csv", "x1_m,y1_m,x2_m,y2_m\n", err, errlen);
    if (!f)
        return -1;
    for (size_t i = 0; i < sc->world.n_occluders; i++)
        fprintf(f, "%.4f,%.4f,%.4f,%.4f\n", sc->world.occluder[i].x1, sc->world.occluder[i].y1,
                sc->world.occluder[i].x2, sc->world.occluder[i].y2);
    fclose(f);
    f = open_log(dir, "path.csv", "s_m,x_m,y_m\n", err, errlen);
    if (!f)
        return -1;
    double sacc = 0;
    for (size_t i = 0; i < nominal->n; i++) {
        sim_piece_t part = nominal->piece[i];
        int steps = (int)ceil(part.length / 0.01);
        for (int k = 0; k <= steps; k++) {
            sim_piece_t q = part;
            q.length = part.length * k / (steps ? steps : 1);
            sim_pose_t e = sim_piece_end(&q);
            fprintf(f, "%.4f,%.6f,%.6f\n", sacc + q.length, e.x, e.y);
        }
        sacc += part.length;
    }
    fclose(f);
    return 0;
}

int sim_telemetry_open(sim_telemetry_t *tm, const char *log_dir, const char *lcm_url,
                       const sim_scenario_t *sc, const sim_path_t *nominal, char *err,
                       size_t errlen)
{
    if (log_dir) {
        if (make_dirs(log_dir, err, errlen))
            return -1;
        tm->f_truth =
            open_log(log_dir, "truth.csv",
                     "t_s,x_m,y_m,heading_deg,speed_mps,steering_deg,cross_track_m\n", err, errlen);
        tm->f_est = tm->f_truth ? open_log(log_dir, "estimate.csv", "t_s,x_m,y_m,heading_deg\n",
                                           err, errlen)
                                : NULL;
        tm->f_fix = tm->f_est ? open_log(log_dir, "fixes.csv",
                                         "t_s,ref_t_s,accepted,x_m,y_m,heading_deg,error_m,"
                                         "heading_error_deg,quality,err_m,gate_m,jump_m,"
                                         "resid_deg,agree,dropped,used,status,reason,beacons\n",
                                         err, errlen)
                              : NULL;
        tm->f_cmd = tm->f_fix ? open_log(log_dir, "commands.csv",
                                         "t_s,kind,steering1_deg,length1_m,steering2_deg,"
                                         "length2_m,speed_mps\n",
                                         err, errlen)
                              : NULL;
        if (tm->f_cmd && sc->mode == SIM_SCENARIO_MODE_PURSUIT) {
            tm->f_pos = open_log(log_dir, "positions.csv",
                                 "t_s,receiver,x_m,y_m,z_m,accepted,reason,true_x_m,true_y_m,"
                                 "error_m\n",
                                 err, errlen);
            tm->f_err = tm->f_pos ? open_log(log_dir, "path_error.csv",
                                             "t_s,segment,error_m,true_error_m\n", err, errlen)
                                  : NULL;
            if (!tm->f_err) {
                sim_telemetry_close(tm);
                return -1;
            }
        }
        if (!tm->f_cmd || write_static_logs(log_dir, sc, nominal, err, errlen)) {
            sim_telemetry_close(tm);
            return -1;
        }
    }
    if (lcm_url) {
        tm->lcm = lcm_create(lcm_url);
        if (!tm->lcm) {
            snprintf(err, errlen, "--lcm: cannot open LCM at %s", lcm_url);
            sim_telemetry_close(tm);
            return -1;
        }
    }
    return 0;
}

void sim_telemetry_close(sim_telemetry_t *tm)
{
    if (tm->f_err) /* the seed's error file ends with the average */
        fprintf(tm->f_err, "average,,%.6f,%.6f\n", tm->err_n ? tm->err_sum / tm->err_n : 0.0,
                tm->err_n ? tm->true_sum / tm->err_n : 0.0);
    FILE **files[] = {&tm->f_truth, &tm->f_est, &tm->f_fix, &tm->f_cmd, &tm->f_pos, &tm->f_err};
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        if (*files[i])
            fclose(*files[i]);
        *files[i] = NULL;
    }
    if (tm->lcm)
        lcm_destroy(tm->lcm);
    tm->lcm = NULL;
    tm->done = 1;
}

/* ------------------------------------------------------------------ sampling */

static void sample(void *ctx, uint64_t t_ns)
{
    sim_telemetry_t *tm = ctx;
    double t = sim_clock_s(t_ns);
    sim_pose_t p = sim_drive_pose(tm->drive, t);
    double ct = sim_path_index_distance(tm->nominal, p.x, p.y);
    double speed = sim_segment_speed(&tm->drive->seg, t);
    if (tm->src && !tm->done && !tm->travel_done && speed != 0) {
        tm->report->pursuit.distance += fabs(speed) * SIM_TELEMETRY_SAMPLE;
        tm->report->pursuit.moving += SIM_TELEMETRY_SAMPLE;
    }
    if (hypot(p.x - tm->last_sample.x, p.y - tm->last_sample.y) >= 1e-3 && !tm->done &&
        !tm->travel_done) {
        sim_stat_add(&tm->report->cross_track, ct); /* while moving: the mean is over distance */
        tm->last_sample = p;
    }
    if (t >= tm->next_log - 1e-9) {
        tm->next_log += SIM_TELEMETRY_LOG;
        gnav_pose_t e;
        posix_board_select(tm->nav_board);
        nav_board_pose(&e);
        double ex = fx_q16_to_double(e.x), ey = fx_q16_to_double(e.y);
        double eh = fx_angle_to_deg(e.heading);
        double v = speed, steer = tm->drive->alpha / DEG;
        if (tm->f_truth)
            fprintf(tm->f_truth, "%.4f,%.6f,%.6f,%.5f,%.4f,%.4f,%.6f\n", t, p.x, p.y,
                    wrap_deg(p.th / DEG), v, steer, ct);
        if (tm->f_est)
            fprintf(tm->f_est, "%.4f,%.6f,%.6f,%.5f\n", t, ex, ey, eh);
        if (tm->lcm) {
            cyclopion_truth_t tmsg = {
                (int64_t)(t_ns / 1000), p.x, p.y, wrap_deg(p.th / DEG), v, steer, ct};
            published(
                tm, SIM_LCM_TRUTH,
                cyclopion_truth_t_publish(tm->lcm, sim_telemetry_channel[SIM_LCM_TRUTH], &tmsg));
            int src = posix_source_find(tm->nav_board, (int)hal_edge_vector(HAL_EDGE_DELTA_L),
                                        (int)hal_edge_pin(HAL_EDGE_DELTA_L));
            cyclopion_pose_t pm = {(int64_t)(t_ns / 1000), ex, ey, eh,
                                   src >= 0 ? (int64_t)posix_source_count(tm->nav_board, src) : 0};
            published(tm, SIM_LCM_POSE,
                      cyclopion_pose_t_publish(tm->lcm, sim_telemetry_channel[SIM_LCM_POSE], &pm));
        }
    }
    posix_schedule(t_ns + sim_clock_ns(SIM_TELEMETRY_SAMPLE), sample, tm);
}

void sim_telemetry_start(sim_telemetry_t *tm, const sim_drive_t *drive,
                         const sim_sensors_t *sensors, sim_path_index_t *nominal, int nav_board,
                         sim_report_t *report)
{
    tm->drive = drive;
    tm->sensors = sensors;
    tm->nominal = nominal;
    tm->nav_board = nav_board;
    tm->report = report;
    tm->last_sample = sim_drive_pose(drive, sim_clock_now());
    tm->next_log = sim_clock_now();
    tm->done = 0;
    posix_schedule(posix_now_ns(), sample, tm);
}

/* ------------------------------------------------------------------ observers */

static void trace_fix(const main_board_fix_event_t *ev, double t, sim_pose_t tp, double err)
{
    double fx = fx_q16_to_double(ev->fix.pose.x), fy = fx_q16_to_double(ev->fix.pose.y);
    fprintf(stderr,
            "t=%.3f fix ref %u status %d: dead reckoning (%.4f %.4f %.3f) truth (%.4f "
            "%.4f %.3f) fix (%.4f %.4f %.3f) error %.4f m\n",
            t, ev->ref_latch, ev->status, fx_q16_to_double(ev->approx.x),
            fx_q16_to_double(ev->approx.y), fx_angle_to_deg(ev->approx.heading), tp.x, tp.y,
            wrap_deg(tp.th / DEG), fx, fy, fx_angle_to_deg(ev->fix.pose.heading), err);
    for (int i = 0; i < ev->n; i++)
        fprintf(stderr, "  sighting %2d at %8.3f deg, %.3f deg wide: beacon %d%s\n", i,
                fx_angle_to_deg(ev->s[i].angle), ev->s[i].width * 360.0 / 65536.0, ev->fix.ident[i],
                ev->status == OPTICAL_OK &&
                        (ev->fix.ident[i] == ev->fix.used[0] ||
                         ev->fix.ident[i] == ev->fix.used[1] || ev->fix.ident[i] == ev->fix.used[2])
                    ? " (used)"
                    : "");
}

/* The quality figures of a fix attempt (optical_fix_t), in the logs' units. */
typedef struct {
    double quality; /* m per count (-1: no solution) */
    double err, gate, jump, resid_deg;
} fix_quality_t;

static fix_quality_t quality_of(const main_board_fix_event_t *ev)
{
    fix_quality_t q = {-1, -1, 0, -1, 0};
    const optical_fix_t *f = &ev->fix;
    if (f->quality != UINT32_MAX && ev->n > 0) {
        q.quality = f->quality * SIM_PER_COUNT;
        q.err = fx_q16_to_double(f->err);
        q.jump = hypot(fx_q16_to_double(f->pose.x - ev->approx.x),
                       fx_q16_to_double(f->pose.y - ev->approx.y));
    }
    q.gate = fx_q16_to_double(f->gate);
    q.resid_deg = f->resid * 360.0 / 65536.0;
    return q;
}

static void publish_fix(sim_telemetry_t *tm, const main_board_fix_event_t *ev, double tref,
                        int accepted, double err)
{
    fix_quality_t q = quality_of(ev);
    cyclopion_fix_t m;
    memset(&m, 0, sizeof m);
    m.utime = (int64_t)(posix_now_ns() / 1000);
    m.ref_utime = (int64_t)llround(tref * 1e6);
    m.accepted = accepted;
    m.x = fx_q16_to_double(ev->fix.pose.x);
    m.y = fx_q16_to_double(ev->fix.pose.y);
    m.heading_deg = fx_angle_to_deg(ev->fix.pose.heading);
    m.quality = q.quality;
    m.err_m = q.err;
    m.gate_m = q.gate;
    m.jump_m = q.jump;
    m.resid_deg = q.resid_deg;
    m.agree = (int8_t)ev->fix.n_agree;
    m.dropped = (int8_t)ev->fix.n_dropped;
    m.error_m = err;
    for (int i = 0; i < 3; i++)
        m.used[i] = accepted ? ev->fix.used[i] : -1;
    char reason[16];
    snprintf(reason, sizeof reason, "%s", optical_status_name(ev->status));
    m.reason = reason;
    published(tm, SIM_LCM_FIX,
              cyclopion_fix_t_publish(tm->lcm, sim_telemetry_channel[SIM_LCM_FIX], &m));

    cyclopion_sightings_t sg;
    double ang[OPTICAL_MAX_SIGHTINGS], wid[OPTICAL_MAX_SIGHTINGS];
    int16_t idn[OPTICAL_MAX_SIGHTINGS], tru[OPTICAL_MAX_SIGHTINGS];
    sg.utime = m.utime;
    sg.n = ev->n;
    for (int i = 0; i < ev->n; i++) {
        ang[i] = fx_angle_to_deg(ev->s[i].angle);
        wid[i] = ev->s[i].width * 360.0 / 65536.0;
        idn[i] = ev->fix.ident[i];
        tru[i] = -100;
    }
    sg.angle_deg = ang;
    sg.width_deg = wid;
    sg.identified = idn;
    sg.truth = tru;
    published(
        tm, SIM_LCM_SIGHTINGS,
        cyclopion_sightings_t_publish(tm->lcm, sim_telemetry_channel[SIM_LCM_SIGHTINGS], &sg));
}

void sim_telemetry_fix(void *ctx, const main_board_fix_event_t *ev)
{
    sim_telemetry_t *tm = ctx;
    sim_report_t *r = tm->report;
    double t = sim_clock_now();
    r->fixes_attempted++;
    int accepted = ev->status == OPTICAL_OK;
    double err = -1, herr = -1, tref = t;
    sim_pose_t tp;
    if (ev->n > 0 && sim_sensors_latch(tm->sensors, ev->ref_latch, &tref, &tp) == 0) {
        if (accepted || ev->fix.quality != UINT32_MAX) { /* (an attempt without a solution has
                                                          * no error) */
            double fx = fx_q16_to_double(ev->fix.pose.x), fy = fx_q16_to_double(ev->fix.pose.y);
            err = hypot(fx - tp.x, fy - tp.y);
            herr = fabs(remainder(fx_angle_to_deg(ev->fix.pose.heading) - tp.th / DEG, 360.0));
        }
        if (tm->trace)
            trace_fix(ev, t, tp, err);
    } else if (tm->trace) {
        fprintf(stderr, "t=%.3f fix status %d: no sightings to pair with latches\n", t, ev->status);
    }
    if (accepted) {
        r->fixes_accepted++;
        if (err >= 0) {
            sim_stat_add(&r->fix_error, err);
            sim_stat_add(&r->heading_error, herr);
        }
    } else {
        r->fixes_rejected++;
    }
    if (tm->f_fix) {
        fix_quality_t q = quality_of(ev);
        fprintf(tm->f_fix,
                "%.6f,%.6f,%d,%.6f,%.6f,%.5f,%.6f,%.5f,%.6f,%.6f,%.6f,%.6f,%.4f,%u,%u,%d;%d;%d,%d,"
                "%s,%d\n",
                t, tref, accepted, fx_q16_to_double(ev->fix.pose.x),
                fx_q16_to_double(ev->fix.pose.y), fx_angle_to_deg(ev->fix.pose.heading), err, herr,
                q.quality, q.err, q.gate, q.jump, q.resid_deg, ev->fix.n_agree, ev->fix.n_dropped,
                accepted ? ev->fix.used[0] : -1, accepted ? ev->fix.used[1] : -1,
                accepted ? ev->fix.used[2] : -1, ev->status, optical_status_name(ev->status),
                ev->n > 0 ? sim_sensors_beacons(tm->sensors, ev->ref_latch, ev->n) : 0);
    }
    if (tm->lcm)
        publish_fix(tm, ev, tref, accepted, err);
}

void sim_telemetry_state(void *ctx, drive_state_t st)
{
    sim_telemetry_t *tm = ctx;
    if (tm->trace) {
        double t = sim_clock_now();
        sim_pose_t p = sim_drive_pose(tm->drive, t);
        fprintf(stderr, "t=%.3f state %s at (%.4f %.4f %.2f)\n", t, drive_seq_state_name(st), p.x,
                p.y, wrap_deg(p.th / DEG));
    }
}

void sim_telemetry_command(void *ctx, double t, const drive_event_t *ev)
{
    sim_telemetry_t *tm = ctx;
    double steer[2], len[2], speed;
    sim_drive_command_si(tm->drive, &ev->cmd, steer, len, &speed);
    int load = ev->type == DRIVE_EV_LOAD;
    if (ev->type == DRIVE_EV_DAC_ANGLE || ev->type == DRIVE_EV_OUTPUTS) {
        /* seed 002's DAC style: the steering DAC, the digital outputs */
        double a = (double)(int32_t)ev->alpha * (180.0 / 2147483648.0);
        if (tm->f_cmd && ev->type == DRIVE_EV_DAC_ANGLE)
            fprintf(tm->f_cmd, "%.6f,steer,%.4f,,,,\n", t, a);
        else if (tm->f_cmd)
            fprintf(tm->f_cmd, "%.6f,outputs,,,,,\n", t);
        return;
    }
    if (tm->f_cmd) {
        if (load)
            fprintf(tm->f_cmd, "%.6f,load,%.4f,%.4f,%.4f,%.4f,%.4f\n", t, steer[0], len[0],
                    steer[1], len[1], speed);
        else
            fprintf(tm->f_cmd, "%.6f,speed,,,,,%.4f\n", t, speed);
    }
    if (tm->lcm) {
        cyclopion_drive_command_t m;
        memset(&m, 0, sizeof m);
        m.utime = (int64_t)(posix_now_ns() / 1000);
        m.kind = load ? "arcs" : (ev->cmd.speed ? "speed" : "stop");
        m.n = load ? 2 : 0;
        m.steering_deg = steer;
        m.length_m = len;
        m.speed_mps = speed;
        published(
            tm, SIM_LCM_DRIVE,
            cyclopion_drive_command_t_publish(tm->lcm, sim_telemetry_channel[SIM_LCM_DRIVE], &m));
    }
}

/* ------------------------------------------------------------------ pursuit mode */

void sim_telemetry_pursuit_start(sim_telemetry_t *tm, const sim_possrc_t *src,
                                 const sim_scenario_t *sc)
{
    tm->src = src;
    tm->sc = sc;
    tm->report->pursuit.on = true;
}

/* Goal point @p i of the pursuit: the start, then the path's positions. */
static void goal_point(const sim_scenario_t *sc, unsigned i, double *x, double *y)
{
    *x = i == 0 ? sc->start_x : sc->path[i - 1].x;
    *y = i == 0 ? sc->start_y : sc->path[i - 1].y;
}

void sim_telemetry_pursuit(void *ctx, const main_pursuit_event_t *ev)
{
    static const char *const reasons[] = {"ok", "zero", "jump", "too_close", "pair"};
    sim_telemetry_t *tm = ctx;
    double t = sim_clock_now();
    sim_xy_t tr = sim_possrc_truth(tm->src, ev->receiver, t);
    double x = ev->pos.x / 1000.0, y = ev->pos.y / 1000.0;
    const char *why = ev->reason < 5 ? reasons[ev->reason] : "?";
    if (tm->f_pos)
        fprintf(tm->f_pos, "%.4f,%d,%.3f,%.3f,%.3f,%d,%s,%.4f,%.4f,%.4f\n", t, ev->receiver + 1, x,
                y, ev->pos.z / 1000.0, ev->reason == POSRX_OK, why, tr.x, tr.y,
                hypot(x - tr.x, y - tr.y));
    if (tm->trace)
        fprintf(stderr, "t=%.3f receiver %d (%.3f %.3f) %s%s\n", t, ev->receiver + 1, x, y, why,
                ev->used ? "" : ", not used");
    if (!ev->used)
        return;
    /* the seed's error: perpendicular distance to the line of the segment it was measured on,
     * for the position used and for the receiver's true position at that instant */
    double ax, ay, bx, by;
    goal_point(tm->sc, (unsigned)ev->rec.segment - 1u, &ax, &ay);
    goal_point(tm->sc, ev->rec.segment, &bx, &by);
    double len = hypot(bx - ax, by - ay);
    double true_err = fabs(((tr.x - ax) * (by - ay) - (tr.y - ay) * (bx - ax)) / len);
    double err = fx_q16_to_double(ev->rec.err);
    sim_stat_add(&tm->report->pursuit.true_error, true_err);
    tm->err_sum += err;
    tm->true_sum += true_err;
    tm->err_n++;
    if (tm->f_err)
        fprintf(tm->f_err, "%.4f,%u,%.6f,%.6f\n", t, ev->rec.segment, err, true_err);
    if (tm->trace)
        fprintf(stderr,
                "  segment %u error %.4f m (true %.4f), goal %u, heading %.2f, heading error "
                "%.2f deg\n",
                ev->rec.segment, err, true_err, ev->rec.goal, fx_angle_to_deg(ev->rec.heading),
                (double)(int32_t)ev->rec.dphi * (180.0 / 2147483648.0));
}
