/*
 * optical_glue.S - MSP430 versions of the per-sighting loops of optical_fix()'s glue
 * (optical/glue.h): optical_sort, optical_buckets, optical_unique, optical_gather. fix.c holds
 * the portable C that defines the results; these perform the very same integer steps, and
 * tests/vectors/optical_vectors.c checks them bit for bit on both worlds.
 *
 * Registers as clang emits calls (TI EABI): arguments in R12..R15, results in R12; R11..R15
 * may be clobbered, R4..R10 are preserved. Structure offsets and sizes, the multiplier's
 * registers and the status codes come from layout.h (checked against the C in fastmath.c).
 * A binary angle rounded to 16 bits, (a + 2^15) >> 16, is its high word plus bit 15 of its low
 * word (RLA low, ADC high).
 */
#include "layout.h"

/*
 * bool optical_setup(const optical_map_t *map, const optical_config_t *cfg,
 * const optical_pose_t *approx, optical_width_t *wd): R12 = map, R13 = cfg, R14 = approx,
 * R15 = wd -> R12. A coordinate v lies within the limit when u = v + 2^29 - 1 < 2^30 - 1
 * (unsigned): u's high word hi + 0x1fff + (lo != 0) below 0x3fff, or equal to it with
 * lo != 0. The product with interrupts enabled (no handler of the main board uses the
 * multiplier: tools/stack_bound.py --no-mpy-in-isr).
 */
    .section .text.optical_setup,"ax",@progbits
    .global optical_setup
    .type optical_setup,@function
optical_setup:
    tst     r12                     ; the map: not NULL, 3..32 beacons
    jz      8f
    mov.b   MAP_N(r12), r11
    cmp.b   #3, r11
    jlo     8f
    cmp.b   #MAX_BEACONS+1, r11
    jhs     8f
    cmp     #1, POSE_X(r14)         ; approx x, y within the limit
    mov     POSE_X+2(r14), r11
    addc    #0x1fff, r11
    cmp     #0x3fff, r11
    jlo     1f
    jne     8f
    tst     POSE_X(r14)
    jz      8f
1:  cmp     #1, POSE_Y(r14)
    mov     POSE_Y+2(r14), r11
    addc    #0x1fff, r11
    cmp     #0x3fff, r11
    jlo     1f
    jne     8f
    tst     POSE_Y(r14)
    jz      8f
1:  mov     MAP_B(r12), &OW+OW_B
    mov.b   MAP_N(r12), &OW+OW_NB
    mov     @r14+, r12              ; x, y (approx walked)
    mov     r12, &OW+OW_X
    mov     r12, WD_X(r15)
    mov     @r14+, r12
    mov     r12, &OW+OW_X+2
    mov     r12, WD_X+2(r15)
    mov     @r14+, r12
    mov     r12, &OW+OW_Y
    mov     r12, WD_Y(r15)
    mov     @r14+, r12
    mov     r12, &OW+OW_Y+2
    mov     r12, WD_Y+2(r15)
    mov     @r14+, r12              ; head
    mov     @r14, r11
    rla     r12
    adc     r11
    mov     r11, &OW+OW_HEAD
    mov     CFG_WIN_POS(r13), r12   ; m8 = ceil(window_pos / 2^8), saturated
    mov     CFG_WIN_POS+2(r13), r11
    mov     #-1, r14
    cmp     #0x0100, r11
    jhs     1f
    swpb    r12
    swpb    r11
    mov.b   r12, r14
    bis     r11, r14
    and     #0xff00, r12
    jz      1f
    inc     r14
    jnz     1f
    mov     #-1, r14
1:  mov     r14, WD_EPS8(r15)
    add     #2, r14                 ; eps8 = m8 + 2, saturated
    jnc     2f
    mov     #-1, r14
2:  mov     r14, &OW+OW_EPS8
    mov     r14, &OW+OW_AMAX8       ; amax8 = eps8, lever8 = 0 (standing)
    clr     &OW+OW_LEVER8
    mov     CFG_DIST_TOL(r13), r12  ; tol8 = dist_tol >> 8, saturated
    mov     CFG_DIST_TOL+2(r13), r11
    mov     #-1, r14
    cmp     #0x0100, r11
    jhs     3f
    swpb    r12
    swpb    r11
    mov.b   r12, r14
    bis     r11, r14
