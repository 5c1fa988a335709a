"""Bless reference outputs: archive a deck's summary.txt and history.csv in reference_outputs/<case>/.

usage: bless.py [--exe EXE] [--inputs DIR] [--references DIR] [--work DIR] [--rtol R] [--force]
                (--all | DECK...)

Runs the decks (EXE -q -o WORK DECK...) and, for each case, rewrites only the
archived files (summary.txt without cpu_s, history.csv) that differ from the
reference beyond the tolerance of python/visco2d/diff.py (its rtol, unit
floors and the case's tolerances.txt): a file within tolerance is left
byte-identical, so blessing one deck or all of them never churns the other
references with round-off. A deck without a reference gets one. For every
rewritten file it prints why: its worst differences. --force rewrites the
given decks' files even within tolerance. --all: every deck of --inputs
(default inputs/), and a note for each reference without a deck.

If any deck fails to run, or misses one of its own EXPECT cards (a summary
key expect_<key>_within_rtol = no; visco2d exits 3), nothing is written and the exit status
is 1; 2 on
usage errors; 0 otherwise. `make bless DECK=inputs/x.inp` and `make bless`
call this script.
"""
import argparse
import glob
import os
import shutil
import sys
import tempfile

from . import diff as compare_outputs
from . import runner
from .case import missed_expectations, read_summary

ARCHIVED = ("summary.txt", "history.csv")
SHOWN = 5
EXPECT_MISSED = 3   # visco2d's exit status: every deck ran, one missed its own EXPECT cards


def archived_text(run_case, name):
    """The text archived for one file of a run's case folder (summary.txt without the machine's keys)."""
    text = compare_outputs.read_text(os.path.join(run_case, name))
    if name == "summary.txt":
        lines = text.splitlines(keepends=True)
        text = "".join(line for line in lines if line.split(" = ", 1)[0].strip() not in compare_outputs.SKIP_KEYS)
    return text


def reasons(reference_path, candidate_path, name, tolerances):
    """The differences beyond tolerance of a candidate file against its reference, worst first."""
    if not os.path.exists(reference_path):
        return ["new reference"]
    comparer = compare_outputs.Comparer(tolerances)
    try:
        compare_outputs.COMPARE[name](reference_path, candidate_path, comparer)
    except compare_outputs.Unusable as error:
        return [f"the reference is unusable: {error}"]
    values, events = compare_outputs.ranked(comparer.differences)
    worst = values + events
    lines = [d.line().strip() for d in worst[:SHOWN]]
    if len(worst) > SHOWN:
        lines.append(f"... and {len(worst) - SHOWN} more")
    return lines


def write(path, text):
    """Write text to path atomically (a temporary file renamed over it)."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    handle, temporary = tempfile.mkstemp(dir=os.path.dirname(path), prefix=".bless-")
    with os.fdopen(handle, "w", newline="") as stream:
        stream.write(text)
    os.chmod(temporary, 0o644)
    os.replace(temporary, path)


def run_decks(exe, decks, work):
    """Run the decks into work/; return the case folders, or None if any deck failed."""
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    result = runner.run(exe, decks, work)
    sys.stdout.write(result.stdout)
    sys.stderr.write(result.stderr)
    folders = {}
    failed = []
    for deck in decks:
        case = os.path.splitext(os.path.basename(deck))[0]
        folder = os.path.join(work, case)
        if case in folders or not os.path.isfile(os.path.join(folder, "summary.txt")):
            failed.append(deck)
        folders[case] = folder
    if result.returncode not in (0, EXPECT_MISSED) or failed:   # a miss (exit 3) is refused below, by name
        names = " ".join(failed) or "one of the decks"
        print(f"bless: refused: {names} failed to run ({exe} exit status {result.returncode});"
              " nothing written", file=sys.stderr)
        return None
    missed = [f"{case} ({', '.join(keys)})" for case, folder in folders.items()
              if (keys := missed_expectations(read_summary(folder)))]
    if missed:
        print(f"bless: refused: an EXPECT card is outside its RTOL in {'; '.join(missed)}:"
              " a reference must meet its deck's own expectations; nothing written", file=sys.stderr)
        return None
    return folders


def plan(folders, references, rtol, force):
    """[(case, name, text, reasons)] of every archived file to write, and the unchanged cases."""
    writes, unchanged = [], []
    for case, folder in folders.items():
        reference = os.path.join(references, case)
        tolerances = compare_outputs.Tolerances(rtol, os.path.join(reference, compare_outputs.TOLERANCE_FILE))
        changed = False
        for name in ARCHIVED:
            if not os.path.exists(os.path.join(folder, name)):
                continue
            text = archived_text(folder, name)
            candidate = os.path.join(folder, name + ".archived")
            write(candidate, text)
            why = reasons(os.path.join(reference, name), candidate, name, tolerances)
            if not why and force:
                why = ["--force (within tolerance)"]
            if why:
                writes.append((case, name, text, why))
                changed = True
        if not changed:
            unchanged.append(case)
    return writes, unchanged


def main(argv):
    parser = argparse.ArgumentParser(prog="python3 -m visco2d.bless", description=__doc__.split("\n")[0])
    parser.add_argument("decks", nargs="*", metavar="DECK")
    parser.add_argument("--all", action="store_true", help="every deck of --inputs")
    parser.add_argument("--exe", default="build/install/bin/visco2d")
    parser.add_argument("--inputs", default="inputs")
    parser.add_argument("--references", default="reference_outputs")
    parser.add_argument("--work", default="build/bless")
    parser.add_argument("--rtol", type=float, default=1e-6)
    parser.add_argument("--force", action="store_true", help="rewrite even within tolerance")
    args = parser.parse_args(argv)
    if args.all == bool(args.decks):
        parser.error("give either --all or the decks to bless")
    decks = sorted(glob.glob(os.path.join(args.inputs, "*.inp"))) if args.all else args.decks
    missing = [deck for deck in decks if not os.path.isfile(deck)]
    if missing or not decks:
        parser.error(f"no such deck: {' '.join(missing)}" if missing else f"no decks in {args.inputs}/")
    inputs = os.path.realpath(args.inputs)
    for deck in decks:
        if os.path.dirname(os.path.realpath(deck)) != inputs:
            print(f"note: {deck} is not in {args.inputs}/: make test checks only the decks there")
    try:
        folders = run_decks(args.exe, decks, args.work)
        if folders is None:
            return 1
        writes, unchanged = plan(folders, args.references, args.rtol, args.force)
    except (OSError, compare_outputs.Unusable) as error:
        print(f"bless: refused: {error}; nothing written", file=sys.stderr)
        return 1
    for case, name, text, why in writes:
        write(os.path.join(args.references, case, name), text)
        print(f"blessed {case}/{name}: {why[0]}")
        for line in why[1:]:
            print(f"   {line}")
    if args.all:
        for folder in sorted(glob.glob(os.path.join(args.references, "*", ""))):
            case = os.path.basename(os.path.dirname(folder))
            if case not in folders:
                print(f"note: {args.references}/{case} has no deck in {args.inputs}/ (git rm it if it is obsolete)")
    cases = sorted({case for case, *_ in writes})
    print(f"bless: {len(writes)} file{'s' * (len(writes) != 1)} of {len(cases)} case{'s' * (len(cases) != 1)}"
          f" rewritten ({' '.join(cases) or 'none'}); {len(unchanged)} case{'s' * (len(unchanged) != 1)}"
          f" unchanged within tolerance"
          + ("; review 'git diff " + args.references + "' and say why in the commit" if writes else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
