"""The local runs of visco2d-batch: `jobs` workers, each handing batches of decks to one visco2d process.

A visco2d process costs some 25 ms of CPU to start (its libraries, its output root) and
visco2d-batch a few more to start and wait for it: for small cases that is most of a core. So each
worker takes a batch of decks off one queue and runs them in one `visco2d -o ROOT DECK...`
(which runs them one after the other, each into its own folder, exactly as alone: doc/command_line.md).
The batch is sized from the wall time a case has taken so far: 1/(2 jobs) of the decks left (so
the workers end together), but at least MIN_SECONDS of work and at most BATCH_SECONDS, and
never more than an equal share of what is left; the first batch of a worker is one deck. Each case is still its own: its result line (visco2d's stdout and stderr,
unbuffered, read as they come) ends it, its folder is finished and the progress line updated
then; its error is its own `visco2d: error:` line. When the process dies in a deck (a signal:
SIGKILL, a crash) that deck fails with the signal and the decks after it go back on the queue;
on Ctrl-C the running processes are sent SIGINT and what had not ended is `not run`.

This module is imported by batch.py (`batch`, set by it: finish_case, located_error, ...).
"""

import collections
import concurrent.futures
import math
import os
import re
import signal
import subprocess
import threading
import time

from . import batch

BATCH_SECONDS = 5.0     # the wall time of work a batch of decks is sized to, once a case's time is known
MIN_SECONDS = 1.0       # ... and at least this much (a process start is some 30 ms), within an equal share
MAX_DECKS = 500         # and never more decks than this in one process
RESULT = re.compile(r'\d+ nodes, \d+ elements')    # visco2d's one-line result: "<case>: N nodes, M elements, ..."
ERROR = 'visco2d: error: '


class Queue:
    """The cases left, and the wall time the ended ones took (to size a batch)."""

    def __init__(self, cases, jobs):
        self.cases = collections.deque(cases)
        self.jobs = max(1, jobs)
        self.lock = threading.Lock()
        self.seconds = 0.0
        self.ended = 0

    def take(self, first):
        """The next batch: one deck as a worker's first; else about BATCH_SECONDS of work."""
        with self.lock:
            left = len(self.cases)
            if not left:
                return []
            if first or not self.ended:
                size = 1
            else:
                mean = max(self.seconds / self.ended, 1e-6)
                share = math.ceil(left / (2 * self.jobs))      # shrinking as the queue empties: the workers end together
                size = max(share, math.ceil(MIN_SECONDS / mean))                # not too short for a process
                size = min(size, math.ceil(BATCH_SECONDS / mean), math.ceil(left / self.jobs), MAX_DECKS)
                size = max(1, size)
            return [self.cases.popleft() for _ in range(size)]

    def give_back(self, cases):
        """Decks a dead process did not start: first in line again."""
        with self.lock:
            self.cases.extendleft(reversed(cases))

    def drain(self):
        with self.lock:
            left = list(self.cases)
            self.cases.clear()
            return left

    def took(self, seconds, count):
        with self.lock:
            self.seconds += seconds
            self.ended += count


def complete(folder):
    return all(os.path.isfile(os.path.join(folder, name)) for name in batch.CASE_FILES)


