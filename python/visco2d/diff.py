"""visco2d-diff: compare visco2d output folders with a reference, worst differences first.

usage: visco2d-diff REFERENCE RUN [--rtol R] [--all] [--max N] [--quiet]

REFERENCE and RUN are two case folders (visco2d -o OUT writes OUT/<case>/) or two
folders of case folders (reference_outputs/ and out/, say); a case folder given
against a folder of cases is compared with the case of the same name in it.
Compared, when the reference case has them: summary.txt, history.csv,
pressure.csv and results.h5 (every numeric dataset element-wise, its text
datasets and attributes exactly, /summary included; needs h5py). A file the
reference has and the run lacks, a case only the reference has, a key, column,
row or dataset on one side only, or a different shape is a difference; a file
only the run has is not compared (archived references keep summary.txt and
history.csv only). A case folder only the run has is listed as
`EXTRA <case>: in the run, not in the reference (not compared)`, and is no
difference.

A damaged reference is unusable input: a reference case folder without
summary.txt or history.csv (every visco2d case folder has both), a reference
file that cannot be parsed, is truncated (its last line has no end of line)
or holds a number that is not finite (NaN, Inf) names the file (and line and
key or column) and exits 2. A non-finite number in the run is a difference.

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
exactly, but for the folder of a `FILE:LINE:` location they quote: visco2d's
warnings start with the deck's path as given, under the output root in a
sweep (OUT/decks/<case>.inp), so `out/decks/x.inp:64:` and
`/scratch/run/decks/x.inp:64:` are the same (the file name and line still
count). cpu_s and wall_s (the machine, not the model) are skipped.
Per deck, REFERENCE/<case>/tolerances.txt may override this, one line each:
    default = RTOL                    the case's rtol (instead of --rtol)
    NAME = RTOL [ABS]                 for a summary key, a CSV column or an HDF5
                                      dataset (its name or its path): ABS, if
                                      given, replaces the floor
('#' starts a comment). Differences are ranked by how far beyond the
quantity's tolerance they are at its largest value, |a - b| / max(rtol * L,
floor), L = max(|b|, the largest magnitude of the quantity in the reference:
its CSV column or HDF5 dataset; for a summary key the history column of the
same quantity, vz_cm_m_s or probe_centre_vz_m_s -> centre_vz_m_s), so a
change at a zero crossing (a velocity at maximum deformation) ranks by its
size against the quantity, not against the crossing, and is shown with
`Nx at the quantity's largest, L` (text, missing and shape differences
first; which differences fail is unchanged).
Time-of-event keys (summary keys in s or ms but dt_s: t_force_max_ms,
time_first_contact_s, envelope_*_time_s, contact_duration_ms, ...) move in
whole time steps, so a peak that moves to the next step is at their
resolution, not 13 % beyond any rtol: they are listed apart, after the
values, each as a move in steps of the summary's DT (dt_s of a one-stage run;
in seconds otherwise), `t_force_max_ms: 1.44 vs reference 1.43 ms: one step
later`, the largest move first. They still count as differences.

Output: one line per compared file, `PASS <case>/<file>` or
`FAIL <case>/<file>: N differences beyond tolerance`, the FAIL followed by its
worst differences (the worst 20 unless --max N; all with --all), each with
both values and the relative error, then its time-of-event keys; then one line
of totals (the matching cases of the reference, and the extra cases).
Exit status: 0 no difference beyond tolerance (extra cases in the run
allowed), 1 differences, 2 unusable input (a missing folder, a damaged
reference, an unreadable or corrupt file or tolerances.txt, bad options).
"""
import argparse
import csv
import math
import os
import re
import signal
import sys

FILES = ("summary.txt", "history.csv", "pressure.csv", "results.h5")
# Every visco2d case folder has these (bless.py archives them): a reference case without one is damaged.
REQUIRED = ("summary.txt", "history.csv")
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
# The location of a message, `FILE:LINE:` (visco2d's warnings start with the deck's path as given on
# the command line, under the run's output root in a sweep): its folder is not part of the result.
LOCATION = re.compile(r"(?<![^\s('\"])(?:[^\s:'\"()]*/)?([^\s:/'\"()]+:[0-9]+:)")
LOCATION_FOLDER = "<dir>/"
# Summary keys in these units are times of an event (t_force_max_ms, time_first_contact_s, ...) or
# durations between events (contact_duration_ms): they move in whole time steps; dt_s is the step.
TIME_UNITS = {"s": 1.0, "ms": 1e-3}
NOT_EVENT_TIMES = {"dt_s"}


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


