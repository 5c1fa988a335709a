#!/usr/bin/env python3
"""visco2d-diff: compare visco2d output folders with a reference, worst differences first.

usage: compare_outputs.py REFERENCE RUN [--rtol R] [--all] [--max N] [--quiet]

REFERENCE and RUN are two case folders (visco2d -o OUT writes OUT/<case>/) or two
folders of case folders (reference_outputs/ and out/, say); a case folder given
against a folder of cases is compared with the case of the same name in it.
Compared, when the reference case has them: summary.txt, history.csv,
pressure.csv and results.h5 (every numeric dataset element-wise, its text
datasets and attributes exactly, /summary included; needs h5py). A file the
reference has and the run lacks, a case on one side only, a key, column,
row or dataset on one side only, or a different shape is a difference; a file
only the run has is not compared (archived references keep summary.txt and
history.csv only).

Tolerance model. Two numbers a (run) and b (reference) agree when
    |a - b| <= allowed = max(rtol * |b|, floor)
with rtol = 1e-6 unless told, and floor = max(1e-9 * S, ROUNDOFF[unit]): S is
the largest magnitude among the reference's values of the same unit in the
same file (HDF5: the same group), the unit is the key or column suffix (_Pa,
_N, _m, _s, _m_s2, _J, ...; HDF5: the dataset's units attribute) and ROUNDOFF
an absolute round-off floor of the unit (1e-6 Pa, 1e-6 N, 1e-15 m, ... far
below anything physical in these models), so a hydrostatic zero of -8.7e-11
Pa against -1.2e-10 Pa never fails while a change of 1 part in 1e6 of any
physical value does. The relative equilibrium and energy-balance errors
(ROUNDOFF_KEYS) agree when both are below 1e-10. Text values must match
exactly. cpu_s and wall_s (the machine, not the model) are skipped.
Per deck, REFERENCE/<case>/tolerances.txt may override this, one line each:
    default = RTOL                    the case's rtol (instead of --rtol)
    NAME = RTOL [ABS]                 for a summary key, a CSV column or an HDF5
                                      dataset (its name or its path): ABS, if
                                      given, replaces the floor
('#' starts a comment). Differences are ranked by how far beyond tolerance
they are, |a - b| / allowed (text, missing and shape differences first).

Output: one line per compared file, `PASS <case>/<file>` or
`FAIL <case>/<file>: N differences beyond tolerance`, the FAIL followed by its
worst differences (the worst 20 unless --max N; all with --all), each with
both values and the relative error; then one line of totals.
Exit status: 0 no difference beyond tolerance, 1 differences, 2 unusable input
(a missing folder, an unreadable or corrupt file or tolerances.txt, bad options).
"""
import csv
import math
import os
import signal
import sys

FILES = ("summary.txt", "history.csv", "pressure.csv", "results.h5")
TOLERANCE_FILE = "tolerances.txt"
SKIP_KEYS = {"cpu_s", "wall_s"}
FLOOR = 1e-9
# Absolute round-off floors per unit (SI and the units the outputs use): a
# difference this small is round-off here, never physics.
ROUNDOFF = {"Pa": 1e-6, "MPa": 1e-12, "J_m3": 1e-6, "N": 1e-6, "m": 1e-15, "mm": 1e-12,
            "s": 1e-15, "ms": 1e-12, "m_s": 1e-15, "s2": 1e-9, "m_s2": 1e-9, "g": 1e-10,
            "J": 1e-15, "kg": 1e-15, "m3": 1e-21, "cm3": 1e-15}
# The units attribute of the HDF5 datasets, as a key suffix.
HDF5_UNITS = {"m/s": "m_s", "m/s^2": "m_s2", "J/m^3": "J_m3", "m^3": "m3", "1": ""}
# Dimensionless round-off diagnostics: equal when both are below 1e-10.
ROUNDOFF_KEYS = {"equilibrium_error_max", "balance_error_max_rel"}
ROUNDOFF_LEVEL = 1e-10
SHOWN = 20


class Unusable(Exception):
    """An input that cannot be compared at all (exit status 2)."""


def unit(name):
    """The unit of a key or column: its suffix after the last underscore (m_s and m_s2 whole)."""
    for compound in ("m_s2", "m_s"):
        if name.endswith("_" + compound):
            return compound
    return name.rsplit("_", 1)[1] if "_" in name else name


