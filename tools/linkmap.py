"""The flash an ld.lld link map gives each object and library (imported by
tests/target/board_flash.py and tools/doc_figures.py; a library, not a tool).

A map line is "VMA LMA Size Align Out In Symbol": an output section line has its name as the
fifth field (.text), an input section line "file(member):(section)". Flash is what lands in
.text, .rodata and .data (its load image); the vectors are the linker script's.
"""
import os
import re

FLASH_OUTPUTS = (".text", ".rodata", ".data")
LINE_RE = re.compile(r"^\s*([0-9a-f]+)\s+([0-9a-f]+)\s+([0-9a-f]+)\s+\d+\s+(\S+)\s*$")


def flash_by_object(map_text):
    """{object: bytes} of the input sections in the flash output sections; an object of a
    library is named "path/libx.a(member.o)"."""
    sizes, out = {}, None
    for line in map_text.splitlines():
        m = LINE_RE.match(line)
        if not m:
            continue
        name = m.group(4)
        if name.startswith("."):
            out = name
        elif ":(" in name and out in FLASH_OUTPUTS:
            obj = name.split(":(", 1)[0]
            sizes[obj] = sizes.get(obj, 0) + int(m.group(3), 16)
    return sizes


def flash_by_library(map_text):
    """{library or object file name: bytes}: flash_by_object() summed per archive
    (libcy_fx.a) or loose object (main_msp430.c.obj), by base name."""
    libs = {}
    for obj, n in flash_by_object(map_text).items():
        name = os.path.basename(obj.split("(", 1)[0])
        libs[name] = libs.get(name, 0) + n
    return libs
