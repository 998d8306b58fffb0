/*
 * drive_proto.h - the drive-board port protocols (SPEC D6) as sequences of bus writes, their
 * transmission through hal/drive_port.h, and a decoder that turns writes back into commands
 * (the host's drive-board model, the tests).
 *
 * 8255 style (seed 000, OUTPUT_TO_PORTS). Registers: port A carries the data byte, port B the
 * strobe codes, port C the transfer lines, CTRL the 8255's control word. A load is:
 *     C <- 0x02                         PC1 up: a transfer begins
 *     CTRL <- 0x80                      mode 0, ports A, B, C outputs (resets C to 0)
 *     A <- steer1 ^ 0xFF, B <- 0x40, B <- 0x00     data inverted, then strobe, then release
 *     A <- arc1   ^ 0xFF, B <- 0x20, B <- 0x00
 *     A <- steer2 ^ 0xFF, B <- 0x50, B <- 0x00
 *     A <- arc2   ^ 0xFF, B <- 0x30, B <- 0x00
 *     A <- speed  ^ 0xFF, B <- 0x60, B <- 0x00
 *     CTRL <- 0x90                      port A back to input: the data bus is released
 *     C <- 0x82                         PC7 up (PC1 again): the transfer is complete, go
 * A speed change alone (stop: speed 0) is the same with only the speed item. The drive board
 * latches the inverted data byte on the rising edge of a strobe code and acts on PC7.
 *
 * DAC style (seed 002): HAL_DRIVE_DAC_ANGLE <- steering value (centre = straight, see
 * drive_dac_angle_byte), HAL_DRIVE_DAC_SPEED <- 128 + speed counts (128 = stop),
 * HAL_DRIVE_DIGITAL <- outputs: bit 0 drive motor (0 = enabled), bit 1 steering motor
 * (0 = enabled), bit 2 brake (0 = engaged), bit 4 left turn light, bit 5 right turn light
 * (1 = on). This board has no arc lengths: the main board times the arcs itself.
 */
#ifndef DRIVE_DRIVE_PROTO_H
#define DRIVE_DRIVE_PROTO_H

#include <stdbool.h>
#include <stdint.h>

#include "drive/drive_cmd.h"
#include "hal/drive_port.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Strobe codes on port B (seed 000). */
#define DRIVE_STROBE_STEER1 0x40u
#define DRIVE_STROBE_ARC1   0x20u
#define DRIVE_STROBE_STEER2 0x50u
#define DRIVE_STROBE_ARC2   0x30u
#define DRIVE_STROBE_SPEED  0x60u
/** 8255 control words and port C values of a transfer. */
#define DRIVE_PPI_CTRL_OUT  0x80u /* mode 0, A, B, C out */
#define DRIVE_PPI_CTRL_REL  0x90u /* mode 0, A in, B, C out */
#define DRIVE_PPI_C_BEGIN   0x02u
#define DRIVE_PPI_C_DONE    0x82u

/** Digital output bits of the DAC style (seed 002's m116 card). */
#define DRIVE_OUT_DRIVE_OFF 0x01u /* 1: drive motor disabled   */
#define DRIVE_OUT_STEER_OFF 0x02u /* 1: steering motor disabled */
#define DRIVE_OUT_BRAKE_REL 0x04u /* 1: brake released          */
#define DRIVE_OUT_LIGHT_L   0x10u /* 1: left turn light on      */
#define DRIVE_OUT_LIGHT_R   0x20u /* 1: right turn light on     */

/** Longest write sequence of this module. */
#define DRIVE_WSEQ_MAX 19u

/** One bus write. */
typedef struct {
    uint8_t reg; /**< hal_drive_reg_t */
    uint8_t value;
} drive_write_t;

/** A sequence of bus writes, sent in order. */
typedef struct {
    uint8_t n;
    drive_write_t w[DRIVE_WSEQ_MAX];
} drive_wseq_t;

/** 8255: put the PPI in its idle state (A input, B and C outputs; 1 write). Once at start. */
void drive_ppi_init(drive_wseq_t *out);

/** 8255: load a double arc and its speed (19 writes). */
void drive_ppi_load(const drive_cmd_t *cmd, drive_wseq_t *out);

/** 8255: change the speed only (7 writes); speed 0 stops the vehicle. */
void drive_ppi_speed(int8_t speed, drive_wseq_t *out);

