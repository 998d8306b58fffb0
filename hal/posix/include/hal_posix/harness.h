/*
 * hal_posix/harness.h - the host harness: boards, a virtual interrupt controller per board,
 * simulated time and a deterministic event queue. Used by sim/ and by tests; never by
 * portable firmware.
 *
 * Model (mirrors the MSP430):
 *  - Each board has the MSP430F2618's 32 vectors, numbered 0..31 as in hal/pinmap.h (vector N
 *    lives at 0xFFC0 + 2N); a higher number is a higher priority. Several sources may share one
 *    vector (the pins of a port); within a vector the lower source bit is served first.
 *  - A source is pending (its flag) and enabled (its mask). Delivery needs the board's global
 *    enable (GIE), except for non-maskable sources (NMI), which are never nested into
 *    themselves. Entering a handler clears the source flag and GIE; returning restores GIE.
 *  - Interrupts are delivered at dispatch points only: after each harness event, when a
 *    board re-enables interrupts (hal_irq_restore/enable, hal_critical_exit) and at
 *    HAL_PREEMPT_POINT() marks. Handlers run on the caller's stack, so a debugger breakpoint
 *    on a portable handler stops inside the harness's call chain.
 *  - Time is a 64-bit nanosecond count that only the event loop advances. Events at the same
 *    instant run in the order they were scheduled. No signals, no wall clock: the same
 *    schedule gives the same run.
 */
#ifndef HAL_POSIX_HARNESS_H
#define HAL_POSIX_HARNESS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "hal/capture.h"
#include "hal/edge.h"
#include "hal/signal.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Most boards one harness holds. */
#define POSIX_MAX_BOARDS  4
/** Sources per board. */
#define POSIX_MAX_SOURCES 32
/** Pending events at most. */
#define POSIX_MAX_EVENTS  4096

/** A handler as the controller sees it: the host twin of a target ISR shim. */
typedef void (*posix_isr_fn)(void *ctx);

/** Reset the whole harness: no boards, no events, time 0. */
void posix_reset(void);

/** Create a board named @p name (copied, up to 15 chars); returns its id or -1 when full. */
int posix_board_create(const char *name);

/** Make @p board the one HAL calls act on (the harness does this before calling into it). */
void posix_board_select(int board);

/** The board HAL calls act on now. */
int posix_board_current(void);

/** Name of @p board. */
const char *posix_board_name(int board);

/** Mark @p board as having main-loop work (what hal_cpu_wake() does on the host). */
void posix_board_wake(int board);

/** True (once) when @p board was woken since the last call: run a main-loop pass then. */
bool posix_board_take_wake(int board);

/**
 * Register a source on @p board: vector 0..HAL_VEC_COUNT-1 (hal/pinmap.h), bit 0..7 within the
 * vector, handler @p fn. Returns the source id, or -1 when the arguments are out of range or the
 * table is full. Registering the same (vector, bit) again replaces the handler and keeps the id.
 */
int posix_source_register(int board, int vector, int bit, bool nonmaskable, posix_isr_fn fn,
                          void *ctx);

/** Find the source (vector, bit) on @p board; -1 when absent. */
int posix_source_find(int board, int vector, int bit);

/** Set the pending flag of a source (what the hardware does on an edge). */
void posix_source_raise(int board, int source);

/** Mask (false) or unmask (true) one source. */
void posix_source_enable(int board, int source, bool enable);

/** True when the source's flag is set. */
bool posix_source_pending(int board, int source);

/** Number of times the source's handler has run. */
uint32_t posix_source_count(int board, int source);

/** Deliver every pending, allowed interrupt on every board (a dispatch point). */
void posix_dispatch(void);

/** True while @p board runs a handler. */
bool posix_in_isr(int board);

/** Global interrupt enable of @p board (its GIE). */
bool posix_gie(int board);

/* ---- simulated time and events ---- */

/** Simulated time, ns since posix_reset(). */
uint64_t posix_now_ns(void);

/** Event callback: runs at its instant with the board selection undefined. */
typedef void (*posix_event_fn)(void *ctx, uint64_t t_ns);

/**
 * Schedule @p fn at @p t_ns (not before now). Returns an event id > 0, or 0 when the queue
 * is full or @p t_ns is in the past.
 */
uint64_t posix_schedule(uint64_t t_ns, posix_event_fn fn, void *ctx);

/** Cancel a scheduled event; true when it was still queued. */
bool posix_cancel(uint64_t id);

/** Time of the next queued event, or UINT64_MAX when none. */
uint64_t posix_next_event_ns(void);

/**
 * Run events in time order up to and including @p t_ns, dispatching interrupts after each
 * one, then set the clock to @p t_ns. Returns the number of events run.
 */
uint64_t posix_run_until(uint64_t t_ns);

/**
 * Run whole instants in time order up to @p end_ns (each instant: every event queued for that
 * time, as posix_run_until() runs it), and return after the first instant at which a board
 * was woken, @p watch_board took an interrupt or an event called posix_run_stop(), or when no
 * event is left up to @p end_ns. Returns the number of events run. A loop that looks at the
 * boards only through their main loops (when woken) and @p watch_board's interrupts sees,
 * between calls, exactly what it would see after every instant of posix_run_until(): the
 * instants in between pass without the loop's overhead.
 */