def hdf5_unit(dataset, name):
    """The unit of an HDF5 dataset: its units attribute, else its name's suffix."""
    units = dataset.attrs.get("units")
    if units is None:
        return unit(name)
    if isinstance(units, bytes):
        units = units.decode("utf-8", "replace")
    units = str(units).split(" ")[0] if str(units).strip() else ""
    return HDF5_UNITS.get(units, units) or unit(name)


def number(text):
    try:
        value = float(text)
    except ValueError:
        return None
    return value


class Tolerances:
    """rtol and absolute floors: the command line's rtol, overridden by a case's tolerances.txt."""

    def __init__(self, rtol, path=None):
        self.rtol = rtol
        self.names = {}
        if path and os.path.exists(path):
            self.read(path)

    def read(self, path):
        try:
            with open(path) as handle:
                lines = handle.readlines()
        except (OSError, UnicodeDecodeError) as error:
            raise Unusable(f"{path}: cannot read: {error}")
        for number_, line in enumerate(lines, start=1):
            text = line.split("#", 1)[0].strip()
            if not text:
                continue
            name, _, values = text.partition("=")
            name, fields = name.strip(), values.split()
            numbers = [number(field) for field in fields]
            if not name or not _ or not 1 <= len(fields) <= 2 or any(
                    v is None or not math.isfinite(v) or v < 0 for v in numbers):
                raise Unusable(f"{path}:{number_}: expected 'NAME = RTOL [ABS]' or 'default = RTOL'"
                               f" with non-negative numbers, found '{line.strip()}'")
            if name == "default":
                if len(numbers) != 1:
                    raise Unusable(f"{path}:{number_}: 'default' takes one rtol, found '{line.strip()}'")
                self.rtol = numbers[0]
            else:
                self.names[name] = (numbers[0], numbers[1] if len(numbers) == 2 else None)

    def lookup(self, names):
        """(rtol, absolute floor or None) of the first of names with an entry."""
        for name in names:
            if name in self.names:
                return self.names[name]
        return self.rtol, None


class Difference:
    """One difference: where, the run's and the reference's values, and how far beyond tolerance."""

    def __init__(self, where, run, reference, excess=math.inf, note=""):
        self.where, self.run, self.reference, self.excess, self.note = where, run, reference, excess, note

    def line(self):
        if self.note:
            return f"   {self.where}: {self.note}"
        if isinstance(self.run, float) and isinstance(self.reference, float):
            error = abs(self.run - self.reference)
            rel = error / abs(self.reference) if self.reference != 0 else math.inf
            beyond = f"{self.excess:.3g}x the tolerance" if math.isfinite(self.excess) else "tolerance 0"
            return (f"   {self.where}: {self.run!r} vs reference {self.reference!r}"
                    f" (rel {rel:.2e}, {beyond})")
        return f"   {self.where}: '{self.run}' vs reference '{self.reference}'"


class Comparer:
    """Compares numbers under one case's tolerances; collects the differences of one file."""

    def __init__(self, tolerances):
        self.tolerances = tolerances
        self.differences = []
        self.compared = 0

    def numbers(self, where, a, b, names, unit_, scale):
        """Compare a (run) with b (reference) of unit unit_; names: the keys tolerances.txt may use."""
        self.compared += 1
        if not math.isfinite(a):
            self.differences.append(Difference(where, a, b, note=f"{a!r} is not finite (reference {b!r})"))
            return
        if not math.isfinite(b):
            self.differences.append(Difference(where, a, b, note=f"reference {b!r} is not finite (run {a!r})"))
            return
        error = abs(a - b)
        if error == 0:
            return
        if names[-1] in ROUNDOFF_KEYS and abs(a) <= ROUNDOFF_LEVEL and abs(b) <= ROUNDOFF_LEVEL:
            return
        rtol, floor = self.tolerances.lookup(names)
        if floor is None:
            floor = max(FLOOR * scale, ROUNDOFF.get(unit_, 0.0))
        allowed = max(rtol * abs(b), floor)
        if error > allowed:
            excess = error / allowed if allowed > 0 else math.inf
            self.differences.append(Difference(where, a, b, excess))

    def texts(self, where, a, b):
        self.compared += 1
        if a != b:
            self.differences.append(Difference(where, a, b))

    def note(self, where, text):
        self.differences.append(Difference(where, None, None, note=text))