3:  mov     r14, WD_TOL8(r15)
    mov     CFG_DIST_REL(r13), r14  ; rel16 = dist_rel, saturated
    tst     CFG_DIST_REL+2(r13)
    jz      4f
    mov     #-1, r14
4:  mov     r14, WD_REL16(r15)
    mov.b   CFG_FLAT(r13), WD_FLAT(r15) ; flat
    mov     CFG_DIAMETER(r13), &MPY
    mov     #10430, &OP2
    mov     &RESLO, r12
    mov     &RESHI, r11
    mov     CFG_DIAMETER+2(r13), &MPY
    mov     #10430, &OP2
    add     &RESLO, r11
    swpb    r12
    mov.b   r12, r12
    swpb    r11
    mov     r11, r14
    and     #0xff00, r14
    bis     r14, r12
    mov.b   r11, r11
    mov     r12, WD_DK(r15)
    mov     r11, WD_DK+2(r15)
    mov     #1, r12
    ret
8:  clr     r12
    ret

/* void optical_fix_init(optical_fix_t *out): R12 = out. */
    .section .text.optical_fix_init,"ax",@progbits
    .global optical_fix_init
    .type optical_fix_init,@function
optical_fix_init:
    mov     #-1, r14
    mov     r14, FIX_IDENT(r12)
    mov     r14, FIX_IDENT+2(r12)
    mov     r14, FIX_IDENT+4(r12)
    mov     r14, FIX_IDENT+6(r12)
    mov     r14, FIX_IDENT+8(r12)
    mov     r14, FIX_IDENT+10(r12)
    mov     r14, FIX_IDENT+12(r12)
    mov.b   r14, FIX_IDENT+MAX_SIGHTINGS-1(r12)
    clr     FIX_N_IDENT(r12)        ; n_ident, widened
    ret

/*
 * uint8_t optical_sort(const optical_sighting_t *s, uint16_t wmin): R12 = s, R13 = wmin ->
 * R12 = the kept. First every mark of the work area NONE and every wchk 0x7F, a word (two
 * sightings) at a time, all 15 (entries beyond n are not read), and bstart[0] = 0 (the word
 * after sm[13]). R12 walks s up
 * to R9 = &s[n]; R6 = i, R14 = &th[i], R10 = t, R15 = th[i - 1] (0 for i = 0: the largest so
 * far), R4 = 1, R5 = 2; the kept (n less the dropped) on the stack. A sighting not below the
 * largest so far is placed at i; otherwise it is inserted (R11 = &th[j], R15 = j; then th[i]
 * holds the largest so far). While none
 * has moved, the buckets up to each one's start are filled as it is placed (R7 = &bstart[b],
 * R8 = 2^12 b - 1: bucket b starts at i when t > R8; 0xFFFF after bucket 15, which no t
 * exceeds); after a move R7 = 0, R8 = 0xFFFF and optical_buckets does them. O4's mark as it
 * is placed: DROPPED when its width is below wmin (the NONE stays otherwise).
 */
    .if OW_BSTART - OW_SM - MAX_SIGHTINGS
    .error "optical_sort: bstart[0] must follow sm[14]"
    .endif
    .section .text.optical_sort,"ax",@progbits
    .global optical_sort
    .type optical_sort,@function
