#!/usr/bin/env python3
"""Compare a run's summary.txt / history.csv with the archived reference.

Numbers agree when |a - b| <= rtol * |b| (rtol = 1e-6 by default) or when
|a - b| <= max(1e-9 * S, F), where S is the largest magnitude among the
reference's values in the same unit (the unit is the key or column suffix:
_m, _Pa, _J, ...) and F an absolute round-off floor of the unit (ROUNDOFF:
1e-6 Pa, 1e-6 N, ... -- far below anything physical in these models). The
floors keep pure round-off values (a shear stress of 1e-8 Pa in a
hydrostatic state, the reaction sum of a self-equilibrated body) from
failing the comparison, also when the BLAS differs from the one that
blessed the references, while a real change of 1 part in 1e6 of any
physical quantity still fails. The round-off diagnostics (ROUNDOFF_KEYS:
relative equilibrium and energy-balance errors) agree when both are at
round-off level (below 1e-10). Text values must match exactly. Keys that
measure the machine, not the model (cpu_s), are skipped.

usage: compare_outputs.py REFERENCE_DIR RUN_DIR [--rtol 1e-6]
prints one line per file: PASS <case>/<file> or FAIL <case>/<file>: details
"""
import csv
import math
import os
import sys

SKIP_KEYS = {"cpu_s", "wall_s"}
FLOOR = 1e-9
# Absolute round-off floors per unit (SI): a value this small is zero here.
ROUNDOFF = {"Pa": 1e-6, "N": 1e-6, "m": 1e-15, "s": 1e-15, "s2": 1e-9, "J": 1e-15, "MPa": 1e-12}
# Dimensionless round-off diagnostics: equal when both are below 1e-10.
ROUNDOFF_KEYS = {"equilibrium_error_max", "balance_error_max_rel"}
ROUNDOFF_LEVEL = 1e-10


def unit(name):
    return name.rsplit("_", 1)[1] if "_" in name else ""


def number(text):
    try:
        value = float(text)
    except ValueError:
        return None
    return value if math.isfinite(value) else None


def close(a, b, rtol, scale, name=""):
    if name in ROUNDOFF_KEYS and abs(a) <= ROUNDOFF_LEVEL and abs(b) <= ROUNDOFF_LEVEL:
        return True
    floor = max(FLOOR * scale, ROUNDOFF.get(unit(name), 0.0))
    return abs(a - b) <= rtol * abs(b) or abs(a - b) <= floor


def read_summary(path):
    items = {}
    with open(path) as handle:
        for line in handle:
            if " = " in line:
                key, value = line.rstrip("\n").split(" = ", 1)
                items[key.strip()] = value.strip()
    return items


def compare_summary(reference, run, rtol):
    ref, new = read_summary(reference), read_summary(run)
    problems = []
    scales = {}
    for key, value in ref.items():
        v = number(value)
        if v is not None:
            scales[unit(key)] = max(scales.get(unit(key), 0.0), abs(v))
    for key, value in ref.items():
        if key in SKIP_KEYS:
            continue
        if key not in new:
            problems.append(f"{key} missing")
            continue
        a, b = number(new[key]), number(value)
        if a is None or b is None:
            if new[key] != value:
                problems.append(f"{key}: '{new[key]}' != '{value}'")
        elif not close(a, b, rtol, scales[unit(key)], key):
            problems.append(f"{key}: {a!r} vs reference {b!r} (rel {abs(a-b)/max(abs(b),1e-300):.2e})")
    for key in new:
        if key not in ref and key not in SKIP_KEYS:
            problems.append(f"{key}: new key not in the reference (bless on purpose)")
    return problems


def compare_history(reference, run, rtol):
    with open(reference) as handle:
        ref = list(csv.reader(handle))
    with open(run) as handle:
        new = list(csv.reader(handle))
    if not ref or not new:
        return ["empty file"]
    if ref[0] != new[0]:
        return [f"header differs: {new[0]} vs {ref[0]}"]
    if len(ref) != len(new):
        return [f"{len(new) - 1} rows vs {len(ref) - 1} in the reference"]
    columns = ref[0]
    column_scales = [max((abs(float(row[j])) for row in ref[1:]), default=0.0) for j in range(len(columns))]
    unit_scales = {}
    for name, scale in zip(columns, column_scales):
        unit_scales[unit(name)] = max(unit_scales.get(unit(name), 0.0), scale)
    scales = [unit_scales[unit(name)] for name in columns]
    problems = []
    for i, (row_ref, row_new) in enumerate(zip(ref[1:], new[1:]), start=2):
        for j, name in enumerate(columns):
            a, b = float(row_new[j]), float(row_ref[j])
            if not math.isfinite(a) or not close(a, b, rtol, scales[j], name):
                problems.append(f"line {i} {name}: {a!r} vs reference {b!r}")
                if len(problems) >= 5:
                    return problems
    return problems


def main():
    args = sys.argv[1:]
    rtol = 1e-6
    if "--rtol" in args:
        k = args.index("--rtol")
        rtol = float(args[k + 1])
        del args[k:k + 2]
    if len(args) != 2:
        print(__doc__)
        return 2
    reference_dir, run_dir = args
    case = os.path.basename(os.path.normpath(reference_dir))
    failed = 0
    for name, compare in (("summary.txt", compare_summary), ("history.csv", compare_history)):
        reference = os.path.join(reference_dir, name)
        run = os.path.join(run_dir, name)
        if not os.path.exists(reference):
            continue
        if not os.path.exists(run):
            problems = ["not produced by the run"]
        else:
            problems = compare(reference, run, rtol)
        if problems:
            failed += 1
            print(f"FAIL {case}/{name}: " + "; ".join(problems[:5]))
        else:
            print(f"PASS {case}/{name}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
