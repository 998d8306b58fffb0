#!/usr/bin/env python3
"""The board link's messages from their one source, firmware/link/messages.toml.

Writes the DBC that describes every frame and signal (firmware/link/cyclopion.dbc is this
output, checked in for candump/cantools users), and the firmware's message table: a public
header of frame ids, message types, value constants and X-macro lists (link/linkmsg_ids.h)
and the private field table that firmware/link/linkmsg.c encodes and decodes with
(linkmsg_table.h), both at build time. The table's compile-time checks make the build fail
when a linkmsg_t member named in `c` is missing or has another size or signedness than the
signal.

  tools/gen_link.py firmware/link/messages.toml --dbc firmware/link/cyclopion.dbc
  tools/gen_link.py firmware/link/messages.toml --ids OUT/link/linkmsg_ids.h --table OUT/t.h
  tools/gen_link.py firmware/link/messages.toml --check-dbc firmware/link/cyclopion.dbc

--check-dbc exits 1 (with a diff) when the checked-in DBC is not what the table gives; rewrite
it with --dbc. The format of messages.toml is described at its top.
"""
import argparse
import difflib
import os
import re
import sys
import tomllib

MAX_ID = 0x7FF
NAME = re.compile(r"^[A-Z][A-Z0-9_]*$")
SIGNAL = re.compile(r"^[a-z][a-z0-9_]*$")
CMEMBER = re.compile(r"^[a-z_][a-z0-9_]*(\.[a-z_][a-z0-9_]*)*$")


class TableError(Exception):
    pass


def num(v):
    """A number as the DBC and C write it: integers plainly, floats round-tripping."""
    if isinstance(v, int) or float(v).is_integer():
        return str(int(v))
    return repr(float(v))


class Signal:
    def __init__(self, d, where):
        for k in d:
            if k not in ("name", "bits", "signed", "scale", "offset", "unit", "c", "comment",
                         "values"):
                raise TableError(f"{where}: unknown key {k!r}")
        self.name = d.get("name", "")
        if not SIGNAL.match(self.name):
            raise TableError(f"{where}: name {self.name!r} must be lower_case")
        where = f"{where} ({self.name})"
        self.bits = d.get("bits")
        if self.bits not in (8, 16, 32):
            raise TableError(f"{where}: bits {self.bits!r} must be 8, 16 or 32 (whole bytes)")
        self.signed = bool(d.get("signed", False))
        self.scale = d.get("scale", 1)
        self.offset = d.get("offset", 0)
        if not isinstance(self.scale, (int, float)) or self.scale <= 0:
            raise TableError(f"{where}: scale {self.scale!r} must be a positive number")
        if not isinstance(self.offset, (int, float)):
            raise TableError(f"{where}: offset {self.offset!r} must be a number")
        self.unit = d.get("unit", "")
        self.c = d.get("c", "")
        if not CMEMBER.match(self.c):
            raise TableError(f"{where}: c {self.c!r} must name a member of linkmsg_t's union")
        self.comment = d.get("comment", "")
        if not self.comment or '"' in self.comment:
            raise TableError(f"{where}: a comment (without double quotes) is required")
        self.raw_min = -(1 << (self.bits - 1)) if self.signed else 0
        self.raw_max = (1 << (self.bits - 1)) - 1 if self.signed else (1 << self.bits) - 1
        self.values = {}
        for k, v in d.get("values", {}).items():
            try:
                raw = int(k)
            except ValueError:
                raise TableError(f"{where}: value key {k!r} is not an integer")
            if not self.raw_min <= raw <= self.raw_max or not NAME.match(v):
                raise TableError(f"{where}: value {k} = {v!r} out of range or not UPPER_CASE")
            self.values[raw] = v

    @property
    def nbytes(self):
        return self.bits // 8

    def phys(self, raw):
        return raw * self.scale + self.offset


class Frame:
    """One CAN frame of a message: its id, name and the signals it carries at byte offsets."""

    def __init__(self, name, fid, sender, comment):
        self.name, self.id, self.sender, self.comment = name, fid, sender, comment
        self.signals = []  # (byte offset, Signal)
        self.len = 0


