/*
 * main_beacon_none.c - the main board image without the beacon travel (see main_beacon.h).
 *
 * The pursuit image (main_board_pursuit.elf: seed 002's pursuit on the serial position
 * receiver, the CAN link) carries neither the optical fix nor the double-arc travel: it links
 * this file instead of main_beacon.c, and main_board_init() refuses a configuration without
 * pursuit mode with DRIVE_ERR_PARAM. The other entry points are reached only in the beacon
 * travel, which such an image never enters; they leave everything as it is.
 */
#include "main_beacon.h"

drive_status_t main_beacon_init(const main_board_config_t *cfg)
{
    (void)cfg;
    return DRIVE_ERR_PARAM; /* this image has no beacon travel */
}

drive_status_t main_beacon_prepare(void)
{
    return DRIVE_ERR_PARAM;
}

void main_beacon_start(void) {}

void main_beacon_poll(void) {}

bool main_beacon_on_msg(const linkmsg_t *m)
{
    (void)m;
    return false; /* the latches and acknowledgements are the beacon travel's */
}

drive_state_t main_beacon_state(void)
{
    return DRIVE_ST_IDLE;
}
