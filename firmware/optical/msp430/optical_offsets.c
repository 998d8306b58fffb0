/*
 * optical_offsets.c - what the optical kernels' assembly (optical_scan.S, optical_tri.S) needs
 * of the C headers, as CY_OFFSET markers: cy_asm_offsets() turns them into optical_offsets.h
 * (docs/kernels.md). The element sizes are there for the assembly's own checks (.if/.error):
 * it steps through the arrays by them.
 */
#include "cy_offsets.h"
#include "optical/fastmath.h"

#define OW_OFF(sym, field) CY_OFFSET(sym, offsetof(optical_work_t, field))

void optical_offsets(void);

void optical_offsets(void)
{
    /* optical_work_t: optical_scan reads the position, the map and the sightings, writes the
     * windows, the marks and the candidate pairs */
    OW_OFF(OW_X, x);
    OW_OFF(OW_Y, y);
    OW_OFF(OW_HEAD, head);
    OW_OFF(OW_EPS8, eps8);
    OW_OFF(OW_LEVER8, lever8);
    OW_OFF(OW_AMAX8, amax8);
    OW_OFF(OW_GATE8, gate8);
    OW_OFF(OW_NB, nb);
    OW_OFF(OW_N, n);
    OW_OFF(OW_NC, nc);
    OW_OFF(OW_TH, th);
    OW_OFF(OW_LEV, lev);
    OW_OFF(OW_WE, we);
    OW_OFF(OW_SM, sm);
    OW_OFF(OW_BSTART, bstart);
    OW_OFF(OW_PSI, u.id.psi);
    OW_OFF(OW_E, u.id.e);
    OW_OFF(OW_G, u.id.g);
    OW_OFF(OW_BM, u.id.bm);
    OW_OFF(OW_CAND, u.id.cand);
    OW_OFF(OW_B8, b8);
    OW_OFF(OW_OX, ox);
    OW_OFF(OW_OY, oy);
    CY_OFFSET(OW_TH_ELEM, sizeof optical_work.th[0]);
    CY_OFFSET(OW_PSI_ELEM, sizeof optical_work.u.id.psi[0]);
    CY_OFFSET(OW_SM_ELEM, sizeof optical_work.sm[0]);
    CY_OFFSET(OW_BM_ELEM, sizeof optical_work.u.id.bm[0]);
    CY_OFFSET(OW_BSTART_N, sizeof optical_work.bstart);
    CY_OFFSET(XY8_X, offsetof(optical_xy8_t, x));
    CY_OFFSET(XY8_Y, offsetof(optical_xy8_t, y));
    CY_OFFSET(XY8_SIZE, sizeof(optical_xy8_t));
    /* the match codes (NONE as a signed byte: the constant generator's -1), the margin, the
     * candidate pairs kept */
    CY_OFFSET(MATCH_NONE, (int8_t)OPTICAL_NONE);
    CY_OFFSET(MATCH_MULTI, OPTICAL_MULTI);
    CY_OFFSET(MATCH_DROPPED, OPTICAL_DROPPED);
    CY_OFFSET(MARGIN, OPTICAL_MARGIN);
    CY_OFFSET(MAX_CAND, OPTICAL_MAX_CAND);
    /* optical_tsol_t: what optical_tri_core writes and optical_tri_quality reads */
    CY_OFFSET(TSOL_OFF, offsetof(optical_tsol_t, off));
    CY_OFFSET(TSOL_W, offsetof(optical_tsol_t, w));
    CY_OFFSET(TSOL_L, offsetof(optical_tsol_t, l));
    CY_OFFSET(TSOL_R, offsetof(optical_tsol_t, r));
    CY_OFFSET(TSOL_X, offsetof(optical_tsol_t, x));
    CY_OFFSET(E_DEGENERATE, OPTICAL_E_DEGENERATE);
    CY_OFFSET(E_SINGULAR, OPTICAL_E_SINGULAR);
    CY_OFFSET(E_INCONSISTENT, OPTICAL_E_INCONSISTENT);
    CY_OFFSET(E_ARG, OPTICAL_E_ARG);
}
