/*
 * link_loss.h - the disturbed board link of a scenario (`link_loss`): every frame is lost in
 * transit with probability `drop`, each independently (a stream of the scenario's seed), and
 * every frame sent inside an outage window is lost. agv-sim hands it to the harness's link
 * (posix_link_set_loss()); the boards see lost frames as silence.
 */
#ifndef SIM_LINK_LOSS_H
#define SIM_LINK_LOSS_H

#include <stdbool.h>
#include <stdint.h>

#include "sim/rng.h"
#include "sim/scenario.h"

typedef struct {
    const sim_scenario_t *sc;
    sim_rng_t rng;
    uint32_t sent, lost; /* frames so far */
} sim_link_loss_t;

/** The link losses of @p sc (kept by reference). */
void sim_link_loss_init(sim_link_loss_t *l, const sim_scenario_t *sc);

/** True when @p sc disturbs the link at all. */
bool sim_link_loss_active(const sim_scenario_t *sc);

/** Is the frame sent at simulated time @p t (s) lost? Counts it. */
bool sim_link_loss_frame(sim_link_loss_t *l, double t);

#endif