/** DAC: set steering and speed values (2 writes: angle, then speed). */
void drive_dac_set(uint8_t angle_value, uint8_t speed_value, drive_wseq_t *out);

/** DAC: write the digital outputs (1 write, DRIVE_OUT_* bits). */
void drive_dac_outputs(uint8_t outputs, drive_wseq_t *out);

/**
 * DAC: start-up as seed 002's Init_AGV: motors off and brake on, speed 128, steering centred,
 * then brake released, steering motor on, drive motor on (6 writes).
 */
void drive_dac_start(uint8_t center, drive_wseq_t *out);

/** DAC: stop as seed 002's End_Path: steering centred, speed 128, brake on, motors off. */
void drive_dac_stop(uint8_t center, drive_wseq_t *out);

/** Send @p seq through hal_drive_port_write(), in order, with interrupts held off. */
void drive_port_send(const drive_wseq_t *seq);

/* ------------------------------------------------------------------ decoder */

/** What the decoder recognised. */
typedef enum {
    DRIVE_EV_NONE = 0,
    DRIVE_EV_LOAD,      /**< 8255: a complete double arc + speed (cmd: steer, arc, speed)  */
    DRIVE_EV_SPEED,     /**< 8255: a speed alone (cmd.speed)                              */
    DRIVE_EV_PARTIAL,   /**< 8255: a transfer with another set of items (mask says which) */
    DRIVE_EV_DAC_ANGLE, /**< DAC: steering value (value; alpha from the centre)           */
    DRIVE_EV_DAC_SPEED, /**< DAC: speed value (value; cmd.speed = value - 128)            */
    DRIVE_EV_OUTPUTS,   /**< DAC: digital outputs (value)                                 */
    DRIVE_EV_ERROR      /**< protocol violation (error says which); the transfer is lost */
} drive_ev_type_t;

/** Protocol violations. */
typedef enum {
    DRIVE_PERR_NONE = 0,
    DRIVE_PERR_MODE,        /**< control word selects a mode other than 0             */
    DRIVE_PERR_PORT_INPUT,  /**< write to a port configured as input                  */
    DRIVE_PERR_STROBE_CODE, /**< unknown strobe code on port B                        */
    DRIVE_PERR_STROBE_HELD, /**< new strobe code without the 0x00 release between     */
    DRIVE_PERR_NO_DATA,     /**< strobe while port A is not driving the bus           */
    DRIVE_PERR_REGISTER     /**< register number out of range                         */
} drive_perr_t;

/** Item bits of a transfer (mask). */
#define DRIVE_ITEM_STEER1 0x01u
#define DRIVE_ITEM_ARC1   0x02u
#define DRIVE_ITEM_STEER2 0x04u
#define DRIVE_ITEM_ARC2   0x08u
#define DRIVE_ITEM_SPEED  0x10u
#define DRIVE_ITEM_ALL    0x1Fu

/** One decoded event. */
typedef struct {
    drive_ev_type_t type;
    drive_perr_t error;
    uint8_t mask;     /**< 8255: items of the transfer */
    uint8_t value;    /**< DAC: the raw value */
    fx_angle_t alpha; /**< DAC_ANGLE: steering angle decoded from the centre */
    drive_cmd_t cmd;  /**< 8255: steer, arc and speed of the items in mask; DAC_SPEED: speed */
} drive_event_t;

/** The decoder's model of the 8255 and the drive board's latches. */
typedef struct {
    uint8_t ctrl, a, b, c; /* control word and output latches */
    uint8_t mask;          /* items latched since the last commit */
    drive_cmd_t items;
    uint8_t dac_center;
} drive_decoder_t;

/** Reset @p d (an 8255 after reset: all ports input; nothing latched). */
void drive_decoder_init(drive_decoder_t *d, uint8_t dac_center);

/**
 * Feed one bus write. Returns true and fills @p ev when the write completes something:
 * a transfer committed by PC7 rising (LOAD, SPEED, PARTIAL), a DAC or output write, or a
 * protocol violation (ERROR, after which the transfer in progress is forgotten).
 */
bool drive_decoder_feed(drive_decoder_t *d, uint8_t reg, uint8_t value, drive_event_t *ev);

#ifdef __cplusplus
}
#endif

#endif
