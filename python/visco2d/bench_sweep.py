#!/usr/bin/env python3
"""Sweep throughput: how close `visco2d-batch run -j N` comes to N cores of computing.

    PYTHONPATH=python python3 -m visco2d.bench_sweep [--cases 200] [--level 1] [-j N] [--repeat 3] [--disk] [--out out/bench-sweep]

The sweep: the peach of inputs/peach_drop.inp at mesh level LEVEL with DROP HEIGHT=${height},
CASES heights from 0.05 to 0.3 m (level 1: 88 elements, some 30 ms a case). Two measurements:

  per-case compute   all CASES decks in one `visco2d -q` process, one after the other: its CPU
                     time (user + sys) / CASES: what a case costs without a process of its own
                     (the summaries' cpu_s, the step loop alone, is printed beside it);
  the sweep          `visco2d-batch run TEMPLATE --param height=... -j N -q` (the launcher make build
                     writes), its wall time.

Each of the REPEAT rounds runs both, in turn (the one process first in odd rounds, the sweep
first in even ones), so that a machine whose speed drifts (a shared or virtual one: the same
process here took 6.0 to 8.7 s within minutes) slows both alike; the efficiency of a round is
its sweep's cases/s against N / its own per-case compute, and the result is the median of the
rounds with their range. Also printed: the CPU all the sweep's processes took against CASES x
the per-case compute (what the sweep adds: process starts, Python), and the one process's wall
time against the sweep's over N (1: the sweep is N such processes).

Both write their outputs into a scratch folder on a RAM file system (/dev/shm when there is one;
removed at the end), each run into a folder of its own: on ext4, creating files soon after
deleting many (the benchmark's own earlier runs) costs kernel time in the inode allocator that
varied 0.2-1.8 s between identical runs, more than the effect measured. --disk writes under OUT
instead (what a user's sweep onto a disk sees). Writes OUT/bench_sweep.md. The machine's load
average is printed: on a shared machine the cores are not all this sweep's. Exit status 1 if a
run failed.
"""
import argparse
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

from .runner import ONE_THREAD, ROOT


def children_cpu():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def main():
    parser = argparse.ArgumentParser(prog="python3 -m visco2d.bench_sweep", description=__doc__.split("\n\n")[0])
    parser.add_argument('--cases', type=int, default=200)
    parser.add_argument('--level', type=int, default=1)
    parser.add_argument('-j', '--jobs', type=int, default=os.cpu_count() or 1)
    parser.add_argument('--repeat', type=int, default=3, help='rounds of one process and one sweep (default 3)')
    parser.add_argument('--disk', action='store_true', help='write the runs under OUT, not on a RAM file system')
    parser.add_argument('--out', default=os.path.join('out', 'bench-sweep'))
    parser.add_argument('--exe', default=os.path.join(ROOT, 'build', 'install', 'bin', 'visco2d'))
    parser.add_argument('--tool', default=os.path.join(ROOT, 'build', 'install', 'bin', 'visco2d-batch'))
    options = parser.parse_args()
    if options.repeat < 1 or options.cases < 1 or options.jobs < 1:
        parser.error('--repeat, --cases and -j must be at least 1')
    os.makedirs(options.out, exist_ok=True)
    template = os.path.join(options.out, 'peach.inp')
    with open(os.path.join(ROOT, 'inputs', 'peach_drop.inp')) as handle:
        text = handle.read()
    text = text.replace('LEVEL=3', f'LEVEL={options.level}').replace('DROP HEIGHT=0.2', 'DROP HEIGHT=${height}')
    with open(template, 'w') as handle:
        handle.write(text)
    sweep = ['--param', f'height=0.05:0.3:{options.cases}']
    ram = '/dev/shm'
    if options.disk or not (os.path.isdir(ram) and os.access(ram, os.W_OK)):
        scratch_parent = options.out
    else:
        scratch_parent = ram
    scratch = tempfile.mkdtemp(prefix='visco2d-bench-sweep-', dir=scratch_parent)
    try:
        return measure(options, template, sweep, scratch, scratch_parent)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)


def one_process(options, decks, folder):
    """All decks in one visco2d process: (wall, CPU) or None when it failed."""
    before = children_cpu()
    start = time.monotonic()
    run = subprocess.run([options.exe, '-q', '-o', folder] + decks, env=dict(os.environ, **ONE_THREAD))
    wall, cpu = time.monotonic() - start, children_cpu() - before
    if run.returncode != 0:
        print(f'bench_sweep: the one-process run failed (exit {run.returncode})', file=sys.stderr)
        return None
    return wall, cpu


