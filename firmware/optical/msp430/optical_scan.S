/*
 * optical_scan.S - optical_scan (optical/fastmath.h) on the MSP430: the expected angle and
 * window of every map beacon and the candidate pairs within the windows, the identification's
 * inner loop (O2-O3). scan_k.c is its C twin, the definition of every result; this performs
 * the very same integer steps (docs/kernels.md: the fix floor needs it; the check images run
 * both on every call).
 *
 * Registers as clang emits calls (TI EABI): arguments in R12..R15 (32-bit ones in pairs, R12
 * the low word), results in R12; R11..R15 may be clobbered, R4..R10 are preserved. The
 * 16 x 16 hardware multiplier (MPY, OP2, RESLO, RESHI) is used with interrupts enabled: the
 * kernel runs on the main board only, where no interrupt handler touches the multiplier
 * (tools/stack_bound.py --no-mpy-in-isr checks the image; docs/optical.md).
 * Cycle counts are mspdebug's: it charges the constant-generator immediates #1, #2, #4, #8 and
 * #-1 like memory operands (see firmware/fx/msp430/fx_trig.S).
 * Structure offsets and sizes, match codes and the margin come from optical_offsets.h,
 * generated from the C headers (msp430/optical_offsets.c); the element sizes the loops step
 * by are checked below.
 */
#include "optical_offsets.h"

#define OW optical_work             /* the work area (optical/fastmath.h) */

/* The 16 x 16 hardware multiplier (MSP430F2618, SLAS541) */
    .set MPY,   0x0130
    .set OP2,   0x0138
    .set RESLO, 0x013a
    .set RESHI, 0x013c

    .if OW_TH_ELEM != 2 || OW_PSI_ELEM != 2 || OW_SM_ELEM != 1 || OW_BM_ELEM != 1
    .error "optical_scan.S steps through th, lev, we, psi, e, g by words, sm, bm, cand by bytes"
    .endif
    .if XY8_X != 0 || XY8_Y != 2 || XY8_SIZE != 4 || OW_BSTART_N != 16
    .error "optical_scan.S reads b8[k] as (x, y) words and 16 buckets"
    .endif

/* The current window centre and half-width. */
    .section .bss.optical_scan_args,"aw",@nobits
    .balign 2
sc_mid:  .skip 2
sc_half: .skip 2

/* The octant's unfolding: angle = (a ^ m[f]) + b[f] (f: 2 swapped, 4 dx < 0, 8 dy < 0), i.e.
 * base[f] + a, or base[f] - a = base[f] + 1 + ~a. */
    .section .rodata.optical_unfold,"a",@progbits
    .balign 2
oct_m:
    .short  0, -1, -1, 0, -1, 0, 0, -1
oct_b:
    .short  0, 16385, 32769, 16384, 1, 49152, 32768, 49153

/* BUCKET_START: R14 = lo -> R14 = bstart[lo >> 12], the first sighting of lo's 1/16 turn. */
.macro BUCKET_START
    swpb    r14
    mov.b   r14, r14
    rra     r14
    rra     r14
    rra     r14
    rra     r14
    mov.b   OW+OW_BSTART(r14), r14
.endm

/*
 * Window part with margin: R13 = lever l (2^-8 m), R11 = g -> R15 = min(ceil(l g / 256),
 * 0x7fff) + MARGIN (0x7fff + MARGIN for g = 0xffff). Clobbers R13.
 */
    .section .text.optical_scan,"ax",@progbits
win6:
    mov     #0x7fff+MARGIN, r15
    cmp     #-1, r11
    jeq     2f
    mov     r13, &MPY
    mov     r11, &OP2
    mov     &RESLO, r15
    add     #255, r15
    mov     &RESHI, r13
    adc     r13
    cmp     #0x0080, r13            ; >= 2^15 after the shift: cap
    jhs     1f
    swpb    r13                     ; (hi:lo) >> 8
    swpb    r15
    mov.b   r15, r15
    bis     r13, r15
    add     #MARGIN, r15
    ret
1:  mov     #0x7fff+MARGIN, r15
2:  ret

/*
 * Marks (optical_pair() in ident.c): R12 = sighting j, R13 = 2j, R4 = 2 beacon k, R15 = w: sm[j],
 * bm[k] get the partner (or MULTI), we[j] = w. Clobbers R9 (= k).
 */
mark:
    mov     r15, OW+OW_WE(r13)
    mov     r4, r9
    rra     r9
    cmp.b   #MATCH_NONE, OW+OW_SM(r12)
    jne     1f
    mov.b   r9, OW+OW_SM(r12)
    jmp     2f