def read_text(path):
    try:
        with open(path, newline="") as handle:
            return handle.read()
    except (OSError, UnicodeDecodeError) as error:
        raise Unusable(f"{path}: cannot read: {error}")


def read_summary(path):
    items = {}
    for number_, line in enumerate(read_text(path).splitlines(), start=1):
        if not line.strip():
            continue
        if " = " not in line:
            raise Unusable(f"{path}:{number_}: expected 'key = value', found '{line[:60]}'")
        key, value = line.split(" = ", 1)
        items[key.strip()] = value.strip()
    if not items:
        raise Unusable(f"{path}: empty")
    return items


def compare_summary(reference, run, comparer):
    ref, new = read_summary(reference), read_summary(run)
    scales = {}
    for key, value in ref.items():
        v = number(value)
        if v is not None and math.isfinite(v):
            scales[unit(key)] = max(scales.get(unit(key), 0.0), abs(v))
    for key, value in ref.items():
        if key in SKIP_KEYS:
            continue
        if key not in new:
            comparer.note(key, "missing from the run")
            continue
        a, b = number(new[key]), number(value)
        if a is None or b is None:
            comparer.texts(key, new[key], value)
        else:
            comparer.numbers(key, a, b, [key], unit(key), scales.get(unit(key), 0.0))
    for key in new:
        if key not in ref and key not in SKIP_KEYS:
            comparer.note(key, f"new key (= {new[key]}) not in the reference")


def read_table(path):
    rows = list(csv.reader(read_text(path).splitlines()))
    if not rows or not rows[0]:
        raise Unusable(f"{path}: empty")
    header, table = rows[0], []
    for line, row in enumerate(rows[1:], start=2):
        values = [number(field) for field in row]
        if len(row) != len(header) or any(v is None for v in values):
            raise Unusable(f"{path}:{line}: expected {len(header)} numbers, found '{','.join(row)[:80]}'")
        table.append(values)
    return header, table


def row_label(header, row, index):
    """How a CSV row is named: its line, and its step and time (history) or node (pressure)."""
    parts = [f"line {index + 2}"]
    for name in ("step", "t_s", "node"):
        if name in header:
            value = row[header.index(name)]
            parts.append(f"{name} {value:g}" if name != "t_s" else f"t {value:.6g} s")
    return " ".join(parts)


def compare_table(reference, run, comparer):
    ref_header, ref = read_table(reference)
    new_header, new = read_table(run)
    columns = [name for name in ref_header if name in new_header]
    for name in ref_header:
        if name not in new_header:
            comparer.note(name, "column missing from the run")
    for name in new_header:
        if name not in ref_header:
            comparer.note(name, "new column not in the reference")
    if len(ref) != len(new):
        comparer.note("rows", f"{len(new)} rows vs {len(ref)} in the reference (the common ones compared)")
    scales = {}
    for name in columns:
        j = ref_header.index(name)
        largest = max((abs(row[j]) for row in ref if math.isfinite(row[j])), default=0.0)
        scales[unit(name)] = max(scales.get(unit(name), 0.0), largest)
    pairs = [(ref_header.index(name), new_header.index(name), name) for name in columns]
    for i, (row_ref, row_new) in enumerate(zip(ref, new)):
        for j_ref, j_new, name in pairs:
            a, b = row_new[j_new], row_ref[j_ref]
            if a != b or not math.isfinite(a):
                comparer.numbers(f"{row_label(ref_header, row_ref, i)} {name}", a, b, [name],
                                 unit(name), scales[unit(name)])
            else:
                comparer.compared += 1


def hdf5_items(path):
    """{path: object} of every group and dataset of an HDF5 file, and the file (open)."""
    try:
        import h5py
    except ImportError:
        raise Unusable(f"{path}: comparing results.h5 needs h5py (pip install h5py)")
    try:
        handle = h5py.File(path, "r")
        items = {"/": handle}
        handle.visititems(lambda name, item: items.__setitem__("/" + name, item))
    except (OSError, RuntimeError, KeyError, ValueError) as error:
        raise Unusable(f"{path}: not a readable HDF5 file: {error}")
    return handle, items


def decoded(value):
    if isinstance(value, bytes):
        return value.decode("utf-8", "replace")
    if hasattr(value, "tolist"):
        value = value.tolist()
    return value


