/*
 * nav_board.c - navigation board application: handler registration and the main loop.
 */
#include "nav_board.h"

#include "hal/edge.h"
#include "hal/irq.h"

static nav_board_stats_t stats;

static void on_delta_l(void *arg)
{
    (void)arg;
    stats.delta_l++;
}

static void on_gyro(void *arg)
{
    stats.gyro += arg ? 1 : -1;
}

static void on_sighted(void *arg)
{
    (void)arg;
    stats.sightings++;
}

void nav_board_init(void)
{
    static uint8_t up;
    hal_edge_init(HAL_EDGE_DELTA_L, HAL_EDGE_RISING, on_delta_l, 0);
    hal_edge_init(HAL_EDGE_GYRO_UP, HAL_EDGE_RISING, on_gyro, &up);
    hal_edge_init(HAL_EDGE_GYRO_DOWN, HAL_EDGE_RISING, on_gyro, 0);
    hal_edge_init(HAL_EDGE_BEACON_SIGHTED, HAL_EDGE_RISING, on_sighted, 0);
}

void nav_board_poll(void) {}

void nav_board_stats(nav_board_stats_t *out)
{
    hal_irq_state_t s = hal_irq_disable();
    *out = stats;
    hal_irq_restore(s);
}
