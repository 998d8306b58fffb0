/*
 * hal/pinmap.h - where the logical lines land: vector and bit, shared by both HAL
 * implementations so that interrupt priorities are the same on the MSP430 and in the harness.
 *
 * MSP430F249 pins: P1.0 TACLK (goniometer angle clock), P1.1 CCI0A (index pulse), P1.2 CCI1A
 * (photodetector), P1.4..P1.7 nav-board pulse inputs, P2.0 delta-S, P2.7 test line, the
 * RST/NMI pin (NMI mode) the nav board's coordinate request.
 * Vectors use clang's interrupt(N) numbering (vector N at 0xFFE0 + 2(N-1)).
 */
#ifndef HAL_PINMAP_H
#define HAL_PINMAP_H

#include "hal/capture.h"
#include "hal/edge.h"

/** Vector numbers of the MSP430F249 (clang interrupt(N) numbering). */
#define HAL_VEC_PORT2   2  /* 0xFFE2 */
#define HAL_VEC_LINK_TX 3  /* 0xFFE4 USCIAB1TX */
#define HAL_VEC_LINK_RX 4  /* 0xFFE6 USCIAB1RX */
#define HAL_VEC_PORT1   5  /* 0xFFE8 */
#define HAL_VEC_TIMERA1 6  /* 0xFFEA */
#define HAL_VEC_TIMERA0 7  /* 0xFFEC */
#define HAL_VEC_WDT     11 /* 0xFFF4 */
#define HAL_VEC_TIMERB1 13 /* 0xFFF8 */
#define HAL_VEC_TIMERB0 14 /* 0xFFFA */
#define HAL_VEC_NMI     15 /* 0xFFFC */
#define HAL_VEC_RESET   16 /* 0xFFFE */

/** Port (1 or 2) of each edge line; 0 for the NMI pin. */
#define HAL_EDGE_PORT_OF(line)                                                                     \
    ((line) == HAL_EDGE_COORD_REQUEST                        ? 0                                   \
     : (line) == HAL_EDGE_DELTA_S || (line) == HAL_EDGE_TEST ? 2                                   \
                                                             : 1)

/** Pin (0..7) of each edge line on its port (bit 0 of the NMI vector for the NMI pin). */
static inline unsigned hal_edge_pin(hal_edge_line_t line)
{
    static const unsigned char pins[HAL_EDGE_COUNT] = {4, 5, 6, 7, 0, 7, 0};
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
