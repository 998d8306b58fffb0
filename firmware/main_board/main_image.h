/*
 * main_image.h - what each main board image builds in (main_image_beacon.c for main_board.elf,
 * main_image_pursuit.c for main_board_pursuit.elf) for the reset-to-main-loop they share
 * (main_msp430.c). MSP430 only.
 */
#ifndef MAIN_IMAGE_H
#define MAIN_IMAGE_H

#include "main_board.h"

/** The image's download, a constant in flash (main_board_init() keeps it by reference). */
extern const main_board_config_t main_image_cfg;

/** The console's banner: the board and its mission, one line with its "\r\n". */
extern const char main_image_banner[];

/** What the console says when the CAN controller does not answer (one line with "\r\n"). */
extern const char main_image_no_link[];

#endif