def is_event_time(key):
    """A summary key that is the time of an event or a duration between events (seconds or ms)."""
    return unit(key) in TIME_UNITS and key not in NOT_EVENT_TIMES and key not in SKIP_KEYS


def without_folders(value):
    """A text with the folder of every `FILE:LINE:` location replaced by <dir>/ (lists: each element)."""
    if isinstance(value, str):
        return LOCATION.sub(lambda m: LOCATION_FOLDER + m.group(1), value)
    if isinstance(value, list):
        return [without_folders(item) for item in value]
    return value


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

    def __init__(self, where, run, reference, excess=math.inf, note="", shift=None, significance=None,
                 largest=None):
        self.where, self.run, self.reference, self.excess, self.note = where, run, reference, excess, note
        self.shift = shift  # an event time's move: (seconds, time steps or None), else None
        # the rank: how far beyond the quantity's tolerance at its largest value (largest: that value)
        self.significance = excess if significance is None else significance
        self.largest = largest

    def line(self):
        if self.note:
            return f"   {self.where}: {self.note}"
        if self.shift is not None:
            key = self.where.rsplit("/", 1)[-1]
            return (f"   {self.where}: {self.run!r} vs reference {self.reference!r} {unit(key)}:"
                    f" {shift_text(*self.shift)}")
        if isinstance(self.run, float) and isinstance(self.reference, float):
            error = abs(self.run - self.reference)
            rel = error / abs(self.reference) if self.reference != 0 else math.inf
            beyond = f"{self.excess:.3g}x the tolerance" if math.isfinite(self.excess) else "tolerance 0"
            if self.largest is not None:
                beyond += f"; {self.significance:.3g}x at the quantity's largest, {self.largest:.4g}"
            return (f"   {self.where}: {self.run!r} vs reference {self.reference!r}"
                    f" (rel {rel:.2e}, {beyond})")
        return f"   {self.where}: '{self.run}' vs reference '{self.reference}'"


def shift_text(seconds, steps):
    """How far an event time moved: in time steps when the summary gives one DT, else in seconds."""
    direction = "later" if seconds > 0 else "earlier"
    if steps is None:
        return f"{abs(seconds):.3g} s {direction}"
    whole = round(steps)
    if abs(steps - whole) <= 1e-6 * max(1.0, abs(steps)):
        return f"one step {direction}" if abs(whole) == 1 else f"{abs(whole)} steps {direction}"
    return f"{abs(steps):.3g} steps {direction}"


def time_step(items):
    """DT in seconds of a case from its summary's {key: text}: dt_s of a one-stage run, else None."""
    dt = number(str(items.get("dt_s", "")))
    stages = number(str(items.get("time_stages", "1")))
    if dt is None or not math.isfinite(dt) or dt <= 0 or stages != 1:
        return None
    return dt


def ranked(differences):
    """(values, event times) of a file's differences, each worst first: values by how far beyond
    tolerance (text and missing first), event times by how many time steps they moved."""
    values = [d for d in differences if d.shift is None]
    events = [d for d in differences if d.shift is not None]
    return sorted(values, key=lambda d: -d.significance), sorted(events, key=lambda d: -d.excess)


