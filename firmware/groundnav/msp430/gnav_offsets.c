/*
 * gnav_offsets.c - what msp430/gnav_arith.S needs of the C headers, as CY_OFFSET markers:
 * cy_asm_offsets() compiles this with -S and tools/gen_asm_offsets.py writes gnav_offsets.h
 * (docs/kernels.md). Never linked.
 */
#include "cy_offsets.h"
#include "gnav_tables.h"
#include "groundnav/gnav.h"

void gnav_offsets(void);

void gnav_offsets(void)
{
    /* gnav_t fields the deficit reads and writes */
    CY_OFFSET(GNAV_TAB_END, offsetof(gnav_t, tab_end));
    CY_OFFSET(GNAV_N0, offsetof(gnav_t, n0));
    CY_OFFSET(GNAV_TAB_E, offsetof(gnav_t, tab_e));
    CY_OFFSET(GNAV_TAB_RHO, offsetof(gnav_t, tab_rho));
    CY_OFFSET(GNAV_RHO_P, offsetof(gnav_t, rho_p));
    CY_OFFSET(GNAV_RHO_DUE, offsetof(gnav_t, rho_due));
    CY_OFFSET(GNAV_X_P, offsetof(gnav_t, x_p));
    CY_OFFSET(GNAV_G_P, offsetof(gnav_t, g_p));
    CY_OFFSET(GNAV_M_Q11, offsetof(gnav_t, m_q11));
    CY_OFFSET(GNAV_M_Q16, offsetof(gnav_t, m_q16));
    /* ... and those the chord reads and writes */
    CY_OFFSET(GNAV_X, offsetof(gnav_t, x));
    CY_OFFSET(GNAV_Y, offsetof(gnav_t, y));
    CY_OFFSET(GNAV_RESID, offsetof(gnav_t, resid));
    CY_OFFSET(GNAV_N_LO, offsetof(gnav_t, n_lo));
    CY_OFFSET(GNAV_N_HI, offsetof(gnav_t, n_hi));
    CY_OFFSET(GNAV_N_P, offsetof(gnav_t, n_p));
    CY_OFFSET(GNAV_REVERSE, offsetof(gnav_t, reverse));
    CY_OFFSET(GNAV_D15_C, offsetof(gnav_t, d15_c));
    CY_OFFSET(GNAV_D15_S, offsetof(gnav_t, d15_s));
    /* the reciprocal table's range (gnav_tables.h, generated) */
    CY_OFFSET(GNAV_RECIP_LO_, GNAV_RECIP_LO);
    CY_OFFSET(GNAV_RECIP_HI_, GNAV_RECIP_HI);
}
