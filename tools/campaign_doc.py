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
import markerdoc  # noqa: E402

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
    return markerdoc.rewrite(a.docs, BLOCK, render, "campaign_doc", "campaign table", a.check)


if __name__ == "__main__":
    sys.exit(main())
