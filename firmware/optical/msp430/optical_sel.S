/*
 * optical_sel.S - MSP430 version of optical_select (O7; select.c holds the portable C that
 * defines the result, and tests/vectors/optical_vectors.c checks both on the same inputs).
 *
 * The same rule on a linked ring instead of shifted arrays: entry i (2-byte offset o = 2i)
 * keeps H[i], the high word of its gap angle[nx] - angle[i] (mod 2^32), and a link word
 * (low byte nx, high byte pv, as offsets 2j). The low word of a gap is needed only where
 * high words tie and is then computed from the angles (lo_of). Dropping entry d unlinks it
 * (a dead d keeps its links, but nx[pv[d]] no longer leads to it), marks it dead (H 0xFFFF)
 * and recomputes the gap of pv[d], which now reaches nx[d] (the sum of the two merged gaps,
 * mod 2^32); after the last drop only the ring forward is updated. The minimum scan walks all entries: a
 * dead one never wins (no live gap is 0xFFFFFFFF while four or more live gaps sum to 0 mod
 * 2^32, and a high-word tie with a dead entry goes to the exact path, which skips it); a
 * sentinel 0 after the last entry ends it. R7 keeps the best's low word once a tie needed it
 * (valid while R10 = R8). The kept are the smallest live index (head) and
 * the next two along the ring.
 *
 * The first step's minimum is found by the loop that computes H, unless a high word ties
 * with the smallest so far (then that step scans as the others).
 *
 * Frame (stack, 62 bytes): H[0..n] at 0 (H[n] the sentinel), the links at 32. R4 = the frame
 * + 2, so an entry's "past" pointer P = R4 + o has H at -2(P), nx at 30(P), pv at 31(P).
 */

    .section .text.optical_select,"ax",@progbits

/* R11 = P of entry i -> R14 = the low word of its gap; clobbers R9. */
lo_of:
    mov.b   30(r11), r9             ; nx (2j)
    mov     r11, r14
    sub     r4, r14                 ; 2i
    rla     r9
    rla     r14
    add     r12, r9
    add     r12, r14
    mov     @r9, r9
    sub     @r14, r9
    mov     r9, r14
    ret

/*
 * void optical_select(const fx_angle_t *angle, uint8_t n, uint8_t keep[3]): R12 = angle,
 * R13 = n (at most 15), R14 = keep. R5 = P of the head, R6 = the scan's end (P of the
 * sentinel), R8 = P of the smallest so far, R9 its high word, R13 the live count.
 */
    .global optical_select
    .type optical_select,@function
optical_select:
    mov.b   r13, r13
    cmp     #4, r13
    jhs     1f
    clr.b   0(r14)                  ; three or fewer: 0, 1, 2
    mov.b   #1, 1(r14)
    mov.b   #2, 2(r14)
    ret
1:  push    r14
    push    r10
    push    r9
    push    r8
    push    r7
    push    r6
    push    r5
    push    r4
    sub     #62, r1
    mov     r1, r15                 ; H pointer
    mov     r12, r11                ; angle pointer
    mov     #0xFE02, r10            ; links of entry 0 (pv patched below): nx 2, pv -2
    mov     #0x0202, r5             ; (constants in registers: cheaper in the loop)
    mov     #2, r14
    mov     r13, r7
    add     r7, r7
    add     r1, r7
    sub     #2, r7                  ; the H address of entry n - 1
    mov     #-1, r6                 ; the first step's minimum on the way: the smallest high
2:  mov     4(r11), r8              ; word so far (R6) at H address R4; a tie with it sets
    sub     @r11+, r8               ; bit 8 of R13 (that step scans after all)
    mov     4(r11), r9              ; H[i] = high word of angle[i + 1] - angle[i]
    subc    @r11+, r9
    mov     r9, 0(r15)
    mov     r10, 32(r15)
    cmp     r9, r6
    jlo     4f
    jne     3f
    bis     #0x100, r13
    jmp     4f
3:  mov     r9, r6
    mov     r15, r4
4:  add     r5, r10
    add     r14, r15
    cmp     r7, r15
    jne     2b
    mov     @r12, r8                ; the last: angle[0] - angle[n - 1]
    sub     @r11+, r8
    mov     2(r12), r9
    subc    @r11, r9
    mov     r9, 0(r15)
    and     #0xff00, r10            ; nx 0
    mov     r10, 32(r15)
    clr     2(r15)                  ; the sentinel
    cmp     r9, r6
    jlo     4f
    jne     3f
    bis     #0x100, r13
    jmp     4f
