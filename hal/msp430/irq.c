/*
 * irq.c - hal/irq.h on the status register's GIE bit.
 */
#include "hal/irq.h"

#include "f2618.h"
#include "hal/fault.h"

static uint8_t critical_depth;
static uint8_t critical_saved;

hal_irq_state_t hal_irq_disable(void)
{
    uint16_t sr = cy_sr_read();
    cy_dint();
    return (hal_irq_state_t)(sr & SR_GIE);
}

void hal_irq_restore(hal_irq_state_t state)
{
    if (state)
        cy_eint();
    else
        cy_dint();
}

void hal_irq_enable(void)
{
    cy_eint();
}

hal_irq_state_t hal_irq_enabled(void)
{
    return (hal_irq_state_t)(cy_sr_read() & SR_GIE);
}

void hal_critical_enter(void)
{
    uint16_t sr = cy_sr_read();
    cy_dint();
    if (critical_depth >= HAL_CRITICAL_MAX_DEPTH)
        hal_fault(HAL_FAULT_CRITICAL_OVERFLOW);
    if (critical_depth == 0)
        critical_saved = (uint8_t)((sr & SR_GIE) != 0);
    critical_depth++;
}

void hal_critical_exit(void)
{
    if (critical_depth == 0)
        hal_fault(HAL_FAULT_CRITICAL_UNDERFLOW);
    critical_depth--;
    if (critical_depth == 0 && critical_saved)
        cy_eint();
}

uint8_t hal_critical_depth(void)
{
    return critical_depth;
}
