"""The local runs of visco2d-batch: `jobs` workers, each feeding the decks to one visco2d process.

A visco2d process costs some 25 ms of CPU to start (its libraries, its output root) and
visco2d-batch a few more to start and wait for it: for small cases that is most of a core. So each
worker keeps one `visco2d -o ROOT --decks-from -` process for the whole sweep and writes the deck
paths to its standard input, one at a time as decks end (AHEAD of them written before their turn,
so the process never waits for the next); visco2d runs each one as its line arrives, exactly as
alone (doc/command_line.md). The queue is one, so the workers end together (within a case).
Each case is still its own: its result line (visco2d's stdout and stderr, unbuffered, read as
they come) ends it, its folder is finished and the progress line updated then; its error is its
own `visco2d: error:` line. When the process dies in a deck (a signal: SIGKILL, a crash) that
deck fails with the signal, the decks written after it go back on the queue and the worker
starts a new process; on Ctrl-C the running processes are sent SIGINT and what had not ended is
`not run`.

This module is imported by batch.py (`batch`, set by it: finish_case, located_error, ...).
"""

import collections
import concurrent.futures
import os
import re
import signal
import subprocess
import threading

from . import batch, runner

AHEAD = 2               # decks written to a process before their turn: one running, one waiting in its pipe
RESULT = re.compile(r'\d+ nodes, \d+ elements')    # visco2d's one-line result: "<case>: N nodes, M elements, ..."
EXPECTS = re.compile(r'; EXPECT (\d+)/(\d+) within RTOL')   # ... its EXPECT cards: within / count
ERROR = 'visco2d: error: '


class Queue:
    """The cases left, one queue for every worker."""

    def __init__(self, cases):
        self.cases = collections.deque(cases)
        self.lock = threading.Lock()

    def take(self):
        """The next case, or None."""
        with self.lock:
            return self.cases.popleft() if self.cases else None

    def give_back(self, cases):
        """Decks a dead process did not start: first in line again."""
        with self.lock:
            self.cases.extendleft(reversed(cases))

    def drain(self):
        with self.lock:
            left = list(self.cases)
            self.cases.clear()
            return left


def misses_of(line):
    """How many EXPECT cards a result line says missed their RTOL (their lines follow it)."""
    match = EXPECTS.search(line)
    return int(match.group(2)) - int(match.group(1)) if match else 0


def complete(folder):
    return all(os.path.isfile(os.path.join(folder, name)) for name in batch.CASE_FILES)


