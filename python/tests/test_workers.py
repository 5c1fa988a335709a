"""The local workers (visco2d.workers) against a stand-in visco2d: a shell script that reads the deck
paths from its standard input as `visco2d --decks-from -` does, writes each case folder and prints a
result line. What is checked is the tool's bookkeeping (one process a worker, a dead process's
decks run again, an interrupt while the decks are written), not visco2d itself (scripts/test_batch.sh
runs the real one)."""
import os
import stat

import pytest

from visco2d import batch, workers

STANDIN = """#!/bin/bash
# visco2d stand-in: -o ROOT --decks-from -
root=$2
echo "process $*" >> "{log}"
echo "threads $OMP_NUM_THREADS $OMP_THREAD_LIMIT $OPENBLAS_NUM_THREADS" >> "{log}.threads"
n=0
while IFS= read -r deck; do
  n=$((n + 1))
  name=$(basename "$deck" .inp)
  echo "deck $name" >> "{log}"
  if [ "$name" = "{die_at}" ] && mkdir "{log}.died" 2> /dev/null; then kill -KILL $$; fi
  mkdir -p "$root/$name"
  for file in summary.txt history.csv listing.txt results.h5 results.xmf; do echo "case = $name" > "$root/$name/$file"; done
  echo "$name: 1 nodes, 1 elements, half-bandwidth 1; cpu 0.0 s"
done
"""


def make_standin(folder, die_at=''):
    log = os.path.join(folder, 'standin.log')
    path = os.path.join(folder, 'visco2d')
    with open(path, 'w') as handle:
        handle.write(STANDIN.format(log=log, die_at=die_at))
    os.chmod(path, os.stat(path).st_mode | stat.S_IXUSR)
    return path, log


def make_cases(out, count):
    cases = [batch.Case(f'c{k:02d}', os.path.join(out, batch.DECKS_DIR, f'c{k:02d}.inp'), {'k': str(k)},
                        f'TITLE case {k}\n', 'template.inp') for k in range(count)]
    for index, case in enumerate(cases):
        case.index = index
    return cases


def read_log(log):
    processes = []
    with open(log) as handle:
        for line in handle:
            word, rest = line.rstrip('\n').split(' ', 1)
            if word == 'process':
                processes.append([])
            else:
                processes[-1].append(rest)
    return processes


def test_one_process_a_worker_every_case_once(tmp_path):
    exe, log = make_standin(str(tmp_path))
    out = str(tmp_path / 'out')
    cases = make_cases(out, 12)
    progress = batch.Progress(len(cases), quiet=True)
    workers.run_local(cases, out, exe, 2, progress, prepare=lambda case: batch.write_deck(case, out))
    processes = read_log(log)
    assert len(processes) == 2
    fed = sorted(name for process in processes for name in process)
    assert fed == [case.name for case in cases]
    for case in cases:
        assert case.error is None and not case.not_run, case.name
        assert os.path.isfile(os.path.join(out, case.name, case.name + '.inp'))   # the deck beside its results


def test_each_worker_process_runs_one_thread(tmp_path, monkeypatch):
    """Two workers on two cores: a process whose CHOLMOD or BLAS starts threads of its own takes CPU
    from the other worker's; every process gets the one-thread settings whatever the caller's are."""
    exe, log = make_standin(str(tmp_path))
    monkeypatch.setenv('OMP_NUM_THREADS', '8')
    monkeypatch.setenv('OPENBLAS_NUM_THREADS', '8')
    out = str(tmp_path / 'out')
    cases = make_cases(out, 4)
    workers.run_local(cases, out, exe, 2, batch.Progress(len(cases), quiet=True),
                      prepare=lambda case: batch.write_deck(case, out))
    with open(log + '.threads') as handle:
        lines = handle.read().splitlines()
    assert lines == ['threads 1 1 1'] * 2


def test_a_dead_process_fails_its_deck_and_the_rest_run_again(tmp_path):
    exe, log = make_standin(str(tmp_path), die_at='c04')
    out = str(tmp_path / 'out')
    cases = make_cases(out, 10)
    progress = batch.Progress(len(cases), quiet=True)
    workers.run_local(cases, out, exe, 1, progress, prepare=lambda case: batch.write_deck(case, out))
    failed = [case.name for case in cases if case.error is not None]
    assert failed == ['c04']
    assert 'stopped by signal 9' in cases[4].error
    processes = read_log(log)
    assert processes[0] == ['c00', 'c01', 'c02', 'c03', 'c04']
    assert processes[1] == ['c05', 'c06', 'c07', 'c08', 'c09']     # those written after c04 go back first


def test_an_interrupt_while_the_decks_are_written(tmp_path):
    exe, _ = make_standin(str(tmp_path))
    out = str(tmp_path / 'out')
    cases = make_cases(out, 8)
    progress = batch.Progress(len(cases), quiet=True)

    def prepare(case):
        if case.name == 'c03':
            raise KeyboardInterrupt
        batch.write_deck(case, out)

    with pytest.raises(batch.Interrupted):
        workers.run_local(cases, out, exe, 2, progress, prepare=prepare)
    assert all(case.not_run for case in cases[3:])                  # never queued: not run
    for case in cases[:3]:                                          # ended, or stopped by the interrupt
        assert case.error is None
        assert case.not_run or os.path.isfile(os.path.join(out, case.name, 'summary.txt'))
