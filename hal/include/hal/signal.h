/*
 * hal/signal.h - output lines from one board to the other.
 *
 * HAL_SIGNAL_COORD_REQUEST: the main board's "request for position" (seed 000, ch. 3.3):
 * MSP430 P2.1, wired to the nav board's RST/NMI pin (HAL_EDGE_COORD_REQUEST, falling edge):
 * hal_signal_pulse() drives it low and back high. POSIX: the harness routes the pulse to the
 * connected board's edge line (posix_signal_connect).
 */
#ifndef HAL_SIGNAL_H
#define HAL_SIGNAL_H

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    HAL_SIGNAL_COORD_REQUEST = 0, /**< main board P2.1 -> nav board RST/NMI */
    HAL_SIGNAL_COUNT
} hal_signal_t;

/** Set the line up, idle (high). */
void hal_signal_init(hal_signal_t s);

/** One pulse on the line (active low). */
void hal_signal_pulse(hal_signal_t s);

#ifdef __cplusplus
}
#endif

#endif