1:  mov.b   #MATCH_MULTI, OW+OW_SM(r12)
2:  cmp.b   #MATCH_NONE, OW+OW_BM(r9)
    jne     3f
    mov.b   r12, OW+OW_BM(r9)
    ret
3:  mov.b   #MATCH_MULTI, OW+OW_BM(r9)
    ret

/*
 * Keep the pair (j, k): R12 = j, R4 = 2k, R8 = 2 nc (0x1fe: more than
 * MAX_CAND pairs, none kept any more). Clobbers R9.
 */
keep:
    cmp     #2*MAX_CAND, r8
    jhs     1f
    mov.b   r12, OW+OW_CAND(r8)
    mov     r4, r9
    rra     r9
    mov.b   r9, OW+OW_CAND+1(r8)
    incd    r8
    ret
1:  mov     #0x1fe, r8
    ret

/*
 * Pair test (optical_pair() in ident.c): R12 = j, R13 = 2j, R4 = 2k -> carry set when the pair
 * lies within the windows (sc_mid, sc_half) (then marked). Clobbers R9, R11, R14, R15.
 */
pair_test:
    mov     OW+OW_E(r4), r15        ; w = e[k], or the lever's window
    tst     &OW+OW_LEVER8
    jz      1f
    mov     OW+OW_LEV(r13), r11
    tst     r11
    jz      1f
    push    r13
    mov     &OW+OW_EPS8, r13        ; min(eps8 + lev, 0xffff)
    add     r11, r13
    jnc     2f
    mov     #-1, r13
2:  mov     OW+OW_G(r4), r11
    call    #win6
    pop     r13
1:  mov     OW+OW_TH(r13), r11      ; |th[j] - psi[k] - mid|
    sub     OW+OW_PSI(r4), r11
    sub     &sc_mid, r11
    tst     r11
    jge     3f
    inv     r11
    inc     r11
3:  mov     &sc_half, r14           ; half + w
    add     r15, r14
    cmp     r11, r14
    jlo     4f
    call    #mark
    setc
    ret
4:  clrc
    ret

/* R15:R14 -> R14 = floor(R15:R14 / 2^8), R15 = 0 when within [-2^23, 2^23), else not 0. */
es_to8:
    add     #0x0080, r15            ; the high word + 128 below 2^8
    cmp     #0x0100, r15
    jhs     1f
    swpb    r14
    mov.b   r14, r14
    swpb    r15                     ; ((high word + 128) << 8) - 2^15: the high word << 8
    sub     #0x8000, r15
    bis     r15, r14
    clr     r15
1:  ret

/*
 * uint8_t optical_scan(int16_t mid, uint16_t half): R12 = mid, R13 = half -> R12 = 0,
 * or 1 when the position lies beyond the compiled map's reach (then nothing is touched). The
 * marks sm as optical_drop leaves them (NONE or DROPPED): not cleared.
 * R4 = 2k, R5 = &b8[k], R6 = px, R7 = k, R8 = 2 nc; per beacon R9 = m8, R10 = eps8 shifted
 * with u (2^l eps8), R11 = flags, then h (R13 from the ratio's product on). The frame: 0 the
 * map's end, 2 min(gate8 + 1, 0xffff) (m8 from there on: gated), 4 the larger of min(2 amax8,
 * 0xffff) and the next (m8 from there on: a window with k = 2/3), 6 max(77, amax8 + 1) (m8
 * from there on: a window; saturated), 8 mid - half, 10 2 half, 12 0x7000 - half, 0 when that
 * is negative or moving (e from there on: every sighting, or moving), 14 py. Without
 * sightings the half-width is taken as 0x7000 (every sighting, i.e. none).
 * (px, py) = floor(((x, y) - (ox, oy)) / 2^8): the offsets b8[k] - (px, py) have magnitudes
 * below 2^16 and the signs that JGE reads after the subtraction (N xor V).
 * The multiplier is used with interrupts enabled: no interrupt handler of the main board
 * touches it (tools/stack_bound.py --no-mpy-in-isr checks the image).
 */
    .global optical_scan
    .type optical_scan,@function
optical_scan:
    mov     &OW+OW_X, r14           ; px = floor((x - ox) / 2^8) into R11, then py into R14
    mov     &OW+OW_X+2, r15
    sub     &OW+OW_OX, r14
    subc    &OW+OW_OX+2, r15
    call    #es_to8
    tst     r15
    jnz     es_far
    mov     r14, r11
    mov     &OW+OW_Y, r14
    mov     &OW+OW_Y+2, r15
    sub     &OW+OW_OY, r14
    subc    &OW+OW_OY+2, r15
    call    #es_to8
    tst     r15
    jz      1f
