#!/usr/bin/env python3
"""Generate agv-sim's scenario reader tables (C) from the scenario's JSON Schema.

The schema (docs/schema/scenario.schema.json) is the one description of the format: the
tests validate files against it and agv-sim's loader reads files with tables generated from
it, so the keys, types, ranges, defaults and required keys cannot drift apart. Each key that
holds a value carries "x-c": the struct field it is stored in (relative to the struct being
filled: the root's "x-c-type", or an array's element "x-c-type"); "x-c-scale": "deg" stores
degrees as radians; an enum's "x-c-enum" names the C constants of its values. Objects without
"x-c" store their members in the same struct. Writes two headers:

  --constants FILE   the enum constants and the limits (included by sim/scenario.h)
  --tables FILE      the reader tables, with compile-time checks that every field exists
                     with the right type and every array has room for maxItems (included by
                     sim/scenario.c)

  tools/gen_schema_c.py docs/schema/scenario.schema.json --constants scenario_keys.h \\
      --tables scenario_schema.h
"""
import argparse
import json
import math
import os
import sys

SCALES = {"deg": "(M_PI / 180.0)"}


class SchemaError(Exception):
    pass


def c_double(v):
    if v is None:
        return "0.0"
    if v == math.inf:
        return "INFINITY"
    if v == -math.inf:
        return "-INFINITY"
    return repr(float(v))


