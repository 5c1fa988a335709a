"""visco2d.runner: which visco2d runs, with which command line and environment."""
import os
import stat

import pytest

from visco2d import runner


def fake_visco2d(folder):
    """An executable that prints its arguments and its BLAS thread setting."""
    path = os.path.join(folder, "visco2d")
    with open(path, "w") as handle:
        handle.write('#!/bin/sh\necho "args: $*"\necho "threads: $OPENBLAS_NUM_THREADS $OMP_NUM_THREADS $OMP_THREAD_LIMIT"\n')
    os.chmod(path, os.stat(path).st_mode | stat.S_IEXEC)
    return path


def test_run_command_line_and_one_thread(tmp_path, monkeypatch):
    exe = fake_visco2d(str(tmp_path))
    monkeypatch.setenv("OPENBLAS_NUM_THREADS", "8")
    done = runner.run(exe, ["a.inp", "b.inp"], "out", options=["--timing"])
    assert done.returncode == 0
    assert "args: --timing -q -o out a.inp b.inp" in done.stdout
    assert "threads: 1 1 1" in done.stdout


def test_explicit_program_first(tmp_path, monkeypatch):
    exe = fake_visco2d(str(tmp_path))
    monkeypatch.setenv("VISCO2D", "/no/such/visco2d")
    assert runner.find_program(exe) == exe
    with pytest.raises(FileNotFoundError, match="not an executable"):
        runner.find_program(str(tmp_path / "missing"))


def test_environment_variable_before_checkout(tmp_path, monkeypatch):
    exe = fake_visco2d(str(tmp_path))
    monkeypatch.setenv("VISCO2D", exe)
    assert runner.find_program() == exe


def test_located_error_of_the_deck():
    stderr = ("visco2d: a.inp:3:7: error: MESH: LEVEL must be 1-8\n"
              "visco2d: b.inp:9:1: error: TIME: DT must be positive\nvisco2d: 2 of 2 decks failed\n")
    assert runner.located_error(stderr, "b.inp") == "TIME: DT must be positive"
    assert runner.located_error("killed\n") == "killed"
    assert runner.located_error("") == "failed without a message"


def test_checkout_root(root):
    assert runner.repository_root() == root
