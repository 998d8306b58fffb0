/*
 * capture.c - hal/capture.h on Timer_A3 clocked by the goniometer's angle clock on TACLK.
 * CCR0 captures the index pulse (CCI0A, rising edge) on its own vector; CCR1 captures both
 * edges of the photodetector (CCI1A) on the shared TIMERA1 vector. The level of CCI after
 * the capture tells the edge: the narrowest beacon pulse (about 13 counts, over 100 us) is
 * far longer than the ISR latency.
 */
#include <stddef.h>

#include "f2618.h"
#include "hal/capture.h"
#include "hal/irq.h"
#include "hal/pinmap.h"

static struct {
    hal_capture_cb_t cb;
    void *arg;
    uint16_t overflows;
} chans[HAL_CAPTURE_COUNT];

int hal_capture_init(hal_capture_channel_t ch, hal_capture_cb_t cb, void *arg)
{
    if ((unsigned)ch >= HAL_CAPTURE_COUNT || cb == NULL)
        return -1;
    hal_irq_state_t s = hal_irq_disable();
    chans[ch].cb = cb;
    chans[ch].arg = arg;
    if ((TACTL & MC_2) == 0)
        TACTL = TASSEL_0 | MC_2 | TACLR; /* count TACLK continuously */
    /* P1.0 TACLK and P1.1 CCI0A (index) or P1.2 CCI1A (beacon) */
    uint8_t pins = ch == HAL_CAPTURE_INDEX ? 0x03u : 0x05u;
    P1DIR &= (uint8_t)~pins;
    P1SEL |= pins;
    if (ch == HAL_CAPTURE_INDEX)
        TACCTL0 = CM_1 | SCS | CAP | CCIE;
    else
        TACCTL1 = CM_3 | SCS | CAP | CCIE;
    hal_irq_restore(s);
    return 0;
}

void hal_capture_enable(hal_capture_channel_t ch, uint8_t enable)
{
    if ((unsigned)ch >= HAL_CAPTURE_COUNT || chans[ch].cb == NULL)
        return;
    volatile uint16_t *ctl = ch == HAL_CAPTURE_INDEX ? &TACCTL0 : &TACCTL1;
    hal_irq_state_t s = hal_irq_disable();
    if (enable) {
        *ctl &= (uint16_t) ~(CCIFG | COV);
        *ctl |= CCIE;
    } else {
        *ctl &= (uint16_t)~CCIE;
    }
    hal_irq_restore(s);
}

uint16_t hal_capture_overflows(hal_capture_channel_t ch)
{
    return (unsigned)ch < HAL_CAPTURE_COUNT ? chans[ch].overflows : 0;
}

CY_ISR(HAL_VEC_TIMERA0, hal_isr_timera0)
{
    uint16_t count = TACCR0;
    if (TACCTL0 & COV) {
        TACCTL0 &= (uint16_t)~COV;
        chans[HAL_CAPTURE_INDEX].overflows++;
    }
    chans[HAL_CAPTURE_INDEX].cb(chans[HAL_CAPTURE_INDEX].arg, count, 1);
}

/*
 * COV is cleared with one read-modify-write of the register (bic), never by writing back a
 * copy read earlier: a capture between that read and the write would set CCIFG, and the copy
 * would clear it (the edge lost).
 */
CY_ISR(HAL_VEC_TIMERA1, hal_isr_timera1)
{
    if (TAIV != TAIV_TACCR1) /* reading TAIV clears the flag it reports; only CCR1 is on */
        return;
    uint16_t count = TACCR1;
    uint16_t ctl = TACCTL1;
    if (ctl & COV) {
        TACCTL1 &= (uint16_t)~COV;
        chans[HAL_CAPTURE_BEACON].overflows++;
    }
    chans[HAL_CAPTURE_BEACON].cb(chans[HAL_CAPTURE_BEACON].arg, count, (ctl & CCI) ? 1u : 0u);
}
