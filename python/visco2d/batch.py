"""visco2d-batch: parameter sweeps, batches on every core or a cluster, tables, thresholds.

  visco2d-batch run [options] DECK...        run decks (templates expanded by a sweep)
  visco2d-batch expand [options] DECK...     write the expanded decks only, list them
  visco2d-batch collect OUT [--keys K,...]   the table of whatever cases OUT holds
  visco2d-batch threshold TEMPLATE --param NAME=LO:HI --when 'KEY>VALUE' --tol T
                                             onset of a condition by bisection
  visco2d-batch boundary TEMPLATE --param NAME=LO:HI --param FRUIT=v1,v2 --surface NAME=CARDS ...
                                             a threshold per fruit and surface: table and chart

A deck is a template when it holds `${name}` placeholders (string.Template);
a sweep gives their values: `--param name=v1,v2,...` (a list),
`--param name=a:b:n` (n evenly spaced values from a to b), `--table rows.csv`
(one case per row, a column per parameter), `--sweep file.toml` (the same in
a file). The axes (every --param, the table's rows) are combined as their
product (default) or zipped (`--zip`). Every case is an ordinary deck,
OUT/decks/<case>.inp, named <deck stem>__<name>=<value>__...; it is run by the
installed visco2d into OUT/<case>/ and copied there as OUT/<case>/<case>.inp
when the run ends. The table of the batch: OUT/table.csv and OUT/table.md.

Exit status: 0 every case ran, 1 a case failed or missed its own EXPECT cards
(visco2d exit 3: its results are written, its table row says `missed`; or no
onset in a bracket), 2 a usage error (nothing run), 130 interrupted (Ctrl-C:
the cases that finished are kept, the table says which did not run; `--resume`
runs those). Details: doc/batch.md.
"""

import argparse
import csv
import json
import math
import os
import re
import shlex
import shutil
import signal
import string
import subprocess
import sys
import threading
import time

from . import runner
from .case import missed_expectations, read_summary
from .runner import located_error

PROGRAM = 'visco2d-batch'
DEFAULT_KEYS = ['alpha_max_mm', 't_alpha_max_ms', 'q_max_MPa', 'force_max_N', 'contact_radius_max_mm',
                'envelope_max_shear_max_Pa', 'bruise_volume_cm3', 'coefficient_of_restitution', 'warnings']
MAX_NAME = 150          # longer case names fall back to <stem>__case=<index>
EXPECT_MISSED = 3        # visco2d's exit status: the deck ran (results written) and missed its own EXPECT cards
DECKS_DIR = 'decks'     # OUT/decks/: the expanded decks, their parameters, the errors of failed cases
MAX_CASES = 10000        # a larger sweep is refused unless --max-cases allows it
CASE_FILES = ('summary.txt', 'history.csv', 'listing.txt', 'results.h5', 'results.xmf')   # of every case folder


class UsageError(Exception):
    """Bad command line, sweep or template: exit 2 before anything runs."""


class Interrupted(Exception):
    """SIGINT (Ctrl-C) or SIGTERM during the runs: the cases that finished are kept; `cases` are the batch's."""

    def __init__(self, cases):
        super().__init__('interrupted')
        self.cases = cases


# ---------------------------------------------------------------- sweeps and templates

def format_number(value):
    """A short decimal of a generated value (ranges, bisection points): 10 significant digits."""
    text = '%.10g' % value
    return '0' if text in ('-0', '0') else text


def parse_values(name, text, where, limit=None):
    """The values of one --param: a list v1,v2,... or a range a:b:n (n values, a and b included).
    A range of more than `limit` values is refused before it is made."""
    text = text.strip()
    if ':' in text and ',' not in text:
        fields = text.split(':')
        if len(fields) != 3:
            raise UsageError(f'{where}: {name}: a range is START:STOP:COUNT, got "{text}"')
        try:
            start, stop = float(fields[0]), float(fields[1])
            count = int(fields[2])
        except ValueError:
            raise UsageError(f'{where}: {name}: a range is START:STOP:COUNT (numbers, COUNT an integer), '
                             f'got "{text}"') from None
        if count < 1 or not (math.isfinite(start) and math.isfinite(stop)):
            raise UsageError(f'{where}: {name}: a range needs finite ends and COUNT >= 1, got "{text}"')
        if limit is not None and count > limit:
            raise UsageError(too_many(f'{where}: {name}: a range of {count} values', limit))
        if count == 1:
            return [format_number(start)]
        return [format_number(start + (stop - start) * k / (count - 1)) for k in range(count)]
    values = [value.strip() for value in text.split(',')]
    if not text or any(not value for value in values):
        raise UsageError(f'{where}: {name}: empty value in "{text}"')
    return values


def too_many(what, limit):
    return (f'{what} makes more than the {limit} cases a sweep may have; nothing was expanded or run '
            f'(give --max-cases N to allow up to N cases)')


def check_name(name, where):
    if not re.fullmatch(r'[A-Za-z_][A-Za-z0-9_]*', name):
        raise UsageError(f'{where}: "{name}" is not a parameter name (letters, digits, _)')
    return name


def check_value(name, value, where):
    if '\n' in value or '\r' in value or '$' in value:
        raise UsageError(f'{where}: {name}: a value may not hold a line break or "$", got {value!r}')
    return value


def param_axis(spec, where='--param', limit=None):
    """One --param NAME=VALUES as an axis: a list of {name: value} points."""
    if '=' not in spec:
        raise UsageError(f'{where}: expected NAME=VALUES, got "{spec}"')
    name, text = spec.split('=', 1)
    name = check_name(name.strip(), where)
    return [{name: check_value(name, value, where)} for value in parse_values(name, text, f'{where} {name}', limit)]


