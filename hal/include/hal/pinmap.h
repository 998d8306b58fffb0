/*
 * hal/pinmap.h - where the logical lines land: vector and bit, shared by both HAL
 * implementations so that interrupt priorities are the same on the MSP430 and in the harness.
 *
 * MSP430F2618 pins: P1.0 TACLK (goniometer angle clock), P1.1 CCI0A (index pulse), P1.2 CCI1A
 * (photodetector), P1.4..P1.7 nav-board pulse inputs, P2.0 delta-S, P2.2 the MCP2515's /INT
 * (CAN), P2.7 test line, the RST/NMI pin (NMI mode) the nav board's coordinate request.
 * Vectors use TI's numbering of the F261x table (datasheet SLAS541, interrupt vector
 * addresses): vector N is the word at 0xFFC0 + 2N and has priority N (31 = reset, highest).
 */
#ifndef HAL_PINMAP_H
#define HAL_PINMAP_H

#ifndef __ASSEMBLER__
#include "hal/capture.h"
#include "hal/edge.h"
#endif

/** Vector numbers of the MSP430F2618 (word at 0xFFC0 + 2N; a higher N is served first). */
#define HAL_VEC_PORT1    18 /* 0xFFE4 */
#define HAL_VEC_PORT2    19 /* 0xFFE6 */
#define HAL_VEC_TIMERA1  24 /* 0xFFF0 TACCR1-2, TAIFG */
#define HAL_VEC_TIMERA0  25 /* 0xFFF2 TACCR0 */
#define HAL_VEC_WDT      26 /* 0xFFF4 */
#define HAL_VEC_TIMERB1  28 /* 0xFFF8 TBCCR1-6, TBIFG */
#define HAL_VEC_TIMERB0  29 /* 0xFFFA TBCCR0 */
#define HAL_VEC_NMI      30 /* 0xFFFC */
#define HAL_VEC_RESET    31 /* 0xFFFE */
/** Number of vectors (0..HAL_VEC_COUNT-1). */
#define HAL_VEC_COUNT    32
/** Receive vectors of the hal/uart.h instances. */
#define HAL_VEC_UART0_RX 17 /* 0xFFE2 USCIAB1RX: USCI_A1 */
#define HAL_VEC_UART1_RX 23 /* 0xFFEE USCIAB0RX: USCI_A0 */

/** CAN instance 0 (hal/can.h): the MCP2515's /INT on P2.2, falling edge, PORT2 vector. */
#define HAL_CAN0_INT_PORT 2
#define HAL_CAN0_INT_PIN  2
#define HAL_CAN0_VECTOR   HAL_VEC_PORT2

#ifndef __ASSEMBLER__
/** Port (1 or 2) of each edge line; 0 for the NMI pin. */
#define HAL_EDGE_PORT_OF(line)                                                                     \
    ((line) == HAL_EDGE_COORD_REQUEST                                                      ? 0     \
     : (line) == HAL_EDGE_DELTA_S || (line) == HAL_EDGE_CAN_INT || (line) == HAL_EDGE_TEST ? 2     \
                                                                                           : 1)

/** Pin (0..7) of each edge line on its port (bit 0 of the NMI vector for the NMI pin). */
static inline unsigned hal_edge_pin(hal_edge_line_t line)
{
    static const unsigned char pins[HAL_EDGE_COUNT] = {4, 5, 6, 7, 0, 2, 7, 0};
    return pins[line];
}

/** Vector of each edge line. */
static inline unsigned hal_edge_vector(hal_edge_line_t line)
{
    unsigned port = HAL_EDGE_PORT_OF(line);
    return port == 0 ? HAL_VEC_NMI : port == 2 ? HAL_VEC_PORT2 : HAL_VEC_PORT1;
}

/** Vector of each capture channel (CCR0 has its own, CCR1 shares TIMERA1). */
static inline unsigned hal_capture_vector(hal_capture_channel_t ch)
{
    return ch == HAL_CAPTURE_INDEX ? HAL_VEC_TIMERA0 : HAL_VEC_TIMERA1;
}
#endif

#endif
