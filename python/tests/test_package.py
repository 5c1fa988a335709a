"""The package as installed commands: pyproject's console scripts, the launchers make build writes,
and visco2d-diff's verdicts through its Python API."""
import os
import shutil
import subprocess
import sys
import tomllib

import pytest

from visco2d import diff

HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def console_scripts():
    with open(os.path.join(HERE, "pyproject.toml"), "rb") as handle:
        return tomllib.load(handle)["project"]["scripts"]


def test_launchers_are_the_console_scripts(tmp_path):
    subprocess.run([sys.executable, os.path.join(HERE, "launchers.py"), str(tmp_path)], check=True)
    scripts = console_scripts()
    assert sorted(os.listdir(tmp_path)) == sorted(scripts) == ["visco2d-batch", "visco2d-diff", "visco2d-fit", "visco2d-report"]
    environment = {key: value for key, value in os.environ.items() if key != "PYTHONPATH"}
    for name in scripts:
        done = subprocess.run([str(tmp_path / name), "--help"], capture_output=True, text=True, env=environment)
        assert done.returncode == 0, done.stderr
        assert done.stdout.startswith("usage: " + name), done.stdout[:80]


def test_every_entry_point_exists():
    import importlib
    for target in console_scripts().values():
        module, function = target.split(":")
        assert callable(getattr(importlib.import_module(module), function))


def test_diff_of_a_reference_with_itself_and_with_a_change(root, tmp_path):
    reference = os.path.join(root, "reference_outputs", "table1_elastic")
    assert diff.compare(reference, reference, out=open(os.devnull, "w")) == 0
    changed = tmp_path / "table1_elastic"
    shutil.copytree(reference, changed)
    summary = (changed / "summary.txt").read_text().splitlines()
    index = next(k for k, line in enumerate(summary) if line.startswith("alpha_max_mm = "))
    value = float(summary[index].split(" = ")[1])
    summary[index] = "alpha_max_mm = %.10g" % (value * 1.001)
    (changed / "summary.txt").write_text("\n".join(summary) + "\n")
    assert diff.compare(reference, str(changed), out=open(os.devnull, "w")) == 1


def test_diff_refuses_a_damaged_reference(root, tmp_path):
    damaged = tmp_path / "table1_elastic"
    shutil.copytree(os.path.join(root, "reference_outputs", "table1_elastic"), damaged)
    os.remove(damaged / "summary.txt")
    with pytest.raises(diff.Unusable, match="summary.txt"):
        diff.compare(str(damaged), os.path.join(root, "reference_outputs", "table1_elastic"),
                     out=open(os.devnull, "w"))