optical_sort:
    push    r10
    push    r9
    push    r8
    push    r7
    push    r6
    push    r5
    push    r4
    mov.b   &OW+OW_N, r11           ; kept = n, less the dropped
    push    r11
    mov     r11, r9                 ; &s[n] = s + 6 n
    rla     r9
    add     r11, r9
    rla     r9
    add     r12, r9
    mov     #-1, r11                ; sm = NONE, wchk = 0x7f
    mov     r11, &OW+OW_SM
    mov     r11, &OW+OW_SM+2
    mov     r11, &OW+OW_SM+4
    mov     r11, &OW+OW_SM+6
    mov     r11, &OW+OW_SM+8
    mov     r11, &OW+OW_SM+10
    mov     r11, &OW+OW_SM+12
    mov     #0x00ff, &OW+OW_SM+14   ; sm[14] and bstart[0] = 0 (bucket 0 starts at 0)
    mov     #0x7f7f, r11
    mov     r11, &OW+OW_WCHK
    mov     r11, &OW+OW_WCHK+2
    mov     r11, &OW+OW_WCHK+4
    mov     r11, &OW+OW_WCHK+6
    mov     r11, &OW+OW_WCHK+8
    mov     r11, &OW+OW_WCHK+10
    mov     r11, &OW+OW_WCHK+12
    mov.b   r11, &OW+OW_WCHK+14
    mov     #1, r4
    mov     #2, r5
    clr     r6
    mov     #OW+OW_TH, r14
    clr     r15
    mov     #0x0fff, r8
    mov     #OW+OW_BSTART+1, r7
    cmp     r9, r12                 ; (n = 0)
    jhs     9f
1:  mov     @r12+, r11              ; t = (angle + 2^15) >> 16
    mov     @r12+, r10
    rla     r11
    adc     r10
    cmp     r15, r10                ; below th[i - 1]: inserted
    jlo     20f
    mov     r10, 0(r14)
    mov     r10, r15
    mov.b   r6, OW+OW_ORD(r6)
    mov     @r12+, r11
    cmp     r13, r11                ; O4: narrower than wmin, dropped
    jlo     30f
3:  cmp     r10, r8                 ; the buckets up to t's start at i
    jhs     5f
4:  mov.b   r6, 0(r7)
    add     r4, r7
    add     #0x1000, r8
    cmp     r10, r8
    jlo     4b
5:  add     r4, r6
    add     r5, r14
    cmp     r9, r12                 ; i < n
    jlo     1b
    jmp     9f
30: mov.b   #MATCH_DROPPED, OW+OW_SM(r6)
    sub     r4, 0(r1)
    jmp     3b
20: mov     r14, r11                ; j = i; while j > 0 and th[j - 1] > t: move up
    mov     r6, r15
21: tst     r15
    jz      22f
    cmp     -2(r11), r10
    jhs     22f
    mov     -2(r11), 0(r11)
    mov.b   OW+OW_ORD-1(r15), OW+OW_ORD(r15)
    mov.b   OW+OW_SM-1(r15), OW+OW_SM(r15)
    sub     r5, r11
    sub     r4, r15
    jmp     21b
22: mov     r10, 0(r11)
    mov     @r12+, r10
    mov.b   r6, OW+OW_ORD(r15)
    mov.b   #MATCH_NONE, OW+OW_SM(r15) ; or DROPPED when narrower than wmin
    cmp     r13, r10
    jhs     24f
    mov.b   #MATCH_DROPPED, OW+OW_SM(r15)
    sub     r4, 0(r1)
24: mov     @r14, r15               ; the largest so far (moved up to i)
    mov     #-1, r8                 ; (moved: the buckets afterwards)
    clr     r7
    jmp     5b
9:  tst     r7
    jz      7f
6:  cmp     #OW+OW_BSTART+16, r7    ; the rest: 0
    jhs     8f
    clr.b   0(r7)
    add     r4, r7
    jmp     6b
7:  call    #optical_buckets
8:  pop     r12
    pop     r4
    pop     r5
    pop     r6
    pop     r7
    pop     r8
    pop     r9
    pop     r10
    ret

/*
 * void optical_buckets(void): R15 = n, R14 = j, R11 = &th[j] + 1 (its high byte), R10 = that
 * byte, R12 = 16 b (the high byte where bucket b starts; 0 after the last), R13 = &bstart[b].
 */
    .section .text.optical_buckets,"ax",@progbits
    .global optical_buckets
    .type optical_buckets,@function
optical_buckets:
    push    r10
    mov.b   &OW+OW_N, r15
    clr     r14
    mov     #OW+OW_TH+1, r11
    clr     r12
    mov     #OW+OW_BSTART, r13
1:  cmp     r15, r14                ; j < n
    jhs     5f
    mov.b   @r11, r10
    incd    r11