es_far:                             ; beyond the compiled map's reach
    mov     #1, r12
    ret
1:  push    r10
    push    r9
    push    r8
    push    r7
    push    r6
    push    r5
    push    r4
    sub     #18, r1
    mov     r12, &sc_mid
    tst.b   &OW+OW_N
    jnz     1f
    mov     #0x7000, r13
1:  mov     r13, &sc_half
    sub     r13, r12                ; mid - half
    mov     r12, 8(r1)
    mov     r13, r12                ; 2 half
    add     r12, r12
    mov     r12, 10(r1)
    mov     #0x7000, r12            ; 0x7000 - half, or 0
    sub     r13, r12
    jnc     2f
    tst     &OW+OW_LEVER8           ; (moving: always, then es_mov)
    jz      3f
2:  clr     r12
3:  mov     r12, 12(r1)
    mov     &OW+OW_GATE8, r12       ; gate8 + 1, saturated
    add     #1, r12
    jnc     7f
    mov     #-1, r12
7:  mov     r12, 2(r1)
    clr     r8                      ; 2 nc
    mov     &OW+OW_AMAX8, r12       ; amax8 + 1, at least 77, saturated
    mov     r12, r13
    add     #1, r13
    jnc     4f
    mov     #-1, r13
4:  cmp     #77, r13
    jhs     5f
    mov     #77, r13
5:  mov     r13, 6(r1)
    rla     r12                     ; 2 amax8, saturated
    jnc     6f
    mov     #-1, r12
