/*
 * delta_s.c - the delta-S pulse counter (drive_seq.h, SPEC D1): the drive board's "current
 * arc almost done" line counted by its interrupt handler, taken by the main loop.
 */
#include "drive/drive_seq.h"
#include "hal/edge.h"
#include "hal/irq.h"

void drive_ds_handler(void *arg)
{
    drive_ds_t *ds = arg;
    if (ds->count < UINT16_MAX)
        ds->count++;
}

int drive_ds_init(drive_ds_t *ds)
{
    ds->count = 0;
    return hal_edge_init(HAL_EDGE_DELTA_S, HAL_EDGE_RISING, drive_ds_handler, ds);
}

uint16_t drive_ds_take(drive_ds_t *ds)
{
    hal_critical_enter();
    uint16_t n = ds->count;
    ds->count = 0;
    hal_critical_exit();
    return n;
}