2:  cmp     r12, r10                ; the buckets up to th[j]'s start at j
    jlo     3f
    mov.b   r14, 0(r13)
    inc     r13
    add.b   #16, r12
    jnz     2b
    pop     r10                     ; all 16 set
    ret
3:  inc     r14
    jmp     1b
5:  cmp     #OW+OW_BSTART+16, r13   ; the rest: 0
    jhs     6f
    clr.b   0(r13)
    inc     r13
    jmp     5b
6:  pop     r10
    ret

/*
 * int8_t optical_unique(const optical_width_t *wd, const optical_sighting_t *s, int16_t *lohi):
 * R12 = wd, R13 = s, R14 = lohi (kept on the stack) -> R12 = the kept. R4 = wd, R5 = s,
 * R6 = &sm[n], R7 = kept, R8 = &sm[j + 1] (walked), R9 = lo, R10 = hi (without lohi: narrowed
 * all the same, and dropped), R11 = k, R12 = j. sm holds a beacon (below 32) or NONE, MULTI,
 * DROPPED (0xfd and up): the sign bit tells them apart. O5 by optical_width_core (R4 = wd; it
 * clobbers R11..R15 only). The cached verdict: c ^ k is 0 (fits) or 0x80 (a misfit) when c is
 * k's.
 */
    .section .text.optical_unique,"ax",@progbits
    .global optical_unique
    .type optical_unique,@function
optical_unique:
    push    r10
    push    r9
    push    r8
    push    r7
    push    r6
    push    r5
    push    r4
    push    r14
    mov     r12, r4
    mov     r13, r5
    mov     #OW+OW_SM, r8
    mov.b   &OW+OW_N, r6
    add     r8, r6
    clr     r7
    clr     r9
    clr     r10
    tst     r14
    jz      1f
    mov     0(r14), r9
    mov     2(r14), r10
1:  cmp     r6, r8                  ; (n = 0)
    jhs     9f
2:  mov.b   @r8+, r11               ; k, a beacon
    tst.b   r11
    jn      8f
    mov     r8, r12                 ; bm[k] = j
    sub     #OW+OW_SM+1, r12
    cmp.b   OW+OW_BM(r11), r12
    jne     7f
    mov.b   OW+OW_WCHK(r12), r13    ; c: the cached verdict when it is k's
    xor.b   r11, r13
    rla.b   r13                     ; (C: bit 7, a misfit)
    jz      3f
    mov.b   OW+OW_ORD(r12), r14     ; O5: the width of s[ord[j]], &b[k]
    mov     r14, r15
    rla     r14
    add     r15, r14
    rla     r14
    add     r5, r14
    mov     SIGHT_WIDTH(r14), r14
    mov     r11, r13
    rla     r13
    rla     r13
    rla     r13
    add     &OW+OW_B, r13
    call    #optical_width_core
    xor.b   -1(r8), r12             ; c = k | 0x80 for a misfit (N)
    mov.b   r12, OW_WCHK-OW_SM-1(r8)
    jn      7f
    mov.b   r12, r11                ; (k)
4:  sub     #-1, r7
    mov     r8, r13                 ; off = th[j] - psi[k], e = we[j]
    sub     #OW+OW_SM+1, r13
    rla     r13
    rla     r11
    mov     OW+OW_TH(r13), r15
    sub     OW+OW_PSI(r11), r15
    mov     OW+OW_WE(r13), r14
    cmp     r15, r9                 ; off > lo and off - lo > e: lo = off - e
    jge     5f
    mov     r15, r13
    sub     r9, r13
    cmp     r13, r14
    jhs     5f
    mov     r15, r9
    sub     r14, r9
5:  cmp     r10, r15                ; off < hi and hi - off > e: hi = off + e
    jge     8f
    mov     r10, r13
    sub     r15, r13
    cmp     r13, r14
    jhs     8f
    mov     r15, r10
    add     r14, r10
    jmp     8f
3:  jnc     4b                      ; (the cached verdict: kept, or a misfit)
7:  mov.b   #MATCH_NONE, -1(r8)
8:  cmp     r6, r8                  ; j < n
    jlo     2b
9:  pop     r14
    tst     r14
    jz      1f
    mov     r9, 0(r14)
    mov     r10, 2(r14)
