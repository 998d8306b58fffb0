/*
 * main_pursuit_none.c - the main board image without pursuit mode (see main_pursuit.h).
 *
 * The beacon image (main_board.elf: optical fixes, double arcs, the CAN link) has no room for
 * seed 002's pursuit besides (docs/posrx.md, "On the target"; pursuit mode is the pursuit
 * image's, main_board_pursuit.elf): it links this file instead of main_pursuit.c, and
 * main_board_init() refuses a configuration that asks for pursuit mode with DRIVE_ERR_PARAM.
 * The other entry points are reached only in pursuit mode, which such an image never enters;
 * they leave everything as it is.
 */
#include "main_pursuit.h"

drive_status_t main_pursuit_init(const struct main_board_config *cfg)
{
    (void)cfg;
    return DRIVE_ERR_PARAM; /* this image has no pursuit mode */
}

void main_pursuit_start(void) {}

void main_pursuit_poll(void) {}

bool main_pursuit_done(void)
{
    return false;
}

void main_pursuit_stats(main_pursuit_stats_t *out)
{
    *out = (main_pursuit_stats_t){0};
}
