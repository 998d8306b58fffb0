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
/** Host only: non-zero while the harness watches preemption points (a hook is set). */
extern volatile int hal_preempt_armed;
/* Interrupts become deliverable mid-code only through a hook: without one, a point costs a
 * load and a branch (the simulator's hot path passes many of them). */
#define HAL_PREEMPT_POINT()                                                                        \
    do {                                                                                           \
        if (hal_preempt_armed)                                                                     \
            hal_preempt_point();                                                                   \
    } while (0)
#endif

#ifdef __cplusplus
}
#endif

#endif
