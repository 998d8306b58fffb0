#!/usr/bin/env python3
"""ctest (label sim): the scenario schema and agv-sim's loader agree, key by key.

Both schemas are valid JSON Schema (draft 2020-12); every shipped scenario follows its
schema. Then, for every key the scenario schema describes, variants of a shipped scenario
that break it (below its minimum, above its maximum, a wrong type, a fraction for an integer,
a value outside an enum, too few or too many entries, a required key removed, an unknown key
in a closed object) must be refused by the schema AND by agv-sim, with exit status 2 and a
message that names the file and the key (and the value, where there is one).

  schema_agreement.py AGV_SIM SCHEMA_DIR SCENARIO...
"""
import copy
import json
import os
import subprocess
import sys
import tempfile

import jsonschema


def leaves(node, path, required):
    """(path, schema node, required) for every key, depth first; array items as index 0."""
    t = node.get("type")
    if t == "object" and "properties" in node:
        req = set(node.get("required", []))
        if path:
            yield path, node, required
        for k, sub in node["properties"].items():
            yield from leaves(sub, path + [k], k in req)
    elif t == "array":
        yield path, node, required
        yield from leaves(node["items"], path + [0], True)
    else:
        yield path, node, required


def name(path):
    out = ""
    for p in path:
        out += f"[{p}]" if isinstance(p, int) else (("." if out else "") + p)
    return out


def get_parent(doc, path):
    for p in path[:-1]:
        if isinstance(p, int):
            doc = doc[p]
        else:
            doc = doc.setdefault(p, {})
    return doc


def variants(path, node, required):
    """(what, mutate(doc), value shown in the message or None)."""
    t = node.get("type")
    key = path[-1]

    def setter(v):
        return lambda d: get_parent(d, path).__setitem__(key, v)
    if t in ("number", "integer"):
        if "minimum" in node:
            v = node["minimum"] - (1 if t == "integer" else max(abs(node["minimum"]) * 0.01, 1e-4))
            yield "below its minimum", setter(v), None
        if "maximum" in node:
            v = node["maximum"] + (1 if t == "integer" else max(abs(node["maximum"]) * 0.01, 1e-4))
            yield "above its maximum", setter(v), None
        yield "a string", setter("seven"), '"seven"'
        if t == "integer":
            yield "a fraction", setter(node.get("minimum", 0) + 0.5), None
    elif t == "boolean":
        yield "a number", setter(1), "1"
    elif t == "string":
        if "enum" in node:
            yield "outside the enum", setter("no-such-" + key), f'"no-such-{key}"'
        if "maxLength" in node:
            yield "too long", setter("x" * (node["maxLength"] + 1)), None
        yield "a number", setter(3), "3"
    elif t == "object":
        yield "a number", setter(3), None
        if node.get("additionalProperties") is False:
            yield "an unknown key", \
                lambda d: get_parent(d, path + ["?"]).__setitem__("no_such_key", 1), "warn"
    elif t == "array":
        yield "not an array", setter(3), None
        if node.get("minItems", 0) > 0:
            yield "too few entries", lambda d: get_parent(d, path).__setitem__(
                key, get_parent(d, path)[key][:node["minItems"] - 1]), None
        if "maxItems" in node:
            yield "too many entries", lambda d: get_parent(d, path).__setitem__(
                key, (get_parent(d, path)[key] * (node["maxItems"] + 1))[:node["maxItems"] + 1]), \
                None
    if required and not isinstance(key, int):
        yield "removed", lambda d: get_parent(d, path).pop(key), "missing"


def main():
    agv, schema_dir, scenarios = sys.argv[1], sys.argv[2], sys.argv[3:]
    failures = 0
    schemas = {}
    for n in ("scenario", "report"):
        with open(os.path.join(schema_dir, f"{n}.schema.json")) as f:
            schemas[n] = json.load(f)
        jsonschema.Draft202012Validator.check_schema(schemas[n])
    validator = jsonschema.Draft202012Validator(schemas["scenario"])
    docs = {}
    for sc in scenarios:
        with open(sc) as f:
            docs[sc] = json.load(f)
        errs = [e.message for e in validator.iter_errors(docs[sc])]
        print(f"{'ok ' if not errs else 'BAD'} {os.path.basename(sc)} follows the schema {errs}")
        failures += bool(errs)
    # Mutate the richest scenario: the one with the most distinct keys (it has every optional
    # object and array), the longest of those.
    def keys(d, path=""):
        if isinstance(d, dict):
            for k, v in d.items():
                yield path + "." + k
                yield from keys(v, path + "." + k)
        elif isinstance(d, list):
            for v in d:
                yield from keys(v, path + "[]")

    base = max(docs.values(), key=lambda d: (len(set(keys(d))), len(json.dumps(d))))
    base = copy.deepcopy(base)
    base.setdefault("start_error", {"x": 0.0, "y": 0.0, "heading_deg": 0.0})
    base.setdefault("success", {})
    base["path"][0].setdefault("speed_mps", 1.0)
    base["spurious"][0].setdefault("width_deg", 0.02)
    base.setdefault("link", {"bus": "can", "bitrate_bps": 250000, "heartbeat_ms": 50,
                             "silence_ms": 250,
                             "faults": [{"kind": "delay", "at_s": 1.0, "duration_s": 1.0,
                                         "node": "any", "frame": "FIX_B", "count": 1,
                                         "delay_ms": 1.0, "id": 0, "len": 8, "period_ms": 0}]})
    # One of each optional array no shipped scenario needs (the disturbances).
    base.setdefault("pillars", [{"x": 500.0, "y": 500.0, "diameter_m": 0.3}])
    base["sensors"]["goniometer"].setdefault("dropouts", [{"t_s": 1000.0, "duration_s": 1.0}])
    checked = 0
    with tempfile.TemporaryDirectory() as tmp:
        for path, node, required in leaves(schemas["scenario"], [], True):
            if not path:
                continue
            try:
                get_parent(copy.deepcopy(base), path)
            except (KeyError, IndexError, TypeError):
                continue
            for what, mutate, shown in variants(path, node, required):
                doc = copy.deepcopy(base)
                try:
                    mutate(doc)
                except (KeyError, IndexError, TypeError, AttributeError):
                    continue
                file = os.path.join(tmp, "variant.json")
                with open(file, "w") as f:
                    json.dump(doc, f)
                schema_refuses = not validator.is_valid(doc)
                r = subprocess.run([agv, "--scenario", file, "--quiet", "--report",
                                    os.path.join(tmp, "r.json")], capture_output=True, text=True,
                                   timeout=600)
                key = name(path)
                if shown == "warn":
                    # Unknown keys: the schema refuses them, agv-sim warns and goes on.
                    ok = schema_refuses and "unknown key" in r.stderr and file in r.stderr
                else:
                    ok = (schema_refuses and r.returncode == 2 and file in r.stderr and
                          key in r.stderr and (shown is None or shown in r.stderr))
                checked += 1
                if not ok:
                    failures += 1
                    print(f"BAD {key} {what}: schema {'refuses' if schema_refuses else 'accepts'}"
                          f", agv-sim exit {r.returncode}: {r.stderr.strip()[:200]}")
    print(f"{checked} variants checked, {failures} disagreements")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
