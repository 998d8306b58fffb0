/*
 * irq.c - hal/irq.h on the virtual interrupt controller of the current board.
 */
#include "hal/irq.h"

#include "hal/fault.h"
#include "hal_posix/harness.h"
#include "harness_internal.h"

hal_irq_state_t hal_irq_disable(void)
{
    return posix_current_set_gie(false) ? 1u : 0u;
}

void hal_irq_restore(hal_irq_state_t state)
{
    posix_current_set_gie(state != 0);
    if (state)
        posix_current_dispatch(); /* pending interrupts are taken right after EINT */
}

void hal_irq_enable(void)
{
    hal_irq_restore(1u);
}

hal_irq_state_t hal_irq_enabled(void)
{
    return posix_current_gie() ? 1u : 0u;
}

void hal_critical_enter(void)
{
    hal_irq_state_t was = hal_irq_disable();
    posix_board_state_t *st = posix_current_state();
    if (st->critical_depth >= HAL_CRITICAL_MAX_DEPTH)
        hal_fault(HAL_FAULT_CRITICAL_OVERFLOW);
    if (st->critical_depth == 0)
        st->critical_saved = was != 0;
    st->critical_depth++;
}

void hal_critical_exit(void)
{
    posix_board_state_t *st = posix_current_state();
    if (st->critical_depth == 0)
        hal_fault(HAL_FAULT_CRITICAL_UNDERFLOW);
    st->critical_depth--;
    if (st->critical_depth == 0 && st->critical_saved)
        hal_irq_restore(1u);
}

uint8_t hal_critical_depth(void)
{
    return posix_current_state()->critical_depth;
}