def table_axis(path):
    """The rows of a CSV table (a header of parameter names; an optional `case` column names the case)."""
    try:
        with open(path, newline='') as handle:
            rows = list(csv.reader(handle))
    except OSError as error:
        raise UsageError(f'{path}: cannot read the table: {error.strerror}') from None
    rows = [row for row in rows if any(cell.strip() for cell in row)]
    if len(rows) < 2:
        raise UsageError(f'{path}: a table needs a header of parameter names and at least one row')
    header = [cell.strip() for cell in rows[0]]
    for name in header:
        if name != 'case':
            check_name(name, f'{path}:1')
    if len(set(header)) != len(header):
        raise UsageError(f'{path}:1: a column name appears twice')
    axis = []
    for number, row in enumerate(rows[1:], start=2):
        if len(row) != len(header):
            raise UsageError(f'{path}:{number}: {len(row)} cells, the header has {len(header)}')
        point = {}
        for name, cell in zip(header, row):
            point[name] = check_value(name, cell.strip(), f'{path}:{number}')
            if not point[name]:
                raise UsageError(f'{path}:{number}: {name}: empty cell')
        axis.append(point)
    return axis


def sweep_file(path, limit=None):
    """A TOML sweep: [param] name = [values] or "a:b:n"; table = "rows.csv"; zip = true; keys = [...]."""
    import tomllib
    try:
        with open(path, 'rb') as handle:
            data = tomllib.load(handle)
    except OSError as error:
        raise UsageError(f'{path}: cannot read the sweep: {error.strerror}') from None
    except tomllib.TOMLDecodeError as error:
        raise UsageError(f'{path}: not TOML: {error}') from None
    known = {'param', 'table', 'zip', 'keys', 'decks'}
    for key in data:
        if key not in known:
            raise UsageError(f'{path}: unknown entry "{key}" (known: {", ".join(sorted(known))})')
    kinds = {'param': (dict, 'a table: [param] then name = [values] or name = "START:STOP:COUNT" lines'),
             'table': (str, 'a file name in quotes, table = "rows.csv"'),
             'zip': (bool, 'true or false'),
             'keys': (list, 'a list of summary keys, keys = ["alpha_max_mm"]'),
             'decks': (list, 'a list of deck files, decks = ["peach.inp"]')}
    for key, (kind, expected) in kinds.items():
        if key in data and not isinstance(data[key], kind):
            raise UsageError(f'{path}: {key}: expected {expected}, got {data[key]!r}')
    if not all(isinstance(deck, str) for deck in data.get('decks', [])):
        raise UsageError(f'{path}: decks: expected {kinds["decks"][1]}, got {data["decks"]!r}')
    base = os.path.dirname(path)
    axes = []
    for name, values in data.get('param', {}).items():
        check_name(name, f'{path}: [param]')
        if isinstance(values, list):
            texts = [value if isinstance(value, str) else repr(value) for value in values]
            if not texts:
                raise UsageError(f'{path}: [param] {name}: no values')
            axes.append([{name: check_value(name, text, f'{path}: [param]')} for text in texts])
        elif isinstance(values, (str, int, float)) and not isinstance(values, bool):
            axes.append(param_axis(f'{name}={values}', f'{path}: [param]', limit))
        else:
            raise UsageError(f'{path}: [param] {name}: a list of values or "START:STOP:COUNT"')
    if 'table' in data:
        axes.append(table_axis(os.path.join(base, data['table'])))
    decks = [os.path.join(base, deck) for deck in data.get('decks', [])]
    keys = data.get('keys')
    if keys is not None and not (isinstance(keys, list) and all(isinstance(key, str) for key in keys)):
        raise UsageError(f'{path}: keys: a list of summary keys')
    return axes, bool(data.get('zip', False)), keys, decks


def combine(axes, zipped):
    """The points of a sweep: the product of the axes or, zipped, their rows side by side."""
    if not axes:
        return [{}]
    if zipped:
        lengths = {len(axis) for axis in axes}
        if len(lengths) != 1:
            raise UsageError(f'--zip: the axes have different lengths {sorted(len(a) for a in axes)}')
        points = [dict() for _ in axes[0]]
        for axis in axes:
            for point, entry in zip(points, axis):
                point.update(entry)
        return points
    points = [{}]
    for axis in axes:
        points = [dict(point, **entry) for point in points for entry in axis]
    return points


def placeholders(path, text):
    """Every ${name} of a template, {name: 'file:line:column'} of its first use; a stray $ is an error."""
    found = {}
    for number, line in enumerate(text.splitlines(), start=1):
        for match in string.Template.pattern.finditer(line):
            column = match.start() + 1
            if match.group('escaped') is not None:
                continue
            name = match.group('named') or match.group('braced')
            if name is None:
                raise UsageError(f'{path}:{number}:{column}: "$" not followed by a parameter '
                                 f'name in braces, ${{name}}')
            found.setdefault(name, f'{path}:{number}:{column}')
    return found


def sanitize(text):
    """A case-name fragment: letters, digits and . _ + - = kept, anything else _."""
    return re.sub(r'[^A-Za-z0-9._+=-]', '_', text)


def case_name(stem, point, index):
    if 'case' in point:
        name = sanitize(point['case'])
    else:
        name = '__'.join([sanitize(stem)] + [f'{sanitize(k)}={sanitize(v)}' for k, v in point.items()])
        if len(name) > MAX_NAME:
            name = f'{sanitize(stem)}__case={index + 1}'
    if name.startswith('.'):
        name = '_' + name[1:]
    return name