class Message:
    def __init__(self, d, where, nodes):
        for k in d:
            if k not in ("name", "id", "sender", "comment", "signals"):
                raise TableError(f"{where}: unknown key {k!r}")
        self.name = d.get("name", "")
        if not NAME.match(self.name):
            raise TableError(f"{where}: name {self.name!r} must be UPPER_CASE")
        where = f"message {self.name}"
        self.id = d.get("id")
        if not isinstance(self.id, int) or not 0 <= self.id <= MAX_ID:
            raise TableError(f"{where}: id {self.id!r} must be 0..0x7FF")
        self.sender = d.get("sender")
        if self.sender not in nodes:
            raise TableError(f"{where}: sender {self.sender!r} is not one of {nodes}")
        self.comment = d.get("comment", "")
        if not self.comment or '"' in self.comment:
            raise TableError(f"{where}: a comment (without double quotes) is required")
        self.signals = [Signal(s, f"{where} signal {i}")
                        for i, s in enumerate(d.get("signals", []))]
        if not self.signals:
            raise TableError(f"{where}: no signals")
        names = [s.name for s in self.signals]
        if len(set(names)) != len(names) or "tag" in names:
            raise TableError(f"{where}: signal names must be distinct (and not 'tag')")
        self.len = sum(s.nbytes for s in self.signals)
        if self.len > 15:
            raise TableError(f"{where}: {self.len} data bytes; at most 15 (two frames and tag)")
        self.pair = self.len > 8
        self.frames = self._frames()

    def _frames(self):
        if not self.pair:
            f = Frame(self.name, self.id, self.sender, self.comment)
            k = 0
            for s in self.signals:
                f.signals.append((k, s))
                k += s.nbytes
            f.len = k
            return [f]
        a = Frame(self.name + "_A", self.id, self.sender, self.comment + " (first frame)")
        b = Frame(self.name + "_B", self.id + 1, self.sender, self.comment + " (second frame)")
        k = 0
        for s in self.signals:
            if k < 8 < k + s.nbytes:
                raise TableError(f"message {self.name}: signal {s.name} straddles its A and "
                                 "B frames (byte 8)")
            (a if k < 8 else b).signals.append((k if k < 8 else k - 8, s))
            k += s.nbytes
        if k <= 8:
            raise TableError(f"message {self.name}: internal: a pair with {k} bytes")
        a.len = 8
        b.len = k - 8 + 1
        tag = Signal({"name": "tag", "bits": 8, "c": "tag",
                      "comment": f"CRC-8 (polynomial 0x07, initial 0) of {a.name}'s 8 data "
                                 "bytes"}, "tag")
        b.signals.append((k - 8, tag))
        return [a, b]


class Table:
    def __init__(self, d, source):
        self.source = source
        bus = d.get("bus", {})
        self.name = bus.get("name", "")
        self.comment = bus.get("comment", "")
        self.nodes = [n.get("name") for n in d.get("nodes", [])]
        self.node_comments = [n.get("comment", "") for n in d.get("nodes", [])]
        if len(self.nodes) < 2 or any(not NAME.match(n or "") for n in self.nodes):
            raise TableError("nodes: at least two, UPPER_CASE names")
        self.messages = [Message(m, f"messages[{i}]", self.nodes)
                         for i, m in enumerate(d.get("messages", []))]
        seen = {}
        for m in self.messages:
            for f in m.frames:
                if f.id > MAX_ID:
                    raise TableError(f"frame {f.name}: id 0x{f.id:03X} is beyond 0x7FF")
                if f.id in seen:
                    raise TableError(f"frames {seen[f.id]} and {f.name} share id 0x{f.id:03X}")
                seen[f.id] = f.name
        members = {}
        for m in self.messages:
            for s in m.signals:
                if members.setdefault(s.c, (s.bits, s.signed)) != (s.bits, s.signed):
                    raise TableError(f"message {m.name} signal {s.name}: member {s.c!r} is "
                                     "another signal's with another size or signedness")

    @property
    def frames(self):
        return [f for m in self.messages for f in m.frames]

    def receivers(self, sender):
        return [n for n in self.nodes if n != sender]

    # ---------------------------------------------------------------- DBC
    def dbc(self):
        out = ['VERSION ""', "", "", "NS_ :", "    CM_", "    VAL_", "", "BS_:", "",
               "BU_: " + " ".join(self.nodes), "", ""]
        for f in self.frames:
            out.append(f"BO_ {f.id} {f.name}: {f.len} {f.sender}")
            rx = ",".join(self.receivers(f.sender))
            for start, s in f.signals:
                lo, hi = s.phys(s.raw_min), s.phys(s.raw_max)
                out.append(f" SG_ {s.name} : {8 * start}|{s.bits}@1{'-' if s.signed else '+'} "
                           f"({num(s.scale)},{num(s.offset)}) [{num(lo)}|{num(hi)}] "
                           f'"{s.unit}" {rx}')
            out.append("")
        out.append("")
        out.append(f'CM_ "{self.comment} (generated by tools/gen_link.py from '
                   f'{self.source}: do not edit)";')
        for n, c in zip(self.nodes, self.node_comments):
            out.append(f'CM_ BU_ {n} "{c}";')
        for f in self.frames:
            out.append(f'CM_ BO_ {f.id} "{f.comment}";')
            for _, s in f.signals:
                out.append(f'CM_ SG_ {f.id} {s.name} "{s.comment}";')
        for f in self.frames:
            for _, s in f.signals:
                if s.values:
                    vals = " ".join(f'{k} "{v}"' for k, v in sorted(s.values.items()))
                    out.append(f"VAL_ {f.id} {s.name} {vals} ;")
        return "\n".join(out) + "\n"

    # ---------------------------------------------------------------- C
    def ids_header(self, head):
        out = [head, "#ifndef LINK_LINKMSG_IDS_H", "#define LINK_LINKMSG_IDS_H", "",
               "/* Nodes (the boards). */"]
        for i, n in enumerate(self.nodes):
            out.append(f"#define LINKMSG_NODE_{n} {i}")
        out += [f"#define LINKMSG_NODES {len(self.nodes)}", "", "/* Frame identifiers. */"]
        for f in self.frames:
            out.append(f"#define LINKMSG_ID_{f.name} 0x{f.id:03X}u")
        out += ["", "/** Message types (linkmsg_t.type). */", "typedef enum {",
                "    LINKMSG_NONE = 0,"]
        for m in self.messages:
            out.append(f"    LINKMSG_{m.name},")
        out += ["} linkmsg_type_t;", "",
                f"#define LINKMSG_TYPES {len(self.messages) + 1} /* with LINKMSG_NONE */",
                f"#define LINKMSG_PAIRS {sum(m.pair for m in self.messages)}"
                " /* messages of two frames */",
                f"#define LINKMSG_MAX_FIELDS {max(len(m.signals) for m in self.messages)}",
                "", "/* Named values of signals. */"]
        for m in self.messages:
            for s in m.signals:
                for raw, v in sorted(s.values.items()):
                    out.append(f"#define LINKMSG_{m.name}_{s.name.upper()}_{v} {raw}")
        out += ["", "/* X(frame name, id, sender node, data bytes), every frame. */",
                "#define LINKMSG_FRAMES(X) \\"]
        out += [f"    X({f.name}, 0x{f.id:03X}u, LINKMSG_NODE_{f.sender}, {f.len}) \\"
                for f in self.frames]
        out += ["", "", "/* X(message name, type, first frame id, frames), every message. */",
                "#define LINKMSG_MESSAGES(X) \\"]
        out += [f"    X({m.name}, LINKMSG_{m.name}, 0x{m.id:03X}u, {len(m.frames)}) \\"
                for m in self.messages]
        out += ["", "", "#endif", ""]
        return "\n".join(out)

    def table_header(self, head):
        out = [head, "/* Included by firmware/link/linkmsg.c after linkmsg_t, msg_desc_t and "
               "FIELD(). */", "", "static const msg_desc_t msgs[] = {"]
        slot = 0
        for m in self.messages:
            fields = ", ".join(f"FIELD({s.c})" for s in m.signals)
            out.append(f"    /* {m.name} */ {{LINKMSG_ID_{m.frames[0].name}, {m.len}u, "
                       f"{slot if m.pair else 0}u, LINKMSG_NODE_{m.sender}, {{{fields}}}}},")
            slot += m.pair
        out += ["};", ""]
        for m in self.messages:
            for s in m.signals:
                member = f"((linkmsg_t *)0)->u.{s.c}"
                out.append(f"_Static_assert(sizeof({member}) == {s.nbytes}, \"{m.name}.{s.name}:"
                           f" linkmsg_t u.{s.c} must be {s.nbytes} byte(s) "
                           f"(firmware/link/messages.toml)\");")
                out.append(f"_Static_assert(((__typeof__({member}))-1 > (__typeof__({member}))0)"
                           f" == {int(not s.signed)}, \"{m.name}.{s.name}: linkmsg_t u.{s.c} must be "
                           f"{'signed' if s.signed else 'unsigned'} "
                           f"(firmware/link/messages.toml)\");")
        out.append("")
        return "\n".join(out)


