#!/usr/bin/env python3
"""Unit test of tools/stack_bound.py on hand-written disassembly (no toolchain needed).

The fixtures are written here in llvm-objdump's MSP430 syntax; the expected figures are
counted by hand from them in the comments."""
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "tools"))
import stack_bound as sb  # noqa: E402

# reset: sets SP, calls main; main (frame 6: two pushes + sub #2) calls leaf (frame 4: one
# push, then pushes r2 and pops it inside its body), tail-calls tail via br; tail (frame 8)
# returns. isr (2 pushes) calls through r12: address-taken are leaf (mov #0x1100) and
# table_fn (a word in rodata); table_fn (frame 10) reaches deeper than leaf.
# Deepest reset chain: 2 (call main) + main's 6 + 2 (call leaf) + leaf's 4 = 14; main's
# br to tail runs at depth 0: 2 + 0 + 8 = 10 is shallower. reset(0) > main(6) > leaf(4).
# isr: 4 (entry) + 4 (pushes) + 2 + table_fn 10 = 20.
GOOD = """
00001000 <reset>:
    1000:      	mov	#2560, r1
    1004:      	call	#4112
    1008:      	jmp	$+0

00001010 <main>:
    1010:      	push	r10
    1012:      	push	r9
    1014:      	sub	#2, r1
    1018:      	call	#4352
    101c:      	tst	r12
    101e:      	jeq	$+6
    1020:      	mov	#4352, r13
    1024:      	add	#2, r1
    1028:      	pop	r9
    102a:      	pop	r10
    102c:      	br	#4608

00001100 <leaf>:
    1100:      	push	r10
    1102:      	push	r2
    1104:      	dint
    1106:      	pop	r2
    1108:      	pop	r10
    110a:      	ret

00001200 <tail>:
    1200:      	sub	#8, r1
    1204:      	add	#8, r1
    1208:      	ret

00001300 <table_fn>:
    1300:      	pushm	#5, r10
    1302:      	popm	#5, r10
    1304:      	ret

00001400 <isr>:
    1400:      	push	r12
    1402:      	push	r13
    1404:      	mov	&512, r12
    1408:      	call	r12
    140a:      	pop	r13
    140c:      	pop	r12
    140e:      	reti
"""


def image(text, data=(), indirect=None):
    img = sb.Image(sb.parse_disassembly(text), sb.functions_from_headers(text), data, indirect)
    img.analyse()
    return img


class Frames(unittest.TestCase):
    def setUp(self):
        # 0x1300 (table_fn) in a data word at 0x2000; 0x1234 is no function.
        self.img = image(GOOD, data=[(0x2000, 0x1300), (0x2002, 0x1234)])

    def test_frames(self):
        f = self.img.funcs
        self.assertEqual(f["main"].frame, 6)
        self.assertEqual(f["leaf"].frame, 4)  # push r10 + push r2 inside the body
        self.assertEqual(f["tail"].frame, 8)
        self.assertEqual(f["table_fn"].frame, 10)  # pushm #5
        self.assertEqual(f["isr"].frame, 4)
        for fn in f.values():
            self.assertEqual(fn.errors, [], fn.name)

    def test_address_taken(self):
        self.assertEqual(sorted(self.img.taken), ["leaf", "table_fn"])

    def test_chain_sum(self):
        b, chain = sb.Bounds(self.img).of("reset")
        self.assertEqual(b, 2 + 6 + 2 + 4)
        self.assertEqual(chain, [("reset", 0), ("main", 6), ("leaf", 4)])
        # the tail call runs at main's depth after its epilogue: 0 + 8
        self.assertIn(("tail", "tail", 0, 0x102c), self.img.funcs["main"].edges)

    def test_indirect_rule(self):
        b, chain = sb.Bounds(self.img).of("isr")
        self.assertEqual(b, 4 + 2 + 10)
        self.assertEqual(chain[1], ("*table_fn", 10))
        narrowed = image(GOOD, data=[(0x2000, 0x1300)], indirect={"isr": ["leaf"]})
        self.assertEqual(sb.Bounds(narrowed).of("isr")[0], 4 + 2 + 4)

    def test_report(self):
        r = sb.report(self.img, {sb.RESET_VECTOR: "reset", 18: "isr"}, free_ram=100, limit=None)
        self.assertEqual(r["errors"], [])
        self.assertFalse(r["nesting"])
        self.assertEqual(r["worst"], 14 + 20)
        # leaf's pop r2 puts back the SR it pushed: a restore, not an enable
        kinds = {(g["function"], g["kind"]) for x in r["roots"] for g in x["gie"]}
        self.assertEqual(kinds, {("leaf", "restore")})
        self.assertEqual(sb.report(self.img, {sb.RESET_VECTOR: "reset", 18: "isr"}, 30, None)["over"],
                         ["worst case 34 B exceeds the free RAM 30 B"])

    def test_ram_budget_counts_static_data_and_stack_together(self):
        vecs = {sb.RESET_VECTOR: "reset", 18: "isr"}
        fits = sb.report(self.img, vecs, 1000, None, static_ram=66, ram_budget=100)
        self.assertEqual(fits["over"], [])
        over = sb.report(self.img, vecs, 1000, None, static_ram=67, ram_budget=100)
        self.assertEqual(over["over"], ["static RAM 67 B + worst case 34 B = 101 B exceeds "
                                        "the RAM budget 100 B"])


