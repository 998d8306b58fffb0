/*
 * hal/irq.h - global interrupt control and nested critical sections.
 *
 * Both implementations (hal/msp430: the SR.GIE bit; hal/posix: the virtual interrupt
 * controller's global enable) give the same semantics:
 *  - hal_irq_disable()/hal_irq_restore() save and restore the global enable, and nest by
 *    construction (each caller keeps its own saved state);
 *  - hal_critical_enter()/hal_critical_exit() nest with a depth counter; only the outermost
 *    exit re-enables interrupts, and only if they were enabled at the outermost enter. An exit
 *    without a matching enter, or nesting deeper than HAL_CRITICAL_MAX_DEPTH, is a misuse and
 *    ends in hal_fault() (HAL_FAULT_CRITICAL_UNDERFLOW / _OVERFLOW).
 */
#ifndef HAL_IRQ_H
#define HAL_IRQ_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Saved global interrupt enable: non-zero when interrupts were enabled. */
typedef uint16_t hal_irq_state_t;

/** Deepest allowed nesting of hal_critical_enter(). */
#define HAL_CRITICAL_MAX_DEPTH 16u

/** Disable interrupts globally; returns the previous state for hal_irq_restore(). */
hal_irq_state_t hal_irq_disable(void);

/** Restore the global interrupt enable saved by hal_irq_disable(). */
void hal_irq_restore(hal_irq_state_t state);

/** Enable interrupts globally (end of initialisation; never inside a critical section). */
void hal_irq_enable(void);

/** Non-zero when interrupts are globally enabled. */
hal_irq_state_t hal_irq_enabled(void);

/** Enter a critical section (interrupts off). Nests up to HAL_CRITICAL_MAX_DEPTH. */
void hal_critical_enter(void);

/** Leave a critical section; the outermost exit restores the state of the outermost enter. */
void hal_critical_exit(void);

/** Current nesting depth of critical sections, 0 outside any. */
uint8_t hal_critical_depth(void);

#ifdef __cplusplus
}
#endif

#endif