uint64_t posix_run_steps(uint64_t end_ns, int watch_board);

/** From an event: make posix_run_steps() return after the current instant. */
void posix_run_stop(void);

/**
 * From an event's handler under posix_run_steps(): deliver the interrupts it raised, then move
 * the clock on to @p t_ns, the handler's next instant, without queueing an event for it (a
 * pulse train: the odometer's). Refused (false: schedule @p t_ns as usual) unless @p t_ns is
 * after now and not after posix_run_steps()'s end, no event is queued up to @p t_ns, and this
 * instant ended nothing (no board woken, no posix_run_stop(), no interrupt of the watched
 * board): then the run is exactly the one the queued event would give. Counted as an event.
 */
bool posix_advance(uint64_t t_ns);

/**
 * posix_advance(), then @p source of @p board raised at the new instant and delivered as an
 * event's would be: at once when the board takes it (interrupts on, nothing of higher
 * priority pending), else it waits, pending. The next pulse of a train whose every pulse
 * raises the same source. False (nothing raised) when posix_advance() refuses.
 */
bool posix_advance_raise(uint64_t t_ns, int board, int source);

/**
 * Hook called at every HAL_PREEMPT_POINT() (with the number of points passed so far on the
 * current board) before pending interrupts are delivered there; NULL removes it. Points are
 * only counted while a hook is set.
 */
typedef void (*posix_preempt_hook_fn)(void *ctx, int board, uint64_t point);
void posix_set_preempt_hook(posix_preempt_hook_fn fn, void *ctx);

/** Preemption points passed on @p board since posix_reset(). */
uint64_t posix_preempt_points(int board);

/* ---- peripherals, host side ---- */

/** Raise a logical edge line on @p board (as a pulse on its pin would). */
void posix_edge_raise(int board, hal_edge_line_t line);

/** Source id of a logical line on @p board, -1 when the firmware did not register it. */
int posix_edge_source(int board, hal_edge_line_t line);

/**
 * Latch a capture on @p board: @p count is what the timer would hold at the edge. A second
 * capture before the handler ran counts an overflow (the MSP430's COV) and is lost.
 */
void posix_capture_raise(int board, hal_capture_channel_t ch, uint16_t count, uint8_t rising);

/** Capture overflows (COV) seen on @p board channel @p ch. */
uint32_t posix_capture_overflows(int board, hal_capture_channel_t ch);

/**
 * Redirect the console of @p board: bytes go to @p sink (NULL restores stdout). The sink is
 * called once per byte.
 */
typedef void (*posix_console_sink_fn)(void *ctx, int board, char c);
void posix_console_redirect(posix_console_sink_fn sink, void *ctx);

/* ---- output lines (hal/signal.h) and the 1 ms clock (hal/clock.h) ---- */

/** Wire output line @p s of @p from_board to edge line @p line of @p to_board. */
void posix_signal_connect(int from_board, hal_signal_t s, int to_board, hal_edge_line_t line);

/** Forget clocks and wiring, and go back to ticked clocks (posix_reset() calls it). */
void posix_clock_signal_reset(void);

/**
 * Tickless clocks (@p on) or ticked ones (the default), for the boards that start their clock
 * after this call. Ticked: every board's tick interrupt every simulated millisecond, as on the
 * MSP430. Tickless: a board's tick interrupt only at the earliest deadline its main loop stated
 * (hal_clock_wake_at()); hal_clock_ms() counts the same milliseconds either way.
 */
void posix_clock_set_tickless(bool on);

/**
 * The tick interrupts @p board's clock took (ticked), or would have taken (tickless): the
 * milliseconds since it started.
 */
uint32_t posix_clock_ticks(int board);

/* ---- CAN (hal/can.h): the bus model, hal_posix/can_bus.h ---- */

/** Forget every CAN bus, node, frame and fault (posix_reset() calls it). */
void posix_can_reset(void);

/* ---- serial receivers (hal/uart.h): the device at the other end of the line ---- */

/** Bytes the line of one instance holds before they go out (posix_uart_send). */
#define POSIX_UART_QUEUE 512

/**
 * Send @p n bytes to instance @p instance of @p board, as the device at the other end of the
 * line does: each takes 10 bit times at the baud rate the firmware opened the instance with
 * and arrives (a receive interrupt) at the end of its stop bit, back to back after the bytes
 * sent before it (the first starts now when the line is idle). @p flags (HAL_UART_RX_ERROR)
 * marks the bytes as received with a framing error. Returns how many were queued: 0 when the
 * instance is not open, fewer than @p n when the line's queue (POSIX_UART_QUEUE) is full.
 */
size_t posix_uart_send(int board, uint8_t instance, const uint8_t *bytes, size_t n, uint8_t flags);

/** When the line of @p instance is idle again (ns): now, or when its last queued byte ends. */
uint64_t posix_uart_idle_ns(int board, uint8_t instance);

/** Source id of the receive interrupt of @p instance on @p board, -1 when not open. */
int posix_uart_source(int board, uint8_t instance);

/** Bytes overrun on @p instance of @p board so far. */
uint32_t posix_uart_overruns(int board, uint8_t instance);

/** Close every line and forget bytes in flight (posix_reset() calls it). */
void posix_uart_reset(void);

#ifdef __cplusplus
}
#endif

#endif
