/*
 * optical_perturb_scan.c - a deliberately wrong C twin of optical_scan for the check's own
 * test (linked with --wrap=optical_scan_c): on the first scan while moving (lever8 > 0) that
 * gives beacon 0 a window, that window one unit wider. The check image must stop there on
 * the state it compares (target.optical_wrong_scan).
 */
#include "optical/fastmath.h"

uint8_t __real_optical_scan_c(int16_t mid, uint16_t half);
uint8_t __wrap_optical_scan_c(int16_t mid, uint16_t half);

uint8_t __wrap_optical_scan_c(int16_t mid, uint16_t half)
{
    uint8_t r = __real_optical_scan_c(mid, half);
    if (r == 0 && optical_work.lever8 != 0 && optical_work.nb > 0 && optical_work.u.id.e[0] != 0)
        optical_work.u.id.e[0]++;
    return r;
}
