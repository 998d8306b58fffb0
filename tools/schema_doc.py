#!/usr/bin/env python3
"""Write the key tables of markdown documents from the JSON Schemas they name.

A document holds a table between two markers:

  <!-- schema-table docs/schema/scenario.schema.json -->
  ...generated rows...
  <!-- end schema-table -->

and this tool rewrites what lies between them from the schema (a key per row: its full
path, type, unit, range, default, whether it is required, its description), so that the
reference cannot drift from the format the tools check. The path is relative to the
repository's root.

  tools/schema_doc.py docs/interfaces.md           rewrite the tables
  tools/schema_doc.py --check docs/interfaces.md   exit 1 when a table is out of date
"""
import argparse
import json
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import markerdoc  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BLOCK = re.compile(r"(<!-- schema-table (\S+) -->\n)(.*?)(<!-- end schema-table -->)", re.S)


def fmt(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float) and v.is_integer() and abs(v) < 1e15:
        v = int(v)
    return f"{v:,}".replace(",", " ") if isinstance(v, int) and abs(v) >= 100000 else str(v)


def rows(node, path, required, out):
    t = node.get("type", "")
    if t == "object" and "properties" in node:
        if path and not path.endswith("[]"):
            out.append((path, "object", "", "", "", "yes" if required else "no",
                        node.get("description", "")))
        req = set(node.get("required", []))
        for k, sub in node["properties"].items():
            rows(sub, f"{path}.{k}" if path else k, k in req, out)
        return
    if t == "array":
        lo, hi = node.get("minItems", 0), node.get("maxItems")
        rng = f"{lo}..{hi} entries" if hi is not None else f"at least {lo} entries"
        out.append((path, "array of objects", "", rng, "", "yes" if required else "no",
                    node.get("description", "")))
        rows(node["items"], path + "[]", True, out)
        return
    rng = ""
    if "enum" in node:
        rng = " or ".join(f"`\"{v}\"`" for v in node["enum"])
    elif "minimum" in node or "maximum" in node:
        rng = f"{fmt(node.get('minimum', '-inf'))} .. {fmt(node.get('maximum', 'inf'))}"
    elif "maxLength" in node:
        rng = f"at most {node['maxLength']} characters"
    if t == "object" and "additionalProperties" in node:
        t = "object of " + node["additionalProperties"].get("type", "any")
    desc = node.get("description", "")
    if "x-doc-keys" in node:
        desc += f" Keys: {node['x-doc-keys']}."
    dflt = f"`{fmt(node['default'])}`" if "default" in node else ""
    out.append((path, t, node.get("x-unit", ""), rng, dflt, "yes" if required else "no", desc))


def table(schema_path):
    with open(os.path.join(ROOT, schema_path)) as f:
        schema = json.load(f)
    out = []
    rows(schema, "", True, out)
    lines = ["| key | type | unit | range | default | required | meaning |",
             "| --- | --- | --- | --- | --- | --- | --- |"]
    for r in out:
        lines.append("| " + " | ".join([f"`{r[0]}`"] + [c.replace("|", "\\|") for c in r[1:]]) +
                     " |")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--check", action="store_true", help="only check; exit 1 when out of date")
    ap.add_argument("docs", nargs="+")
    a = ap.parse_args()
    return markerdoc.rewrite(a.docs, BLOCK, table, "schema_doc", "key table", a.check)


if __name__ == "__main__":
    sys.exit(main())
