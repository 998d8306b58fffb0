/*
 * mission/mission.h - the parts of a mission that no scenario sets: how the main board spaces
 * its path and times its travel, and the board link's bit rate, heartbeat and silence (a
 * scenario's "link" may set these three for agv-sim). How far the vehicle may go without an
 * optical fix (the blind distance) is the scenario's, the same for both boards. One source for
 * the board images (main_board/main_msp430.c, nav_board/main_msp430.c) and for agv-sim
 * (sim/mission.c), which build the rest of their configuration from a scenario. Metres and
 * metres per second in Q16 (fx_q16_t).
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
 * The main board's travel configuration (drive_seq_config_t) in @p mode (drive_mode_t) with
 * the blind distance @p blind (metres Q16): the load 35 ms after the fix, 50 ms of servo
 * settling, 0.15 m/s on the stopping arc, the next target taken 0.4 m ahead; simplified travel
 * tolerates three consecutive failed fixes; full travel drives on dead reckoning through fix
 * gaps, slower as they grow, and stops after @p blind without a fix. The nav board's stop
 * distance (G6) is the same @p blind: one value, the scenario's `blind_distance_m`
 * (MISSION_BLIND_DISTANCE in the generated mission of the board images).
 */
#define MISSION_SEQ_CONFIG(mode, blind)                                                            \
    {                                                                                              \
        (mode), 35u, 50u, 9830l /* 0.15 m/s */, 26214l /* 0.4 m */, 3u, (blind)                    \
    }

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
