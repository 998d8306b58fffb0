"""Rewrite or check the generated blocks of Markdown documents (imported by
tools/schema_doc.py and tools/campaign_doc.py; a library, not a tool).

A block is what a tool's regular expression matches: group 1 the opening marker, group 2 its
argument (what to render from), group 3 the block's current text, group 4 the closing marker.
"""
import sys


def rewrite(docs, block, render, tool, what, check):
    """Render every block of each document in @p docs. With @p check, say which documents are
    out of date; else write them. Returns the exit status: 0, 1 (check: out of date) or 2 (a
    document without markers, or a render that failed)."""
    stale = 0
    for doc in docs:
        with open(doc) as f:
            text = f.read()
        try:
            new, n = block.subn(lambda m: m.group(1) + render(m.group(2)) + m.group(4), text)
        except (OSError, ValueError, KeyError) as e:
            print(f"{tool}: {doc}: {e}", file=sys.stderr)
            return 2
        if n == 0:
            print(f"{tool}: {doc}: no {what} markers", file=sys.stderr)
            return 2
        if new == text:
            continue
        if check:
            print(f"{tool}: {doc}: a {what} is out of date (run tools/{tool}.py {doc})",
                  file=sys.stderr)
            stale += 1
        else:
            with open(doc, "w") as f:
                f.write(new)
            print(f"{tool}: {doc}: {what} rewritten")
    return 1 if stale else 0