class Workers:
    """`jobs` worker threads running the cases added to them (`add`), batches of decks a process.
    A case that ends (its result, error or not_run) is announced to `ended()`; `close()` lets the
    workers end once the queue is empty; `interrupt()` (Ctrl-C) stops them: no further process
    starts, the running ones are sent SIGINT, what had not ended is `not_run`."""

    def __init__(self, out, exe, jobs, progress, stage=None):
        self.out, self.exe, self.progress, self.stage = out, exe, progress, stage
        self.root = stage or out
        self.queue = Queue([], jobs)
        self.stop = threading.Event()
        self.running = set()
        self.guard = threading.Lock()
        self.changed = threading.Condition()      # a case added or ended, or the queue closed
        self.closed = False
        self.done = collections.deque()           # the cases ended since the last ended()
        self.environment = dict(os.environ, GFORTRAN_UNBUFFERED_PRECONNECTED='y')   # each line as written
        self.pool = concurrent.futures.ThreadPoolExecutor(max_workers=max(1, jobs))
        self.futures = [self.pool.submit(self.worker) for _ in range(max(1, jobs))]

    def add(self, cases):
        with self.changed:
            with self.queue.lock:
                self.queue.cases.extend(cases)
            self.changed.notify_all()

    def close(self):
        with self.changed:
            self.closed = True
            self.changed.notify_all()

    def ended(self, timeout=0.2):
        """The cases that ended since the last call (waits up to `timeout` s for one)."""
        with self.changed:
            if not self.done:
                self.changed.wait(timeout)
            cases = list(self.done)
            self.done.clear()
            return cases

    def join(self):
        for future in self.futures:
            future.result()
        self.pool.shutdown(wait=True)

    def interrupt(self):
        self.stop.set()
        with self.changed:
            self.changed.notify_all()
        for case in self.queue.drain():
            case.not_run = True
        with self.guard:
            for process in self.running:
                try:
                    process.send_signal(signal.SIGINT)
                except OSError:
                    pass
        self.pool.shutdown(wait=True)
        for case in self.queue.drain():       # given back by a process that died meanwhile
            case.not_run = True

    def worker(self):
        first = True
        while not self.stop.is_set():
            decks = self.queue.take(first)
            if not decks:
                with self.changed:
                    if self.closed or self.stop.is_set():
                        if not self.queue.cases:
                            return
                        continue
                    self.changed.wait(0.2)
                continue
            first = False
            self.queue.give_back(self.run_batch(decks))

    def end(self, case, line):
        """A case has ended: its folder finished (moved from the stage), the progress line, ended()."""
        if case.error is None and not case.not_run:
            if self.stage:
                os.replace(os.path.join(self.stage, case.name), os.path.join(self.out, case.name))
        if not case.not_run:
            batch.finish_case(case, self.out)
            self.progress.update(case, batch.result_message(case, line))
        with self.changed:
            self.done.append(case)
            self.changed.notify_all()

    def run_batch(self, decks):
        """One visco2d process for `decks`; returns the decks it did not start (to run again)."""
        with self.guard:
            if self.stop.is_set():
                for case in decks:
                    case.not_run = True
                    self.end(case, '')
                return []
            try:
                process = subprocess.Popen([self.exe, '-o', self.root] + [case.deck for case in decks],
                                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                           env=self.environment)
            except OSError as error:
                process = None
                message = f'cannot run {self.exe}: {error.strerror}'
            else:
                self.running.add(process)
        if process is None:
            for case in decks:
                case.error = message
                self.end(case, '')
            return []
        k = 0                    # the deck running: the first that has not ended
        own = []                 # its lines so far (warnings, notes)
        missed = None            # (case, result line, misses to come, their lines): a deck that missed EXPECTs
        start = time.monotonic()
        ended_at = start

        def ended(count=1):
            nonlocal ended_at
            now = time.monotonic()
            self.queue.took(now - ended_at, count)
            ended_at = now

        for line in process.stdout:
            line = line.rstrip('\n')
            if missed is not None:
                case, result, left, lines = missed
                if line.startswith(ERROR) and left > 0:
                    lines.append(line)
                    missed = (case, result, left - 1, lines)
                    if left > 1:
                        continue
                    line = None
                case, result, _, lines = missed
                case.missed = batch.located_error('\n'.join(lines))
                self.end(case, result)
                missed = None
                if line is None:
                    continue
            if k < len(decks) and line.startswith(decks[k].name + ': ') and \
                    RESULT.match(line[len(decks[k].name) + 2:]):
                case = decks[k]
                k += 1
                own = []
                ended()
                summary = os.path.join(self.root, case.name, 'summary.txt')
                misses = batch.missed_expectations(batch.read_summary(summary)) if os.path.isfile(summary) else []
                if misses:
                    missed = (case, line, len(misses), [])
                else:
                    self.end(case, line)
            elif k < len(decks) and line.startswith(ERROR):
                case = decks[k]
                k += 1
                case.error = batch.located_error('\n'.join(own + [line]))
                own = []
                ended()
                self.end(case, '')
            else:
                own.append(line)
        status = process.wait()
        with self.guard:
            self.running.discard(process)
        if missed is not None:
            case, result, _, lines = missed
            case.missed = batch.located_error('\n'.join(lines)) if lines else 'outside the RTOL of its EXPECT card(s)'
            self.end(case, result)
        left = decks[k:]
        if not left:
            return []
        if status == 2:                  # a usage error or an unusable root, before any deck ran: every deck's
            message = batch.located_error('\n'.join(own))
            for case in left:
                case.error = message
                self.end(case, '')
            return []
        case, rest = left[0], left[1:]
        folder = os.path.join(self.root, case.name)
        interrupted = self.stop.is_set() or status == -signal.SIGINT
        if complete(folder) and case.error is None:
            self.end(case, f'{case.name}: done')   # the signal came after its folder was moved into place: it ended
        elif interrupted:
            case.not_run = True              # stopped by the interrupt: no result, and no error of its own
            self.end(case, '')
        else:
            case.error = batch.located_error('\n'.join(own)) if own else f'visco2d exited with status {status}'
            if status < 0:
                case.error = f'visco2d stopped by signal {-status}: {case.error}'
            self.end(case, '')
        if interrupted:
            for other in rest:
                other.not_run = True
                self.end(other, '')
            return []
        return rest                          # not started: they run again, in another process


def run_local(cases, out, exe, jobs, progress, stage=None):
    """The cases on `jobs` workers (batch.run_local's contract): each case ends with its
    folder in OUT (moved there from `stage`, a shard's own root), or its error, or `not_run`
    after an interrupt, which raises batch.Interrupted once the running processes have ended."""
    workers = Workers(out, exe, min(jobs, max(1, len(cases))), progress, stage)
    workers.add(cases)
    workers.close()
    try:
        with batch.interrupts_raised():
            workers.join()
    except KeyboardInterrupt:
        workers.interrupt()
        raise batch.Interrupted(cases) from None