def load(path):
    try:
        with open(path, "rb") as f:
            d = tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError) as e:
        raise TableError(str(e))
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    return Table(d, os.path.relpath(os.path.abspath(path), root))


def write(path, text):
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("table", help="the message table (firmware/link/messages.toml)")
    ap.add_argument("--dbc", help="write the DBC there")
    ap.add_argument("--ids", help="write the public C header (link/linkmsg_ids.h) there")
    ap.add_argument("--table", dest="ctable", help="write linkmsg.c's field table there")
    ap.add_argument("--check-dbc", metavar="DBC",
                    help="exit 1 unless DBC is exactly what the table gives")
    a = ap.parse_args()
    if not (a.dbc or a.ids or a.ctable or a.check_dbc):
        ap.error("nothing to do: give --dbc, --ids, --table or --check-dbc")
    try:
        t = load(a.table)
    except TableError as e:
        sys.exit(f"gen_link: {a.table}: {e}")
    head = f"/* Generated by tools/gen_link.py from {t.source}: do not edit. */"
    if a.dbc:
        write(a.dbc, t.dbc())
    if a.ids:
        write(a.ids, t.ids_header(head))
    if a.ctable:
        write(a.ctable, t.table_header(head))
    if a.check_dbc:
        try:
            with open(a.check_dbc) as f:
                have = f.read()
        except OSError as e:
            sys.exit(f"gen_link: {e}")
        want = t.dbc()
        if have != want:
            sys.stdout.writelines(difflib.unified_diff(
                have.splitlines(True), want.splitlines(True), a.check_dbc, "generated"))
            print(f"gen_link: {a.check_dbc} is stale: run tools/gen_link.py {a.table} "
                  f"--dbc {a.check_dbc}")
            return 1
        print(f"gen_link: {a.check_dbc} is what {a.table} gives "
              f"({len(t.frames)} frames, {len(t.messages)} messages)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