class Comparer:
    """Compares numbers under one case's tolerances; collects the differences of one file."""

    def __init__(self, tolerances):
        self.tolerances = tolerances
        self.differences = []
        self.compared = 0
        self.dt = None  # the case's time step (s), for the event times of a summary

    def numbers(self, where, a, b, names, unit_, scale, event=False, largest=None):
        """Compare a (run) with b (reference) of unit unit_; names: the keys tolerances.txt may use;
        event: a is the time of an event (unit s or ms), reported as a move in time steps;
        largest: the largest magnitude of the quantity in the reference (its column, its dataset),
        which ranks the difference (not whether it is one)."""
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
            if event:
                seconds = (a - b) * TIME_UNITS[unit_]
                steps = seconds / self.dt if self.dt else None
                self.differences.append(Difference(where, a, b, abs(steps if steps is not None else seconds),
                                                   shift=(seconds, steps)))
            elif largest is not None and largest > abs(b):
                # the same tolerance at the quantity's largest value: a change at a zero crossing of a
                # history column ranks by its size against the column, not against the crossing
                at_largest = max(rtol * largest, floor)
                self.differences.append(Difference(where, a, b, excess, significance=error / at_largest,
                                                   largest=largest))
            else:
                self.differences.append(Difference(where, a, b, excess))

    def texts(self, where, a, b):
        """Texts must be equal, but for the folders of the FILE:LINE: locations they quote."""
        self.compared += 1
        if without_folders(a) != without_folders(b):
            self.differences.append(Difference(where, a, b))

    def note(self, where, text):
        self.differences.append(Difference(where, None, None, note=text))


def read_text(path):
    try:
        with open(path, newline="") as handle:
            return handle.read()
    except (OSError, UnicodeDecodeError) as error:
        raise Unusable(f"{path}: cannot read: {error}")


def read_lines(path):
    """The lines of a text output: visco2d ends every line, so a last line without its end is truncated."""
    text = read_text(path)
    if text and not text.endswith("\n"):
        last = text.rsplit("\n", 1)[-1]
        raise Unusable(f"{path}: truncated: its last line has no end of line ('{last[-60:]}')")
    return text.splitlines()


def not_finite(path, line, name, text):
    return Unusable(f"{path}:{line}: {name} = {text} is not a finite number (a damaged reference)")


def read_summary(path, reference=False):
    """{key: text} of a summary.txt; a reference's numbers must be finite."""
    items = {}
    for number_, line in enumerate(read_lines(path), start=1):
        if not line.strip():
            continue
        if " = " not in line:
            raise Unusable(f"{path}:{number_}: expected 'key = value', found '{line[:60]}'")
        key, value = line.split(" = ", 1)
        key, value = key.strip(), value.strip()
        v = number(value)
        if reference and v is not None and not math.isfinite(v):
            raise not_finite(path, number_, key, value)
        items[key] = value
    if not items:
        raise Unusable(f"{path}: empty")
    return items


def history_column(key):
    """The history column a summary key takes a value of: the same name (vz_cm_m_s, kinetic_J), or a
    probe's without `probe_` (probe_centre_vz_m_s: centre_vz_m_s)."""
    return [key, key[len("probe_"):]] if key.startswith("probe_") else [key]


def column_largest(path):
    """{column: largest finite magnitude} of a history.csv; {} when it cannot be read (its own
    comparison says why)."""
    try:
        header, table = read_table(path)
    except Unusable:
        return {}
    return {name: max((abs(row[j]) for row in table if math.isfinite(row[j])), default=0.0)
            for j, name in enumerate(header)}


def compare_summary(reference, run, comparer):
    ref, new = read_summary(reference, reference=True), read_summary(run)
    comparer.dt = time_step(ref)
    history = column_largest(os.path.join(os.path.dirname(reference), "history.csv"))
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
            largest = next((history[name] for name in history_column(key) if name in history), None)
            comparer.numbers(key, a, b, [key], unit(key), scales.get(unit(key), 0.0), is_event_time(key),
                             largest)
    for key in new:
        if key not in ref and key not in SKIP_KEYS:
            comparer.note(key, f"new key (= {new[key]}) not in the reference")