class Case:
    """One deck of a batch: its name, the deck visco2d runs, and its parameters."""

    def __init__(self, name, deck, params, text=None, source=None):
        self.name = name
        self.deck = deck          # the path visco2d is given
        self.params = params      # {name: value string}
        self.text = text          # the expanded deck's text (None: a plain deck, run where it is)
        self.source = source      # the template or plain deck it comes from
        self.index = 0
        self.error = None
        self.missed = None        # the located EXPECT misses of a run that exited 3 (its results are written)
        self.not_run = False      # interrupted before it ran or while it ran: no result, no error
        self.recorded = False     # its OUT/decks/<case>.json written by this run


def deck_stem(path):
    """visco2d's case name of a deck path: the file name without its last extension."""
    name = os.path.basename(path)
    dot = name.rfind('.')
    return name[:dot] if dot > 0 else name


def expand(decks, points, out):
    """The cases of a batch: every deck with every point (a template) or as it is (a plain deck)."""
    swept = any(points)
    cases = []
    for deck in decks:
        try:
            with open(deck) as handle:
                text = handle.read()
        except OSError as error:
            raise UsageError(f'{deck}: cannot read the deck: {error.strerror}') from None
        except UnicodeDecodeError:
            raise UsageError(f'{deck}: not a text deck') from None
        uses = placeholders(deck, text)
        stem = deck_stem(deck)
        if not uses:
            if swept:
                names = ', '.join(sorted(set(k for point in points for k in point) - {'case'}))
                raise UsageError(f'{deck}: the sweep gives {names} but the deck has no ${{name}} placeholder')
            cases.append(Case(stem, deck, {}, None, deck))
            continue
        for point in points:
            given = {k: v for k, v in point.items() if k != 'case'}
            missing = [name for name in uses if name not in given]
            if missing:
                raise UsageError(f'{uses[missing[0]]}: ${{{missing[0]}}}: no value for parameter '
                                 f'"{missing[0]}" (give --param {missing[0]}=..., a table column or a sweep entry)')
            unused = sorted(name for name in given if name not in uses)
            if unused:
                raise UsageError(f'{deck}: parameter "{unused[0]}" is given but the template has no '
                                 f'${{{unused[0]}}} (its parameters: {", ".join(uses)})')
            name = case_name(stem, point, len(cases))
            body = string.Template(text).substitute(given)
            cases.append(Case(name, os.path.join(out, DECKS_DIR, name + '.inp'), given, body, deck))
    seen = {}
    for case in cases:
        if case.name in seen:
            raise UsageError(f'two decks of the batch have the case name "{case.name}" ({seen[case.name]} and '
                             f'{case.source}): their outputs would overwrite each other in '
                             f'{os.path.join(out, case.name)}/; rename one')
        seen[case.name] = case.source
        if case.name == DECKS_DIR:
            raise UsageError(f'{case.source}: the case name "{DECKS_DIR}" is reserved for the expanded decks')
    for index, case in enumerate(cases):
        case.index = index
    return cases


def write_decks(cases, out, total):
    """OUT/decks/<case>.inp (a template's expansion or a copy of a plain deck) and <case>.json."""
    for case in cases:
        write_deck(case, out)
    write_records(cases, out, total)


def write_deck(case, out):
    """OUT/decks/<case>.inp, the deck a case runs (and no .error of an earlier run beside it)."""
    folder = os.path.join(out, DECKS_DIR)
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, case.name + '.inp')
    if case.text is not None:
        with open(path, 'w') as handle:
            handle.write(case.text)
    elif os.path.abspath(case.deck) != os.path.abspath(path):
        shutil.copyfile(case.deck, path)
    stale = os.path.join(folder, case.name + '.error')
    if os.path.exists(stale):
        os.remove(stale)


def write_records(cases, out, total):
    """OUT/decks/<case>.json (the case's index, source and parameters: the table's rows) of the
    cases that have none from this run yet."""
    folder = os.path.join(out, DECKS_DIR)
    os.makedirs(folder, exist_ok=True)
    for case in cases:
        if case.recorded:
            continue
        record = {'case': case.name, 'index': case.index, 'total': total, 'source': case.source,
                  'params': case.params}
        with open(os.path.join(folder, case.name + '.json'), 'w') as handle:
            json.dump(record, handle, indent=1)
        case.recorded = True


# ---------------------------------------------------------------- running

def find_program(explicit, variable, name, relative):
    """runner.find_program, an explicit path that is not an executable a usage error."""
    try:
        return runner.find_program(explicit, variable, name, relative)
    except FileNotFoundError as error:
        raise UsageError(str(error)) from None


class Progress:
    """cases done / total, failed, time left: one line on stderr, rewritten, when stderr is a terminal."""

    def __init__(self, total, quiet):
        self.total = total
        self.done = 0
        self.failed = 0
        self.start = time.monotonic()
        self.shown = not quiet and sys.stderr.isatty()
        self.quiet = quiet
        self.lock = threading.Lock()
        if self.shown:
            sys.stderr.write(self.line())
            sys.stderr.flush()

    def line(self):
        elapsed = time.monotonic() - self.start
        text = f'{PROGRAM}: {self.done}/{self.total} cases done, {self.failed} failed'
        if 0 < self.done < self.total:
            text += f', ~{elapsed / self.done * (self.total - self.done):.0f} s left'
        elif self.done == self.total:
            text += f', {elapsed:.1f} s'
        return text

    def update(self, case, message):
        with self.lock:
            self.done += 1
            self.failed += case.error is not None or case.missed is not None
            if self.shown:
                sys.stderr.write('\r\033[K')
            if not self.quiet:
                print(message, flush=True)
            if self.shown:
                sys.stderr.write(self.line())
                sys.stderr.flush()

    def finish(self):
        if self.shown:
            sys.stderr.write('\r\033[K' + self.line() + '\n')
            sys.stderr.flush()


