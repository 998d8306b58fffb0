/*
 * edge.c - hal/edge.h on ports 1 and 2 (pins and vectors in hal/pinmap.h).
 * The ISRs are thin: read and clear the flags of enabled pins, then call the portable handler
 * of each flagged line, lowest pin first. An edge arriving while handlers run sets its flag
 * again and the ISR is re-entered after RETI.
 */
#include <stddef.h>

#include "f2618.h"
#include "hal/edge.h"
#include "hal/irq.h"
#include "hal/pinmap.h"

/* Offsets of a port's registers from its PxIN: ports 1 and 2 have the same layout. */
enum { PORT_DIR = 2, PORT_IFG = 3, PORT_IES = 4, PORT_IE = 5, PORT_SEL = 6 };

static struct {
    hal_edge_cb_t cb;
    void *arg;
} slots[HAL_EDGE_COUNT];

/* Pin @p bit of the port at @p port (P1IN or P2IN) as an input interrupting on @p flank. */
__attribute__((noinline)) static void port_init(volatile uint8_t *port, uint8_t bit,
                                                hal_edge_flank_t flank)
{
    port[PORT_DIR] &= (uint8_t)~bit;
    port[PORT_SEL] &= (uint8_t)~bit;
    if (flank == HAL_EDGE_FALLING)
        port[PORT_IES] |= bit;
    else
        port[PORT_IES] &= (uint8_t)~bit;
    port[PORT_IFG] &= (uint8_t)~bit;
    port[PORT_IE] |= bit;
}

int hal_edge_init(hal_edge_line_t line, hal_edge_flank_t flank, hal_edge_cb_t cb, void *arg)
{
    if ((unsigned)line >= HAL_EDGE_COUNT || cb == NULL)
        return -1;
    uint8_t bit = (uint8_t)(1u << hal_edge_pin(line));
    hal_irq_state_t s = hal_irq_disable();
    slots[line].cb = cb;
    slots[line].arg = arg;
    if (HAL_EDGE_PORT_OF(line) == 0) {
        /* RST/NMI pin in NMI mode; the watchdog stays held. */
        WDTCTL = (uint16_t)(WDTPW | WDTHOLD | WDTNMI | (flank == HAL_EDGE_FALLING ? WDTNMIES : 0u));
        IFG1 &= (uint8_t)~NMIIFG;
        IE1 |= NMIIE;
    } else {
        port_init(HAL_EDGE_PORT_OF(line) == 1 ? &P1IN : &P2IN, bit, flank);
    }
    hal_irq_restore(s);
    return 0;
}

void hal_edge_enable(hal_edge_line_t line, uint8_t enable)
{
    if ((unsigned)line >= HAL_EDGE_COUNT || slots[line].cb == NULL)
        return;
    uint8_t bit = (uint8_t)(1u << hal_edge_pin(line));
    volatile uint8_t *ie = &P2IE;
    if (HAL_EDGE_PORT_OF(line) == 0) {
        ie = &IE1;
        bit = NMIIE;
    } else if (HAL_EDGE_PORT_OF(line) == 1) {
        ie = &P1IE;
    }
    hal_irq_state_t s = hal_irq_disable();
    if (enable)
        *ie |= bit;
    else
        *ie &= (uint8_t)~bit;
    hal_irq_restore(s);
}

/* Lines are enumerated in ascending pin order within each port (hal/edge.h). */
static inline void dispatch(unsigned port, uint8_t flags)
{
    for (unsigned line = 0; line < HAL_EDGE_COUNT; line++) {
        if (HAL_EDGE_PORT_OF(line) == port && (flags & (1u << hal_edge_pin(line))))
            slots[line].cb(slots[line].arg);
    }
}

CY_ISR(HAL_VEC_PORT1, hal_isr_port1)
{
    uint8_t f = P1IFG & P1IE;
    P1IFG &= (uint8_t)~f;
    dispatch(1, f);
}

CY_ISR(HAL_VEC_PORT2, hal_isr_port2)
{
    uint8_t f = P2IFG & P2IE;
    P2IFG &= (uint8_t)~f;
    dispatch(2, f);
}

/*
 * The NMI: its entry hal_isr_nmi (nmi.S, which also binds the vector) calls this with NMIIE
 * cleared by the hardware and sets NMIIE again as its last instruction before RETI. NMIIFG stays
 * set after acceptance until software clears it: first, so that a request arriving while the
 * handler runs is kept for after it.
 */
void hal_isr_nmi_body(void);
void hal_isr_nmi_body(void)
{
    IFG1 &= (uint8_t)~NMIIFG;
    slots[HAL_EDGE_COORD_REQUEST].cb(slots[HAL_EDGE_COORD_REQUEST].arg);
}