def read_table(path, reference=False):
    """(header, rows of numbers) of a CSV output; a reference's numbers must be finite."""
    rows = list(csv.reader(read_lines(path)))
    if not rows or not rows[0]:
        raise Unusable(f"{path}: empty")
    header, table = rows[0], []
    for line, row in enumerate(rows[1:], start=2):
        values = [number(field) for field in row]
        if len(row) != len(header) or any(v is None for v in values):
            raise Unusable(f"{path}:{line}: expected {len(header)} numbers, found '{','.join(row)[:80]}'")
        if reference:
            for name, field, value in zip(header, row, values):
                if not math.isfinite(value):
                    raise not_finite(path, line, name, field)
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
    ref_header, ref = read_table(reference, reference=True)
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
    scales, largest = {}, {}
    for name in columns:
        j = ref_header.index(name)
        largest[name] = max((abs(row[j]) for row in ref if math.isfinite(row[j])), default=0.0)
        scales[unit(name)] = max(scales.get(unit(name), 0.0), largest[name])
    pairs = [(ref_header.index(name), new_header.index(name), name) for name in columns]
    for i, (row_ref, row_new) in enumerate(zip(ref, new)):
        for j_ref, j_new, name in pairs:
            a, b = row_new[j_new], row_ref[j_ref]
            if a != b or not math.isfinite(a):
                comparer.numbers(f"{row_label(ref_header, row_ref, i)} {name}", a, b, [name],
                                 unit(name), scales[unit(name)], largest=largest[name])
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
        scales, largest = {}, {}
        for where, (b, _) in datasets.items():
            if numpy.asarray(b).dtype.kind in "iuf":
                key = (where.rsplit("/", 1)[0], hdf5_unit(ref[where], where.rsplit("/", 1)[1]))
                magnitude = numpy.abs(numpy.asarray(b, dtype=float))
                if not numpy.isfinite(magnitude).all():
                    raise Unusable(f"{reference}: {where} holds a value that is not a finite number"
                                   " (a damaged reference)")
                largest[where] = float(magnitude.max()) if magnitude.size else 0.0
                scales[key] = max(scales.get(key, 0.0), largest[where])
        steps = {}  # the reference's dt_s and time_stages, for its /summary event times
        for name in ("dt_s", "time_stages"):
            values = datasets.get(f"/summary/{name}", (None,))[0]
            if values is not None and numpy.ndim(values) == 0:
                steps[name] = decoded(values[()])
        comparer.dt = time_step(steps)
        for where, (b, a) in datasets.items():
            if where.startswith("/summary/") and where.rsplit("/", 1)[1] in SKIP_KEYS:
                continue
            name = where.rsplit("/", 1)[1]
            if where.startswith("/summary/"):  # a summary value ranks against its history column
                quantity = next((largest[f"/history/{column}"] for column in history_column(name)
                                 if f"/history/{column}" in largest), None)
            else:
                quantity = largest.get(where)
            compare_dataset(where, a, b, ref[where], comparer, scales, quantity)
    finally:
        ref_file.close()
        new_file.close()


def compare_dataset(where, a, b, ref_item, comparer, scales, largest=None):
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
    event = where.startswith("/summary/") and a.ndim == 0 and is_event_time(name)
    a, b = a.astype(float), b.astype(float)
    differ = numpy.flatnonzero((a != b).ravel() | ~numpy.isfinite(a).ravel())
    comparer.compared += a.size - differ.size
    for flat in differ:
        index = numpy.unravel_index(flat, a.shape) if a.ndim else ()
        label = f"{where}[{','.join(str(int(i)) for i in index)}]" if a.ndim else where
        comparer.numbers(label, float(a.ravel()[flat]), float(b.ravel()[flat]), names,
                         group_unit[1], scales.get(group_unit, 0.0), event and group_unit[1] in TIME_UNITS,
                         largest)


COMPARE = {"summary.txt": compare_summary, "history.csv": compare_table,
           "pressure.csv": compare_table, "results.h5": compare_hdf5}


def is_case(folder):
    return any(os.path.isfile(os.path.join(folder, name)) for name in FILES)