def result_message(case, stdout):
    if case.error is not None:
        return f'FAILED {case.name}: {case.error}'
    if case.missed is not None:
        return f'MISSED {case.name}: {case.missed}'
    lines = [line for line in stdout.splitlines() if line.strip()]
    return lines[-1] if lines else f'{case.name}: done'


def finish_case(case, out):
    """After a run: the deck beside its results, or the error beside the deck."""
    folder = os.path.join(out, case.name)
    deck_copy = os.path.join(out, DECKS_DIR, case.name + '.inp')
    if case.error is None and not os.path.isfile(os.path.join(folder, 'summary.txt')):
        case.error = 'no summary.txt was written'
    if case.error is None:
        shutil.copyfile(deck_copy, os.path.join(folder, case.name + '.inp'))
    else:
        with open(os.path.join(out, DECKS_DIR, case.name + '.error'), 'w') as handle:
            handle.write(case.error + '\n')


def clear_case(out, case):
    """Remove an older OUT/<case>/, so a failed run never leaves a stale result in the table."""
    folder = os.path.join(out, case.name)
    if os.path.isdir(folder) and not os.path.islink(folder):
        shutil.rmtree(folder)


def run_local(cases, out, exe, jobs, progress, stage=None, prepare=None, records=None):
    """The cases on `jobs` local workers, each feeding the decks to one `visco2d -o ROOT --decks-from -`
    process (python/visco2d/workers.py: a process start costs more than a small case). With `stage`,
    into that root and then moved into OUT/ (shards on several hosts never see each other's temporary
    folders). `prepare(case)` (its deck written) is called for each case before it is queued, and
    `records()` once all are, while the first cases run. Each case ends on its own (its folder, its
    error, the progress line). On SIGINT (Ctrl-C) or SIGTERM no further case starts, the running
    processes are sent SIGINT (visco2d removes what it was writing), and Interrupted is raised once
    they have ended; a case that was never queued is `not_run`."""
    workers_module().run_local(cases, out, exe, jobs, progress, stage, prepare, records)


def workers_module():
    """visco2d.workers: the local workers (imported when first needed: it uses this module)."""
    from . import workers
    return workers


class interrupts_raised:
    """Within: SIGINT (Ctrl-C) and SIGTERM (a scheduler ending the job) are raised as
    KeyboardInterrupt. SIGINT gets the handler explicitly: a process started with SIGINT
    ignored (from a shell that runs it in the background, as `make test &` does) would
    otherwise keep ignoring it, and a Ctrl-C sent to it would run the whole queue."""

    def __enter__(self):
        self.previous = signal.signal(signal.SIGTERM, self.handler)
        self.previous_interrupt = signal.signal(signal.SIGINT, self.handler)
        return self

    @staticmethod
    def handler(number, frame):
        raise KeyboardInterrupt

    def __exit__(self, *details):
        signal.signal(signal.SIGTERM, self.previous)
        signal.signal(signal.SIGINT, self.previous_interrupt)
        return False


def run_mpi(cases, out, ranks, farm, mpirun_args, progress):
    """All cases in one `mpirun -np N visco2d-farm -o OUT DECK...`; its log in OUT/decks/mpi.log."""
    mpirun = shutil.which('mpirun')
    if mpirun is None:
        raise UsageError('--mpi: no mpirun on PATH (install OpenMPI: bash scripts/setup.sh, or load its module)')
    command = [mpirun, '-np', str(ranks)]
    if ranks > (os.cpu_count() or 1):
        command.append('--oversubscribe')
    command += shlex.split(mpirun_args or '') + [farm, '-o', out] + [case.deck for case in cases]
    environment = dict(os.environ, **runner.ONE_THREAD)     # one thread a rank: a rank a core
    if hasattr(os, 'geteuid') and os.geteuid() == 0:
        environment.setdefault('OMPI_ALLOW_RUN_AS_ROOT', '1')
        environment.setdefault('OMPI_ALLOW_RUN_AS_ROOT_CONFIRM', '1')
    if not progress.quiet:
        print(f'{PROGRAM}: {" ".join(shlex.quote(part) for part in command[:8])} ... ({len(cases)} decks)',
              flush=True)
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=environment)
    interrupted = False
    try:
        with interrupts_raised():
            stdout, stderr = process.communicate()
    except KeyboardInterrupt:          # mpirun passes SIGINT on to the ranks; after 10 s it is killed
        interrupted = True
        process.send_signal(signal.SIGINT)
        try:
            stdout, stderr = process.communicate(timeout=10)
        except subprocess.TimeoutExpired:
            process.kill()
            stdout, stderr = process.communicate()
    done = subprocess.CompletedProcess(command, process.returncode, stdout, stderr)
    with open(os.path.join(out, DECKS_DIR, 'mpi.log'), 'w') as handle:
        handle.write(f'$ {" ".join(shlex.quote(part) for part in command)}\n# exit status {done.returncode}\n'
                     f'# stdout\n{done.stdout}# stderr\n{done.stderr}')
    for case in cases:
        summary = os.path.join(out, case.name, 'summary.txt')
        if interrupted and not os.path.isfile(summary):
            case.not_run = True
            continue
        if not os.path.isfile(summary):
            case.error = located_error(done.stderr, case.deck) if case.deck in done.stderr else (
                f'no results (mpirun exit status {done.returncode}; see {out}/{DECKS_DIR}/mpi.log)')
        elif missed_expectations(read_summary(summary)):
            case.missed = located_error(done.stderr, case.deck) if case.deck in done.stderr else (
                'outside the RTOL of its EXPECT card(s): ' + ', '.join(missed_expectations(read_summary(summary))))
        finish_case(case, out)
        lines = [line for line in done.stdout.splitlines() if line.startswith(case.name + ':')]
        progress.update(case, result_message(case, lines[-1] if lines else ''))
    if interrupted:
        raise Interrupted(cases)
    if done.returncode not in (0, 1, EXPECT_MISSED):
        print(f'{PROGRAM}: mpirun exited with status {done.returncode}: see {out}/{DECKS_DIR}/mpi.log '
              f'(the cases without results are failed: {PROGRAM} run ... --resume runs only those)',
              file=sys.stderr)