1:  mov     r7, r12
    pop     r4
    pop     r5
    pop     r6
    pop     r7
    pop     r8
    pop     r9
    pop     r10
    ret

/*
 * void optical_gather(const optical_sighting_t *s, int8_t *ident): R12 = s, R13 = ident.
 * R13 = &sm[j + 1] (walked), R8 = ident, R10 = &sm[n], R14 = &pos[m], R15 = &ang[m], R11 =
 * sm[j] (a beacon, below 32, or NONE, MULTI, DROPPED: the sign bit tells them apart), R9 =
 * ord[j], then the sighting's address, then j; R7 = &ident[ord[j]].
 */
    .section .text.optical_gather,"ax",@progbits
    .global optical_gather
    .type optical_gather,@function
optical_gather:
    push    r10
    push    r9
    push    r8
    push    r7
    mov     r13, r8
    mov     #OW+OW_SM, r13
    mov.b   &OW+OW_N, r10
    add     r13, r10
    mov     #OW+OW_POS, r14
    mov     #OW+OW_ANG, r15
1:  cmp     r10, r13                ; j < n
    jhs     9f
    mov.b   @r13+, r11              ; a beacon
    tst.b   r11
    jn      1b
    mov.b   OW_ORD-OW_SM-1(r13), r9 ; ident[ord[j]] = sm[j]
    mov     r9, r7
    add     r8, r7
    mov.b   r11, 0(r7)
    rla     r9                      ; s + 6 ord[j]
    mov     r9, r11
    rla     r9
    add     r11, r9
    add     r12, r9
    mov     @r9, 0(r15)
    mov     2(r9), 2(r15)
    add     #4, r15
    mov     r13, r9                 ; j
    sub     #OW+OW_SM+1, r9
    mov.b   r9, 0(r14)
    sub     #-1, r14
    jmp     1b
9:  sub     #OW+OW_POS, r14
    mov.b   r14, &OW+OW_M
    pop     r7
    pop     r8
    pop     r9
    pop     r10
    ret

/*
 * int8_t optical_resid(const optical_pose_t *p, const uint8_t t3[3], uint16_t tol): R12 = p,
 * R13 = t3, R14 = tol -> R12. R4 = p, R5 = m, R6 = tol, R7 = i, R8 = left, R9 = a16(heading),
 * R10 = the triplet's positions as bits, shifted right once a step (bit 0: i is one of them;
 * at most 3 + CHECK_MAX steps are taken, so positions from 7 on need none). optical_angle16
 * preserves R4..R10.
 */
    .section .rodata.optical_resid_bits,"a",@progbits
resid_bits:
    .byte   0x01, 0x02, 0x04, 0x08, 0x10, 0x20, 0x40, 0x80, 0, 0, 0, 0, 0, 0, 0, 0

    .section .text.optical_resid,"ax",@progbits
    .global optical_resid
    .type optical_resid,@function
optical_resid:
    push    r10
    push    r9
    push    r8
    push    r7
    push    r6
    push    r5
    push    r4
    mov     r12, r4
    mov     r14, r6
    mov.b   @r13+, r12              ; the triplet's bits
    mov.b   resid_bits(r12), r10
    mov.b   @r13+, r12
    bis.b   resid_bits(r12), r10
    mov.b   @r13, r12
    bis.b   resid_bits(r12), r10
    mov.b   &OW+OW_M, r5
    mov     POSE_HEADING(r4), r12   ; a16(heading)
    mov     POSE_HEADING+2(r4), r9
    rla     r12
    adc     r9
    clr     r7
    mov     #4, r8                  ; CHECK_MAX
1:  cmp     r5, r7                  ; i < m
    jhs     8f
    rra     r10                     ; not one of the triplet
    jc      7f
    mov.b   OW+OW_POS(r7), r11      ; &b[sm[pos[i]]]
    mov.b   OW+OW_SM(r11), r11
    rla     r11
    rla     r11
    rla     r11
    add     &OW+OW_B, r11
    mov     @r11+, r12              ; b - p
    mov     @r11+, r13
    sub     POSE_X(r4), r12
    subc    POSE_X+2(r4), r13
    mov     @r11+, r14
    mov     @r11, r15
    sub     POSE_Y(r4), r14
    subc    POSE_Y+2(r4), r15
    call    #optical_angle16
    sub     r9, r12
    mov     r7, r13                 ; - a16(ang[i])
    rla     r13
    rla     r13
    mov     OW+OW_ANG(r13), r11
    mov     OW+OW_ANG+2(r13), r13
    rla     r11
    adc     r13
    sub     r13, r12
    jn      3f
