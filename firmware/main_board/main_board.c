/*
 * main_board.c - main board application: handler registration and the main loop.
 */
#include "main_board.h"

#include "hal/capture.h"
#include "hal/edge.h"
#include "hal/irq.h"

static main_board_stats_t stats;

static void on_capture(void *arg, uint16_t count, uint8_t rising)
{
    (void)count;
    (void)rising;
    if (arg == &stats.index_pulses)
        stats.index_pulses++;
    else
        stats.edges++;
}

static void on_delta_s(void *arg)
{
    (void)arg;
    stats.delta_s++;
}

void main_board_init(void)
{
    hal_capture_init(HAL_CAPTURE_INDEX, on_capture, &stats.index_pulses);
    hal_capture_init(HAL_CAPTURE_BEACON, on_capture, &stats.edges);
    hal_edge_init(HAL_EDGE_DELTA_S, HAL_EDGE_RISING, on_delta_s, 0);
}

void main_board_poll(void) {}

void main_board_stats(main_board_stats_t *out)
{
    hal_irq_state_t s = hal_irq_disable();
    *out = stats;
    hal_irq_restore(s);
}