def parse_shard(text):
    match = re.fullmatch(r'(\d+)/(\d+)', text or '')
    if not match or int(match.group(2)) < 1 or int(match.group(1)) >= int(match.group(2)):
        raise UsageError(f'--shard: expected K/N with 0 <= K < N (K: 0-based, as SLURM_ARRAY_TASK_ID), got "{text}"')
    return int(match.group(1)), int(match.group(2))


def execute(cases, out, options):
    """Run the cases: locally on -j processes, through the MPI farm (--mpi N), or one shard of them."""
    total = len(cases)
    if options.shard:
        shard, shards = parse_shard(options.shard)
        cases = [case for case in cases if case.index % shards == shard]
    exe = farm = None
    if options.mpi:
        farm = find_program(options.farm, 'VISCO2D_FARM', 'visco2d-farm', 'build/mpi/bin/visco2d-farm')
        if farm is None:
            raise UsageError('--mpi: the MPI task farm visco2d-farm is not built: run `make mpi` '
                             '(it builds build/mpi/bin/visco2d-farm), or give --farm PATH')
    else:
        exe = find_program(options.exe, 'VISCO2D', 'visco2d', 'build/install/bin/visco2d')
        if exe is None:
            raise UsageError('no visco2d executable: run `make build` (build/install/bin/visco2d), '
                             'or give --exe PATH')
    os.makedirs(out, exist_ok=True)
    todo = cases
    if getattr(options, 'resume', False):
        todo = [case for case in cases if not verified_result(case, out)]
        if not options.quiet:
            print(f'{PROGRAM}: --resume: {len(cases) - len(todo)} of {len(cases)} cases have a complete, '
                  f'verified result in {out}; running the other {len(todo)}', flush=True)
    progress = Progress(len(todo), options.quiet)
    prepare = records = None
    if options.mpi or not todo:
        write_decks(cases, out, total)
        for case in todo:
            clear_case(out, case)
    else:                                # locally: the first cases run while the others are written
        running = set(id(case) for case in todo)
        write_decks([case for case in cases if id(case) not in running], out, total)

        def prepare(case):
            write_deck(case, out)
            clear_case(out, case)

        def records():
            write_records(cases, out, total)
    try:
        if not todo:
            pass
        elif options.mpi:
            run_mpi(todo, out, options.mpi, farm, options.mpirun_args, progress)
        elif options.shard:
            stage = os.path.join(out, '.shard-%d-of-%d' % parse_shard(options.shard))
            os.makedirs(stage, exist_ok=True)
            try:
                run_local(todo, out, exe, options.jobs, progress, stage, prepare, records)
            finally:
                shutil.rmtree(stage, ignore_errors=True)
        else:
            run_local(todo, out, exe, options.jobs, progress, prepare=prepare, records=records)
    except Interrupted:
        progress.finish()
        write_records(cases, out, total)         # the table's rows of the cases that did not run too
        raise Interrupted(cases) from None
    progress.finish()
    return cases


def verified_result(case, out):
    """True if OUT/<case>/ holds a complete result of this very deck: every file of a case folder
    (visco2d moves a folder into place only when all are written), a summary of this case with
    its cpu_s, and the copy of the deck it ran (made when the run ended) equal to this sweep's deck."""
    folder = os.path.join(out, case.name)
    if not all(os.path.isfile(os.path.join(folder, name)) for name in CASE_FILES):
        return False
    try:
        with open(os.path.join(folder, case.name + '.inp')) as handle:
            ran = handle.read()
        if case.text is not None:
            expected = case.text
        else:
            with open(case.deck) as handle:
                expected = handle.read()
        summary = read_summary(os.path.join(folder, 'summary.txt'))
    except (OSError, UnicodeDecodeError):
        return False
    return ran == expected and summary.get('case') == case.name and 'cpu_s' in summary


# ---------------------------------------------------------------- the table


def gather(out, names=None, not_run=()):
    """Every case of OUT: the expanded decks (OUT/decks/*.json) and any case folder with a summary;
    with `names`, only those cases (a run's own; an earlier sweep into the same OUT is left out).
    The cases of `not_run` without results are `not run` (an interrupted batch)."""
    rows = {}
    folder = os.path.join(out, DECKS_DIR)
    if os.path.isdir(folder):
        for entry in os.listdir(folder):
            if entry.endswith('.json'):
                try:
                    with open(os.path.join(folder, entry)) as handle:
                        record = json.load(handle)
                    rows[record['case']] = record
                except (OSError, ValueError, KeyError):
                    continue
    for entry in os.listdir(out):
        if entry != DECKS_DIR and not entry.startswith('.') and \
                os.path.isfile(os.path.join(out, entry, 'summary.txt')):
            rows.setdefault(entry, {'case': entry, 'params': {}})
    if names is not None:
        names = set(names)
        rows = {name: record for name, record in rows.items() if name in names}
    table = []
    for name, record in rows.items():
        summary_path = os.path.join(out, name, 'summary.txt')
        error_path = os.path.join(folder, name + '.error')
        row = {'case': name, 'params': record.get('params', {}), 'index': record.get('index'),
               'summary': {}, 'status': 'ok', 'error': ''}
        if os.path.isfile(summary_path):
            row['summary'] = read_summary(summary_path)
            missed = missed_expectations(row['summary'])
            if missed:                       # it ran (visco2d exit 3): a verification deck that failed
                row['status'], row['error'] = 'missed', 'outside the RTOL of its EXPECT card(s): ' + ', '.join(missed)
        elif name in not_run:
            row['status'], row['error'] = 'not run', 'interrupted before it ended'
        elif os.path.isfile(error_path):
            with open(error_path) as handle:
                row['status'], row['error'] = 'failed', handle.read().strip()
        else:
            row['status'], row['error'] = 'missing', 'not run (or still running)'
        table.append(row)
    table.sort(key=lambda row: (row['index'] is None, row['index'] or 0, row['case']))
    return table


