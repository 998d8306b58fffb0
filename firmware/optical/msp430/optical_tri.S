/*
 * optical_tri.S - the triangulation kernels optical_tri_core and optical_tri_quality
 * (optical/fastmath.h) on the MSP430. tri_k.c is their C twin, the definition of every
 * result; these perform the very same integer steps (docs/kernels.md: the fix floor needs
 * them; the check images run both on every call). Conventions as optical_scan.S. mspdebug's
 * simulator charges the constant #1 (INC, DEC) like a memory operand: counts step with #-1
 * (ADD, SUB) instead.
 *
 * Products: dot() of tri_k.c, sums of x y / 2^32 with every operand split into balanced
 * halves x = h 2^16 + l (l the low word read as signed, h the high word plus bit 15 of l): the
 * products h h accumulated in one chain of the multiplier, h l + l h in another (the callers
 * keep both below 2^31), l l dropped, the second chain's high word added. The operands live in
 * the kernels' own static frame as (h, l) pairs of 4 bytes; the dot routines take pointers to
 * two lists of pairs. The multiplier is used with interrupts enabled: no interrupt handler of
 * the main board touches it (tools/stack_bound.py --no-mpy-in-isr). The offsets of
 * optical_tsol_t and the status codes come from optical_offsets.h, generated from the C
 * headers (msp430/optical_offsets.c).
 */
#include "optical_offsets.h"

/* The 16 x 16 hardware multiplier (MSP430F2618, SLAS541) */
    .set MPY,    0x0130
    .set MPYS,   0x0132
    .set MACS,   0x0136
    .set OP2,    0x0138
    .set RESLO,  0x013a
    .set RESHI,  0x013c
    .set SUMEXT, 0x013e

