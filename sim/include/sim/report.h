/*
 * report.h - what agv-sim measures and writes (docs/interfaces.md "Report file"): fix accuracy,
 * path tracking, how the run ended, interrupt counts, the board link. Numbers are rounded to fixed
 * decimals so that the same run gives the same bytes (wall time aside).
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
/** stop_reason of a run whose travel was still going when duration_s ran out (the others are
 * the main board's: MAIN_BOARD_STOP_REASONS in firmware/main_board/main_board.h). */
#define SIM_STOP_DURATION "duration"
#define SIM_LINK_MESSAGES 16 /* message types with a latency figure, at most */

/** One board's side of the link: its CAN controller's counters and its link's. */
typedef struct {
    uint32_t tx_frames, rx_frames, tx_errors, rx_errors, rx_overruns, tx_aborted;
    uint32_t error_passive, bus_off, recoveries;
    uint32_t heartbeats_sent, heartbeats_missed, silences, send_refused, message_errors;
} sim_link_board_t;

/** The board link's figures (the report's "link"). */
typedef struct {
    uint32_t bitrate_bps;
    uint64_t frames;        /* frames that went through */
    uint64_t errors;        /* transmissions that ended in an error frame */
    uint64_t lost;          /* frame copies acknowledged and lost by a receiver */
    double bus_load;        /* share of the run's time the bus was busy, 0..1 */
    uint32_t bus_off;       /* times a node went bus-off */
    uint32_t recoveries;    /* times a node came back */
    double recovery_ms_max; /* longest bus-off to recovery, ms */
    const char *latency_name[SIM_LINK_MESSAGES];
    double latency_ms[SIM_LINK_MESSAGES]; /* worst, queued to received */
    size_t n_latency;
    sim_link_board_t board[2]; /* main, nav */
} sim_link_report_t;

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
    const char *stop_reason; /* why the travel stopped short of the goal ("" when it did not) */
    double stop_at;          /* s: when it stopped (or the run ended), -1 at the goal */
    double standstill_at;    /* s: when the vehicle stood after the stop, -1 if it did not */
    sim_stat_t cross_track;  /* m, sampled along the travelled distance */
    double final_error;      /* m, truth at the end vs the last prescribed point */
    sim_pursuit_report_t pursuit;
    const char *isr_name[SIM_MAX_ISR_NAMES];
    uint64_t isr_count[SIM_MAX_ISR_NAMES];
    size_t n_isr;
    sim_link_report_t link;
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