class Errors(unittest.TestCase):
    def test_recursion_names_the_cycle(self):
        text = """
00001000 <a>:
    1000:      	push	r10
    1002:      	call	#4096
    1006:      	pop	r10
    1008:      	ret

00001100 <b>:
    1100:      	call	#4352
    1104:      	call	#4608
    1108:      	ret

00001200 <c>:
    1200:      	jmp	$-256
"""
        img = image(text)
        with self.assertRaises(sb.Recursion) as e:
            sb.Bounds(img).of("a")
        self.assertEqual(str(e.exception), "a -> a")
        with self.assertRaises(sb.Recursion) as e:
            sb.Bounds(img).of("b")
        self.assertEqual(str(e.exception), "b -> b")  # b calls b; c tail-jumps to b too

    def test_unbalanced_return(self):
        text = """
00001000 <f>:
    1000:      	push	r10
    1002:      	tst	r12
    1004:      	jeq	$+4
    1006:      	pop	r10
    1008:      	ret
"""
        img = image(text)
        self.assertTrue(any("returns with 2 bytes" in e for e in img.funcs["f"].errors))

    def test_autoincrement_reads_pop(self):
        # Four words pushed, then summed off the stack with @r1+ (as fx_hypot does): each
        # read pops 2 bytes, so the return finds the depth back at 0; the frame is 8.
        text = """
00001000 <f>:
    1000:      	push	r15
    1002:      	push	r14
    1004:      	push	r13
    1006:      	push	r12
    1008:      	add	@r1+, r12
    100a:      	addc	@r1+, r13
    100c:      	addc	@r1+, r14
    100e:      	addc	@r1+, r15
    1010:      	ret
"""
        img = image(text)
        self.assertEqual(img.funcs["f"].errors, [])
        self.assertEqual(img.funcs["f"].frame, 8)

    def test_join_with_two_depths(self):
        text = """
00001000 <f>:
    1000:      	tst	r12
    1002:      	jeq	$+4
    1004:      	push	r10
    1006:      	pop	r11
    1008:      	ret
"""
        img = image(text)
        self.assertTrue(any("reached with stack depth" in e for e in img.funcs["f"].errors))

    def test_isr_enabling_interrupts_counts_nesting(self):
        text = """
00001000 <reset>:
    1000:      	mov	#2560, r1
    1004:      	sub	#10, r1
    1008:      	jmp	$+0

00001100 <isr_a>:
    1100:      	push	r12
    1102:      	bis	#8, r2
    1106:      	pop	r12
    1108:      	reti

00001200 <isr_b>:
    1200:      	sub	#20, r1
    1204:      	add	#20, r1
    1208:      	reti
"""
        r = sb.report(image(text), {sb.RESET_VECTOR: "reset", 18: "isr_a", 19: "isr_b"}, 1000, None)
        self.assertTrue(r["nesting"])
        self.assertEqual(r["worst"], 10 + (4 + 2) + (4 + 20))

    def test_multiplier_in_a_handler_is_reported_when_forbidden(self):
        text = """
00001000 <reset>:
    1000:      	mov	#2560, r1
    1004:      	mov	r12, &304
    1008:      	jmp	$+0

00001100 <isr_a>:
    1100:      	call	#4608
    1104:      	reti

00001200 <helper>:
    1200:      	mov	&314, r12
    1204:      	ret

00001300 <isr_b>:
    1300:      	mov	&400, r12
    1304:      	reti
"""
        vectors = {sb.RESET_VECTOR: "reset", 18: "isr_a", 19: "isr_b"}
        r = sb.report(image(text), vectors, 1000, None, no_mpy_in_isr=True)
        self.assertEqual(r["errors"], ["isr_a reaches the hardware multiplier: helper "
                                       "1200: mov &314, r12"])
        # the main line may use it; without the option nothing is reported
        self.assertEqual(sb.report(image(text), vectors, 1000, None)["errors"], [])

    # The nav board's coordinate request before issue 18: the NMI handler converted the pose
    # to metres, through q4_to_m and the compiler's multiply helper (which holds interrupts
    # off with DINT: no help against an NMI). --no-mpy-in-nmi names the helper and the path;
    # the same code in a maskable handler is no NMI finding.
    NMI_MULTIPLIES = """
00001000 <reset>:
    1000:      	mov	#2560, r1
    1004:      	jmp	$+0

00001100 <nmi>:
    1100:      	call	#4608
    1104:      	reti

00001200 <coord_request>:
    1200:      	call	#4864
    1204:      	ret

00001300 <q4_to_m>:
    1300:      	call	#5120
    1304:      	ret

00001400 <__mspabi_mpyl_hw>:
    1400:      	push	r2
    1402:      	dint
    1404:      	mov	r12, &304
    1408:      	mov	r14, &312
    140c:      	mov	&314, r12
    1410:      	pop	r2
    1412:      	ret

00001500 <copy_only>:
    1500:      	mov	@r12+, r13
    1502:      	ret

00001600 <isr>:
    1600:      	call	#4608
    1604:      	reti
"""

    def test_nmi_reaching_a_multiply_helper_is_reported_with_its_path(self):
        vectors = {sb.RESET_VECTOR: "reset", sb.NMI_VECTOR: "nmi", 18: "isr"}
        r = sb.report(image(self.NMI_MULTIPLIES), vectors, 1000, None, no_mpy_in_nmi=True)
        self.assertEqual(r["errors"], [
            "the NMI handler nmi reaches the multiply helper __mspabi_mpyl_hw: "
            "nmi > coord_request > q4_to_m > __mspabi_mpyl_hw"])
        # without the option, or with the maskable handler alone reaching it: nothing
        self.assertEqual(sb.report(image(self.NMI_MULTIPLIES), vectors, 1000, None)["errors"], [])
        no_nmi = {sb.RESET_VECTOR: "reset", 18: "isr"}
        self.assertEqual(sb.report(image(self.NMI_MULTIPLIES), no_nmi, 1000, None,
                                   no_mpy_in_nmi=True)["errors"], [])

    def test_nmi_naming_a_multiplier_register_is_reported(self):
        text = self.NMI_MULTIPLIES.replace("    1100:      	call	#4608\n",
                                           "    1100:      	mov	r12, &306\n")
        vectors = {sb.RESET_VECTOR: "reset", sb.NMI_VECTOR: "nmi"}
        r = sb.report(image(text), vectors, 1000, None, no_mpy_in_nmi=True)
        self.assertEqual(r["errors"], ["the NMI handler nmi reaches the hardware multiplier: "
                                       "nmi 1100: mov r12, &306: nmi"])

    def test_nmi_that_only_copies_passes(self):
        text = self.NMI_MULTIPLIES.replace("    1100:      	call	#4608\n",
                                           "    1100:      	call	#5376\n")
        vectors = {sb.RESET_VECTOR: "reset", sb.NMI_VECTOR: "nmi", 18: "isr"}
        self.assertEqual(sb.report(image(text), vectors, 1000, None, no_mpy_in_nmi=True,
                                   no_mpy_in_isr=False)["errors"], [])

    def test_noreturn_call_does_not_fall_into_the_next_function(self):
        text = """
00001000 <f>:
    1000:      	call	#4352

00001004 <g>:
    1004:      	sub	#50, r1
    1008:      	add	#50, r1
    100c:      	ret

00001100 <halt>:
    1100:      	jmp	$+0
"""
        img = image(text)
        self.assertEqual(sb.Bounds(img).of("f")[0], 2)


