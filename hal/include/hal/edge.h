/*
 * hal/edge.h - edge-triggered interrupt lines.
 *
 * Every pulse input of the two boards is a logical line. The pin map (hal/msp430: port, pin
 * and vector; hal/posix: the same vector numbers on the virtual interrupt controller) decides
 * where it lands; the firmware only registers the portable handler. Priorities are the
 * MSP430's and identical on both targets: Port 1 (vector 5) above Port 2 (vector 2), and
 * within one port the lower pin is served first. HAL_EDGE_COORD_REQUEST is the RST/NMI pin
 * in NMI mode (vector 15): it is served even with interrupts disabled, inside critical
 * sections and inside other handlers (the seed's unmaskable "Coordinate Request"), but never
 * nested into itself.
 */
#ifndef HAL_EDGE_H
#define HAL_EDGE_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Logical pulse lines. */
typedef enum {
    HAL_EDGE_DELTA_L = 0,    /**< nav board: odometer pulse (front-wheel travel dl)     P1.4 */
    HAL_EDGE_GYRO_UP,        /**< nav board: gyro heading +1 step (counter-clockwise)   P1.5 */
    HAL_EDGE_GYRO_DOWN,      /**< nav board: gyro heading -1 step (clockwise)           P1.6 */
    HAL_EDGE_BEACON_SIGHTED, /**< nav board: main board photodetector pulse (sighting) P1.7 */
    HAL_EDGE_DELTA_S,        /**< main board: drive board's segment-almost-done pulse   P2.0 */
    HAL_EDGE_CAN_INT,        /**< both boards: the MCP2515's /INT (falling edge)         P2.2 */
    HAL_EDGE_TEST,           /**< free line for tests                                   P2.7 */
    HAL_EDGE_COORD_REQUEST,  /**< nav board: coordinate request, NON-MASKABLE    RST/NMI pin */
    HAL_EDGE_COUNT
} hal_edge_line_t;

/** Which edge raises the interrupt. */
typedef enum { HAL_EDGE_RISING = 0, HAL_EDGE_FALLING = 1 } hal_edge_flank_t;

/** Portable handler of a line: runs in interrupt context with interrupts disabled. */
typedef void (*hal_edge_cb_t)(void *arg);

/**
 * Route @p line to @p cb (called with @p arg) on @p flank and enable it.
 * Returns 0, or -1 when @p line is out of range or @p cb is NULL (nothing changed).
 */
int hal_edge_init(hal_edge_line_t line, hal_edge_flank_t flank, hal_edge_cb_t cb, void *arg);

/** Mask (0) or unmask (non-zero) one line without losing its registration. */
void hal_edge_enable(hal_edge_line_t line, uint8_t enable);

#ifdef __cplusplus
}
#endif

#endif