2:  cmp     r12, r6                 ; |res| > tol: disagree
    jlo     9f
    add     #-1, r8
    jz      8f
7:  sub     #-1, r7
    jmp     1b
3:  inv     r12
    sub     #-1, r12
    jmp     2b
8:  clr     r12                     ; OPTICAL_OK
    jmp     4f
9:  mov     #E_DISAGREE, r12
4:  pop     r4
    pop     r5
    pop     r6
    pop     r7
    pop     r8
    pop     r9
    pop     r10
    ret

/*
 * TAKE_DIFF off: R15:R11 -= |p.off - ap.off| (R12 = p, R13 = ap, 32-bit fields at @p off),
 * the difference left in R9:R10; the carry of the last step set when the rest stays >= 0
 * (unsigned).
 */
.macro TAKE_DIFF off
    mov     \off(r12), r10
    mov     \off+2(r12), r9
    sub     \off(r13), r10
    subc    \off+2(r13), r9
    jn      1f
    sub     r10, r11
    subc    r9, r15
    jmp     2f
1:  add     r10, r11
    addc    r9, r15
2:
.endm

/*
 * int8_t optical_jump(const optical_pose_t *p, const optical_pose_t *ap,
 * const optical_config_t *cfg): R12 = p, R13 = ap, R14 = cfg -> R12. R15:R11 = jump_max -
 * jx - jy (then turn_max - |dh|), R9:R10 a difference d: its magnitude taken off by
 * subtracting d, or adding it when negative (the carry tells whether the rest stays >= 0,
 * unsigned, either way). Only when it does not, the root of dx and dy (fx_hypot takes their
 * magnitudes).
 */
    .section .text.optical_jump,"ax",@progbits
    .global optical_jump
    .type optical_jump,@function
optical_jump:
    push    r10
    push    r9
    mov     CFG_JUMP_MAX(r14), r11  ; jx > jump_max or jy > jump_max - jx: the root decides
    mov     CFG_JUMP_MAX+2(r14), r15
    TAKE_DIFF POSE_X                ; - |p.x - ap.x|
    jnc     3f
    TAKE_DIFF POSE_Y                ; - |p.y - ap.y|
    jc      4f
3:  push    r12
    push    r13
    push    r14
    mov     POSE_Y(r12), r14        ; hypot(dx, dy) (of the magnitudes)
    mov     POSE_Y+2(r12), r15
    sub     POSE_Y(r13), r14
    subc    POSE_Y+2(r13), r15
    mov     POSE_X(r12), r10
    mov     POSE_X+2(r12), r11
    sub     POSE_X(r13), r10
    subc    POSE_X+2(r13), r11
    mov     r10, r12
    mov     r11, r13
    call    #fx_hypot
    pop     r14
    mov     CFG_JUMP_MAX(r14), r11  ; hypot > jump_max: a jump
    mov     CFG_JUMP_MAX+2(r14), r15
    sub     r12, r11
    subc    r13, r15
    pop     r13
    pop     r12
    jlo     8f
4:  mov     CFG_TURN_MAX(r14), r11  ; |heading - ap heading| > turn_max: a turn
    mov     CFG_TURN_MAX+2(r14), r15
    mov     POSE_HEADING(r12), r10
    mov     POSE_HEADING+2(r12), r9
    sub     POSE_HEADING(r13), r10
    subc    POSE_HEADING+2(r13), r9
    jn      1f
    sub     r10, r11
    subc    r9, r15
    jmp     2f
1:  add     r10, r11
    addc    r9, r15
2:  jnc     9f
    clr     r12                     ; OPTICAL_OK
    jmp     6f
8:  mov     #E_JUMP, r12
    jmp     6f
9:  mov     #E_TURN, r12
6:  pop     r9
    pop     r10
    ret
