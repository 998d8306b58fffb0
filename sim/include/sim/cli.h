/*
 * cli.h - agv-sim's command line (docs/interfaces.md "agv-sim").
 */
#ifndef SIM_CLI_H
#define SIM_CLI_H

#include <stdio.h>

typedef struct {
    const char *scenario; /* --scenario FILE (required) */
    long long seed;       /* --seed N, -1 = the scenario's */
    const char *report;   /* --report FILE, NULL = stdout */
    const char *log_dir;  /* --log-dir DIR, or NULL */
    const char *lcm_url;  /* --lcm URL, or NULL */
    const char *can;      /* --can IFACE, or NULL */
    const char *candump;  /* --candump FILE, or NULL */
    int quiet;            /* --quiet */
    int trace;            /* --trace */
    int stats;            /* --stats */
    int ticks;            /* --ticks: every board's clock interrupt every millisecond */
    double realtime;      /* --realtime[=FACTOR]: simulated s per wall s, 0 = not paced */
} sim_cli_t;

/**
 * Parse @p argc / @p argv into @p cli. Returns -1 when the run should go ahead; otherwise the
 * exit status: 0 after -h/--help (usage on @p out) or --version (on @p out), 2 for a bad
 * command line (the reason and the usage on @p err).
 */
int sim_cli_parse(int argc, char **argv, sim_cli_t *cli, FILE *out, FILE *err);

/** The usage text. */
void sim_cli_usage(FILE *f);

#endif
