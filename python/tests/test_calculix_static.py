"""The fast part of scripts/calculix_plastic_static.py (the CalculiX check of the static indentation,
doc/calculix_plastic_static.md): with --dry-run it writes both codes' inputs and runs no CalculiX
job; without ccx it says so and skips the CalculiX runs. Level 1, 4 increments: about a second."""
import os
import subprocess
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(ROOT, "scripts", "calculix_plastic_static.py")
EXE = os.path.join(ROOT, "build", "install", "bin", "visco2d")

pytest.importorskip("h5py")
pytestmark = pytest.mark.skipif(not os.access(EXE, os.X_OK), reason="no visco2d executable (make build)")


def run(out, *extra):
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "python"))
    return subprocess.run([sys.executable, SCRIPT, str(out), "--level", "1", "--increments", "4", "--checkpoints",
                           "2,4", "--yields", "0.3e6", "--penalty-factors", "1,10", *extra],
                          capture_output=True, text=True, env=env, timeout=120)


def test_dry_run_writes_both_codes_inputs(tmp_path):
    result = run(tmp_path, "--dry-run")
    assert result.returncode == 0, result.stderr
    ccx = (tmp_path / "ccx_Y300000_K1.inp").read_text()
    assert "*STATIC\n0.25, 1.0, 2.5e-05, 0.25\n" in ccx
    assert "*TIME POINTS, NAME=TP\n0.25, 0.5, 0.75, 1\n" in ccx
    assert "*DLOAD\nESPHERE, GRAV, 2000, 0., -1., 0.\n" in ccx
    # the bilinear curve: (Y, 0) and (Y + 10 H, 10), H = E Et / (E - Et) = 4e6 0.4e6 / 3.6e6
    assert "*PLASTIC\n300000, 0.0\n4744444.444, 10\n" in ccx
    assert "*CONTACT PAIR, INTERACTION=FRICTIONLESS, TYPE=NODE TO SURFACE\nSSLAVE, SPLATE\n" in ccx
    assert "*PLASTIC" not in (tmp_path / "ccx_elastic_K1.inp").read_text()
    # the 10 K deck differs from the K deck in the penalty slope only
    k1 = ccx.splitlines()
    k10 = (tmp_path / "ccx_Y300000_K10.inp").read_text().splitlines()
    diff = [(a, b) for a, b in zip(k1, k10) if a != b]
    assert len(k1) == len(k10) and len(diff) == 1
    slope1, slope10 = (float(x.split(",")[0]) for x in diff[0])
    assert abs(slope10 / slope1 - 10) < 1e-5
    # visco2d's path point k: the load k/N in k increments
    deck = (tmp_path / "v_Y300000_standard_02of4.inp").read_text().splitlines()
    assert "ANALYSIS STATIC INCREMENTS=2" in deck and "GRAVITY G=1000" in deck
    assert "PLATE Z=0 SLIP" in deck and "PLASTIC YIELD=300000 TANGENT=400000" in deck
    assert "PLASTIC YIELD=1e12 TANGENT=0" in (tmp_path / "v_elastic_standard_04of4.inp").read_text()
    assert not (tmp_path / "comparison.md").exists()


def test_without_ccx_skips_with_a_message(tmp_path):
    result = run(tmp_path, "--ccx", "")
    assert result.returncode == 0, result.stderr
    assert "ccx (CalculiX) is not installed" in result.stdout
    assert not (tmp_path / "comparison.md").exists()
    assert not list(tmp_path.glob("*.dat"))