def compare_attributes(where, ref_item, new_item, comparer):
    for name in sorted(set(ref_item.attrs) | set(new_item.attrs)):
        label = f"{where} @{name}"
        if name not in new_item.attrs or name not in ref_item.attrs:
            comparer.note(label, "attribute on one side only")
            continue
        a, b = decoded(new_item.attrs[name]), decoded(ref_item.attrs[name])
        if isinstance(a, (int, float)) and isinstance(b, (int, float)) and not isinstance(a, bool):
            comparer.numbers(label, float(a), float(b), [name], unit(name), abs(float(b)))
        else:
            comparer.texts(label, a, b)


def compare_hdf5(reference, run, comparer):
    import numpy
    ref_file, ref = hdf5_items(reference)
    new_file, new = hdf5_items(run)
    try:
        for where in sorted(set(ref) - set(new)):
            comparer.note(where, "missing from the run")
        for where in sorted(set(new) - set(ref)):
            comparer.note(where, "not in the reference")
        common = [where for where in ref if where in new]
        datasets = {}
        for where in common:
            compare_attributes(where, ref[where], new[where], comparer)
            if hasattr(ref[where], "shape") != hasattr(new[where], "shape"):
                comparer.note(where, "a group on one side, a dataset on the other")
            elif hasattr(ref[where], "shape"):
                try:
                    datasets[where] = (ref[where][()], new[where][()])
                except (OSError, RuntimeError, ValueError) as error:
                    raise Unusable(f"{reference} or {run}: cannot read {where}: {error}")
        scales = {}
        for where, (b, _) in datasets.items():
            if numpy.asarray(b).dtype.kind in "iuf":
                key = (where.rsplit("/", 1)[0], hdf5_unit(ref[where], where.rsplit("/", 1)[1]))
                finite = numpy.abs(numpy.asarray(b, dtype=float))
                finite = finite[numpy.isfinite(finite)]
                scales[key] = max(scales.get(key, 0.0), float(finite.max()) if finite.size else 0.0)
        for where, (b, a) in datasets.items():
            if where.startswith("/summary/") and where.rsplit("/", 1)[1] in SKIP_KEYS:
                continue
            compare_dataset(where, a, b, ref[where], comparer, scales)
    finally:
        ref_file.close()
        new_file.close()


def compare_dataset(where, a, b, ref_item, comparer, scales):
    import numpy
    a, b = numpy.asarray(a), numpy.asarray(b)
    name = where.rsplit("/", 1)[1]
    if a.dtype.kind not in "iuf" or b.dtype.kind not in "iuf":
        comparer.texts(where, decoded(a[()] if a.ndim == 0 else a.tolist()),
                       decoded(b[()] if b.ndim == 0 else b.tolist()))
        return
    if a.shape != b.shape:
        comparer.note(where, f"shape {a.shape} vs {b.shape} in the reference")
        return
    group_unit = (where.rsplit("/", 1)[0], hdf5_unit(ref_item, name))
    names = [where, where.lstrip("/"), name]
    a, b = a.astype(float), b.astype(float)
    differ = numpy.flatnonzero((a != b).ravel() | ~numpy.isfinite(a).ravel())
    comparer.compared += a.size - differ.size
    for flat in differ:
        index = numpy.unravel_index(flat, a.shape) if a.ndim else ()
        label = f"{where}[{','.join(str(int(i)) for i in index)}]" if a.ndim else where
        comparer.numbers(label, float(a.ravel()[flat]), float(b.ravel()[flat]), names,
                         group_unit[1], scales.get(group_unit, 0.0))


COMPARE = {"summary.txt": compare_summary, "history.csv": compare_table,
           "pressure.csv": compare_table, "results.h5": compare_hdf5}


def is_case(folder):
    return any(os.path.isfile(os.path.join(folder, name)) for name in FILES)