def short(value):
    try:
        number = float(value)
    except ValueError:
        return value
    if number == int(number) and abs(number) < 1e9 and re.fullmatch(r'-?\d+', value):
        return value
    return '%.4g' % number


def write_table(out, keys, quiet=False, names=None, not_run=()):
    """OUT/table.csv (full precision) and OUT/table.md (4 digits): case, status, parameters, keys, error;
    of the cases `names` (a run's), or of every case OUT holds (collect)."""
    rows = gather(out, names, not_run)
    params = []
    for row in rows:
        for name in row['params']:
            if name not in params:
                params.append(name)
    header = ['case', 'status'] + params + keys + ['error']
    records = []
    for row in rows:
        records.append([row['case'], row['status']] + [row['params'].get(name, '') for name in params]
                       + [row['summary'].get(key, '') for key in keys] + [row['error']])
    with open(os.path.join(out, 'table.csv'), 'w', newline='') as handle:
        writer = csv.writer(handle)
        writer.writerow(header)
        writer.writerows(records)
    failed = sum(row['status'] != 'ok' for row in rows)
    with open(os.path.join(out, 'table.md'), 'w') as handle:
        handle.write(f'# {out}: {len(rows)} cases, {failed} failed or missing\n\n')
        handle.write('| ' + ' | '.join(header) + ' |\n|' + '---|' * len(header) + '\n')
        for record in records:
            cells = record[:2 + len(params)] + [short(cell) for cell in record[2 + len(params):-1]] + [record[-1]]
            handle.write('| ' + ' | '.join(cell.replace('|', '\\|') for cell in cells) + ' |\n')
    if not quiet:
        print(f'{PROGRAM}: {len(rows)} cases, {failed} failed or missing: '
              f'{os.path.join(out, "table.csv")}, {os.path.join(out, "table.md")}')
    return rows


def parse_keys(text):
    if text is None:
        return list(DEFAULT_KEYS)
    keys = [key.strip() for key in text.split(',') if key.strip()]
    if not keys:
        raise UsageError('--keys: no key given')
    return keys


# ---------------------------------------------------------------- thresholds

CONDITION = re.compile(r'\s*([A-Za-z0-9_]+)\s*(>=|<=|>|<)\s*(\S+)\s*')


def parse_condition(text):
    match = CONDITION.fullmatch(text or '')
    if not match:
        raise UsageError(f'--when: expected KEY>VALUE (or >=, <, <=), e.g. \'bruise_volume_cm3>0\', got "{text}"')
    try:
        limit = float(match.group(3))
    except ValueError:
        raise UsageError(f'--when: "{match.group(3)}" is not a number') from None
    return match.group(1), match.group(2), limit


def holds(case, out, condition):
    key, operator, limit = condition
    summary = read_summary(os.path.join(out, case.name, 'summary.txt'))
    if key not in summary:
        raise UsageError(f'--when: the summary of {case.name} has no key "{key}" '
                         f'(see {os.path.join(out, case.name, "summary.txt")})')
    value = float(summary[key])
    return {'>': value > limit, '>=': value >= limit, '<': value < limit, '<=': value <= limit}[operator], value


