"""`make bench-sweep` (visco2d.bench_sweep) on a sweep of 3 level-1 cases, 2 rounds: the table has
every row, each round ran both measurements into a scratch folder of its own, and the scratch is
gone afterwards. No time is asserted (timings are the benchmark's output, not a test's)."""
import glob
import os
import re
import sys

import pytest

from visco2d import bench_sweep

from conftest import ROOT


def test_two_rounds_of_a_small_sweep(tmp_path, monkeypatch):
    exe = os.path.join(ROOT, 'build', 'install', 'bin', 'visco2d')
    tool = os.path.join(ROOT, 'build', 'install', 'bin', 'visco2d-batch')
    if not (os.access(exe, os.X_OK) and os.access(tool, os.X_OK)):
        pytest.skip('no build/install/bin/visco2d or visco2d-batch (make build)')
    out = str(tmp_path / 'bench')
    monkeypatch.setattr(sys, 'argv', ['bench_sweep', '--cases', '3', '--repeat', '2', '-j', '2', '--disk',
                                      '--out', out, '--exe', exe, '--tool', tool])
    assert bench_sweep.main() == 0
    with open(os.path.join(out, 'bench_sweep.md')) as handle:
        text = handle.read()
    assert text.startswith('# Sweep throughput: 3 peach impacts at level 1, -j 2')
    assert '2 rounds of one process and one sweep' in text
    for row in ('per-case compute', 'sweep wall', 'achieved', 'ideal', 'efficiency (achieved / ideal',
                'CPU efficiency', 'load average'):
        assert f'| {row}' in text, row
    median, least, most = map(float, re.search(r'efficiency \(achieved / ideal[^|]*\| (\S+) \((\S+)-(\S+)\) %',
                                                text).groups())
    assert 0 < least <= median <= most
    assert glob.glob(os.path.join(out, 'visco2d-bench-sweep-*')) == []      # the scratch is removed
