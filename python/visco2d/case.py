"""Read a visco2d case folder: summary.txt, history.csv, pressure.csv and results.h5.

Every tool of the package reads a case through these functions: one parser of
summary.txt (`key = value` lines), one of the CSV tables.
"""
import csv
import math
import os

SUMMARY = "summary.txt"
HISTORY = "history.csv"
RESULTS = "results.h5"


class NotACase(ValueError):
    """A folder or file that is not a visco2d case (the message says why)."""


def read_summary(path):
    """{key: text} of a summary.txt (a case folder or the file itself): every `key = value` line.

    The value is the text after the first " = " (warning texts may hold "="), both sides stripped.
    Undecodable bytes are replaced, never fatal (the fuzzer reads summaries of mutated decks).
    """
    if os.path.isdir(path):
        path = os.path.join(path, SUMMARY)
    values = {}
    with open(path, encoding="utf-8", errors="replace") as handle:
        for line in handle:
            key, sep, value = line.rstrip("\n").partition(" = ")
            if sep:
                values[key.strip()] = value.strip()
    return values


def typed(text):
    """A summary value as an int, a float or the text itself ('yes'/'no' and words stay text).

    Fortran exponents (1.0D+03) are read; a value that reads as a non-finite number stays text
    (visco2d never writes one: the fuzzer looks for them as text).
    """
    try:
        return int(text)
    except ValueError:
        pass
    try:
        value = float(text.replace("D", "E").replace("d", "e"))
    except ValueError:
        return text
    return value if math.isfinite(value) else text


def number(summary, key, default=None):
    """summary[key] as a finite float, or default when the key is absent or not a number."""
    if not summary or key not in summary:
        return default
    value = typed(summary[key])
    return float(value) if isinstance(value, (int, float)) else default


def read_typed_summary(path):
    """{key: int | float | str} of a summary.txt (see typed)."""
    return {key: typed(value) for key, value in read_summary(path).items()}


def missed_expectations(summary):
    """The keys of a summary whose EXPECT card is outside its RTOL (expect_<key>_within_rtol = no)."""
    return [key[len("expect_"):-len("_within_rtol")] for key, value in summary.items()
            if key.startswith("expect_") and key.endswith("_within_rtol") and value.strip() == "no"]


def read_table(path):
    """{column: [float, ...]} of a visco2d CSV table (history.csv, pressure.csv), in column order."""
    with open(path, newline="") as handle:
        reader = csv.DictReader(handle)
        rows = list(reader)
        return {key.strip(): [float(row[key]) for row in rows] for key in reader.fieldnames}


def read_history(path):
    """history.csv of a case folder (or the file itself) as {column: [float, ...]}."""
    if os.path.isdir(path):
        path = os.path.join(path, HISTORY)
    return read_table(path)


def text_of(value):
    """An HDF5 string (bytes or str) as str."""
    if isinstance(value, bytes) or type(value).__name__ == "bytes_":
        return value.decode()
    return str(value)


def summary_value(value):
    """A /summary dataset's value of results.h5: a str for text, else the number."""
    if isinstance(value, (bytes, str)) or type(value).__name__ in ("bytes_", "str_"):
        return text_of(value)
    return value.item() if hasattr(value, "item") else value


def read_group(group):
    """Every dataset of an HDF5 group as {name: numpy array or scalar}."""
    import h5py
    return {name: item[...] for name, item in group.items() if isinstance(item, h5py.Dataset)}


def read_results(folder):
    """OUT/<case>/results.h5 as a dict (raises NotACase with the reason when it is not a case).

    Keys: folder, path, case, title, geometry, analysis, nodes (nnode, 2) in m, elements (nelem, 4)
    0-based, summary {key: number or text}, history, pressure and bruise ({dataset: array}; None when
    the run has none) and fields (the snapshots in time order: name, label, time, displacement,
    stress, stress_gauss).
    """
    import h5py
    path = os.path.join(folder, RESULTS)
    if not os.path.isdir(folder):
        raise NotACase(f"{folder} is not a folder")
    if not os.path.isfile(path):
        raise NotACase(f"{folder} is not a visco2d case folder (no {RESULTS} in it)")
    try:
        with h5py.File(path, "r") as f:
            for group in ("/mesh", "/summary", "/history"):
                if group not in f:
                    raise NotACase(f"{path} has no {group} group: not a visco2d results file")
            fields = []
            for name in sorted(f["/fields"].keys()) if "/fields" in f else []:
                group = f["/fields"][name]
                fields.append({
                    "name": name,
                    "label": text_of(group.attrs.get("label", "")),
                    "time": float(group.attrs["time"]),
                    "displacement": group["displacement"][...],
                    "stress": group["stress"][...],
                    "stress_gauss": group["stress_gauss"][...] if "stress_gauss" in group else None,
                })
            return {
                "folder": folder,
                "path": path,
                "case": text_of(f.attrs.get("case", os.path.basename(os.path.normpath(folder)))),
                "title": text_of(f.attrs.get("title", "")),
                "geometry": text_of(f.attrs.get("geometry", "AXISYMMETRIC")),
                "analysis": text_of(f.attrs.get("analysis", "")),
                "nodes": f["/mesh/nodes"][...],
                "elements": f["/mesh/elements"][...] - 1,
                "summary": {key: summary_value(item[()]) for key, item in f["/summary"].items()},
                "history": read_group(f["/history"]),
                "pressure": read_group(f["/pressure"]) if "/pressure" in f else None,
                "bruise": read_group(f["/bruise"]) if "/bruise" in f else None,
                "fields": fields,
                "has_fields": "/fields" in f,
            }
    except OSError as problem:
        raise NotACase(f"{path} cannot be read as HDF5 ({problem})") from None
