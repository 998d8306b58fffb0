/*
 * report.h - what agv-sim measures and writes (docs/interfaces.md "Report file"): fix accuracy,
 * path tracking, interrupt counts. Numbers are rounded to fixed decimals so that the same run gives
 * the same bytes (wall time aside).
 */
#ifndef SIM_REPORT_H
#define SIM_REPORT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "sim/scenario.h"

/** Samples of one quantity: mean, RMS, max, 95th percentile. */
typedef struct {
    double *v;
    size_t n, cap;
    double sum, sumsq, max;
} sim_stat_t;

void sim_stat_add(sim_stat_t *s, double x);
double sim_stat_mean(const sim_stat_t *s);
double sim_stat_rms(const sim_stat_t *s);
/** The p-quantile (0..1), nearest rank; 0 for no samples. */
double sim_stat_quantile(sim_stat_t *s, double p);
void sim_stat_free(sim_stat_t *s);

#define SIM_MAX_ISR_NAMES 16

/** Mode pursuit: what the receivers, the pursuit and the positioning system did. */
typedef struct {
    bool on;                 /* the report has a pursuit section */
    uint32_t updates;        /* positions the pursuit used */
    double error_mean;       /* m: the seed's average path error (the firmware's records) */
    double error_max;        /* m */
    sim_stat_t true_error;   /* m: the true receiver position's, at each update */
    double distance, moving; /* m and s travelled while moving (speed = distance / moving) */
    uint32_t n_receivers;
    struct {
        uint32_t framed, reason[5], resyncs, skipped, error_bytes, dropped, overruns;
    } rx[2];          /* reason: ok, zero, jump, too_close, pair */
    uint32_t src[10]; /* sim_possrc_stats_t, in its order */
    uint32_t corrections, goals, slowdowns, stops, resumes, regulations, pair_rejects;
    uint32_t unpaired, nav_timeouts;
} sim_pursuit_report_t;

typedef struct {
    char scenario[64];
    uint64_t seed;
    const char *mode; /* travel mode, as in the scenario file */
    double sim_time, wall_time;
    uint32_t fixes_attempted, fixes_accepted, fixes_rejected;
    sim_stat_t fix_error;     /* m, accepted fixes vs truth at their reference instant */
    sim_stat_t heading_error; /* deg, absolute */
    bool reached_goal;
    bool fault, stop_requested; /* why the goal was not reached: a fault, the nav board's stop */
    sim_stat_t cross_track;     /* m, sampled along the travelled distance */
    double final_error;         /* m, truth at the end vs the last prescribed point */
    sim_pursuit_report_t pursuit;
    const char *isr_name[SIM_MAX_ISR_NAMES];
    uint64_t isr_count[SIM_MAX_ISR_NAMES];
    size_t n_isr;
} sim_report_t;

/**
 * Judge the run against the scenario's criteria @p c. Returns 1 when every criterion is met,
 * else 0 with the misses in @p why ("; "-separated, each with the measured value and its
 * limit).
 */
int sim_report_judge(sim_report_t *r, const sim_success_t *c, char *why, size_t whylen);

/** Free the samples the report holds. */
void sim_report_free(sim_report_t *r);

/** Write the report as JSON to @p path. Returns 0 or -1 (errno set). */
int sim_report_write(sim_report_t *r, const char *path);

/** The report as a JSON string (malloc'd; the caller frees it). */
char *sim_report_json(sim_report_t *r);

#endif
