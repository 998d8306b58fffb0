#!/usr/bin/env python3
"""Write the fault campaign's table into documents from the campaign's JSON output
(tools/campaign.py --json), so that the figures shown are the measured ones.

A document holds the table between two markers naming the JSON file (relative to the
repository's root):

  <!-- campaign-table docs/campaign/full.json -->
  ...generated table...
  <!-- end campaign-table -->

  tools/campaign_doc.py README.md docs/campaign.md           rewrite the tables
  tools/campaign_doc.py --check README.md docs/campaign.md   exit 1 when one is out of date
"""
import argparse
import json
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import campaign  # noqa: E402  (the table is campaign.py's own)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BLOCK = re.compile(r"(<!-- campaign-table (\S+) -->\n)(.*?)(<!-- end campaign-table -->)", re.S)


def render(json_path):
    with open(os.path.join(ROOT, json_path)) as f:
        c = json.load(f)
    seeds = c["seeds"]
    runs = c["summary"]["overall"]["runs"]
    head = (f"{runs} runs: {len(c['kinds'])} kinds x {len(seeds)} seeds "
            f"({seeds[0]}-{seeds[-1]}) of `{c['world']}`.\n\n")
    checks = "".join(f"- {'met' if k['ok'] else 'MISSED'}: {k['check']}"
                     f"{'' if k['ok'] else ' (' + k['why'] + ')'}\n" for k in c["checks"])
    return head + campaign.table(c["summary"], c["kinds"], c["wrong_m"]) + \
        ("\n" + checks if checks else "")


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--check", action="store_true", help="only check; exit 1 when out of date")
    ap.add_argument("docs", nargs="+", help="documents with campaign-table markers")
    a = ap.parse_args()
    stale = 0
    for doc in a.docs:
        with open(doc) as f:
            text = f.read()
        try:
            new, n = BLOCK.subn(lambda m: m.group(1) + render(m.group(2)) + m.group(4), text)
        except (OSError, ValueError, KeyError) as e:
            print(f"campaign_doc: {doc}: {e}", file=sys.stderr)
            return 2
        if n == 0:
            print(f"campaign_doc: {doc}: no campaign-table markers", file=sys.stderr)
            return 2
        if new != text:
            if a.check:
                print(f"campaign_doc: {doc}: the campaign table is out of date "
                      f"(run tools/campaign_doc.py {doc})", file=sys.stderr)
                stale += 1
            else:
                with open(doc, "w") as f:
                    f.write(new)
                print(f"campaign_doc: {doc}: table rewritten")
    return 1 if stale else 0


if __name__ == "__main__":
    sys.exit(main())