def one_sweep(options, template, sweep, folder):
    """The sweep by visco2d-batch: (wall, CPU of all its processes) or None when it failed."""
    before = children_cpu()
    start = time.monotonic()
    run = subprocess.run([options.tool, 'run', template] + sweep +
                         ['-j', str(options.jobs), '-q', '--exe', options.exe, '-o', folder])
    wall, cpu = time.monotonic() - start, children_cpu() - before
    if run.returncode != 0:
        print(f'bench_sweep: the sweep failed (exit {run.returncode})', file=sys.stderr)
        return None
    return wall, cpu


def measure(options, template, sweep, scratch, scratch_parent):
    # The decks, expanded once; all of them in one process: the per-case compute.
    decks_root = os.path.join(scratch, 'expanded')
    subprocess.run([options.tool, 'expand', template] + sweep + ['-o', decks_root],
                   check=True, stdout=subprocess.DEVNULL)
    decks = sorted(os.path.join(decks_root, 'decks', name) for name in os.listdir(os.path.join(decks_root, 'decks'))
                   if name.endswith('.inp'))
    count, jobs = len(decks), options.jobs
    rounds = []
    for index in range(options.repeat):
        one_folder = os.path.join(scratch, f'one_process_{index + 1}')
        sweep_folder = os.path.join(scratch, f'sweep_{index + 1}')
        if index % 2 == 0:
            one = one_process(options, decks, one_folder)
            swept = one and one_sweep(options, template, sweep, sweep_folder)
        else:
            swept = one_sweep(options, template, sweep, sweep_folder)
            one = swept and one_process(options, decks, one_folder)
        if not one or not swept:
            return 1
        (one_wall, one_cpu), (wall, cpu) = one, swept
        per_case = one_cpu / count
        rounds.append({'per_case': per_case, 'one_wall': one_wall, 'wall': wall, 'cpu': cpu,
                       'efficiency': (count / wall) / (jobs / per_case),
                       'against_one': one_wall / wall / jobs,
                       'cpu_efficiency': count * per_case / cpu})
    cpu_s = []
    for name in os.listdir(os.path.join(scratch, 'one_process_1')):
        path = os.path.join(scratch, 'one_process_1', name, 'summary.txt')
        if os.path.isfile(path):
            with open(path) as handle:
                cpu_s += [float(line.split('=')[1]) for line in handle if line.startswith('cpu_s =')]
    loop = sum(cpu_s) / len(cpu_s)

    def spread(key, scale=100.0, digits=0):
        values = sorted(scale * entry[key] for entry in rounds)
        text = f'{statistics.median(values):.{digits}f}'
        return text if len(values) == 1 else f'{text} ({values[0]:.{digits}f}-{values[-1]:.{digits}f})'

    load = os.getloadavg()[0]
    where = 'a RAM file system' if scratch_parent == '/dev/shm' else f'disk ({scratch_parent})'
    lines = [f'# Sweep throughput: {count} peach impacts at level {options.level}, -j {jobs}', '',
             f'{len(rounds)} round{"s" if len(rounds) > 1 else ""} of one process and one sweep, '
             f'outputs on {where}; median (least-most) of the rounds.', '',
             '| measure | value |', '|---|---|',
             f'| per-case compute (one process, CPU / case) | {spread("per_case", 1000, 1)} ms |',
             f'| per-case cpu_s of the summaries (step loop) | {loop * 1000:.1f} ms |',
             f'| one process, wall | {spread("one_wall", 1, 2)} s |',
             f'| sweep wall (-j {jobs}) | {spread("wall", 1, 2)} s |',
             f'| achieved | {count / statistics.median(entry["wall"] for entry in rounds):.1f} cases/s |',
             f'| ideal: {jobs} cores / per-case compute | '
             f'{jobs / statistics.median(entry["per_case"] for entry in rounds):.1f} cases/s |',
             f'| efficiency (achieved / ideal, each round against its own one process) | {spread("efficiency")} % |',
             f'| against the one process: one-process wall / sweep wall / {jobs} | {spread("against_one")} % |',
             f'| sweep CPU, every process (visco2d-batch and its visco2d runs) | {spread("cpu", 1, 2)} s |',
             f'| CPU efficiency: {count} x per-case compute / sweep CPU | {spread("cpu_efficiency")} % |',
             f'| load average (1 min) at the end | {load:.2f} |']
    text = '\n'.join(lines) + '\n'
    print(text, end='')
    with open(os.path.join(options.out, 'bench_sweep.md'), 'w') as handle:
        handle.write(text)
    return 0


if __name__ == '__main__':
    sys.exit(main())