6:  cmp     r13, r12                ; (and at least the window's threshold)
    jhs     8f
    mov     r13, r12
8:  mov     r12, 4(r1)
    mov     &OW+OW_B8, r5
    mov.b   &OW+OW_NB, r12          ; the map's end
    rla     r12
    rla     r12
    add     r5, r12
    mov     r12, 0(r1)
    mov     r14, 14(r1)             ; py
    mov     r11, r6                 ; px
    clr     r4
    clr     r7
    cmp     @r1, r5
    jhs     es_done
es_beacon:
    mov     @r5+, r12               ; x8 = b8.x - px, y8 = b8.y - py, each to its magnitude
    mov     @r5+, r14
    clr     r11                     ; flags 4 x8 < 0, 8 y8 < 0, 2 swapped
    sub     14(r1), r14
    jge     2f
    mov     r14, r9
    clr     r14
    sub     r9, r14
    bis     #8, r11
2:  sub     r6, r12
    jge     1f
    mov     r12, r9
    clr     r12
    sub     r9, r12
    bis     #4, r11
1:  cmp     r14, r12                ; the larger in R12
    jhs     3f
    xor     r12, r14
    xor     r14, r12
    xor     r12, r14
    bis     #2, r11
3:  cmp     2(r1), r12              ; beyond the gate
    jhs     es_gated
    mov     r12, r9                 ; m8
    mov     &OW+OW_EPS8, r10        ; u, v and eps8 left by l: 8, 4, 2, 1
    cmp     #0x0100, r12
    jhs     4f
    tst     r12
    jz      es_zero                 ; (0, 0): angle 0
    swpb    r12
    swpb    r14
    swpb    r10                     ; (eps8 < m8 < 2^8 where it is used)
4:  cmp     #0x1000, r12
    jhs     5f
    rla     r12
    rla     r12
    rla     r12
    rla     r12
    rla     r14
    rla     r14
    rla     r14
    rla     r14
    rla     r10
    rla     r10
    rla     r10
    rla     r10
5:  cmp     #0x4000, r12
    jhs     6f
    rla     r12
    rla     r12
    rla     r14
    rla     r14
    rla     r10
    rla     r10
6:  tst     r12
    jn      7f
    rla     r12
    rla     r14
    rla     r10
7:
es_octant:                          ; the octant's arctangent as optical_octant (ident.c), and h
    mov     r12, r13                ; r = RT[i] - ((u mod 2^9) (RT[i] - RT[i+1]) 2^7) >> 16
    and     #0x01ff, r13
    mov     r13, &MPY
    mov     r12, r15                ; 2 (u >> 9): the tables - 128 based
    swpb    r15
    and     #0x00fe, r15
    mov     optical_recip_d_tab-128(r15), &OP2
    mov     optical_recip_tab-128(r15), r13
    sub     &RESHI, r13
    mov     r13, &MPY               ; q = (r v) >> 14, saturated (r stays the multiplier's
    mov     r14, &OP2               ; first operand for h)
    mov     &RESHI, r12
    cmp     #0x4000, r12
    jhs     es_osat
    mov     &RESLO, r15
    swpb    r12                     ; 2i = 2 (q >> 10)
    mov.b   r12, r14
    rla     r14
    mov     optical_ct_tab(r14), &OP2 ; h = (r C[i]) >> 16
    and     #0xff00, r12            ; f = q << 6
    swpb    r15
    and     #0x00c0, r15
    bis     r15, r12
    mov     &RESHI, r13
es_o1:                              ; a = AT[i] + ((AT[i+1] - AT[i]) f) >> 16, 2^-18 turn
    mov     r12, &MPY
    mov     optical_atan_tab(r14), r12
    mov     optical_atan_tab+2(r14), r15
    sub     r12, r15
    mov     r15, &OP2
    add     &RESHI, r12             ; (the table holds + 2: a >> 2 rounds; a <= 32770, C = 0)
    rrc     r12
    rra     r12
    xor     oct_m(r11), r12         ; unfold
    add     oct_b(r11), r12
    cmp     4(r1), r9               ; a window with k = 2/3
    jlo     es_wk1
    sub     &OW+OW_HEAD, r12        ; psi
    mov     r12, OW+OW_PSI(r4)
    mov     r13, r11
    mov     r13, &MPY               ; e = (h 2^l eps8) >> 16 + 1 + margin (below 2^14 + 7)
    mov     r10, &OP2
    mov     &RESHI, r15
    add     #1+MARGIN, r15
es_e:                               ; R9 = m8, R11 = h (0xffff: none), R12 = psi, R15 = e
    mov     r15, OW+OW_E(r4)
es_stand:                           ; standing: rel <= span is the window test itself
    cmp     12(r1), r15             ; that wide (or moving): test every sighting
    jhs     es_wide
    mov     r12, r10                ; lo = psi - e + mid - half, span = 2 e + 2 half
    sub     r15, r10
    add     8(r1), r10
    mov     r15, r9
    add     r9, r9
    add     10(r1), r9
    mov     r10, r14                ; j = bstart[lo >> 12]
    BUCKET_START
    mov     r14, r13                ; R13 = &th[j], R14 = j - n (counted up to 0)
    add     r13, r13
    add     #OW+OW_TH, r13
    sub.b   &OW+OW_N, r14
    mov     #-1, r12                ; bm[k]: NONE, then the sighting, then MULTI
es_walk:
    mov     @r13+, r11
    sub     r10, r11
    cmp     r11, r9                 ; rel <= span: a pair
    jlo     es_nopair
    mov     r13, r11                ; R11 = j: marks, we[j] = e, the pair kept
    sub     #OW+OW_TH+2, r11
    rra     r11
    cmp.b   #MATCH_NONE, OW+OW_SM(r11) ; sm[j]: k or MULTI (DROPPED: left alone)
    jne     es_pmulti
    mov.b   r7, OW+OW_SM(r11)
es_pwe:
    mov     r15, OW_WE-OW_TH-2(r13) ; we[j] = e
    tst     r12
    jn      1f
    mov     #MATCH_MULTI, r12
    jmp     2f
1:  mov     r11, r12
2:  cmp     #2*MAX_CAND, r8         ; keep (cand, nc)
    jhs     es_pfull
    mov.b   r11, OW+OW_CAND(r8)
    mov.b   r7, OW+OW_CAND+1(r8)
    incd    r8
es_wnext:
    sub.b   #-1, r14
    jnz     es_walk
    mov.b   &OW+OW_N, r11           ; at the list's end: from its start (not twice, and not
    rla     r11                     ; when the run began there)
    add     #OW+OW_TH, r11
    cmp     r11, r13
    jne     es_wend
    call    #es_bucket
    tst     r14
    jz      es_wend
    mov     #OW+OW_TH, r13
    inv.b   r14
    sub.b   #-1, r14
    jmp     es_walk
es_nopair:
    cmp     #0xf000, r11            ; (in lo's 1/16 turn, before lo: the next)
    jhs     es_wnext                ; else past the window
es_wend:
    mov.b   r12, OW+OW_BM(r7)
es_next:
    incd    r4
    sub     #-1, r7                 ; (mspdebug charges #1 three cycles, #-1 two)
    cmp     @r1, r5
    jlo     es_beacon
es_done:
    clr     r12
    add     #18, r1
    rra     r8                      ; nc
    mov.b   r8, &OW+OW_NC
    pop     r4
    pop     r5
    pop     r6
    pop     r7
    pop     r8
    pop     r9
    pop     r10
    ret
