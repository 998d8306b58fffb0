/*
 * status.c - the names of optical_fix()'s verdicts (optical_status_t) for logs and telemetry;
 * its own file so that a board image that never prints them does not carry them.
 */
#include "optical/optical.h"

const char *optical_status_name(int st)
{
    static const char *const names[OPTICAL_STATUS_COUNT] = {
        "ok",   "arg",  "rev",      "few",          "degenerate",  "singular",
        "jump", "turn", "disagree", "inconsistent", "unconfirmed", "poor"};
    return st >= 0 && st < OPTICAL_STATUS_COUNT ? names[st] : "?";
}