class Gen:
    def __init__(self, root, source):
        self.source = source
        self.root = root
        self.struct = root.get("x-c-type")
        if not self.struct:
            raise SchemaError("the root needs \"x-c-type\" (the struct it fills)")
        self.defs = []  # C definitions, children first
        self.asserts = []
        self.constants = []
        self.names = set()

    def ident(self, path):
        name = "node_" + "".join(c if c.isalnum() else "_" for c in path or "root")
        while name in self.names:
            name += "_"
        self.names.add(name)
        return name

    def field_check(self, struct, field, ctype_test, what, path):
        self.asserts.append(
            f"_Static_assert({ctype_test.format(f=f'(({struct} *)0)->{field}')}, "
            f"\"{path}: {struct}.{field} must be {what}\");")

    def object_members(self, node, path, struct):
        props = node.get("properties", {})
        required = set(node.get("required", []))
        unknown = required - set(props)
        if unknown:
            raise SchemaError(f"{path or 'root'}: required keys without properties: {unknown}")
        rows = []
        for key, sub in props.items():
            rows.append(self.node(key, sub, f"{path}.{key}" if path else key, struct,
                                  key in required))
        name = self.ident(path + ".members")
        self.defs.append(f"static const sim_schema_node_t {name}[] = {{\n" +
                         "".join(f"    {r},\n" for r in rows) + "};")
        return name, len(rows)

    def node(self, key, sub, path, struct, required):
        t = sub.get("type")
        if "$ref" in sub:
            raise SchemaError(f"{path}: $ref is not supported by the generator: write it out")
        fields = dict(key=f'"{key}"', kind=None, required="true" if required else "false",
                      has_default="false", closed="false", dflt="0.0", min="0.0", max="0.0",
                      scale="1.0", offset="0", size="0", count_offset="0", elem_size="0",
                      members="NULL", n_members="0", names="NULL", n_names="0")
        if "default" in sub:
            if required:
                raise SchemaError(f"{path}: a required key has no default")
            d = sub["default"]
            fields["has_default"] = "true"
            fields["dflt"] = c_double(float(d) if not isinstance(d, str) else
                                      sub.get("enum", []).index(d))
        field = sub.get("x-c")
        if t == "object":
            if field:
                raise SchemaError(f"{path}: an object stores through its members; no x-c")
            fields["kind"] = "SIM_SCHEMA_OBJECT"
            fields["closed"] = "true" if sub.get("additionalProperties") is False else "false"
            fields["members"], fields["n_members"] = self.object_members(sub, path, struct)
        elif t == "array":
            item = sub.get("items", {})
            etype = sub.get("x-c-type")
            count = sub.get("x-c-count")
            if item.get("type") != "object" or not field or not etype or not count:
                raise SchemaError(f"{path}: an array needs object items, x-c, x-c-count and "
                                  "x-c-type (its element struct)")
            lo, hi = sub.get("minItems", 0), sub.get("maxItems")
            if hi is None:
                raise SchemaError(f"{path}: an array needs maxItems (the C array's room)")
            item_node = self.node("", item, path + "[]", etype, True)
            name = self.ident(path + ".item")
            self.defs.append(f"static const sim_schema_node_t {name}[] = {{{item_node}}};")
            fields.update(kind="SIM_SCHEMA_ARRAY", min=c_double(lo), max=c_double(hi),
                          offset=f"offsetof({struct}, {field})",
                          count_offset=f"offsetof({struct}, {count})",
                          elem_size=f"sizeof((({struct} *)0)->{field}[0])",
                          members=name, n_members="1")
            self.asserts.append(
                f"_Static_assert(sizeof((({struct} *)0)->{field}) / "
                f"sizeof((({struct} *)0)->{field}[0]) >= {hi}, "
                f"\"{path}: {struct}.{field} has room for fewer than maxItems = {hi}\");")
            self.field_check(struct, count, "_Generic({f}, size_t: 1, default: 0)", "a size_t",
                             path)
            self.constants.append((path, "MAX_ITEMS", hi))
        elif t in ("number", "integer", "boolean", "string"):
            if not field:
                raise SchemaError(f"{path}: a value needs x-c (the field it is stored in)")
            fields["offset"] = f"offsetof({struct}, {field})"
            fields["size"] = f"sizeof((({struct} *)0)->{field})"
            if t in ("number", "integer"):
                fields["min"] = c_double(sub.get("minimum", -math.inf))
                fields["max"] = c_double(sub.get("maximum", math.inf))
                if "exclusiveMinimum" in sub or "exclusiveMaximum" in sub:
                    raise SchemaError(f"{path}: exclusive bounds are not supported")
            if t == "number":
                fields["kind"] = "SIM_SCHEMA_NUMBER"
                scale = sub.get("x-c-scale")
                if scale is not None and scale not in SCALES:
                    raise SchemaError(f"{path}: x-c-scale must be one of {sorted(SCALES)}")
                fields["scale"] = SCALES.get(scale, "1.0")
                self.field_check(struct, field, "_Generic({f}, double: 1, default: 0)",
                                 "a double", path)
            elif t == "integer":
                fields["kind"] = "SIM_SCHEMA_INTEGER"
                self.field_check(struct, field,
                                 "_Generic({f}, uint32_t: 1, uint64_t: 1, default: 0)",
                                 "a uint32_t or uint64_t", path)
            elif t == "boolean":
                fields["kind"] = "SIM_SCHEMA_BOOLEAN"
                self.field_check(struct, field, "_Generic({f}, bool: 1, default: 0)", "a bool",
                                 path)
            elif "enum" in sub:
                values = sub["enum"]
                prefix = sub.get("x-c-enum")
                if not prefix:
                    raise SchemaError(f"{path}: an enum needs x-c-enum (its constants' prefix)")
                names = self.ident(path + ".names")
                self.defs.append(f"static const char *const {names}[] = {{" +
                                 ", ".join(f'"{v}"' for v in values) + "};")
                fields.update(kind="SIM_SCHEMA_ENUM", names=names, n_names=str(len(values)))
                for i, v in enumerate(values):
                    self.constants.append((None, prefix + "_" +
                                           "".join(c if c.isalnum() else "_" for c in v).upper(),
                                           i))
                self.constants.append((None, prefix + "_COUNT", len(values)))
                self.field_check(struct, field, "_Generic({f}, int: 1, default: 0)", "an int",
                                 path)
            else:
                fields["kind"] = "SIM_SCHEMA_STRING"
                hi = sub.get("maxLength")
                if hi is None:
                    raise SchemaError(f"{path}: a string needs maxLength (the C array's room)")
                fields["max"] = c_double(hi)
                self.asserts.append(
                    f"_Static_assert(sizeof((({struct} *)0)->{field}) > {hi}, "
                    f"\"{path}: {struct}.{field} has room for fewer than maxLength = {hi}\");")
                self.field_check(struct, field, "_Generic({f}, char *: 1, default: 0)",
                                 "a char array", path)
        else:
            raise SchemaError(f"{path}: type {t!r} is not supported by the generator")
        return "{" + ", ".join(f".{k} = {v}" for k, v in fields.items()) + "}"

    def run(self, stem):
        root = self.node("", self.root, "", self.struct, True)
        self.defs.append(f"static const sim_schema_node_t {stem}_schema = {root};")


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("schema")
    ap.add_argument("--constants", required=True, help="header of constants to write")
    ap.add_argument("--tables", required=True, help="header of reader tables to write")
    ap.add_argument("--stem", default="sim_scenario", help="C name prefix (sim_scenario)")
    a = ap.parse_args()
    try:
        with open(a.schema) as f:
            schema = json.load(f)
        g = Gen(schema, a.schema)
        g.run(a.stem)
    except (OSError, ValueError, SchemaError) as e:
        sys.exit(f"gen_schema_c: {a.schema}: {e}")
    src = os.path.relpath(a.schema, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    head = f"/* Generated by tools/gen_schema_c.py from {src}: do not edit. */"
    guard = a.stem.upper() + "_KEYS_H"
    out = [head, f"#ifndef {guard}", f"#define {guard}", ""]
    for path, name, value in g.constants:
        if path is None:
            out.append(f"#define {name} {value}")
        else:
            cname = a.stem.upper() + "_" + \
                "".join(c if c.isalnum() else "_" for c in path).upper() + "_" + name
            out.append(f"#define {cname} {value}")
    out += ["", "#endif", ""]
    with open(a.constants, "w") as f:
        f.write("\n".join(out))
    guard = a.stem.upper() + "_SCHEMA_H"
    out = [head, f"#ifndef {guard}", f"#define {guard}", "",
           "#include <math.h>", "#include <stdbool.h>", "#include <stddef.h>",
           "#include <stdint.h>", "", "#include \"sim/schema.h\"", ""]
    out += g.asserts + [""] + g.defs + ["", "#endif", ""]
    with open(a.tables, "w") as f:
        f.write("\n".join(out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