es_wk1:
    cmp     6(r1), r9               ; a window: m8 >= max(77, amax8 + 1)
    jlo     es_nowin
    sub     &OW+OW_HEAD, r12        ; psi
    mov     r12, OW+OW_PSI(r4)
    mov     r13, r11                ; k = 1: h + h / 2 + 2; e capped at 0x7fff + margin
    mov     r11, r15
    clrc
    rrc     r15
    add     r15, r11
    add     #2, r11
    mov     r11, &MPY
    mov     r10, &OP2
    mov     &RESHI, r15
    cmp     #0x7fff, r15
    jhs     2f
    add     #1+MARGIN, r15
    jmp     es_e
2:  mov     #0x7fff+MARGIN, r15
    jmp     es_e
es_zero:
    clr     r12
    jmp     1f
es_nowin:
1:  sub     &OW+OW_HEAD, r12        ; psi
    mov     r12, OW+OW_PSI(r4)
    mov     #-1, r11
    mov     #0x7fff+MARGIN, r15
    jmp     es_e
es_osat:                            ; (the octant) q = 0xffff: i = 63, f = 0xffc0; h
    mov     #126, r14
    mov     optical_ct_tab+126, &OP2
    mov     #0xffc0, r12
    mov     &RESHI, r13
    jmp     es_o1
es_gated:
    clr     OW+OW_E(r4)
    mov.b   #MATCH_NONE, OW+OW_BM(r7)
    jmp     es_next

es_pfull:                           ; more than MAX_CAND: nc = 0xff
    mov     #0x1fe, r8
    jmp     es_wnext
es_pmulti:                          ; sm[j] had a match: MULTI (DROPPED: left alone)
    cmp.b   #MATCH_DROPPED, OW+OW_SM(r11)
    jeq     es_wnext
    mov.b   #MATCH_MULTI, OW+OW_SM(r11)
    jmp     es_pwe

/* R14 = bstart[R10 >> 12]: the first sighting in the bucket of the window's start lo. */
es_bucket:
    mov     r10, r14
    BUCKET_START
    ret

es_wide:
    tst     &OW+OW_LEVER8
    jz      es_all
es_mov:                             ; moving: g, then each sighting's window
    cmp     #-1, r11
    jeq     4f
    cmp     #0x0100, r9             ; g = h >> (8 - l) + 1 (m8 in [2^(15 - l), 2^(16 - l)))
    jlo     2f
    clrc
    rrc     r11
1:  cmp     #0x0200, r9
    jlo     3f
    clrc
    rrc     r9
    clrc
    rrc     r11
    jmp     1b
2:  cmp     #0x0080, r9             ; (l = 8: h + 1)
    jhs     3f
    rla     r11                     ; l = 9: 2 h + 1, at most 0xfffe
    jc      5f
    cmp     #0xfffe, r11
    jhs     5f
3:  inc     r11
    jmp     4f
5:  mov     #0xfffe, r11
4:  mov     r11, OW+OW_G(r4)
    mov.b   #MATCH_NONE, OW+OW_BM(r7)
    mov     &OW+OW_AMAX8, r13       ; the widest window: the largest lever's, + half
    call    #win6
    add     &sc_half, r15
    jc      es_all2
    cmp     #0x7000, r15
    jhs     es_all2
    mov     r12, r10                ; lo = psi + mid - wmax, span = 2 wmax
    add     &sc_mid, r10
    sub     r15, r10
    mov     r15, r9
    add     r9, r9
    call    #es_bucket
    mov     r14, r12                ; j
    mov.b   &OW+OW_N, r14
31: mov     r12, r13
    add     r13, r13
    mov     OW+OW_TH(r13), r11
    sub     r10, r11
    cmp     #0xf000, r11
    jhs     32f
    cmp     r11, r9
    jlo     es_next
    cmp.b   #MATCH_DROPPED, OW+OW_SM(r12)
    jeq     32f
    push    r9
    push    r14
    call    #pair_test
    pop     r14
    jnc     33f
    call    #keep
33: pop     r9
32: inc     r12
    cmp.b   &OW+OW_N, r12
    jlo     34f
    clr     r12
34: dec     r14
    jnz     31b
    jmp     es_next
es_all:                             ; that wide: every sighting
    mov.b   #MATCH_NONE, OW+OW_BM(r7)
es_all2:
    mov.b   &OW+OW_N, r14
    tst     r14
    jz      es_next
    clr     r12
35: mov     r12, r13
    add     r13, r13
    cmp.b   #MATCH_DROPPED, OW+OW_SM(r12)
    jeq     36f
    push    r14
    call    #pair_test
    pop     r14
    jnc     36f
    call    #keep
36: inc     r12
    dec     r14
    jnz     35b
    jmp     es_next
    .size optical_scan, .-optical_scan