class Workers:
    """`jobs` worker threads running the cases added to them (`add`), one visco2d process each.
    A case that ends (its result, error or not_run) is announced to `ended()`; `close()` lets the
    workers end once the queue is empty; `interrupt()` (Ctrl-C) stops them: no further process
    starts, the running ones are sent SIGINT, what had not ended is `not_run`."""

    def __init__(self, out, exe, jobs, progress, stage=None):
        self.out, self.exe, self.progress, self.stage = out, exe, progress, stage
        self.root = stage or out
        self.queue = Queue([])
        self.stop = threading.Event()
        self.running = set()
        self.guard = threading.Lock()
        self.changed = threading.Condition()      # a case added or ended, or the queue closed
        self.closed = False
        self.done = collections.deque()           # the cases ended since the last ended()
        self.environment = dict(os.environ, **runner.ONE_THREAD,        # one thread a process: a worker a core
                                GFORTRAN_UNBUFFERED_PRECONNECTED='y')   # each line as written
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

    def next_case(self):
        """The next case to run, waiting for one to be added; None once the queue is closed and
        empty, or on an interrupt."""
        with self.changed:
            while not self.stop.is_set():
                case = self.queue.take()
                if case is not None:
                    return case
                if self.closed:
                    return None
                self.changed.wait(0.2)
            return None

    def worker(self):
        while not self.stop.is_set():
            case = self.next_case()
            if case is None:
                return
            self.queue.give_back(self.run_process(case))

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

    def start(self):
        """A `visco2d --decks-from -` process (None and the message if it cannot start)."""
        with self.guard:
            if self.stop.is_set():
                return None, None
            try:
                process = subprocess.Popen([self.exe, '-o', self.root, '--decks-from', '-'],
                                           stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                           stderr=subprocess.STDOUT, text=True, env=self.environment)
            except OSError as error:
                return None, f'cannot run {self.exe}: {error.strerror}'
            self.running.add(process)
            return process, None

    def run_process(self, first):
        """One visco2d process, fed `first` and then the queue's cases until it is closed and empty
        (or an interrupt); returns the cases it was given but did not start (to run again)."""
        process, message = self.start()
        if process is None:
            if message is None:
                first.not_run = True
            else:
                first.error = message
            self.end(first, '')
            return []
        flight = collections.deque()     # the decks written to it that have not ended; the first is running
        own = []                         # the running deck's lines so far (warnings, notes)
        missed = None                    # (case, result line, misses to come, their lines): a deck that missed EXPECTs

        def send(case):
            flight.append(case)
            try:
                process.stdin.write(case.deck + '\n')
                process.stdin.flush()
            except OSError:              # it has died: its output ends, and the case goes back
                pass

        send(first)
        while True:
            while len(flight) < AHEAD and not self.stop.is_set():
                case = self.queue.take()
                if case is None:
                    break
                send(case)
            if not flight and missed is None:
                case = self.next_case()      # idle until a case is added, or the end
                if case is None:
                    break
                send(case)
                continue
            line = process.stdout.readline()
            if not line:
                break                        # the process has ended: died, or interrupted
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
            if flight and line.startswith(flight[0].name + ': ') and RESULT.match(line[len(flight[0].name) + 2:]):
                case = flight.popleft()
                own = []
                misses = misses_of(line)
                if misses:
                    missed = (case, line, misses, [])
                else:
                    self.end(case, line)
            elif flight and line.startswith(ERROR):
                case = flight.popleft()
                case.error = batch.located_error('\n'.join(own + [line]))
                own = []
                self.end(case, '')
            else:
                own.append(line)
        try:
            process.stdin.close()            # no more decks: it ends after the last
        except OSError:
            pass
        for line in process.stdout:          # its closing lines ("N of M decks failed")
            own.append(line.rstrip('\n'))
        status = process.wait()
        with self.guard:
            self.running.discard(process)
        if missed is not None:
            case, result, _, lines = missed
            case.missed = batch.located_error('\n'.join(lines)) if lines else 'outside the RTOL of its EXPECT card(s)'
            self.end(case, result)
        if not flight:
            return []
        if status == 2:                  # a usage error or an unusable root, before any deck ran: every deck's
            message = batch.located_error('\n'.join(own))
            for case in flight:
                case.error = message
                self.end(case, '')
            return []
        case, rest = flight[0], list(flight)[1:]
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


def run_local(cases, out, exe, jobs, progress, stage=None, prepare=None, records=None):
    """The cases on `jobs` workers (batch.run_local's contract): each case ends with its
    folder in OUT (moved there from `stage`, a shard's own root), or its error, or `not_run`
    after an interrupt, which raises batch.Interrupted once the running processes have ended.
    Each case is queued once `prepare(case)` has written its deck, so the first ones run while
    the rest are written; then `records()`."""
    workers = Workers(out, exe, min(jobs, max(1, len(cases))), progress, stage)
    queued = 0
    try:
        with batch.interrupts_raised():
            for case in cases:
                if prepare is not None:
                    prepare(case)
                workers.add([case])
                queued += 1
            workers.close()
            if records is not None:
                records()
            workers.join()
    except KeyboardInterrupt:
        for case in cases[queued:]:
            case.not_run = True
        workers.close()
        workers.interrupt()
        raise batch.Interrupted(cases) from None
