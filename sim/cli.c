/*
 * cli.c - agv-sim's command line (see cli.h).
 */
#include "sim/cli.h"

#include <errno.h>
#include <getopt.h>
#include <stdlib.h>
#include <string.h>

#include "sim/pace.h"

#ifndef CY_VERSION
#error "CY_VERSION (the CMake project version) must be defined"
#endif

void sim_cli_usage(FILE *f)
{
    fprintf(f,
            "usage: agv-sim --scenario FILE [--seed N] [--report FILE.json] [--log-dir DIR]\n"
            "               [--lcm URL] [--can IFACE] [--candump FILE] [--realtime[=FACTOR]]\n"
            "               [--quiet] [--trace] [--stats] [--ticks] [-h|--help] [--version]\n"
            "Runs both boards' firmware against a simulated vehicle and building.\n"
            "  --scenario FILE   the scenario (JSON; format: docs/interfaces.md and\n"
            "                    docs/schema/scenario.schema.json; examples in sim/scenarios/)\n"
            "  --seed N          override the scenario's seed (a non-negative integer)\n"
            "  --report FILE     write the report (JSON, docs/schema/report.schema.json) there\n"
            "                    (default: stdout)\n"
            "  --log-dir DIR     create DIR (and its parents) and write truth.csv,\n"
            "                    estimate.csv, fixes.csv, commands.csv, path.csv, beacons.csv,\n"
            "                    glints.csv, walls.csv\n"
            "  --lcm URL         publish telemetry on LCM (e.g. udpm://239.255.76.67:7667?ttl=0)\n"
            "  --can IFACE       carry every board-link frame through a SocketCAN raw socket on\n"
            "                    IFACE (vcan0, can0) and back; the run stays the same\n"
            "  --candump FILE    write the bus traffic there in candump's log format\n"
            "                    (simulated timestamps; decode with firmware/link/cyclopion.dbc)\n"
            "  --realtime[=FACTOR]  pace simulated time to the wall clock, FACTOR times faster\n"
            "                    (default 1; 0.5 is half speed) so that lcm-spy, lcm-logger and\n"
            "                    candump see the run as it happens; only waits: the run's\n"
            "                    report and logs are the same as without it\n"
            "  --quiet           no progress on stderr\n"
            "  --trace           every fix attempt (dead-reckoning pose, truth and fix at the\n"
            "                    reference latch, sightings, status), travel state, CAN error and\n"
            "                    CAN state change on stderr\n"
            "  --stats           the run's work counters (events, cross-track samples, path\n"
            "                    pieces examined, LCM messages published per channel) and its\n"
            "                    CPU time as one JSON line on stderr\n"
            "  --ticks           every board's 1 ms clock interrupt every simulated\n"
            "                    millisecond, as on the MSP430 (slower); without it a board's\n"
            "                    main loop runs at the deadlines it states and when its\n"
            "                    interrupts wake it: the report and logs are the same\n"
            "  -h, --help        this text\n"
            "  --version         the version\n"
            "Exit status: 0 criteria met, 1 criteria missed, 2 bad input.\n"
            "Reference: docs/interfaces.md in the source tree.\n");
}

int sim_cli_parse(int argc, char **argv, sim_cli_t *cli, FILE *out, FILE *err)
{
    enum {
        OPT_SCENARIO = 256,
        OPT_SEED,
        OPT_REPORT,
        OPT_LOG_DIR,
        OPT_LCM,
        OPT_CAN,
        OPT_CANDUMP,
        OPT_QUIET,
        OPT_TRACE,
        OPT_STATS,
        OPT_REALTIME,
        OPT_TICKS,
        OPT_VERSION
    };
    static const struct option opts[] = {{"scenario", required_argument, 0, OPT_SCENARIO},
                                         {"seed", required_argument, 0, OPT_SEED},
                                         {"report", required_argument, 0, OPT_REPORT},
                                         {"log-dir", required_argument, 0, OPT_LOG_DIR},
                                         {"lcm", required_argument, 0, OPT_LCM},
                                         {"can", required_argument, 0, OPT_CAN},
                                         {"candump", required_argument, 0, OPT_CANDUMP},
                                         {"quiet", no_argument, 0, OPT_QUIET},
                                         {"trace", no_argument, 0, OPT_TRACE},
                                         {"stats", no_argument, 0, OPT_STATS},
                                         {"realtime", optional_argument, 0, OPT_REALTIME},
                                         {"ticks", no_argument, 0, OPT_TICKS},
                                         {"help", no_argument, 0, 'h'},
                                         {"version", no_argument, 0, OPT_VERSION},
                                         {0, 0, 0, 0}};
    memset(cli, 0, sizeof *cli);
    cli->seed = -1;
    optind = 0; /* GNU getopt: start afresh (the parser may be called more than once) */
    opterr = 0; /* the messages below name the option */
    int c;
    while ((c = getopt_long(argc, argv, ":h", opts, NULL)) != -1) {
        switch (c) {
        case OPT_SCENARIO:
            cli->scenario = optarg;
            break;
        case OPT_SEED: {
            char *end;
            errno = 0;
            cli->seed = strtoll(optarg, &end, 10);
            if (errno || end == optarg || *end || cli->seed < 0) {
                fprintf(err, "agv-sim: --seed: \"%s\" is not a non-negative integer\n", optarg);
                return 2;
            }
            break;
        }
        case OPT_REPORT:
            cli->report = optarg;
            break;
        case OPT_LOG_DIR:
            cli->log_dir = optarg;
            break;
        case OPT_LCM:
            cli->lcm_url = optarg;
            break;
        case OPT_CAN:
            cli->can = optarg;
            break;
        case OPT_CANDUMP:
            cli->candump = optarg;
            break;
        case OPT_QUIET:
            cli->quiet = 1;
            break;
        case OPT_TRACE:
            cli->trace = 1;
            break;
        case OPT_STATS:
            cli->stats = 1;
            break;
        case OPT_TICKS:
            cli->ticks = 1;
            break;
        case OPT_REALTIME: {
            char *end;
            errno = 0;
            cli->realtime = optarg ? strtod(optarg, &end) : 1.0;
            if (optarg && (errno || end == optarg || *end || !(cli->realtime > 0) ||
                           cli->realtime > SIM_PACE_MAX_FACTOR)) {
                fprintf(err,
                        "agv-sim: --realtime: \"%s\" is not a factor above 0 and at most %g "
                        "(e.g. --realtime=10)\n",
                        optarg, SIM_PACE_MAX_FACTOR);
                return 2;
            }
            break;
        }
        case 'h':
            sim_cli_usage(out);
            return 0;
        case OPT_VERSION:
            fprintf(out, "agv-sim %s\n", CY_VERSION);
            return 0;
        case ':':
            fprintf(err, "agv-sim: %s needs a value\n", argv[optind - 1]);
            sim_cli_usage(err);
            return 2;
        default:
            fprintf(err, "agv-sim: unknown option \"%s\"\n", argv[optind - 1]);
            sim_cli_usage(err);
            return 2;
        }
    }
    if (optind < argc) {
        if (cli->realtime > 0 && strtod(argv[optind], NULL) > 0) /* "--realtime 10" */
            fprintf(err, "agv-sim: --realtime takes its factor after '=': --realtime=%s\n",
                    argv[optind]);
        else
            fprintf(err, "agv-sim: unexpected argument \"%s\"\n", argv[optind]);
        sim_cli_usage(err);
        return 2;
    }
    if (!cli->scenario) {
        fprintf(err, "agv-sim: --scenario is required\n");
        sim_cli_usage(err);
        return 2;
    }
    return -1;
}