3:  mov     r15, r4
4:  mov     r4, r8                  ; P of the smallest
    incd    r8
    sub     r1, r15                 ; pv of entry 0: 2(n - 1)
    mov.b   r15, 33(r1)
    mov     r1, r4
    incd    r4
    mov.b   r13, r6
    add     r6, r6
    add     r4, r6                  ; P of the sentinel
    mov     r4, r5                  ; head: entry 0
    sub     #3, r13                 ; the steps
    bit     #0x100, r13
    jz      .Lsel_found
    bic     #0x100, r13

.Lsel_step:
    mov     #-1, r9
    clr     r8
    mov     #-1, r7                 ; the best's low word, known for R10 = R8 (none yet:
    clr     r10                     ; 0xFFFF, which no tie beats)
    mov     r1, r15
3:  cmp     @r15+, r9
    jlo     3b                      ; larger: next
    jeq     .Lsel_tie
    cmp     r6, r15                 ; smaller: the sentinel ends the scan
    jeq     .Lsel_found
4:  mov     -2(r15), r9
    mov     r15, r8
    jmp     3b
.Lsel_tie:                          ; equal high words (or the sentinel, when the best is 0)
    cmp     r6, r15
    jeq     .Lsel_found
    mov.b   31(r15), r11            ; dead (nx[pv] does not lead to it): never
    add     r4, r11
    mov.b   30(r11), r11
    add     r4, r11
    cmp     r11, r15
    jne     3b
    cmp     r8, r10
    jeq     5f
    mov     r8, r11                 ; the best's low word
    call    #lo_of
    mov     r14, r7
    mov     r8, r10
5:  mov     r15, r11
    call    #lo_of
    mov     -2(r15), r9
    cmp     r7, r14
    jhs     3b
    mov     r14, r7                 ; strictly smaller: the new best, its low word known
    mov     r15, r10
    jmp     4b

.Lsel_found:                        ; k = R8; its neighbours' gaps decide
    mov.b   30(r8), r10
    mov.b   31(r8), r11
    add     r4, r10                 ; P of nx
    add     r4, r11                 ; P of pv
    cmp     -2(r10), -2(r11)        ; gap(pv) - gap(nx), high words
    jlo     .Lsel_drop              ; gap(pv) < gap(nx): drop k
    jne     6f                      ; larger: drop nx
    call    #lo_of                  ; equal: the low words
    mov     r14, r7
    mov     r10, r11
    call    #lo_of
    cmp     r14, r7
    jlo     .Lsel_drop
6:  mov     r10, r8                 ; drop nx
.Lsel_drop:                         ; unlink R8: its pv takes the gap to its nx
    mov.b   30(r8), r10             ; nx (2j)
    mov.b   31(r8), r11             ; pv
    mov     r11, r15
    add     r4, r15
    mov.b   r10, 30(r15)            ; nx[pv] = nx
    mov     r10, r14
    add     r4, r14
    cmp     r8, r5
    jne     7f
    mov     r14, r5                 ; the head went: its nx is the smallest live index now
7:  sub     #1, r13
    jz      .Lsel_finish            ; (the last: only the ring forward is read)
    mov.b   r11, 31(r14)            ; pv[nx] = pv
    mov     #-1, -2(r8)             ; dead (its links stay: nx[pv] no longer leads to it)
    rla     r10
    rla     r11
    add     r12, r10
    add     r12, r11
    mov     @r10+, r9               ; H[pv] = high word of angle[nx] - angle[pv]
    sub     @r11+, r9
    mov     @r10, r9
    subc    @r11, r9
    mov     r9, -2(r15)
    jmp     .Lsel_step

.Lsel_finish:                       ; head, its nx and that one's
    mov     r5, r15
    sub     r4, r15
    rra     r15                     ; head
    mov.b   30(r5), r13             ; its nx
    mov     r13, r12
    add     r4, r12
    mov.b   30(r12), r12            ; and that one's
    rra     r13
    rra     r12
    add     #62, r1
    pop     r4
    pop     r5
    pop     r6
    pop     r7
    pop     r8
    pop     r9
    pop     r10
    pop     r14
    mov.b   r15, 0(r14)
    mov.b   r13, 1(r14)
    mov.b   r12, 2(r14)
    ret
