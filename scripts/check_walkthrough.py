#!/usr/bin/env python3
"""Check that doc/walkthrough.md quotes the code as it is.

Every fenced code block that follows a line `<!-- code: PATH -->` must
appear in PATH: each of its lines (stripped of trailing blanks; a line
`...` stands for lines left out) is a line of PATH, and they come in the
file's order. A quoted line that is not in the file, or out of order,
fails: the walk-through has gone stale. Prints one PASS/FAIL line per
block and exits 1 on any failure.

usage: check_walkthrough.py [doc/walkthrough.md]
"""
import os
import re
import sys

MARK = re.compile(r"^<!-- code: (\S+) -->\s*$")


def blocks(lines):
    """(line number, path, quoted lines) of every marked code block."""
    found = []
    k = 0
    while k < len(lines):
        match = MARK.match(lines[k])
        if match:
            start = k + 1
            if start >= len(lines) or not lines[start].startswith("```"):
                found.append((k + 1, match.group(1), None))
                k += 1
                continue
            end = start + 1
            while end < len(lines) and not lines[end].startswith("```"):
                end += 1
            found.append((k + 1, match.group(1), lines[start + 1:end]))
            k = end
        k += 1
    return found


def check_block(root, path, quoted):
    """None if every quoted line is in the file in order, else the reason."""
    full = os.path.join(root, path)
    if not os.path.isfile(full):
        return f"{path} does not exist"
    source = [line.rstrip() for line in open(full, encoding="utf-8")]
    position = 0
    for line in quoted:
        text = line.rstrip()
        if text.strip() in ("", "..."):
            continue
        try:
            position = source.index(text, position) + 1
        except ValueError:
            where = "not in the file" if text not in source else "out of order"
            return f"quoted line {where}: {text.strip()!r}"
    return None


def main():
    page = sys.argv[1] if len(sys.argv) > 1 else "doc/walkthrough.md"
    root = os.path.dirname(os.path.dirname(os.path.abspath(page)))
    lines = open(page, encoding="utf-8").read().split("\n")
    failures = 0
    found = blocks(lines)
    if not found:
        print(f"FAIL walkthrough {page}: no quoted code blocks (<!-- code: PATH --> before a fence)")
        return 1
    for number, path, quoted in found:
        reason = "the marker is not followed by a code fence" if quoted is None else check_block(root, path, quoted)
        if reason:
            failures += 1
            print(f"FAIL walkthrough {page}:{number} ({path}): {reason}")
        else:
            print(f"PASS walkthrough {page}:{number} ({path}, {sum(1 for q in quoted if q.strip() not in ('', '...'))} lines)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
