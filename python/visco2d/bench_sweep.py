#!/usr/bin/env python3
"""Sweep throughput: how close `visco2d-batch run -j N` comes to N cores of computing.

    PYTHONPATH=python python3 -m visco2d.bench_sweep [--cases 200] [--level 2] [-j N] [--repeat 1] [--out out/bench-sweep]

The sweep: the peach of inputs/peach_drop.inp at mesh level LEVEL with DROP HEIGHT=${height},
CASES heights from 0.05 to 0.3 m (level 1: 88 elements, some 25 ms a case). Two measurements:

  per-case compute   all CASES decks in one `visco2d -q` process, one after the other: its CPU
                     time (user + sys) / CASES: what a case costs without a process of its own
                     (the summaries' cpu_s, the step loop alone, is printed beside it);
  the sweep          `visco2d-batch run TEMPLATE --param height=... -j N -q` (the launcher make build
                     writes), its wall time.

Prints the cases/s achieved, the ideal N / per-case compute, and their ratio, the efficiency, and
the CPU the sweep took in all its processes against CASES x the per-case compute (what the sweep
adds: process starts, Python; unlike the wall time it hardly depends on what else the machine
runs), and the one process's wall time against the sweep's over N (1: the sweep is N such processes);
with --repeat R the fastest of R sweeps, and the least wall and CPU of R one-process runs. The machine's load average is printed too: on a shared
machine the cores are not all this sweep's. Writes OUT/bench_sweep.md. Exit status 1 if a run failed.
"""
import argparse
import os
import resource
import shutil
import subprocess
import sys
import time

from .runner import ROOT


def children_cpu():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def main():
    parser = argparse.ArgumentParser(prog="python3 -m visco2d.bench_sweep", description=__doc__.split("\n\n")[0])
    parser.add_argument('--cases', type=int, default=200)
    parser.add_argument('--level', type=int, default=1)
    parser.add_argument('-j', '--jobs', type=int, default=os.cpu_count() or 1)
    parser.add_argument('--repeat', type=int, default=1)
    parser.add_argument('--out', default=os.path.join('out', 'bench-sweep'))
    parser.add_argument('--exe', default=os.path.join(ROOT, 'build', 'install', 'bin', 'visco2d'))
    parser.add_argument('--tool', default=os.path.join(ROOT, 'build', 'install', 'bin', 'visco2d-batch'))
    options = parser.parse_args()
    os.makedirs(options.out, exist_ok=True)
    template = os.path.join(options.out, 'peach.inp')
    with open(os.path.join(ROOT, 'inputs', 'peach_drop.inp')) as handle:
        text = handle.read()
    text = text.replace('LEVEL=3', f'LEVEL={options.level}').replace('DROP HEIGHT=0.2', 'DROP HEIGHT=${height}')
    with open(template, 'w') as handle:
        handle.write(text)
    sweep = ['--param', f'height=0.05:0.3:{options.cases}']

    # The decks, expanded once; all of them in one process: the per-case compute.
    decks_root = os.path.join(options.out, 'expanded')
    subprocess.run([options.tool, 'expand', template] + sweep + ['-o', decks_root],
                   check=True, stdout=subprocess.DEVNULL)
    decks = sorted(os.path.join(decks_root, 'decks', name) for name in os.listdir(os.path.join(decks_root, 'decks'))
                   if name.endswith('.inp'))
    one_walls, one_cpus = [], []
    for _ in range(options.repeat):          # the least of R, as for the sweep: the noise of a shared machine only adds
        shutil.rmtree(os.path.join(options.out, 'one_process'), ignore_errors=True)
        before = children_cpu()
        start = time.monotonic()
        one = subprocess.run([options.exe, '-q', '-o', os.path.join(options.out, 'one_process')] + decks)
        one_walls.append(time.monotonic() - start)
        one_cpus.append(children_cpu() - before)
        if one.returncode != 0:
            print(f'bench_sweep: the one-process run failed (exit {one.returncode})', file=sys.stderr)
            return 1
    one_wall, one_cpu = min(one_walls), min(one_cpus)
    per_case = one_cpu / len(decks)
    cpu_s = []
    for name in os.listdir(os.path.join(options.out, 'one_process')):
        path = os.path.join(options.out, 'one_process', name, 'summary.txt')
        if os.path.isfile(path):
            with open(path) as handle:
                cpu_s += [float(line.split('=')[1]) for line in handle if line.startswith('cpu_s =')]
    loop = sum(cpu_s) / len(cpu_s)

    walls, cpus = [], []
    for _ in range(options.repeat):
        before = children_cpu()
        start = time.monotonic()
        run = subprocess.run([options.tool, 'run', template] + sweep +
                             ['-j', str(options.jobs), '-q', '--exe', options.exe, '-o', os.path.join(options.out, 'sweep')])
        walls.append(time.monotonic() - start)
        cpus.append(children_cpu() - before)
        if run.returncode != 0:
            print(f'bench_sweep: the sweep failed (exit {run.returncode})', file=sys.stderr)
            return 1
    wall = min(walls)
    sweep_cpu = cpus[walls.index(wall)]
    achieved = len(decks) / wall
    ideal = options.jobs / per_case
    load = os.getloadavg()[0]
    lines = [f'# Sweep throughput: {len(decks)} peach impacts at level {options.level}, -j {options.jobs}', '',
             '| measure | value |', '|---|---|',
             f'| per-case compute (one process, CPU / case) | {per_case * 1000:.1f} ms |',
             f'| per-case cpu_s of the summaries (step loop) | {loop * 1000:.1f} ms |',
             f'| one process, wall | {one_wall:.2f} s |',
             f'| sweep wall (-j {options.jobs}{", best of %d" % options.repeat if options.repeat > 1 else ""}) '
             f'| {wall:.2f} s |',
             f'| achieved | {achieved:.1f} cases/s |',
             f'| ideal: {options.jobs} cores / per-case compute | {ideal:.1f} cases/s |',
             f'| efficiency (achieved / ideal) | {100 * achieved / ideal:.0f} % |',
             f'| against the one process: one-process wall / sweep wall / {options.jobs} | '
             f'{100 * one_wall / wall / options.jobs:.0f} % |',
             f'| sweep CPU, every process (visco2d-batch and its visco2d runs) | {sweep_cpu:.2f} s |',
             f'| CPU efficiency: {len(decks)} x per-case compute / sweep CPU | '
             f'{100 * len(decks) * per_case / sweep_cpu:.0f} % |',
             f'| load average (1 min) at the end | {load:.2f} |']
    text = '\n'.join(lines) + '\n'
    print(text, end='')
    with open(os.path.join(options.out, 'bench_sweep.md'), 'w') as handle:
        handle.write(text)
    return 0


if __name__ == '__main__':
    sys.exit(main())
