"""visco2d.case: the one reader of summary.txt and of the CSV tables."""
import glob
import math
import os

from visco2d import case


def write(path, text):
    with open(path, "w") as handle:
        handle.write(text)
    return str(path)


def test_summary_value_after_first_separator(tmp_path):
    path = write(tmp_path / "summary.txt",
                 "alpha_max_mm = 1.25\nwarning_1 = deck.inp:3: PAD: strain = 0.4 past 0.3\nnot a pair\n")
    summary = case.read_summary(path)
    assert summary == {"alpha_max_mm": "1.25", "warning_1": "deck.inp:3: PAD: strain = 0.4 past 0.3"}


def test_summary_of_a_folder(tmp_path):
    write(tmp_path / "summary.txt", "steps = 12\n")
    assert case.read_summary(str(tmp_path)) == {"steps": "12"}


def test_undecodable_bytes_are_replaced(tmp_path):
    path = tmp_path / "summary.txt"
    path.write_bytes(b"title = caf\xe9\nsteps = 3\n")
    summary = case.read_summary(str(path))
    assert summary["steps"] == "3" and summary["title"].startswith("caf")


def test_typed_values():
    assert case.typed("12") == 12 and isinstance(case.typed("12"), int)
    assert case.typed("1.5D+03") == 1500.0
    assert case.typed("-2.5e-7") == -2.5e-7
    assert case.typed("yes") == "yes"
    assert case.typed("NaN") == "NaN"          # never silently a number
    assert case.typed("Infinity") == "Infinity"


def test_number_defaults():
    summary = {"a": "2", "b": "stick", "c": "nan"}
    assert case.number(summary, "a") == 2.0
    assert case.number(summary, "b") is None
    assert case.number(summary, "c", default=-1.0) == -1.0
    assert case.number(summary, "missing", default=0.0) == 0.0
    assert case.number(None, "a") is None


def test_missed_expectations():
    summary = {"expect_alpha_max_mm_within_rtol": "no", "expect_q_max_MPa_within_rtol": "yes", "alpha_max_mm": "no"}
    assert case.missed_expectations(summary) == ["alpha_max_mm"]


def test_history_columns(tmp_path):
    write(tmp_path / "history.csv", "t_ms,alpha_mm\n0,0\n0.5,1.25e-1\n")
    history = case.read_history(str(tmp_path))
    assert list(history) == ["t_ms", "alpha_mm"]
    assert history["alpha_mm"] == [0.0, 0.125]


def test_every_archived_reference_reads(root):
    """Each archived summary parses, its numbers are finite, and its history has the summary's step count."""
    folders = sorted(glob.glob(os.path.join(root, "reference_outputs", "*", "summary.txt")))
    assert len(folders) >= 20
    for path in folders:
        summary = case.read_typed_summary(path)
        assert summary, path
        numbers = [value for value in summary.values() if isinstance(value, float)]
        assert numbers and all(math.isfinite(value) for value in numbers), path
        history = case.read_history(os.path.dirname(path))
        lengths = {len(column) for column in history.values()}
        assert len(lengths) == 1, path


def test_results_of_a_run_and_not_a_case(root, tmp_path):
    """read_results on a run of the Table 1 deck: the mesh the summary counts, 0-based elements,
    the history as long as history.csv; and the reasons a folder is not a case."""
    import pytest
    from visco2d import runner
    exe = os.path.join(root, "build", "install", "bin", "visco2d")
    if not os.access(exe, os.X_OK):
        pytest.skip("no build/install/bin/visco2d (make build)")
    done = runner.run(exe, [os.path.join(root, "inputs", "table1_elastic.inp")], str(tmp_path))
    assert done.returncode == 0, done.stderr
    results = case.read_results(str(tmp_path / "table1_elastic"))
    summary = case.read_summary(str(tmp_path / "table1_elastic"))
    assert results["case"] == "table1_elastic" and results["analysis"] == "DYNAMIC"
    assert results["nodes"].shape == (int(summary["nodes"]), 2)
    assert results["elements"].shape == (int(summary["elements"]), 4)
    assert results["elements"].min() == 0 and results["elements"].max() == int(summary["nodes"]) - 1
    history = case.read_history(str(tmp_path / "table1_elastic"))
    assert len(results["history"]["alpha_mm"]) == len(history["alpha_mm"])
    assert results["summary"]["alpha_max_mm"] == pytest.approx(float(summary["alpha_max_mm"]), rel=1e-9)
    assert results["fields"] and results["fields"][0]["displacement"].shape[0] == int(summary["nodes"])
    with pytest.raises(case.NotACase, match="no results.h5"):
        case.read_results(str(tmp_path))
    (tmp_path / "broken").mkdir()
    (tmp_path / "broken" / "results.h5").write_text("not HDF5")
    with pytest.raises(case.NotACase, match="cannot be read as HDF5"):
        case.read_results(str(tmp_path / "broken"))
