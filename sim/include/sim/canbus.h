/*
 * canbus.h - the board link's CAN bus in a run: the scenario's "link" checked and its faults
 * put into the harness's bus model (hal_posix/can_bus.h), every bus event watched: the candump
 * log of --candump (candump's log format, simulated timestamps), the --trace lines of errors
 * and state changes, and the figures of the report's "link" (docs/interfaces.md).
 */
#ifndef SIM_CANBUS_H
#define SIM_CANBUS_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "hal_posix/can_bus.h"
#include "link/link.h"
#include "sim/report.h"
#include "sim/scenario.h"

typedef struct {
    int main_b, nav_b; /* harness boards */
    FILE *candump;     /* --candump, or NULL */
    char iface[32];    /* the interface named in candump lines */
    int trace;         /* errors and state changes on stderr */
    /* measured */
    uint64_t a_queued[LINKMSG_TYPES]; /* queue time of a pair's A frame, waiting for its B */
    uint8_t a_have[LINKMSG_TYPES];
    uint64_t latency_max_ns[LINKMSG_TYPES]; /* queued (first frame) to received (last frame) */
    uint8_t latency_seen[LINKMSG_TYPES];
    uint64_t off_since[POSIX_CAN_NODES]; /* when a node went bus-off */
    uint64_t recovery_max_ns;            /* longest bus-off to recovered */
    uint32_t recoveries_seen;
} sim_canbus_t;

/**
 * What the scenario's "link" asks beyond its schema: a bit rate whose bit time is a whole
 * number of nanoseconds, silence longer than the heartbeat, fault nodes and frame names the
 * bus has (the DBC's), at most one babbler. Returns 0, or -1 with the reason (naming the key
 * and the value) in @p err.
 */
int sim_canbus_check(const sim_scenario_t *sc, char *err, size_t errlen);

/** The boards' link configuration for @p sc (its "link", else mission/mission.h's). */
link_config_t sim_canbus_link_config(const sim_scenario_t *sc, uint8_t node);

/**
 * Watch bus 0 (boards @p main_b and @p nav_b on it) and add @p sc's faults; with @p candump
 * (may be NULL) write every frame there, naming interface @p iface. Returns 0, or -1 with the
 * reason in @p err (the file cannot be written).
 */
int sim_canbus_start(sim_canbus_t *cb, const sim_scenario_t *sc, int main_b, int nav_b,
                     const char *candump, const char *iface, int trace, char *err, size_t errlen);

/**
 * Fill @p r->link from the bus, its nodes and the boards' links (@p main_link, @p nav_link)
 * at simulated time @p sim_time (s).
 */
void sim_canbus_report(const sim_canbus_t *cb, const link_stats_t *main_link,
                       const link_stats_t *nav_link, double sim_time, sim_report_t *r);

/** Stop watching; close the candump log (returns -1 when writing it failed). */
int sim_canbus_close(sim_canbus_t *cb);

#endif
