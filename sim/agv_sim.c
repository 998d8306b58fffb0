/*
 * agv-sim - the closed-loop harness: a simulated vehicle in a simulated building whose sensors
 * raise the real firmware's interrupts on both boards (hal/posix), and whose drive board
 * executes what the main board writes to its port. The command line, the scenario and report
 * formats and the logs are described in docs/interfaces.md.
 *
 * Exit status: 0 the run met the scenario's success criteria, 1 it did not, 2 bad input.
 *
 * The rooms: cli (the command line), scenario (the file, checked against its schema), mission
 * (the boards' download and the nominal path), run (the boards on the harness and the loop),
 * drive_board (the drive board and the vehicle's motion), sensors (odometer, gyro and
 * goniometer pulses, with their disturbances), telemetry (measurements, logs, LCM, trace),
 * canbus (the board link's CAN bus: faults, candump log, figures), socketcan (--can), report
 * (the JSON report and the verdict).
 */
#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sim/canbus.h"
#include "sim/cli.h"
#include "sim/mission.h"
#include "sim/report.h"
#include "sim/run.h"
#include "sim/scenario.h"

static int bad_input(const char *file, const char *msg)
{
    if (file)
        fprintf(stderr, "agv-sim: %s: %s\n", file, msg);
    else
        fprintf(stderr, "agv-sim: %s\n", msg);
    return 2;
}

int main(int argc, char **argv)
{
    sim_cli_t cli;
    int rc = sim_cli_parse(argc, argv, &cli, stdout, stderr);
    if (rc >= 0)
        return rc;

    static sim_scenario_t sc;
    static sim_mission_t mission;
    char err[768];
    if (sim_scenario_load(cli.scenario, &sc, err, sizeof err))
        return bad_input(NULL, err); /* the loader names the file */
    if (cli.seed >= 0)
        sc.seed = (uint64_t)cli.seed;
    if (sim_canbus_check(&sc, err, sizeof err) || sim_mission_build(&mission, &sc, err, sizeof err))
        return bad_input(cli.scenario, err);

    sim_run_options_t opt = {cli.log_dir, cli.lcm_url, cli.quiet,    cli.trace,
                             cli.can,     cli.candump, cli.realtime, cli.ticks};
    sim_report_t r;
    sim_run_stats_t stats;
    if (sim_run(&sc, &mission, &opt, &r, &stats, err, sizeof err))
        return bad_input(cli.scenario, err);

    if (cli.report) {
        if (sim_report_write(&r, cli.report)) {
            fprintf(stderr, "agv-sim: cannot write %s: %s\n", cli.report, strerror(errno));
            sim_report_free(&r);
            return 2;
        }
    } else {
        char *text = sim_report_json(&r);
        puts(text);
        free(text);
    }
    if (cli.stats) {
        fprintf(stderr,
                "agv-sim: stats {\"sim_time_s\":%.6f,\"events\":%" PRIu64 ",\"samples\":%" PRIu64
                ",\"pieces\":%" PRIu64 ",\"pieces_indexed\":%" PRIu64
                ",\"pieces_examined\":%" PRIu64 ",\"cpu_time_s\":%.6f",
                r.sim_time, stats.events, stats.samples, stats.pieces, stats.pieces_indexed,
                stats.pieces_examined, stats.cpu_time_s);
        if (cli.lcm_url) {
            fprintf(stderr, ",\"lcm_published\":{");
            for (int i = 0; i < SIM_LCM_CHANNELS; i++)
                fprintf(stderr, "%s\"%s\":%" PRIu64, i ? "," : "", sim_telemetry_channel[i],
                        stats.lcm_published[i]);
            fprintf(stderr, "},\"lcm_failed\":%" PRIu64, stats.lcm_failed);
        }
        fprintf(stderr, "}\n");
    }
    if (cli.lcm_url && !cli.quiet) {
        uint64_t n = 0;
        for (int i = 0; i < SIM_LCM_CHANNELS; i++)
            n += stats.lcm_published[i];
        fprintf(stderr, "agv-sim: LCM %s: %" PRIu64 " messages published, %" PRIu64 " failed\n",
                cli.lcm_url, n, stats.lcm_failed);
    }

    char why[512];
    int ok = sim_report_judge(&r, &sc.success, why, sizeof why);
    if (!cli.quiet)
        fprintf(stderr, "agv-sim: %s: %s%s (%.1f s simulated in %.2f s, %.0fx real time)\n",
                sc.name, ok ? "criteria met" : "criteria missed:", ok ? "" : why, r.sim_time,
                r.wall_time, r.wall_time > 0 ? r.sim_time / r.wall_time : 0.0);
    else if (!ok)
        fprintf(stderr, "agv-sim: %s: criteria missed:%s\n", sc.name, why);
    sim_report_free(&r);
    return ok ? 0 : 1;
}
