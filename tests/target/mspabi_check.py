"""Checker for tests/target/mspabi_test.c (tools/msp430sim.py --check): recomputes every line
with Python integers.

C semantics: truncating division, remainder with the dividend's sign, wrap-around at the
operand width. The helpers' documented extras (hal/msp430/mspabi.c): x / 0 is the maximum
(unsigned) or the maximum/minimum by the dividend's sign (signed), x % 0 is x, MIN / -1 is
MIN and MIN % -1 is 0.
"""

WIDTH = {"mpyi": 16, "mpyi_sw": 16, "mpysl": 32, "mpyul": 32, "divi": 16, "remi": 16,
         "divu": 16, "remu": 16, "divi_c": 16, "remi_c": 16, "divu_c": 16, "remu_c": 16,
         "mpyl": 32, "mpyl_sw": 32, "divli": 32, "remli": 32, "divul": 32, "remul": 32,
         "divli_c": 32, "remli_c": 32, "divul_c": 32, "remul_c": 32,
         "slll": 32, "srll": 32, "sral": 32,
         "mpyll": 64, "mpyll_sw": 64, "divlli": 64, "remlli": 64, "divull": 64, "remull": 64,
         "shl64": 64, "shr64": 64, "sar64": 64}


def signed(v, w):
    return v - (1 << w) if v & (1 << (w - 1)) else v


def sdiv(a, b, w):
    if b == 0:
        return (1 << (w - 1)) - 1 if a >= 0 else -(1 << (w - 1))
    q = abs(a) // abs(b)
    return q if (a < 0) == (b < 0) else -q


def srem(a, b):
    if b == 0:
        return a
    r = abs(a) % abs(b)
    return -r if a < 0 else r


def expected(op, a, b):
    w = WIDTH[op]
    base = op[:-2] if op.endswith("_c") else op[:-3] if op.endswith("_sw") else op
    if base in ("mpysl",):
        return signed(a, 16) * signed(b, 16)
    if base in ("mpyul",):
        return a * b
    if base in ("mpyi", "mpyl", "mpyll"):
        return a * b
    if base in ("divi", "divli", "divlli"):
        return sdiv(signed(a, w), signed(b, w), w)
    if base in ("remi", "remli", "remlli"):
        return srem(signed(a, w), signed(b, w))
    if base in ("divu", "divul", "divull"):
        return a // b if b else (1 << w) - 1
    if base in ("remu", "remul", "remull"):
        return a % b if b else a
    if base in ("slll", "shl64"):
        return a << b
    if base in ("srll", "shr64"):
        return a >> b
    if base in ("sral", "sar64"):
        return signed(a, w) >> b
    raise KeyError(op)


def check(lines):
    errors = []
    seen = {}
    for line in lines:
        f = line.split()
        if len(f) != 4 or f[0] not in WIDTH:
            errors.append(f"unexpected line: {line!r}")
            continue
        op = f[0]
        w = WIDTH[op]
        a, b, r = (int(x, 16) for x in f[1:])
        want = expected(op, a, b) & ((1 << w) - 1)
        if r != want:
            errors.append(f"{op}({f[1]}, {f[2]}) = {f[3]}, expected {want:0{w // 4}x}")
        seen[op] = seen.get(op, 0) + 1
    for op in WIDTH:
        if seen.get(op, 0) < 100:
            errors.append(f"{op}: only {seen.get(op, 0)} vectors checked")
    return errors
