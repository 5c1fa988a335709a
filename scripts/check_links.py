#!/usr/bin/env python3
"""Check the documentation's links, paths and tables (a stage of `make test`).

For README.md, every doc/*.md and test/fuzz/README.md:

  - every relative Markdown link [text](target) names a file or folder of the
    repository, and its #anchor, if any, a heading of that page (GitHub's
    anchors: lower case, punctuation dropped, spaces to hyphens, -1, -2, ...
    for repeats); a bare (#anchor) a heading of the page itself;
  - every repository path quoted in backquotes outside code blocks
    (`src/...`, `doc/...`, `scripts/...`, `test/...`, `inputs/...`, `app/...`,
    `reference_outputs/...`) exists;
  - doc/architecture.md names every module under src/ (as `visco2d_name` in
    backquotes), and every module it names exists;
  - every table renders: a table starts with a header row and a separator row
    of as many cells, and every row has that many cells (a blank line inside a
    table starts a new, headless, broken one).

Links to web addresses are not followed. Prints one PASS or FAIL line per file
(and a FAIL line per defect); exits 1 on any defect.

usage: check_links.py [ROOT]
"""
import glob
import os
import re
import sys

# Pages written on other branches of the same change: a link to one of them
# is accepted while the page is missing from this tree (a NOTE line says so);
# once it exists its anchors are checked like any other. Empty this set when
# the branches are merged.
PENDING = set()  # pages written on another branch, accepted with a NOTE until merged

LINK = re.compile(r"(?<!!)\[([^\]]*)\]\(([^)\s]+)\)|!\[([^\]]*)\]\(([^)\s]+)\)")
CODE_SPAN = re.compile(r"(`+)(.+?)\1")
PATH = re.compile(r"(?<![\w/.-])((?:src|app|test|scripts|doc|inputs|reference_outputs)/[\w.\-/]*[\w/])")
MODULE = re.compile(r"^\s*module\s+(visco2d_\w+)\s*$", re.IGNORECASE | re.MULTILINE)
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")


def slug(title):
    """GitHub's anchor of a heading."""
    text = re.sub(r"`([^`]*)`", r"\1", title)
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)
    text = text.strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def outside_fences(lines):
    """(line number, text) of the lines outside fenced code blocks."""
    fenced = False
    for number, line in enumerate(lines, 1):
        if line.lstrip().startswith("```"):
            fenced = not fenced
            continue
        if not fenced:
            yield number, line


def anchors_of(path, cache={}):
    if path not in cache:
        seen, anchors = {}, set()
        with open(path, encoding="utf-8") as handle:
            for _, line in outside_fences(handle.read().split("\n")):
                match = HEADING.match(line)
                if not match:
                    continue
                base = slug(match.group(2))
                count = seen.get(base, 0)
                seen[base] = count + 1
                anchors.add(base if count == 0 else f"{base}-{count}")
        cache[path] = anchors
    return cache[path]


def cells(row):
    """The number of cells of a table row (pipes in code spans or escaped do not count)."""
    row = CODE_SPAN.sub(lambda m: "x" * len(m.group(0)), row.replace("\\|", "xx"))
    row = row.strip()
    if row.startswith("|"):
        row = row[1:]
    if row.endswith("|"):
        row = row[:-1]
    return row.count("|") + 1


def check_tables(page, lines, defects):
    header = None
    for number, line in outside_fences(lines):
        is_row = line.lstrip().startswith("|")
        if is_row and header is None:
            following = lines[number] if number < len(lines) else ""
            if not re.match(r"^\s*\|?\s*:?-{3,}", following):
                defects.append(f"{page}:{number}: a table row without a header and separator row "
                               "(a blank line inside a table?)")
                header = cells(line)
            else:
                header = cells(line)
                if cells(following) != header:
                    defects.append(f"{page}:{number + 1}: separator row has {cells(following)} cells, "
                                   f"the header {header}")
        elif is_row:
            if cells(line) != header:
                defects.append(f"{page}:{number}: {cells(line)} cells in a table of {header}")
        else:
            header = None


def check_page(root, page):
    path = os.path.join(root, page)
    with open(path, encoding="utf-8") as handle:
        lines = handle.read().split("\n")
    defects, notes, links, paths = [], [], 0, 0
    here = os.path.dirname(page)
    for number, line in outside_fences(lines):
        bare = CODE_SPAN.sub("", line)
        for match in LINK.finditer(bare):
            target = match.group(2) or match.group(4)
            if re.match(r"^[a-z]+:", target):
                continue
            links += 1
            file_part, _, anchor = target.partition("#")
            target_page = os.path.normpath(os.path.join(here, file_part)) if file_part else page
            target_path = os.path.join(root, target_page)
            if not os.path.exists(target_path):
                if target_page in PENDING:
                    notes.append(f"NOTE links {page}:{number}: {target} is written on another branch "
                                 "(not in this tree yet)")
                else:
                    defects.append(f"{page}:{number}: link to {target}: no such file")
                continue
            if anchor and target_page.endswith(".md") and anchor not in anchors_of(target_path):
                defects.append(f"{page}:{number}: link to {target}: no heading with anchor #{anchor} "
                               f"in {target_page}")
        for span in CODE_SPAN.finditer(line):
            for quoted in PATH.findall(span.group(2)):
                paths += 1
                if not os.path.exists(os.path.join(root, quoted)):
                    defects.append(f"{page}:{number}: `{quoted}` does not exist")
    check_tables(page, lines, defects)
    return defects, notes, links, paths


def check_code_map(root):
    """Defects of doc/architecture.md's code map: modules missing from it, or named but absent."""
    page = os.path.join(root, "doc", "architecture.md")
    if not os.path.exists(page):
        return ["doc/architecture.md is missing"]
    named = set()
    with open(page, encoding="utf-8") as handle:
        for _, line in outside_fences(handle.read().split("\n")):
            named |= {span.group(2).lower() for span in CODE_SPAN.finditer(line)
                      if re.fullmatch(r"visco2d_\w+", span.group(2))}
    modules = {}
    for path in glob.glob(os.path.join(root, "src", "**", "*.f90"), recursive=True):
        with open(path, encoding="utf-8") as handle:
            for module in MODULE.findall(handle.read()):
                modules[module.lower()] = os.path.relpath(path, root)
    defects = [f"doc/architecture.md: module {name} ({modules[name]}) is not in the code map"
               for name in sorted(set(modules) - named)]
    defects += [f"doc/architecture.md: names module {name}, which no file under src/ defines"
                for name in sorted(named - set(modules))]
    return defects


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    pages = ["README.md"] + sorted(os.path.relpath(p, root) for p in glob.glob(os.path.join(root, "doc", "*.md")))
    if os.path.exists(os.path.join(root, "test", "fuzz", "README.md")):
        pages.append("test/fuzz/README.md")
    failures = 0
    for page in pages:
        defects, notes, links, paths = check_page(root, page)
        for note in notes:
            print(note)
        if defects:
            failures += 1
            print(f"FAIL links {page}: {len(defects)} defect(s)")
            for defect in defects:
                print(f"   {defect}")
        else:
            print(f"PASS links {page}: {links} links, {paths} quoted paths, tables whole")
    defects = check_code_map(root)
    if defects:
        failures += 1
        print(f"FAIL code map doc/architecture.md: {len(defects)} defect(s)")
        for defect in defects:
            print(f"   {defect}")
    else:
        print("PASS code map doc/architecture.md: every module under src/ is named, every named module exists")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
