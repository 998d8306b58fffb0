/*
 * mission/mission.h - the parts of a mission that no scenario sets: how the main board spaces
 * its path and times its travel, how far the nav board lets the vehicle go without an optical
 * fix, and the board link's bit rate, heartbeat and silence (a scenario's "link" may set
 * these three for agv-sim). One source for the board images (main_board/main_msp430.c,
 * nav_board/main_msp430.c) and for agv-sim (sim/mission.c), which build the rest of their
 * configuration from a scenario. Metres and metres per second in Q16 (fx_q16_t).
 */
#ifndef MISSION_MISSION_H
#define MISSION_MISSION_H

/** Longest distance between secondary points on the path: the double-arc length, 0.8 m. */
#define MISSION_ARC_SPACING 52429l

/** The main board's path configuration (drive_path_config_t) for corner radius @p radius
 * (metres Q16): forward travel, points every MISSION_ARC_SPACING. */
#define MISSION_PATH_CONFIG(radius)                                                                \
    {                                                                                              \
        (radius), MISSION_ARC_SPACING, false                                                       \
    }

/**
 * The main board's travel configuration (drive_seq_config_t) in @p mode (drive_mode_t): the
 * load 35 ms after the fix, 50 ms of servo settling, 0.15 m/s on the stopping arc, the next
 * target taken 0.4 m ahead, three consecutive failed fixes tolerated.
 */
#define MISSION_SEQ_CONFIG(mode)                                                                   \
    {                                                                                              \
        (mode), 35u, 50u, 9830l /* 0.15 m/s */, 26214l /* 0.4 m */, 3u                             \
    }

/** The nav board asks for a stop after this much travel without a fix (G6): 5 m, Q16. */
#define MISSION_STOP_DISTANCE 327680l

/** The board link (firmware/link/link.h): the CAN bit rate, bit/s. */
#define MISSION_CAN_BITRATE  250000ul
/** Each board's heartbeat period, ms. */
#define MISSION_HEARTBEAT_MS 50u
/** A board that heard nothing from the other for this long stops (main) or asks for a stop
 * (nav), ms: five heartbeat periods. */
#define MISSION_SILENCE_MS   250u

/** The link configuration (link_config_t) of board @p node (LINKMSG_NODE_MAIN or _NAV). */
#define MISSION_LINK_CONFIG(node)                                                                  \
    {                                                                                              \
        (node), MISSION_CAN_BITRATE, MISSION_HEARTBEAT_MS, MISSION_SILENCE_MS                      \
    }

#endif
