/*
 * link_loss.c - frames of the board link lost in transit (see link_loss.h).
 */
#include "sim/link_loss.h"

void sim_link_loss_init(sim_link_loss_t *l, const sim_scenario_t *sc)
{
    l->sc = sc;
    sim_rng_seed(&l->rng, sc->seed, 5);
    l->sent = l->lost = 0;
}

bool sim_link_loss_active(const sim_scenario_t *sc)
{
    return sc->link_drop > 0 || sc->n_link_outages > 0;
}

bool sim_link_loss_frame(sim_link_loss_t *l, double t)
{
    const sim_scenario_t *sc = l->sc;
    /* The draw is made for every frame, so that outages do not shift the stream. */
    bool lost = sc->link_drop > 0 && sim_rng_uniform(&l->rng) < sc->link_drop;
    for (size_t i = 0; i < sc->n_link_outages; i++)
        lost |= t >= sc->link_outage[i].t && t < sc->link_outage[i].t + sc->link_outage[i].duration;
    l->sent++;
    l->lost += lost;
    return lost;
}