def compare_case(reference, run, case, rtol, shown, out):
    """Compare one case folder; print its lines; return (files compared, files differing)."""
    tolerances = Tolerances(rtol, os.path.join(reference, TOLERANCE_FILE))
    compared = failed = 0
    for name in FILES:
        ref_path, run_path = os.path.join(reference, name), os.path.join(run, name)
        if not os.path.exists(ref_path):
            continue
        compared += 1
        comparer = Comparer(tolerances)
        if not os.path.exists(run_path):
            comparer.note(name, "not produced by the run")
        else:
            COMPARE[name](ref_path, run_path, comparer)
        if not comparer.differences:
            print(f"PASS {case}/{name}", file=out)
            continue
        failed += 1
        worst = sorted(comparer.differences, key=lambda d: -d.excess)  # stable: file order on ties
        print(f"FAIL {case}/{name}: {len(worst)} difference{'s' * (len(worst) != 1)} beyond tolerance"
              f" ({comparer.compared} values compared; worst first)", file=out)
        for difference in worst[:shown]:
            print(difference.line(), file=out)
        if len(worst) > shown:
            print(f"   ... and {len(worst) - shown} more (--all to list them)", file=out)
    if not os.path.exists(os.path.join(reference, "summary.txt")) and not compared:
        raise Unusable(f"{reference}: no {', '.join(FILES)}: not a case folder")
    return compared, failed


def cases(folder):
    return sorted(name for name in os.listdir(folder)
                  if os.path.isdir(os.path.join(folder, name)) and is_case(os.path.join(folder, name)))


def pairs(reference, run):
    """[(case, reference case folder or None, run case folder or None)] of the two arguments."""
    for folder in (reference, run):
        if not os.path.isdir(folder):
            raise Unusable(f"{folder}: no such folder")
    if is_case(reference):
        case = os.path.basename(os.path.normpath(reference))
        if not is_case(run) and os.path.isdir(os.path.join(run, case)):
            run = os.path.join(run, case)
        if not is_case(run):
            raise Unusable(f"{run}: not a case folder (no {', '.join(FILES)}) and no {case}/ in it")
        return [(case, reference, run)]
    if is_case(run):
        raise Unusable(f"{reference} is a folder of cases but {run} is a case folder")
    ref_cases, run_cases = cases(reference), cases(run)
    if not ref_cases and not run_cases:
        raise Unusable(f"{reference} and {run}: no case folders in either")
    return [(case, os.path.join(reference, case) if case in ref_cases else None,
             os.path.join(run, case) if case in run_cases else None)
            for case in sorted(set(ref_cases) | set(run_cases))]


def compare(reference, run, rtol=1e-6, shown=SHOWN, out=sys.stdout):
    """Compare two case folders or folders of cases; print; return 0 (same) or 1 (different)."""
    differing = files = 0
    work = pairs(reference, run)
    for case, ref_case, run_case in work:
        if ref_case is None:
            print(f"FAIL {case}: in the run, not in the reference", file=out)
            differing += 1
        elif run_case is None:
            print(f"FAIL {case}: in the reference, not in the run", file=out)
            differing += 1
        else:
            compared, failed = compare_case(ref_case, run_case, case, rtol, shown, out)
            files += compared
            differing += failed > 0
    print(f"# {len(work) - differing} of {len(work)} case{'s' * (len(work) != 1)} match"
          f" ({files} files compared, --rtol {rtol:g})"
          + (f"; {differing} differ" if differing else ""), file=out)
    return 1 if differing else 0


def main(argv):
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # quiet when piped into head
    args = list(argv)
    rtol, shown, quiet = 1e-6, SHOWN, False
    try:
        if "-h" in args or "--help" in args:
            print(__doc__)
            return 0
        if "--all" in args:
            args.remove("--all")
            shown = sys.maxsize
        if "--quiet" in args:
            args.remove("--quiet")
            quiet = True
        for option in ("--rtol", "--max"):
            if option in args:
                k = args.index(option)
                value = float(args[k + 1])
                if not math.isfinite(value) or value < 0:
                    raise ValueError(value)
                del args[k:k + 2]
                if option == "--rtol":
                    rtol = value
                else:
                    shown = int(value)
        if len(args) != 2 or any(arg.startswith("-") for arg in args):
            raise ValueError(args)
    except (ValueError, IndexError):
        print("usage: compare_outputs.py REFERENCE RUN [--rtol R] [--all] [--max N] [--quiet]"
              " (--help for more)", file=sys.stderr)
        return 2
    out = open(os.devnull, "w") if quiet else sys.stdout
    try:
        return compare(args[0], args[1], rtol, shown, out)
    except Unusable as error:
        print(f"compare_outputs.py: unusable input: {error}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