def threshold(options):
    """Bisection (k-section with -j points a round) for the onset of a condition on one parameter."""
    condition = parse_condition(options.when)
    if not options.tol or options.tol <= 0:
        raise UsageError('--tol: a positive tolerance in the parameter\'s unit')
    search = None
    fixed = {}
    for spec in options.param:
        if '=' not in spec:
            raise UsageError(f'--param: expected NAME=VALUE, got "{spec}"')
        name, text = spec.split('=', 1)
        name = check_name(name.strip(), '--param')
        fields = text.split(':')
        if len(fields) == 2:
            if search:
                raise UsageError(f'--param {name}: only one parameter is searched ({search[0]} already is)')
            try:
                low, high = float(fields[0]), float(fields[1])
            except ValueError:
                raise UsageError(f'--param {name}: a bracket LOW:HIGH of numbers, got "{text}"') from None
            if not (math.isfinite(low) and math.isfinite(high) and low < high):
                raise UsageError(f'--param {name}: a bracket LOW:HIGH with LOW < HIGH, got "{text}"')
            search = (name, low, high)
        else:
            values = parse_values(name, text, f'--param {name}')
            if len(values) != 1:
                raise UsageError(f'--param {name}: the other parameters take one value each, got "{text}"')
            fixed[name] = check_value(name, values[0], '--param')
    if search is None:
        raise UsageError('threshold: give the searched parameter as --param NAME=LOW:HIGH')
    name, low, high = search
    runs = []

    def evaluate(values):
        points = [dict(fixed, **{name: format_number(value)}) for value in values]
        cases = expand([options.template], points, options.out)
        for offset, case in enumerate(cases):
            case.index = len(runs) + offset
        cases = execute(cases, options.out, options)
        results = []
        for case, point in zip(cases, points):
            if case.error is not None:
                raise RuntimeError(f'{case.name}: {case.error}')
            state, value = holds(case, options.out, condition)
            runs.append((float(point[name]), state, value, case.name))
            results.append(state)
        return results

    options.shard = None
    low_state, high_state = evaluate([low, high])
    key, operator, limit = condition
    if low_state == high_state:
        print(f'{PROGRAM}: {key} {operator} {format_number(limit)} is {str(low_state).lower()} at both ends, '
              f'{name} = {format_number(low)} and {format_number(high)}: no onset in the bracket', file=sys.stderr)
        return 1, runs
    points_per_round = max(1, options.jobs)
    rounds = 1
    while high - low > options.tol:
        step = (high - low) / (points_per_round + 1)
        values = [float(format_number(low + step * k)) for k in range(1, points_per_round + 1)]
        values = [value for value in values if low < value < high]
        if not values:
            break
        states = evaluate(values)
        rounds += 1
        switch = next((k for k, state in enumerate(states) if state == high_state), len(values))
        if any(state == low_state for state in states[switch:]):
            print(f'{PROGRAM}: warning: the condition switches more than once between {name} = '
                  f'{format_number(low)} and {format_number(high)}; following its first switch', file=sys.stderr)
        new_low = values[switch - 1] if switch > 0 else low
        new_high = values[switch] if switch < len(values) else high
        low, high = new_low, new_high
    critical = (low + high) / 2
    onset = 'true' if high_state else 'false'
    record, at_bracket, warned = boundary_module().threshold_record(name, condition, options.tol, low, high,
                                                                    critical, runs, options.out)
    print(f'{name}_critical = {format_number(critical)}'
          + boundary_module().warning_note(at_bracket, warned, len(runs)))
    print(f'bracket = [{format_number(low)}, {format_number(high)}]  ({key} {operator} {format_number(limit)} '
          f'is {onset} at {format_number(high)}, {"false" if high_state else "true"} at {format_number(low)})')
    print(f'runs = {len(runs)} ({rounds} rounds of at most {points_per_round} runs after the two ends)'
          if points_per_round > 1 else f'runs = {len(runs)}')
    for case, line in at_bracket:
        print(f'warning = {case}: {line}')
    write_table(options.out, parse_keys(options.keys) if options.keys else [key] + [
        other for other in DEFAULT_KEYS if other != key], quiet=True, names=[run[3] for run in runs])
    with open(os.path.join(options.out, 'threshold.txt'), 'w') as handle:
        handle.write(record)      # the search, its warnings and every run (boundary.threshold_record)
    return 0, runs


def boundary_module():
    """visco2d.boundary: the boundary command, the warnings of a search (imported when first needed: it uses
    this module)."""
    from . import boundary
    return boundary


# ---------------------------------------------------------------- command line

def add_run_options(parser, sweep=True):
    parser.add_argument('-o', '--out', default='out', help='output root (default: out)')
    parser.add_argument('-j', '--jobs', type=int, default=os.cpu_count() or 1,
                        help='local processes (default: all cores, %(default)s here)')
    parser.add_argument('--param', action='append', default=[], metavar='NAME=VALUES',
                        help='v1,v2,... or START:STOP:COUNT (repeatable)')
    if sweep:
        parser.add_argument('--zip', action='store_true', help='zip the axes instead of their product')
        parser.add_argument('--table', metavar='CSV', help='one case per row, a column per parameter')
        parser.add_argument('--sweep', metavar='TOML', help='a sweep file ([param], table, zip, keys, decks)')
        parser.add_argument('--shard', metavar='K/N', help='run only cases K, K+N, K+2N, ... (K from 0)')
        parser.add_argument('--mpi', type=int, metavar='N', help='run through mpirun -np N visco2d-farm')
        parser.add_argument('--farm', metavar='PATH', help='the MPI farm (default build/mpi/bin/visco2d-farm)')
        parser.add_argument('--mpirun-args', metavar='ARGS', help='more mpirun options, e.g. "--hostfile hosts"')
    if sweep:
        parser.add_argument('--resume', action='store_true',
                            help='run only the cases without a complete, verified result in OUT')
        parser.add_argument('--max-cases', type=int, default=MAX_CASES, metavar='N',
                            help='refuse a sweep of more than N cases (default %(default)s; 0: no limit)')
    parser.add_argument('--keys', metavar='K1,K2', help='summary keys of the table (default: '
                        + ','.join(DEFAULT_KEYS) + ')')
    parser.add_argument('--exe', metavar='PATH', help='visco2d (default: beside this tool, build/install/bin)')
    parser.add_argument('-q', '--quiet', action='store_true', help='no line per case, no progress')