class NmiRearm(unittest.TestCase):
    """The NMI handler may set NMIIE again only as its last instruction before RETI
    (SLAU144); a second request then nests on the first one's 4 bytes, counted once."""

    RESET_AND_ISR = """
00001000 <reset>:
    1000:      	mov	#2560, r1
    1004:      	sub	#10, r1
    1008:      	jmp	$+0

00001100 <isr>:
    1100:      	sub	#6, r1
    1104:      	add	#6, r1
    1108:      	reti
"""

    def nmi(self, body):
        text = self.RESET_AND_ISR + "\n00001200 <nmi>:\n" + body
        return sb.report(image(text), {sb.RESET_VECTOR: "reset", 18: "isr", sb.NMI_VECTOR: "nmi"},
                         1000, None)

    def test_rearmed_last_counts_one_nested_nmi(self):
        # reset 10 + isr (4 + 6) + nmi (4 + 4) + the first NMI's 4 bytes under a second one
        r = self.nmi("""    1200:      	push	r12
    1202:      	push	r13
    1204:      	pop	r13
    1206:      	pop	r12
    1208:      	bis.b	#16, &0
    120e:      	reti
""")
        self.assertEqual(r["errors"], [])
        self.assertEqual(r["nmi_nested"], 4)
        self.assertEqual(r["worst"], 10 + 10 + 8 + 4)

    def test_rearmed_before_the_pops_is_an_error(self):
        r = self.nmi("""    1200:      	push	r12
    1202:      	bis.b	#16, &0
    1208:      	pop	r12
    120a:      	reti
""")
        self.assertEqual(len(r["errors"]), 1)
        self.assertIn("nested NMIs are not bounded", r["errors"][0])
        self.assertIsNone(r["worst"])

    def test_not_rearmed_adds_nothing(self):
        r = self.nmi("""    1200:      	bic.b	#16, &2
    1206:      	reti
""")
        self.assertEqual((r["errors"], r["nmi_nested"], r["worst"]), ([], 0, 10 + 10 + 4))


if __name__ == "__main__":
    unittest.main(verbosity=2)