/* the kernels' frame, tri_frame below */
    .set F_Z,   0                   ; pairs -s2, c2, s2, s1, c1, -s1
    .set F_B,   24                  ; b1x, b1y, b3x, b3y (scaled)
    .set F_W,   40                  ; ax, cx, ay, cy
    .set F_K,   64                  ; 4 ax, 4 cx, 4 cy, -4 ay; later the offsets' bound
    .set F_U,   80                  ; u0, u1 (U^), k (K')
    .set F_KN,  92                  ; K''
    .set F_R,   96                  ; R'
    .set F_T,   100                 ; T'
    .set F_V,   104                 ; the offsets' pointer
    .set F_SIG, 106                 ; sigma (word)
    .set F_SH,  108                 ; out until sigma is known; then 12 - f - g - t (word)

    .section .bss.optical_tri_frame,"aw",@nobits
    .balign 2
tri_frame:
    .skip   110

/* R13:R12 -> the pair at address a: h = R13 + bit 15 of R12 (also left in R14), l = R12. */
    .macro  PUT a
    mov     r12, r14
    rla     r14
    mov     r13, r14
    adc     r14
    mov     r14, &\a
    mov     r12, &\a+2
    .endm

/* \hi:\lo <<= 8 (\t the temporary) */
    .macro  BYTEL lo, hi, t
    swpb    \hi
    swpb    \lo
    mov.b   \lo, \t
    xor     \t, \lo
    and     #0xff00, \hi
    bis     \t, \hi
    .endm

/* \hi:\lo = floor(\hi:\lo / 2^8) (\t the temporary) */
    .macro  BYTER lo, hi, t
    swpb    \lo
    mov.b   \lo, \lo
    swpb    \hi
    mov     \hi, \t
    and     #0xff00, \t
    bis     \t, \lo
    sxt     \hi
    .endm

/* \hi:\lo -> the pair at address a (as PUT; \t the temporary) */
    .macro  PAIR lo, hi, a, t
    mov     \lo, \t
    rla     \t
    mov     \hi, \t
    adc     \t
    mov     \t, &\a
    mov     \lo, &\a+2
    .endm

/* R11:R4 |= |\hi:\lo| (R8 the temporary; BIS and MOV keep the borrow of the low word) */
    .macro  MAGOR lo, hi
    tst     \hi
    jn      8f
    bis     \lo, r4
    bis     \hi, r11
    jmp     9f
8:  clr     r8
    sub     \lo, r8
    bis     r8, r4
    clr     r8
    subc    \hi, r8
    bis     r8, r11
9:
    .endm

/* To inconsistent unless R13:R12 is nonzero with the sign of K' (R7). Clobbers R14. */
    .macro  LSIGN
    mov     r12, r14
    bis     r13, r14
    tst     r14
    jz      inconsistent
    mov     r13, r14
    xor     r7, r14
    jn      inconsistent
    .endm

/* R13:R12 = -R13:R12 */
    .macro  NEG
    inv     r12
    inv     r13
    sub     #-1, r12
    adc     r13
    .endm

/* \hi:\lo = -\hi:\lo */
    .macro  NEGR lo, hi
    inv     \lo
    inv     \hi
    sub     #-1, \lo
    adc     \hi
    .endm

    .section .text.optical_tri_kernels,"ax",@progbits

/*
 * dot1, dot2: R5 -> x pairs, R6 -> y pairs -> R13:R12 = dot(x, y, n). dot3s: the same for
 * three, the first two x pairs 8 bytes apart, the third at R4. Clobber R14.
 */
dot1:
    mov     @r5, &MPYS              ; h h
    mov     @r6, &OP2
    mov     &RESLO, r12
    mov     &RESHI, r13
    mov     @r5, &MPYS              ; h l + l h
    mov     2(r6), &OP2
    mov     2(r5), &MACS
    mov     @r6, &OP2
    jmp     dot_end
dot3s:
    mov     @r5, &MPYS
    mov     @r6, &OP2
    mov     8(r5), &MACS
    mov     4(r6), &OP2
    mov     @r4, &MACS
    mov     8(r6), &OP2
    mov     &RESLO, r12
    mov     &RESHI, r13
    mov     @r5, &MPYS
    mov     2(r6), &OP2
    mov     2(r5), &MACS
    mov     @r6, &OP2
    mov     @r4, &MACS
    mov     10(r6), &OP2
    mov     2(r4), &MACS
    mov     8(r6), &OP2
    mov     8(r5), &MACS
    mov     6(r6), &OP2
    mov     10(r5), &MACS
    mov     4(r6), &OP2
    jmp     dot_end
dot2:                               ; (the most frequent: falls through)
    mov     @r5, &MPYS
    mov     @r6, &OP2
    mov     4(r5), &MACS
    mov     4(r6), &OP2
    mov     &RESLO, r12
    mov     &RESHI, r13
    mov     @r5, &MPYS
    mov     2(r6), &OP2
    mov     2(r5), &MACS
    mov     @r6, &OP2
    mov     4(r5), &MACS
    mov     6(r6), &OP2
    mov     6(r5), &MACS
    mov     4(r6), &OP2
dot_end:
    add     &RESHI, r12             ; floor(chain / 2^16), sign-extended (SUMEXT)
    addc    &SUMEXT, r13
    ret

/* R11:R10 and R13:R12 = floor(each / 2^R14) (R14 below 32), whole bytes first. Clobbers R14,
 * R15. */
asr2:
1:  cmp     #8, r14
    jlo     2f
    BYTER   r10, r11, r15
    BYTER   r12, r13, r15
    sub     #8, r14
    jmp     1b
2:  tst     r14
    jz      3f
4:  rra     r11
    rrc     r10
    rra     r13
    rrc     r12
    add     #-1, r14
    jnz     4b
3:  ret

/* R13:R12 = floor(R13:R12 / 2^R14) (R14 below 32), whole bytes first. Clobbers R14, R15. */
asr:
1:  cmp     #8, r14
    jlo     2f
    swpb    r12
    mov.b   r12, r12
    swpb    r13
    mov     r13, r15
    and     #0xff00, r15
    bis     r15, r12
    sxt     r13
    sub     #8, r14
    jmp     1b
2:  tst     r14
    jz      3f
    mov     #1, r15
4:  rra     r13
    rrc     r12
    sub     r15, r14
    jnz     4b
3:  ret

/*
 * int8_t optical_tri_core(int32_t v[4], const int32_t sc[4], optical_tsol_t *out):
 * R12 = v, R13 = sc, R14 = out -> R12 = OPTICAL_OK, OPTICAL_E_ARG, OPTICAL_E_DEGENERATE,
 * OPTICAL_E_SINGULAR or OPTICAL_E_INCONSISTENT. The entry puts the sines and cosines into the
 * frame's pairs Z, the body does the rest: R9 = out, R8 = e (then e - g), R7 the high word of
 * K' (its sign), R5 and R6 the dot pointers; 16 K waits in out->l[1].
 */
    .section .text.optical_tri_core,"ax",@progbits
    .global optical_tri_core
    .type optical_tri_core,@function
optical_tri_core:
    push    r10
    push    r9
    push    r8
    push    r7
    push    r6
    push    r5
    push    r4
    mov     r12, r10
    mov     r14, r9
    mov     r13, r8
    ; the sines: Z = (-s2, c2, s2, s1, c1, -s1); c1, c2 also in W
    mov     @r8+, r12               ; s1
    mov     @r8+, r13
    PUT     tri_frame+F_Z+12
    NEG
    PUT     tri_frame+F_Z+20
    mov     @r8+, r12               ; c1
    mov     @r8+, r13
    PUT     tri_frame+F_Z+16
    mov     @r8+, r12               ; s2
    mov     @r8+, r13
    PUT     tri_frame+F_Z+8
    NEG
    PUT     tri_frame+F_Z
    mov     @r8+, r12               ; c2
    mov     @r8+, r13
    PUT     tri_frame+F_Z+4
    mov     r10, r12
    mov     r9, r14
    call    #tri_core_body
    pop     r4
    pop     r5
    pop     r6
    pop     r7
    pop     r8
    pop     r9
    pop     r10
    ret

/* The body, with the pairs Z in place: R4..R10 not kept. */
    .section .text.optical_tri_kernels,"ax",@progbits
arg:
    mov     #E_ARG, r12
    ret
degenerate:
    mov     #E_DEGENERATE, r12
    ret
tri_core_body:
    mov     r14, &tri_frame+F_SH           ; (out, for now: R9 counts sigma)
    mov     r12, &tri_frame+F_V
    mov     r12, r11                ; v in registers
    mov     @r11+, r12
    mov     @r11+, r13
    mov     @r11+, r14
    mov     @r11+, r15
    mov     @r11+, r5
    mov     @r11+, r6
    mov     @r11+, r7
    mov     @r11, r10
    ; |v| or'ed (R11:R4): 2^27 or more OPTICAL_E_ARG
    clr     r4
    clr     r11
    MAGOR   r12, r13
    MAGOR   r14, r15
    MAGOR   r5, r6
    MAGOR   r7, r10
    cmp     #0x0800, r11
    jhs     arg
    ; b1 = 0, b3 = 0 or b1 = b3: OPTICAL_E_DEGENERATE
    mov     r12, r8
    bis     r13, r8
    bis     r14, r8
    bis     r15, r8
    tst     r8
    jz      degenerate
    mov     r5, r8
    bis     r6, r8
    bis     r7, r8
    bis     r10, r8
    tst     r8
    jz      degenerate
    cmp     r12, r5
    jne     2f
    cmp     r13, r6
    jne     2f
    cmp     r14, r7
    jne     2f
    cmp     r15, r10
    jeq     degenerate
    ; sigma (R9): |v| or'ed to [2^28, 2^29), v with it, whole bytes below 2^21, then bits
2:  clr     r9
    jmp     5f
3:  BYTEL   r4, r11, r8
    BYTEL   r12, r13, r8
    BYTEL   r14, r15, r8
    BYTEL   r5, r6, r8
    BYTEL   r7, r10, r8
    add     #8, r9
5:  cmp     #0x0020, r11
    jlo     3b
    jmp     7f
6:  rla     r4
    rlc     r11
    rla     r12
    rlc     r13
    rla     r14
    rlc     r15
    rla     r5
    rlc     r6
    rla     r7
    rlc     r10
    sub     #-1, r9
7:  cmp     #0x1000, r11
    jlo     6b
    mov     r9, &tri_frame+F_SIG
    mov     &tri_frame+F_SH, r9            ; out
    ; v 2^sigma in place and as the pairs B
    mov     &tri_frame+F_V, r4
    mov     r12, 0(r4)
    mov     r13, 2(r4)
    mov     r14, 4(r4)
    mov     r15, 6(r4)
    mov     r5, 8(r4)
    mov     r6, 10(r4)
    mov     r7, 12(r4)
    mov     r10, 14(r4)
    PAIR    r12, r13, tri_frame+F_B, r4
    PAIR    r14, r15, tri_frame+F_B+4, r4
    PAIR    r5, r6, tri_frame+F_B+8, r4
    PAIR    r7, r10, tri_frame+F_B+12, r4
    ; A = R(alpha1) b1 / 4, C = R(-alpha2) b3 / 4 into W and (times 4) K
    mov     #tri_frame+F_Z+16, r5          ; ax = (c1, -s1) b1
    mov     #tri_frame+F_B, r6
    call    #dot2
    PUT     tri_frame+F_W
    rla     r12
    rlc     r13
    rla     r12
    rlc     r13
    PUT     tri_frame+F_K
    mov     #tri_frame+F_Z+12, r5          ; ay = (s1, c1) b1
    call    #dot2
    PUT     tri_frame+F_W+8
    NEG
    rla     r12
    rlc     r13
    rla     r12
    rlc     r13
    PUT     tri_frame+F_K+12
    mov     #tri_frame+F_Z+4, r5           ; cx = (c2, s2) b3
    mov     #tri_frame+F_B+8, r6
    call    #dot2
    PUT     tri_frame+F_W+4
    rla     r12
    rlc     r13
    rla     r12
    rlc     r13
    PUT     tri_frame+F_K+4
    mov     #tri_frame+F_Z, r5             ; cy = (-s2, c2) b3
    call    #dot2
    PUT     tri_frame+F_W+12
    rla     r12
    rlc     r13
    rla     r12
    rlc     r13
    PUT     tri_frame+F_K+8
    ; 16 K = (4 ax, 4 cx) (4 cy, -4 ay) into out->l[1] (for now)
    mov     #tri_frame+F_K, r5
    mov     #tri_frame+F_K+8, r6
    call    #dot2
    mov     r12, TSOL_L+4(r9)
    mov     r13, TSOL_L+6(r9)
    ; V = (s2, s1) (ax, cx), (s2, s1) (ay, cy): R7:R4 and R6:R5
    mov     #tri_frame+F_Z+8, r5
    mov     #tri_frame+F_W, r6
    call    #dot2
    mov     r12, r4
    mov     r13, r7
    mov     #tri_frame+F_W+8, r6
    call    #dot2
    mov     r12, r5
    mov     r13, r6
    ; e (R8): |V| or'ed (R15:R14) to [2^27, 2^28), U^ = V 2^e with it into out->w and the
    ; pairs U: whole bytes below 2^19, then bits
    mov     r4, r14
    mov     r7, r15
    tst     r15
    jge     1f
    clr     r14                     ; (MOV and CLR keep the borrow of the low word)
    sub     r4, r14
    clr     r15
    subc    r7, r15
1:  tst     r13
    jge     2f
    clr     r12
    sub     r5, r12
    clr     r13
    subc    r6, r13
2:  bis     r12, r14
    bis     r13, r15
    mov     r14, r13
    bis     r15, r13
    tst     r13
    jz      singular                ; U = 0
    clr     r8
    jmp     5f
3:  BYTEL   r14, r15, r10
    BYTEL   r4, r7, r10
    BYTEL   r5, r6, r10
    add     #8, r8
5:  cmp     #0x0008, r15
    jlo     3b
    jmp     7f
6:  rla     r14
    rlc     r15
    rla     r4
    rlc     r7
    rla     r5
    rlc     r6
    sub     #-1, r8
7:  cmp     #0x0800, r15
    jlo     6b
    mov     r4, TSOL_W(r9)
    mov     r7, TSOL_W+2(r9)
    mov     r5, TSOL_W+4(r9)
    mov     r6, TSOL_W+6(r9)
    PAIR    r4, r7, tri_frame+F_U, r10
    PAIR    r5, r6, tri_frame+F_U+4, r10
    ; K' = 16 K 2^(e - 4) within [-2^28, 2^28) (else beacon 2 lies beyond 2^31 lambda): floor
    ; when e < 4, else doubled, refused as soon as bits 31 and 30 differ
    mov     TSOL_L+4(r9), r12
    mov     TSOL_L+6(r9), r13
    mov     r8, r11
    sub     #4, r11
    jz      3f
    jge     2f
1:  rra     r13
    rrc     r12
    sub     #-1, r11
    jnz     1b
    jmp     3f
2:  mov     r13, r15
    rla     r15
    xor     r13, r15
    jn      singular
    rla     r12
    rlc     r13
    add     #-1, r11
    jnz     2b
3:  mov     r13, r14
    add     #0x1000, r14
    cmp     #0x2000, r14
    jhs     singular
    mov     r13, r7                 ; its sign from here
    mov     r12, TSOL_L+4(r9)
    mov     r13, TSOL_L+6(r9)
    PUT     tri_frame+F_U+8
    bis     r12, r13
    tst     r13
    jz      inconsistent            ; K' = 0: the vehicle on beacon 2
    ; l1 = (ax, ay, c1) (U^, K'), l3 = (cx, cy, c2) (U^, K'): both with the sign of K';
    ; out->l[0] = 4 l1, out->l[2] = 4 l3
    mov     #tri_frame+F_W, r5
    mov     #tri_frame+F_U, r6
    mov     #tri_frame+F_Z+16, r4
    call    #dot3s
    LSIGN
    rla     r12
    rlc     r13
    rla     r12
    rlc     r13
    mov     r12, TSOL_L(r9)
    mov     r13, TSOL_L+2(r9)
    mov     #tri_frame+F_W+4, r5
    mov     #tri_frame+F_Z+4, r4
    call    #dot3s
    LSIGN
    rla     r12
    rlc     r13
    rla     r12
    rlc     r13
    mov     r12, TSOL_L+8(r9)
    mov     r13, TSOL_L+10(r9)
    ; Q = |U^|^2 / 2^32 in [2^22, 2^25); R' = 2^(52 + g) / Q (recip_q in tri_k.c)
    mov     r6, r5                  ; (R6 = the pairs U as both lists)
    call    #dot2
    ; Qn = Q 2^n in [2^31, 2^32) (R13:R12), g = 9 - n (R11): Q 2^8 (R10:R13:R12), then one
    ; bit back or on
    swpb    r13
    swpb    r12
    mov.b   r12, r14
    xor     r14, r12
    mov.b   r13, r10
    xor     r10, r13
    bis     r14, r13
    mov     #1, r11
    rra     r10
    jnc     1f
    rrc     r13                     ; n = 7
    rrc     r12
    mov     #2, r11
    jmp     2f
1:  tst     r13
    jn      2f
    rla     r12                     ; n = 9
    rlc     r13
    clr     r11
2:  mov     r13, r15                ; f = qh << 7
    swpb    r15
    bit     #1, r15
    bic     #0x00ff, r15
    rrc     r15
    mov     r13, r14                ; 2 (qh >> 9): recip_tab - 128 based
    swpb    r14
    and     #0x00fe, r14
    mov     r15, &MPY               ; r0 = RT[i] - (d f) / 2^16, rounded
    mov     optical_recip_tab-128(r14), r15
    sub     optical_recip_tab-126(r14), r15
    mov     r15, &OP2
    mov     optical_recip_tab-128(r14), r14
    mov     &RESLO, r15
    rla     r15
    mov     &RESHI, r15
    adc     r15
    sub     r15, r14                ; r0
    mov     r14, &MPY               ; S = qh r0 + (ql r0) / 2^16
    mov     r12, &OP2
    mov     &RESHI, r10
    mov     r13, &OP2
    mov     &RESLO, r12
    mov     &RESHI, r13
    add     r10, r12
    adc     r13
    clr     r15                     ; E = 2^30 - S, E / 4 (16 bits: |E| < 2^17)
    sub     r12, r15
    mov     #0x4000, r10
    subc    r13, r10
    rra     r10
    rrc     r15
    rra     r10
    rrc     r15
    clrc                            ; h = r0 / 2 (R14), its bit 0 to R12's bit 15
    rrc     r14
    clr     r12
    rrc     r12
    mov     r14, &MPYS              ; P = h E / 4
    mov     r15, &OP2
    mov     &RESLO, r15
    mov     &RESHI, r13
    mov     r13, r10                ; floor(P / 2^12): R10:R13 (R10 the sign first)
    rla     r10
    subc    r10, r10
    inv     r10
    rla     r15
    rlc     r13
    rlc     r10
    rla     r15
    rlc     r13
    rlc     r10
    rla     r15
    rlc     r13
    rlc     r10
    rla     r15
    rlc     r13
    rlc     r10
    add     r13, r12                ; R' = r0 2^15 + floor(P / 2^12)
    addc    r10, r14
    mov     r14, r13
    sub     r11, r8                 ; e - g
    mov     #12, r5                 ; 12 - g - f - t, for the moment in R5
    sub     r11, r5
    mov     r12, TSOL_R(r9)
    mov     r13, TSOL_R+2(r9)
    PUT     tri_frame+F_R
    ; K'' = K' 2^f, |K''| in [2^29, 2^30): |K'| (nonzero, below 2^28) shifted, whole bytes
    ; below 2^21, four bits below 2^25, then bits, f counted off R5
    mov     TSOL_L+4(r9), r14
    mov     TSOL_L+6(r9), r15
    tst     r15
    jge     2f
    clr     r14                     ; (CLR keeps the borrow of the low word)
    sub     TSOL_L+4(r9), r14
    clr     r15
    subc    TSOL_L+6(r9), r15
    jmp     2f
1:  BYTEL   r14, r15, r10
    sub     #8, r5
2:  cmp     #0x0020, r15
    jlo     1b
    mov     #0x2000, r13
    mov     #-1, r12
    cmp     #0x0200, r15            ; below 2^25: four bits at once
    jhs     4f
    rla     r14
    rlc     r15
    rla     r14
    rlc     r15
    rla     r14
    rlc     r15
    rla     r14
    rlc     r15
    sub     #4, r5
    jmp     4f
3:  rla     r14
    rlc     r15
    add     r12, r5
4:  cmp     r13, r15
    jlo     3b
    mov     r14, r12
    mov     r15, r13
    tst     r7
    jge     7f
    NEG
7:  PUT     tri_frame+F_KN
    ; T = K'' R' / 2^32, T' = T 2^t, |T'| in [2^29, 2^30)
    mov     r5, &tri_frame+F_SH
    mov     #tri_frame+F_KN, r5
    mov     #tri_frame+F_R, r6
    call    #dot1
    mov     r13, r6                 ; (its sign)
    mov     r12, r14
    mov     r13, r15
    tst     r15
    jge     8f
    inv     r14
    inv     r15
    sub     #-1, r14
    adc     r15
    ; |T| in [2^26, 2^28] (K'' in [2^29, 2^30), R' in [2^29 + 16, 2^30]): t = 3, 2 or (at
    ; 2^28) 1, as lead()
8:  mov     #2, r11
    rla     r14
    rlc     r15
    rla     r14
    rlc     r15
    cmp     #0x2000, r15
    jhs     9f
    rla     r14
    rlc     r15
    sub     #-1, r11
9:  cmp     #0x4000, r15
    jlo     9f
    clrc
    rrc     r15
    rrc     r14
    add     #-1, r11
9:  mov     r14, r12
    mov     r15, r13
    tst     r6
    jge     8f
    NEG
8:  sub     r11, &tri_frame+F_SH
    PUT     tri_frame+F_T
    ; the offsets' range (offset): d = d' 2^sh within [-2^31, 2^31) when the high word of d'
    ; (inverted when negative) lies below 2^(15 - sh) (sh <= 12); none for sh <= 0: 0xFFFF
    mov     #-1, r12
    mov     &tri_frame+F_SH, r11
    tst     r11
    jl      2f
    jz      2f
    rla     r11
    mov     tri_bound-2(r11), r12
2:  mov     r12, &tri_frame+F_K            ; (the products K are done with)
    ; d = T' U^ / 2^32 2^(12 - f - g - t): beacon 2 from the vehicle; the vehicle at -d
    ; relative to it, -d / 2^sigma rounded half up (Q16 m): both components by one shift
    ; by sigma - sh
    mov     #tri_frame+F_T, r5
    mov     #tri_frame+F_U, r6
    call    #offset
    jc      singular
    mov     r12, r10
    mov     r13, r11
    mov     #tri_frame+F_U+4, r6
    call    #offset
    jc      singular
    mov     &tri_frame+F_SIG, r14
    sub     &tri_frame+F_SH, r14
    jl      5f
    jz      6f
    add     #-1, r14
    call    #asr2
    rra     r11
    rrc     r10
    adc     r10
    adc     r11
    rra     r13
    rrc     r12
    adc     r12
    adc     r13
    jmp     6f
5:  rla     r10                     ; (sigma < sh <= 12: at most 10 bits to the left)
    rlc     r11
    rla     r12
    rlc     r13
    sub     #-1, r14
    jnz     5b
6:  mov     r10, TSOL_OFF(r9)
    mov     r11, TSOL_OFF+2(r9)
    mov     r12, TSOL_OFF+4(r9)
    mov     r13, TSOL_OFF+6(r9)
    ; w: U^ with the sign of K' (the direction to beacon 2)
    tst     r7
    jge     9f
    mov     TSOL_W(r9), r12
    mov     TSOL_W+2(r9), r13
    NEG
    mov     r12, TSOL_W(r9)
    mov     r13, TSOL_W+2(r9)
    mov     TSOL_W+4(r9), r12
    mov     TSOL_W+6(r9), r13
    NEG
    mov     r12, TSOL_W+4(r9)
    mov     r13, TSOL_W+6(r9)
9:  sub     &tri_frame+F_SIG, r8           ; x = e - g - sigma
    mov.b   r8, TSOL_X(r9)
    clr     r12                     ; OPTICAL_OK
    ret
inconsistent:
    mov     #E_INCONSISTENT, r12
    ret
singular:
    mov     #E_SINGULAR, r12
tri_ret:
    ret

/* 2^(15 - sh), sh = 1..12: the offsets' bound */
    .section .rodata.optical_tri_bound,"a",@progbits
    .p2align 1
tri_bound:
    .word   0x4000, 0x2000, 0x1000, 0x0800, 0x0400, 0x0200, 0x0100, 0x0080, 0x0040, 0x0020
    .word   0x0010, 0x0008
    .section .text.optical_tri_kernels,"ax",@progbits

/*
 * One component: d' = dot1(@R5, @R6) = d / 2^sh (sh in F_SH; carry set when d = d' 2^sh
 * lies beyond [-2^31, 2^31), by the bound the core left in F_K), -d' to R13:R12.
 */
offset:
    call    #dot1
    mov     r13, r14                ; the high word of d', inverted when negative, below
    tst     r14                     ; the bound in F_K (carry set when not)
    jge     1f
    inv     r14
1:  cmp     &tri_frame+F_K, r14
    jhs     4f
    NEG
    clrc
4:  ret

/*
 * uint32_t optical_tri_quality(const int32_t v[4], const optical_tsol_t *s): R12 = v,
 * R13 = s -> R13:R12. R9 = s, R8 = the exponent x, R4..R7 the chords' parts b1, b3 / 2^15.
 */
    .section .text.optical_tri_quality,"ax",@progbits
    .global optical_tri_quality
    .type optical_tri_quality,@function
optical_tri_quality:
    push    r10
    push    r9
    push    r8
    push    r7
    push    r6
    push    r5
    push    r4
    call    #tri_quality_body
    pop     r4
    pop     r5
    pop     r6
    pop     r7
    pop     r8
    pop     r9
    pop     r10
    ret

/* The body: R4..R10 not kept. */
tri_quality_body:
    mov     r13, r9
    ; the chords b1, b3 / 2^15 (floor; the high word after one left shift)
    mov     @r12+, r14
    mov     @r12+, r4
    rla     r14
    rlc     r4
    mov     @r12+, r14
    mov     @r12+, r5
    rla     r14
    rlc     r5
    mov     @r12+, r14
    mov     @r12+, r6
    rla     r14
    rlc     r6
    mov     @r12+, r14
    mov     @r12+, r7
    rla     r14
    rlc     r7
    ; the ranges' l to 16 bits by a common shift sr: with ls = 16 - sr the left shifts that
    ; bring the largest |l| to 2^30 (at most 16), the high words of l 2^ls; x = s->x + sr - 19
    mov     r9, r13
    add     #TSOL_L, r13
    clr     r14
    clr     r15
    mov     #3, r8
1:  mov     @r13+, r10
    mov     @r13+, r11
    tst     r11
    jge     2f
    clr     r12                     ; (BIS and MOV keep the borrow of the low word)
    sub     r10, r12
    bis     r12, r14
    clr     r12
    subc    r11, r12
    bis     r12, r15
    jmp     3f
2:  bis     r10, r14
    bis     r11, r15
3:  add     #-1, r8
    jnz     1b
    mov.b   TSOL_X(r9), r8          ; x = s->x - ls - 3 (R8), P = 2^ls (R12): a byte at
    sxt     r8                      ; once below 2^22 (below 2^15: ls = 16), four bits
    sub     #3, r8                  ; below 2^26, then bits
    mov     #1, r12
    cmp     #0x0040, r15
    jhs     4f
    swpb    r15
    swpb    r14
    mov.b   r14, r14
    bis     r14, r15
    mov     #0x0100, r12
    sub     #8, r8
    cmp     #0x0080, r15
    jhs     4f
    sub     #8, r8                  ; ls = 16 (below 2^15): the low words
    mov     TSOL_L(r9), r11
    mov     TSOL_L+4(r9), r13
    mov     TSOL_L+8(r9), r15
    jmp     7f
4:  cmp     #0x0400, r15
    jhs     6f
    rla     r15
    rla     r15
    rla     r15
    rla     r15
    rla     r12
    rla     r12
    rla     r12
    rla     r12
    sub     #4, r8
    jmp     6f
5:  rla     r15
    rla     r12
    add     #-1, r8
6:  cmp     #0x4000, r15
    jlo     5b
    ; the high words of l 2^ls = lh P + (ll P) / 2^16 (ls <= 15), mod 2^16
    mov     r12, &MPY
    mov     TSOL_L(r9), &OP2
    mov     &RESHI, r11
    mov     TSOL_L+2(r9), &OP2
    add     &RESLO, r11
    mov     TSOL_L+4(r9), &OP2
    mov     &RESHI, r13
    mov     TSOL_L+6(r9), &OP2
    add     &RESLO, r13
    mov     TSOL_L+8(r9), &OP2
    mov     &RESHI, r15
    mov     TSOL_L+10(r9), &OP2
    add     &RESLO, r15
    ; M = sum of ((r_k chord) / 2^16)^2: r3 (R15) with b1, r1 (R11) with b3, r2 (R13) with
    ; b3 - b1
7:  mov     r15, &MPYS
    mov     r4, &OP2
    mov     &RESHI, r10
    mov     r5, &OP2
    mov     &RESHI, r15
    mov     r11, &MPYS
    mov     r6, &OP2
    mov     &RESHI, r11
    mov     r7, &OP2
    mov     &RESHI, r12
    sub     r4, r6
    sub     r5, r7
    mov     r13, &MPYS
    mov     r6, &OP2
    mov     &RESHI, r13
    mov     r7, &OP2
    mov     &RESHI, r14
    mov     r10, &MPYS
    mov     r10, &OP2
    mov     r11, &MACS
    mov     r11, &OP2
    mov     r12, &MACS
    mov     r12, &OP2
    mov     r13, &MACS
    mov     r13, &OP2
    mov     r14, &MACS
    mov     r14, &OP2
    mov     r15, &MACS
    mov     r15, &OP2
    mov     &RESLO, r12
    mov     &RESHI, r13
    mov     r12, r14
    bis     r13, r14
    tst     r14
    jz      sat                     ; M = 0
    ; to [2^30, 2^32) by factors of 4; the root; S = root R' 2^x / 1000
    jmp     8f
7:  rla     r12
    rlc     r13
    rla     r12
    rlc     r13
    add     #-1, r8
8:  cmp     #0x4000, r13
    jlo     7b
    mov     r13, r15                ; the root: k = M / 2^27 - 8 (2 k + 16 in R14), the
    swpb    r15                     ; fraction f = (M / 2^16) 2^5 mod 2^16 (R13)
    mov.b   r15, r14
    rra     r14
    rra     r14
    and     #0x003e, r14
    rla     r13
    rla     r13
    rla     r13
    rla     r13
    rla     r13
    mov     optical_sqrt_tab-14(r14), r15
    sub     optical_sqrt_tab-16(r14), r15
    mov     r15, &MPY
    mov     r13, &OP2
    mov     optical_sqrt_tab-16(r14), r12
    add     #0x8000, r12
    add     &RESHI, r12
    mov     TSOL_R(r9), r14         ; R' / 2^15
    mov     TSOL_R+2(r9), r15
    rla     r14
    rlc     r15
    mov     r12, &MPY               ; root 2^25 / 1000 / 2^16
    mov     #33554, &OP2
    mov     &RESHI, &MPY
    mov     r15, &OP2
    mov     &RESLO, r12
    mov     &RESHI, r13
    tst     r8
    jge     11f
    clr     r14                     ; x < 0: floor shift right by -x (0 from 32 on)
    sub     r8, r14
    cmp     #32, r14
    jhs     10f
    call    #asr
    jmp     q_out
10: clr     r12
    clr     r13
    jmp     q_out
11: tst     r8                      ; x >= 0: saturate when a bit leaves
    jz      q_out
    rla     r12
    rlc     r13
    jc      sat
    add     #-1, r8
    jmp     11b
sat:
    mov     #-1, r12
    mov     #-1, r13
q_out:
    ret
