/*
 * layout.h - what the MSP430 assembly needs of the public headers as plain numbers: the
 * offsets of the structures it reads and writes (MSP430 layout: 2-byte pointers and enums,
 * int32 aligned to 2), states, events and actions. seq.c checks every one against the C
 * definitions when it is compiled for the MSP430.
 */
#ifndef DRIVE_MSP430_LAYOUT_H
#define DRIVE_MSP430_LAYOUT_H

/* drive_pose_t, drive_board_t */
#define POSE_HEADING   8
#define BOARD_MIN_R    4
/* drive_path_t */
#define PATH_PTS       0
#define PATH_N         2
#define PATH_START     4
#define PATH_NOMINAL   16
#define PATH_REVERSE   24
#define PATH_BOARD     26
#define PATH_READY     28
#define PATH_BAD_LEG   29
#define PATH_BAD_SUB   30
#define PATH_BAD_WHY   32
#define PATH_CACHE_LEG 34
#define PATH_CACHE     36
/* drive_cmd_t */
#define CMD_PULSES     5
#define CMD_SIZE       14
/* drive_seq_t */
#define SEQ_MODE       0
#define SEQ_LOAD_MS    2
#define SEQ_SETTLE_MS  4
#define SEQ_STOP_SPD   6
#define SEQ_ADVANCE    10
#define SEQ_MAX_FIX    14
#define SEQ_PATH       16
#define SEQ_STATE      18
#define SEQ_TARGET     20
#define SEQ_LOADED     22
#define SEQ_PENDING    36
#define SEQ_PEND_LAST  50
#define SEQ_LOAD_LAST  51
#define SEQ_SEEN       52
#define SEQ_FIXFAIL    53
#define SEQ_STATUS     54
#define SEQ_IGNORED    56
#define SEQ_UNDERRUNS  58
#define SEQ_LOADS      60
/* drive_seq_out_t */
#define OUT_ACTIONS    0
#define OUT_CMD        2
#define OUT_SPEED      16
#define OUT_TIMER      18
#define OUT_POSE_MS    20
#define OUT_FAULT      22
#define OUT_STATUS     24
#define OUT_SIZE       26
/* drive_seq_event_t */
#define EV_POSE        2
/* drive_seq_row_t */
#define ROW_SIZE       6

/* drive_state_t, drive_evt_t, drive_mode_t, drive_fault_t */
#define ST_F_START       1
#define ST_F_PREDICT     5
#define ST_S_FIX         11
#define ST_ANY           0xFF
#define EVT_FIX_READY    2
#define EVT_FIX_FAILED   3
#define EVT_POSE         4
#define EVT_DELTA_S      5
#define MODE_FULL        0
#define FAULT_NOT_READY  1
#define FAULT_SOLVE      2
#define FAULT_FIXES      3
/* DRIVE_ACT_* */
#define ACT_REQUEST_POSE 0x0008
#define ACT_LOAD         0x0010
#define ACT_SET_SPEED    0x0020
#define ACT_TIMER        0x0040
#define ACT_FAULT        0x0400

/* The halves of a 32-bit constant. */
#define HI(x) ((x) >> 16)
#define LO(x) ((x)&0xFFFF)

#endif