def build_parser():
    parser = argparse.ArgumentParser(prog=PROGRAM, description=__doc__.split('\n\n')[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog='doc/batch.md: the sweeps, the cluster recipe, the threshold command')
    commands = parser.add_subparsers(dest='command', required=True)
    run = commands.add_parser('run', help='run decks, templates expanded by a sweep')
    run.add_argument('decks', nargs='*', metavar='DECK')
    add_run_options(run)
    expand_command = commands.add_parser('expand', help='write the expanded decks, list them, run nothing')
    expand_command.add_argument('decks', nargs='*', metavar='DECK')
    add_run_options(expand_command)
    collect = commands.add_parser('collect', help='OUT/table.csv and table.md of the cases OUT holds')
    collect.add_argument('out', metavar='OUT')
    collect.add_argument('--keys', metavar='K1,K2')
    collect.add_argument('-q', '--quiet', action='store_true')
    search = commands.add_parser('threshold', help='bisection for the onset of a condition on one parameter')
    search.add_argument('template', metavar='TEMPLATE')
    search.add_argument('--when', required=True, metavar="'KEY>VALUE'", help='>, >=, < or <= on a summary key')
    search.add_argument('--tol', type=float, required=True, help='final bracket width (parameter unit)')
    add_run_options(search, sweep=False)
    search.set_defaults(jobs=1, mpi=None, farm=None, mpirun_args=None, shard=None, resume=False)
    boundary_module().add_parser(commands)
    return parser


def check_axes(axes, zipped, limit):
    """Refuse a parameter given by two axes (the later one would replace the earlier's values)
    and, before anything is expanded, a sweep of more than `limit` cases."""
    given = {}
    for axis, where in axes:
        for name in dict.fromkeys(key for point in axis for key in point):
            if name in given:
                raise UsageError(f'{where}: the parameter "{name}" is already given by {given[name]}: '
                                 f'give each parameter once (one --param with all its values, v1,v2,...)')
            given[name] = where
    lengths = [len(axis) for axis, _ in axes]
    count = (max(lengths) if zipped else math.prod(lengths)) if lengths else 1
    if limit and count > limit:
        shape = ' x '.join(str(length) for length in lengths)
        raise UsageError(too_many(f'the sweep ({shape} values{" zipped" if zipped else ""}) has {count} cases '
                                  f'per deck and', limit))


def sweep_cases(options):
    limit = options.max_cases
    if limit is not None and limit < 0:
        raise UsageError(f'--max-cases: 0 (no limit) or more, got {limit}')
    axes = [(param_axis(spec, limit=limit), f'--param {spec.split("=", 1)[0].strip()}') for spec in options.param]
    zipped, keys, decks = options.zip, options.keys, list(options.decks)
    if options.table:
        axes.append((table_axis(options.table), f'--table {options.table}'))
    if options.sweep:
        file_axes, file_zip, file_keys, file_decks = sweep_file(options.sweep, limit)
        axes += [(axis, options.sweep) for axis in file_axes]
        zipped = zipped or file_zip
        decks += file_decks
        if keys is None and file_keys:
            keys = ','.join(file_keys)
    check_axes(axes, zipped, limit)
    axes = [axis for axis, _ in axes]
    if not decks:
        raise UsageError('no deck given')
    if options.jobs < 1:
        raise UsageError(f'-j: at least 1, got {options.jobs}')
    if options.mpi is not None and options.mpi < 1:
        raise UsageError(f'--mpi: at least 1 rank, got {options.mpi}')
    if options.shard:
        parse_shard(options.shard)
    return expand(decks, combine(axes, zipped), options.out), parse_keys(keys)


def report_interrupt(cases, options, keys):
    """After Ctrl-C (or SIGTERM): the table of the cases as they are, what did not run; exit 130."""
    not_run = [case.name for case in cases if case.not_run]
    if not options.shard:
        write_table(options.out, keys, True, names=[case.name for case in cases], not_run=set(not_run))
    shown = ', '.join(not_run[:10]) + (f', ... ({len(not_run) - 10} more)' if len(not_run) > 10 else '')
    table = '' if options.shard else f' (their table: {os.path.join(options.out, "table.csv")})'
    print(f'{PROGRAM}: interrupted: {len(cases) - len(not_run)} of {len(cases)} cases ended{table}; '
          f'{len(not_run)} did not run{": " + shown if not_run else ""}. The same command with --resume '
          f'runs only those', file=sys.stderr)
    return 130


def main(argv=None):
    options = build_parser().parse_args(argv)
    try:
        if options.command == 'collect':
            if not os.path.isdir(options.out):
                raise UsageError(f'{options.out}: no such output folder')
            rows = write_table(options.out, parse_keys(options.keys), options.quiet)
            return 1 if any(row['status'] != 'ok' for row in rows) else 0
        if options.command == 'threshold':
            parse_keys(options.keys)
            if options.jobs < 1:
                raise UsageError(f'-j: at least 1, got {options.jobs}')
            status, _ = threshold(options)
            return status
        if options.command == 'boundary':
            return boundary_module().boundary(options)
        cases, keys = sweep_cases(options)
        if options.command == 'expand':
            write_decks(cases, options.out, len(cases))
            for case in cases:
                print(os.path.join(options.out, DECKS_DIR, case.name + '.inp'))
            return 0
        try:
            cases = execute(cases, options.out, options)
        except Interrupted as stopped:
            return report_interrupt(stopped.cases, options, keys)
        if options.shard:
            if not options.quiet:
                print(f'{PROGRAM}: shard {options.shard}: {len(cases)} cases; the table: '
                      f'{PROGRAM} collect {options.out}')
        else:
            write_table(options.out, keys, options.quiet, names=[case.name for case in cases])
        return 1 if any(case.error is not None or case.missed is not None for case in cases) else 0
    except UsageError as error:
        print(f'{PROGRAM}: error: {error}', file=sys.stderr)
        return 2
    except RuntimeError as error:
        print(f'{PROGRAM}: error: {error}', file=sys.stderr)
        return 1
    except Interrupted as stopped:     # a threshold search: the runs that ended keep their folders
        ended = sum(not case.not_run for case in stopped.cases)
        print(f'{PROGRAM}: interrupted: {ended} of the {len(stopped.cases)} runs of this round ended', file=sys.stderr)
        return 130
    except KeyboardInterrupt:
        print(f'{PROGRAM}: interrupted', file=sys.stderr)
        return 130


if __name__ == '__main__':
    sys.exit(main())