def compare_case(reference, run, case, rtol, shown, out):
    """Compare one case folder; print its lines; return (files compared, files differing)."""
    for name in REQUIRED:
        if not os.path.isfile(os.path.join(reference, name)):
            raise Unusable(f"{os.path.join(reference, name)}: missing from the reference (every visco2d"
                           f" case folder has {' and '.join(REQUIRED)})")
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
        values, events = ranked(comparer.differences)  # stable: file order on ties
        total = len(values) + len(events)
        print(f"FAIL {case}/{name}: {total} difference{'s' * (total != 1)} beyond tolerance"
              f" ({comparer.compared} values compared; worst first)", file=out)
        for difference in values[:shown]:
            print(difference.line(), file=out)
        if len(values) > shown:
            print(f"   ... and {len(values) - shown} more (--all to list them)", file=out)
        if events:
            step = f"in steps of DT = {comparer.dt:g} s" if comparer.dt else "in seconds: no single DT"
            print(f"   time-of-event keys ({step}): {len(events)} differ", file=out)
            for difference in events[:shown]:
                print(difference.line(), file=out)
            if len(events) > shown:
                print(f"   ... and {len(events) - shown} more (--all to list them)", file=out)
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
    # a reference folder named as a run's case but holding no case files has lost them
    # (compare_case says which): it is a damaged reference, not an extra case of the run
    ref_cases += [name for name in run_cases
                  if name not in ref_cases and os.path.isdir(os.path.join(reference, name))]
    if not ref_cases:
        raise Unusable(f"{reference}: no case folders in the reference")
    return [(case, os.path.join(reference, case) if case in ref_cases else None,
             os.path.join(run, case) if case in run_cases else None)
            for case in sorted(set(ref_cases) | set(run_cases))]


def compare(reference, run, rtol=1e-6, shown=SHOWN, out=sys.stdout):
    """Compare two case folders or folders of cases; print; return 0 (same) or 1 (different).
    A case only the run has is listed as extra, not compared and not a difference."""
    differing = files = 0
    work = pairs(reference, run)
    extras = [case for case, ref_case, _ in work if ref_case is None]
    for case in extras:
        print(f"EXTRA {case}: in the run, not in the reference (not compared)", file=out)
    work = [item for item in work if item[1] is not None]
    for case, ref_case, run_case in work:
        if run_case is None:
            print(f"FAIL {case}: in the reference, not in the run", file=out)
            differing += 1
        else:
            compared, failed = compare_case(ref_case, run_case, case, rtol, shown, out)
            files += compared
            differing += failed > 0
    print(f"# {len(work) - differing} of {len(work)} case{'s' * (len(work) != 1)} match"
          f" ({files} files compared, --rtol {rtol:g})"
          + (f"; {differing} differ" if differing else "")
          + (f"; {len(extras)} extra case{'s' * (len(extras) != 1)} in the run, not compared" if extras else ""),
          file=out)
    return 1 if differing else 0


def non_negative(kind):
    """An argparse type: a finite number >= 0 of the given kind (float or int)."""
    def parse(text):
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"not a number: '{text}'")
        if not math.isfinite(value) or value < 0 or (kind is int and value != int(value)):
            raise argparse.ArgumentTypeError(f"expected a finite {'whole ' * (kind is int)}number >= 0,"
                                             f" found '{text}'")
        return kind(value)
    return parse


def parser():
    result = argparse.ArgumentParser(
        prog="visco2d-diff",
        description=__doc__.split("\n\n", 1)[0] + "\n\n" + __doc__.split("\n\n", 2)[2],
        formatter_class=argparse.RawDescriptionHelpFormatter,
        usage="%(prog)s REFERENCE RUN [--rtol R] [--all] [--max N] [--quiet]")
    result.add_argument("reference", metavar="REFERENCE", help="a reference case folder or folder of cases")
    result.add_argument("run", metavar="RUN", help="the run's case folder or folder of cases")
    result.add_argument("--rtol", type=non_negative(float), default=1e-6, metavar="R",
                        help="relative tolerance (default 1e-6; a case's tolerances.txt wins)")
    result.add_argument("--all", action="store_true", help="list every difference")
    result.add_argument("--max", type=non_negative(int), default=SHOWN, metavar="N",
                        help=f"list the worst N differences per file (default {SHOWN})")
    result.add_argument("--quiet", action="store_true", help="print nothing; the exit status only")
    return result


def main(argv=None):
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # quiet when piped into head
    args = parser().parse_args(argv)  # a usage error exits 2
    shown = sys.maxsize if args.all else args.max
    out = open(os.devnull, "w") if args.quiet else sys.stdout
    try:
        return compare(args.reference, args.run, args.rtol, shown, out)
    except Unusable as error:
        print(f"visco2d-diff: unusable input: {error}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
