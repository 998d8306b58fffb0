/*
 * hal/preempt.h - preemption points for the host harness.
 *
 * On the MSP430 an interrupt can land between any two instructions. The host harness runs
 * handlers as plain function calls, so it can only interrupt code where that code lets it:
 * HAL_PREEMPT_POINT() marks such a place. On the target it compiles to nothing; on the host it
 * lets the harness raise interrupts "now" (tests use it to land an interrupt at every marked
 * point of a reader or a writer) and delivers whatever is pending and allowed.
 */
#ifndef HAL_PREEMPT_H
#define HAL_PREEMPT_H

#ifdef __cplusplus
extern "C" {
#endif

#ifdef __MSP430__
#define HAL_PREEMPT_POINT() ((void)0)
#else
/** Host only: give the harness a chance to deliver interrupts here. */
void hal_preempt_point(void);
#define HAL_PREEMPT_POINT() hal_preempt_point()
#endif

#ifdef __cplusplus
}
#endif

#endif
