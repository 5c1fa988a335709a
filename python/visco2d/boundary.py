"""visco2d-batch boundary: the damage boundary, a threshold search per fruit and surface.

  visco2d-batch boundary TEMPLATE --param height=LOW:HIGH --when 'bruise_volume_cm3>0' --tol T \\
      --param radius=0.025,0.03,0.035 --surface steel=none --surface 'foam=MATERIAL ...; PAD ...' -o OUT

Every point of the fruit grid (the product of the --param lists) on every surface is one
threshold search of the searched parameter (the one given as LOW:HIGH), the same bisection
(k-section) as `visco2d-batch threshold`; the searches run side by side on one set of -j workers
(python/visco2d/workers.py), each search's next round queued as soon as its last has ended.
A surface is the card text put in the template's line holding ${surface} alone (`none`:
nothing, no PAD card; `@FILE`: the cards of a file; `;` separates cards on the command line; a
${surface} elsewhere, in the TITLE say, is the surface's name) or a named set of parameter
values (`NAME:pad_t=0.01,pad_e=2e6`) for a template with its own placeholders. Writes
OUT/boundary.csv, OUT/boundary.txt, OUT/boundary.png (matplotlib) and each search's record
OUT/searches/<search>.txt (threshold.txt's format). doc/batch.md.

Imported by visco2d.batch when a command needs it; it uses batch's sweeps, decks, workers and tables.
"""

import csv
import math
import os
import re
import sys
import textwrap

from . import batch

SURFACE = 'surface'                     # the template's placeholder for a surface's cards
TEMPLATES_DIR = 'templates'             # OUT/templates/<stem>__surface=<name>.inp: the template of each surface
SEARCHES_DIR = 'searches'               # OUT/searches/<search>.txt: each search's record
LOCATION = re.compile(r'^\S+?:\d+(?::\d+)?: ')         # "deck.inp:19: " before a warning's card
EXPONENT = re.compile(r'[-+]?\d+\.\d+E[-+]\d+')        # visco2d's 3.2541E+01 in a warning


# ---------------------------------------------------------------- warnings of runs

def run_warnings(out, name):
    """The warning lines of a case's summary, without the deck's location, numbers to 3 digits."""
    summary = batch.read_summary(os.path.join(out, name, 'summary.txt'))
    count = int(summary.get('warnings', '0') or 0)
    lines = []
    for k in range(1, count + 1):
        text = summary.get(f'warning_{k}', '')
        text = LOCATION.sub('', text)
        lines.append(EXPONENT.sub(lambda match: '%.3g' % float(match.group(0)), text))
    return lines


def search_warnings(out, runs, low, high):
    """(the warnings of the runs at the bracket's ends, how many runs of the search warned)."""
    at_bracket = []
    warned = 0
    for value, _, _, name in runs:
        lines = run_warnings(out, name)
        warned += bool(lines)
        if value in (low, high):
            at_bracket += [(name, line) for line in lines]
    return at_bracket, warned


def warning_note(at_bracket, warned, total):
    """The words the result line of a search carries when its runs warned ('' when none did)."""
    if at_bracket:
        return (f'  (warned: {len(at_bracket)} warning(s) in the runs at the bracket, see the warning lines; '
                f'{warned} of the {total} runs warned)')
    if warned:
        return f'  ({warned} of the {total} runs warned, none at the bracket)'
    return ''


def threshold_record(name, condition, tol, low, high, critical, runs, out):
    """The text of threshold.txt: the search, its bracket, its warnings and every run."""
    key, operator, limit = condition
    fmt = batch.format_number
    at_bracket, warned = search_warnings(out, runs, low, high)
    text = (f'parameter = {name}\ncondition = {key} {operator} {fmt(limit)}\ntolerance = {fmt(tol)}\n'
            f'critical = {fmt(critical)}\nbracket_low = {fmt(low)}\nbracket_high = {fmt(high)}\n'
            f'runs = {len(runs)}\n')
    if warned:
        text += f'warnings = {len(at_bracket)}\nwarned_runs = {warned}\n'
        text += ''.join(f'warning = {case}: {line}\n' for case, line in at_bracket)
    for value, state, key_value, case in runs:
        count = len(run_warnings(out, case))
        text += (f'run = {fmt(value)} {key}={key_value:.10g} {str(state).lower()} {case}'
                 + (f' warnings={count}' if count else '') + '\n')
    return text, at_bracket, warned


# ---------------------------------------------------------------- surfaces

class Surface:
    """A surface: its name, the cards for ${surface} (None: a parameter set) and its parameters."""

    def __init__(self, name, cards, params):
        self.name, self.cards, self.params = name, cards, params


def parse_surface(spec):
    """NAME=none | NAME=@FILE | NAME=CARD; CARD... | NAME:PARAM=VALUE,PARAM=VALUE,..."""
    match = re.fullmatch(r'([A-Za-z0-9_.+-]+)([=:])(.*)', spec, re.S)
    if not match:
        raise batch.UsageError(f'--surface: expected NAME=CARDS, NAME=none, NAME=@FILE or NAME:PARAM=VALUE,..., '
                               f'got "{spec}" (a name of letters, digits and . _ + -)')
    name, kind, text = match.groups()
    if kind == ':':
        params = {}
        for item in text.split(','):
            if '=' not in item:
                raise batch.UsageError(f'--surface {name}: expected PARAM=VALUE,..., got "{text}"')
            key, value = (part.strip() for part in item.split('=', 1))
            batch.check_name(key, f'--surface {name}')
            params[key] = batch.check_value(key, value, f'--surface {name}')
        return Surface(name, None, params)
    text = text.strip()
    if text.lower() == 'none':
        return Surface(name, '', {})
    if text.startswith('@'):
        try:
            with open(text[1:]) as handle:
                cards = handle.read()
        except OSError as error:
            raise batch.UsageError(f'--surface {name}: {text[1:]}: cannot read the cards: {error.strerror}') from None
    else:
        cards = '\n'.join(card.strip() for card in text.split(';'))
    if not cards.strip():
        raise batch.UsageError(f'--surface {name}: no cards (give `{name}=none` for the bare plate)')
    if '$' in cards:
        raise batch.UsageError(f'--surface {name}: the cards may not hold "$"')
    return Surface(name, cards.rstrip('\n'), {})


def surface_templates(template, surfaces, out):
    """OUT/templates/<stem>__surface=<name>.inp: the template with each surface's cards in ${surface}."""
    try:
        with open(template) as handle:
            text = handle.read()
    except OSError as error:
        raise batch.UsageError(f'{template}: cannot read the template: {error.strerror}') from None
    uses = batch.placeholders(template, text)
    stem = batch.deck_stem(template)
    paths = []
    for surface in surfaces:
        if surface.cards is not None and SURFACE not in uses:
            raise batch.UsageError(f'{template}: --surface {surface.name} gives cards but the template has no '
                                   f'${{{SURFACE}}} line to put them in (put ${{{SURFACE}}} on a line of its own '
                                   f'after the PLATE card)')
        if surface.cards is None and SURFACE in uses:
            raise batch.UsageError(f'{uses[SURFACE]}: ${{{SURFACE}}}: --surface {surface.name} gives parameters, '
                                   f'not the cards this placeholder needs (NAME=CARDS or NAME=none)')
        body = text
        if surface.cards is not None:     # a line of its own: the cards; anywhere else (a title): the name
            alone = re.compile(r'^[ \t]*\$(\{' + SURFACE + r'\}|' + SURFACE + r'\b)[ \t]*$', re.M)
            if not alone.search(text):
                raise batch.UsageError(f'{uses[SURFACE]}: ${{{SURFACE}}}: the cards of --surface {surface.name} '
                                       f'need a line holding ${{{SURFACE}}} alone')
            body = alone.sub(lambda _: surface.cards, text)
            body = re.sub(r'\$(\{' + SURFACE + r'\}|' + SURFACE + r'\b)', lambda _: surface.name, body)
        named = f'__{SURFACE}={batch.sanitize(surface.name)}' if surface.name else ''   # '': no --surface
        path = os.path.join(out, TEMPLATES_DIR, f'{stem}{named}.inp')
        paths.append((path, body))
    if SURFACE in uses and not surfaces:
        raise batch.UsageError(f'{uses[SURFACE]}: ${{{SURFACE}}}: give the surfaces, --surface NAME=CARDS '
                               f'(--surface steel=none: no PAD card)')
    return paths


# ---------------------------------------------------------------- one search

class Search:
    """One threshold search: the bisection (k-section, `points` a round) of batch.threshold,
    driven from outside: `propose()` the values of the next round, `receive()` their results."""

    def __init__(self, template, surface, fruit, fixed, name, low, high, tol, points):
        self.template, self.surface, self.fruit = template, surface, fruit
        self.fixed = fixed                # every parameter but the searched one, in threshold's order
        self.name, self.low, self.high, self.tol, self.points = name, low, high, tol, points
        self.runs = []                    # (value, state, key value, case), as threshold's
        self.low_state = self.high_state = None
        self.rounds = 0
        self.status = 'running'           # ok | holds at both ends | holds at neither end | failed: ...
        self.pending = []
        self.switched_back = False
        self.reported = False
        self.at_bracket, self.warned = [], 0
        self.round, self.waiting = [], set()   # the cases of the round running, those not ended
        self.label = batch.sanitize('__'.join([batch.deck_stem(template)] +
                                              [f'{k}={v}' for k, v in fixed.items()]))

    def propose(self):
        if self.status != 'running':
            return []
        if self.low_state is None:
            self.pending = [self.low, self.high]
            return self.pending
        if self.high - self.low <= self.tol:
            self.status = 'ok'
            return []
        step = (self.high - self.low) / (self.points + 1)
        values = [float(batch.format_number(self.low + step * k)) for k in range(1, self.points + 1)]
        self.pending = [value for value in values if self.low < value < self.high]
        if not self.pending:
            self.status = 'ok'
        return self.pending

    def receive(self, results):
        """results: (state, key value, case name) of each proposed value, in order."""
        for value, (state, key_value, case) in zip(self.pending, results):
            self.runs.append((value, state, key_value, case))
        states = [state for state, _, _ in results]
        if self.low_state is None:
            self.low_state, self.high_state = states
            self.rounds = 1
            if self.low_state == self.high_state:
                self.status = 'holds at both ends' if self.high_state else 'holds at neither end'
            return
        self.rounds += 1
        values = self.pending
        switch = next((k for k, state in enumerate(states) if state == self.high_state), len(values))
        if any(state == self.low_state for state in states[switch:]):
            self.switched_back = True
        new_low = values[switch - 1] if switch > 0 else self.low
        new_high = values[switch] if switch < len(values) else self.high
        self.low, self.high = new_low, new_high

    @property
    def critical(self):
        return (self.low + self.high) / 2 if self.status == 'ok' else None


# ---------------------------------------------------------------- the command

def add_parser(commands):
    """The `boundary` subcommand of visco2d-batch."""
    parser = commands.add_parser('boundary', help='the damage boundary: a threshold search per fruit and surface, '
                                                  'a table and a chart')
    parser.add_argument('template', metavar='TEMPLATE')
    parser.add_argument('--when', required=True, metavar="'KEY>VALUE'", help='>, >=, < or <= on a summary key')
    parser.add_argument('--tol', type=float, required=True, help='final bracket width (parameter unit)')
    parser.add_argument('--surface', action='append', default=[], metavar='NAME=CARDS',
                        help='a surface: NAME=none (no PAD card), NAME=@FILE, NAME="CARD; CARD" (into the '
                             "template's ${surface}) or NAME:PARAM=VALUE,... (repeatable)")
    parser.add_argument('--x', metavar='NAME', help="the chart's x axis: a fruit parameter (default: the first "
                                                    'with several values)')
    parser.add_argument('--x-scale', type=float, default=1.0, metavar='F', help='x values times F on the chart '
                                                                              '(1000: m to mm)')
    parser.add_argument('--x-label', metavar='TEXT', help="the chart's x label (default: the parameter's name)")
    parser.add_argument('--y-label', metavar='TEXT', help="the chart's y label")
    parser.add_argument('--title', metavar='TEXT', help="the chart's title")
    parser.add_argument('--resume', action='store_true', help='reuse the runs OUT holds with a verified result')
    batch.add_run_options(parser, sweep=False)
    parser.set_defaults(jobs=os.cpu_count() or 1, mpi=None, farm=None, mpirun_args=None, shard=None)
    return parser


def parse_grid(options):
    """(searched (name, low, high), the fruit axes [(name, [values])] in order, the fixed parameters)."""
    search = None
    axes = []
    for spec in options.param:
        if '=' not in spec:
            raise batch.UsageError(f'--param: expected NAME=VALUES, got "{spec}"')
        name, text = spec.split('=', 1)
        name = batch.check_name(name.strip(), '--param')
        if any(name == axis for axis, _ in axes) or (search and search[0] == name):
            raise batch.UsageError(f'--param {name}: the parameter is given twice')
        fields = text.split(':')
        if len(fields) == 2:
            if search:
                raise batch.UsageError(f'--param {name}: only one parameter is searched ({search[0]} already is)')
            try:
                low, high = float(fields[0]), float(fields[1])
            except ValueError:
                raise batch.UsageError(f'--param {name}: a bracket LOW:HIGH of numbers, got "{text}"') from None
            if not (math.isfinite(low) and math.isfinite(high) and low < high):
                raise batch.UsageError(f'--param {name}: a bracket LOW:HIGH with LOW < HIGH, got "{text}"')
            search = (name, low, high)
        else:
            values = batch.parse_values(name, text, f'--param {name}', options.max_searches)
            axes.append((name, [batch.check_value(name, value, '--param') for value in values]))
    if search is None:
        raise batch.UsageError('boundary: give the searched parameter as --param NAME=LOW:HIGH')
    return search, axes


def boundary(options):
    """Run every search of the grid; write the table and the chart. The exit status."""
    condition = batch.parse_condition(options.when)
    if not options.tol or options.tol <= 0:
        raise batch.UsageError('--tol: a positive tolerance in the parameter\'s unit')
    if options.jobs < 1:
        raise batch.UsageError(f'-j: at least 1, got {options.jobs}')
    keys = batch.parse_keys(options.keys) if options.keys else None
    options.max_searches = 1000
    (name, low, high), axes = parse_grid(options)
    surfaces = [parse_surface(spec) for spec in options.surface] or [Surface('', None, {})]
    if len({surface.name for surface in surfaces}) != len(surfaces):
        raise batch.UsageError('--surface: two surfaces have one name')
    fruits = batch.combine([[{axis: value} for value in values] for axis, values in axes], False)
    if len(fruits) * len(surfaces) > options.max_searches:
        raise batch.UsageError(f'{len(fruits)} fruits x {len(surfaces)} surfaces: more than '
                               f'{options.max_searches} searches')
    x_name = options.x or next((axis for axis, values in axes if len(values) > 1), axes[0][0] if axes else None)
    if x_name is not None and x_name not in dict(axes):
        raise batch.UsageError(f'--x {x_name}: not a fruit parameter (--param {x_name}=v1,v2,...)')
    if x_name is not None:
        for value in dict(axes)[x_name]:
            try:
                float(value)
            except ValueError:
                raise batch.UsageError(f'--x {x_name}: the chart needs numbers, got "{value}"') from None
    for surface in surfaces:
        for key in surface.params:
            if key in dict(axes) or key == name:
                raise batch.UsageError(f'--surface {surface.name}: {key} is also given by --param')
    templates = surface_templates(options.template, surfaces, options.out)
    os.makedirs(os.path.join(options.out, TEMPLATES_DIR), exist_ok=True)
    for path, body in templates:
        with open(path, 'w') as handle:
            handle.write(body)
    points = max(1, options.jobs // (len(fruits) * len(surfaces)))
    searches = []
    for fruit in fruits:
        for surface, (path, _) in zip(surfaces, templates):
            fixed = dict(fruit, **surface.params)
            searches.append(Search(path, surface.name, fruit, fixed, name, low, high, options.tol, points))
    for search in searches:       # every template expands (its placeholders all given) before anything runs
        batch.expand([search.template], [dict(search.fixed, **{name: batch.format_number(low)})], options.out)
    if not options.quiet:
        print(f'{batch.PROGRAM}: boundary: {len(searches)} searches ({len(fruits)} fruits x {len(surfaces)} '
              f'surfaces) of {name} in [{batch.format_number(low)}, {batch.format_number(high)}], '
              f'{points} point(s) a round each, on {options.jobs} process(es)', flush=True)
    names = run_searches(searches, condition, options)
    batch.write_table(options.out, keys or [condition[0]] + [k for k in batch.DEFAULT_KEYS if k != condition[0]],
                      quiet=True, names=names)
    rows = write_boundary(searches, axes, surfaces, condition, options)
    print(boundary_text(rows, axes, surfaces, condition, options, name, low, high), end='')
    chart = os.path.join(options.out, 'boundary.png')
    plot(rows, axes, surfaces, x_name, condition, options, name, low, high, chart)
    print(f'{batch.PROGRAM}: boundary: {os.path.join(options.out, "boundary.csv")}, '
          f'{os.path.join(options.out, "boundary.txt")}, {chart}')
    return 0 if all(search.status == 'ok' for search in searches) else 1


def run_searches(searches, condition, options):
    """Every search on one set of workers (python/visco2d/workers.py): a search's next round starts
    as soon as its last one has ended, so the cores stay busy while any search is left. The names
    of the runs, in the order they were made."""
    exe = batch.find_program(options.exe, 'VISCO2D', 'visco2d', 'build/install/bin/visco2d')
    if exe is None:
        raise batch.UsageError('no visco2d executable: run `make build` (build/install/bin/visco2d), '
                               'or give --exe PATH')
    os.makedirs(options.out, exist_ok=True)
    progress = batch.Progress(0, options.quiet)
    workers = batch.workers_module().Workers(options.out, exe, options.jobs, progress)
    made = []                 # every case, in order
    owner = {}                # case name -> its search
    reused = 0

    def launch(search):
        """The next round of a search onto the workers (or its report, when it has ended)."""
        nonlocal reused
        while True:
            values = search.propose()
            if not values:
                if not search.reported:
                    report_search(search, condition, options)
                return
            cases = batch.expand([search.template], [dict(search.fixed, **{search.name: batch.format_number(value)})
                                                     for value in values], options.out)
            for case in cases:
                case.index = len(made)
                made.append(case)
                owner[case.name] = search
            batch.write_decks(cases, options.out, len(made))
            todo = [case for case in cases if not (options.resume and batch.verified_result(case, options.out))]
            reused += len(cases) - len(todo)
            for case in todo:
                batch.clear_case(options.out, case)
            search.round, search.waiting = cases, {case.name for case in todo}
            with progress.lock:
                progress.total += len(todo)
            if todo:
                workers.add(todo)
                return
            settle(search)          # every run of the round reused: the next round at once

    def settle(search):
        """A search's round has ended: its results into the search (a failed run ends it)."""
        failed = next((case for case in search.round if case.error is not None), None)
        if failed is not None:
            search.status = f'failed: {failed.name}: {failed.error}'
            report_search(search, condition, options)
            return
        search.receive([batch.holds(case, options.out, condition) + (case.name,)
                        for case in search.round])

    try:
        with batch.interrupts_raised():
            for search in searches:
                launch(search)
            while any(search.waiting for search in searches):
                for case in workers.ended():
                    search = owner[case.name]
                    search.waiting.discard(case.name)
                    if not search.waiting:
                        settle(search)
                        if search.status == 'running':
                            launch(search)
                        elif not search.reported:
                            report_search(search, condition, options)
    except KeyboardInterrupt:
        workers.interrupt()
        progress.finish()
        raise batch.Interrupted(made) from None
    except BaseException:          # an error (a summary without the --when key): stop the workers, then say it
        workers.interrupt()
        raise
    workers.close()
    workers.join()
    progress.finish()
    if reused and not options.quiet:
        print(f'{batch.PROGRAM}: --resume: {reused} of the {len(made)} runs had a verified result in '
              f'{options.out}', flush=True)
    return [case.name for case in made]


def report_search(search, condition, options):
    """A finished search: OUT/searches/<search>.txt, and a line on stdout (a warning on stderr if
    the condition switched back)."""
    fmt = batch.format_number
    search.reported = True
    folder = os.path.join(options.out, SEARCHES_DIR)
    os.makedirs(folder, exist_ok=True)
    if search.switched_back:
        print(f'{batch.PROGRAM}: warning: {search.label}: the condition switches more than once in the bracket; '
              f'following its first switch', file=sys.stderr)
    if search.status != 'ok':
        with open(os.path.join(folder, search.label + '.txt'), 'w') as handle:
            handle.write(f'parameter = {search.name}\nstatus = {search.status}\nruns = {len(search.runs)}\n'
                         + ''.join(f'run = {fmt(value)} {condition[0]}={key_value:.10g} {str(state).lower()} '
                                   f'{case}\n' for value, state, key_value, case in search.runs))
        if not options.quiet or not search.status.startswith('holds'):
            print(f'{search.label}: {search.status}'
                  + (' (no onset in the bracket)' if search.status.startswith('holds') else ''), flush=True)
        return
    text, at_bracket, warned = threshold_record(search.name, condition, search.tol, search.low, search.high,
                                                search.critical, search.runs, options.out)
    search.at_bracket, search.warned = at_bracket, warned
    with open(os.path.join(folder, search.label + '.txt'), 'w') as handle:
        handle.write(text)
    if not options.quiet:
        print(f'{search.label}: {search.name}_critical = {fmt(search.critical)} in [{fmt(search.low)}, '
              f'{fmt(search.high)}], {len(search.runs)} runs'
              + warning_note(at_bracket, warned, len(search.runs)), flush=True)


# ---------------------------------------------------------------- the table and the chart

def write_boundary(searches, axes, surfaces, condition, options):
    """OUT/boundary.csv: one row per fruit and surface; the rows, with their footnote numbers."""
    fmt = batch.format_number
    notes = {}                      # a warning's kind (its text, numbers masked) -> its footnote number
    rows = []
    for search in searches:
        at_bracket = search.at_bracket
        marks = []
        for _, line in at_bracket:
            kind = re.sub(r'\d+(\.\d+)?(e[-+]?\d+)?', '#', line)
            if kind not in notes:
                notes[kind] = (len(notes) + 1, line)
            if notes[kind][0] not in marks:
                marks.append(notes[kind][0])
        rows.append({'search': search, 'marks': marks})
    fruit_names = [axis for axis, _ in axes]
    header = (['surface'] + fruit_names + [f'{searches[0].name}_critical', 'bracket_low', 'bracket_high',
                                           'status', 'runs', 'warnings', 'warned_runs', 'warning', 'search'])
    with open(os.path.join(options.out, 'boundary.csv'), 'w', newline='') as handle:
        writer = csv.writer(handle)
        writer.writerow(header)
        for row in rows:
            search = row['search']
            at_bracket = search.at_bracket
            writer.writerow([search.surface] + [search.fruit[axis] for axis in fruit_names]
                            + [fmt(search.critical) if search.critical is not None else '', fmt(search.low),
                               fmt(search.high), search.status, len(search.runs), len(at_bracket),
                               search.warned, ' | '.join(sorted({line for _, line in at_bracket})),
                               search.label])
    for row in rows:
        row['notes'] = notes
    return rows


def footnotes(rows):
    """'N) the warning (for: the points it marks)', one a footnote, the text of its first run."""
    notes = rows[0]['notes'] if rows else {}
    lines = []
    for number, line in sorted(notes.values()):
        marked = [row['search'] for row in rows if number in row['marks']]
        where = '; '.join(', '.join([search.surface] * bool(search.surface) +
                                    [f'{k}={v}' for k, v in search.fruit.items()]) for search in marked)
        lines.append(f'{number}) {line} (the runs at the bracket of: {where})')
    return lines


def boundary_text(rows, axes, surfaces, condition, options, name, low, high):
    """OUT/boundary.txt (also printed): the critical values, a row per fruit, a column per surface."""
    fmt = batch.format_number
    key, operator, limit = condition
    fruit_names = [axis for axis, _ in axes]
    surface_names = list(dict.fromkeys(row['search'].surface for row in rows))
    lines = [f'Damage boundary: the {name} from which {key} {operator} {fmt(limit)}, searched in '
             f'[{fmt(low)}, {fmt(high)}] to {fmt(options.tol)} ({options.template})',
             f'each cell: {name}_critical [its bracket]; *N: the runs at the bracket warn (footnote N); '
             f'"< LOW": the condition holds already at LOW; "> HIGH": not even at HIGH', '']
    table = [[', '.join(fruit_names) or 'fruit'] + [surface or f'{name}_critical' for surface in surface_names]]
    grid = {}
    for row in rows:
        search = row['search']
        fruit = ', '.join(f'{axis}={search.fruit[axis]}' for axis in fruit_names) or '-'
        if search.status == 'ok':         # four digits to read (the CSV and the records: ten)
            cell = f'{search.critical:#.4g} [{search.low:#.4g}, {search.high:#.4g}]'
            cell += ''.join(f' *{mark}' for mark in row['marks'])
        elif search.status == 'holds at both ends':
            cell = f'< {fmt(search.low)}'
        elif search.status == 'holds at neither end':
            cell = f'> {fmt(search.high)}'
        else:
            cell = 'failed'
        grid.setdefault(fruit, {})[search.surface] = cell
    for fruit, cells in grid.items():
        table.append([fruit] + [cells.get(surface, '') for surface in surface_names])
    widths = [max(len(record[k]) for record in table) for k in range(len(table[0]))]
    for number, record in enumerate(table):
        lines.append('  '.join(cell.ljust(width) for cell, width in zip(record, widths)).rstrip())
        if number == 0:
            lines.append('  '.join('-' * width for width in widths))
    failed = [row['search'] for row in rows if row['search'].status.startswith('failed')]
    notes = footnotes(rows)
    if notes or failed:
        lines.append('')
    lines += notes
    lines += [f'failed: {search.label}: {search.status[len("failed: "):]}' for search in failed]
    text = '\n'.join(lines) + '\n'
    with open(os.path.join(options.out, 'boundary.txt'), 'w') as handle:
        handle.write(text)
    return text


def plot(rows, axes, surfaces, x_name, condition, options, name, low, high, path):
    """OUT/boundary.png: the critical value against the x parameter, one line per surface (and per
    value of the other fruit parameters); a warned point hollow with its footnote number."""
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D

    fmt = batch.format_number
    key, operator, limit = condition
    scale = options.x_scale
    others = [axis for axis, _ in axes if axis != x_name]
    series = {}
    for row in rows:
        search = row['search']
        label = search.surface
        extra = ', '.join(f'{axis}={search.fruit[axis]}' for axis in others)
        label = ', '.join(part for part in (label, extra) if part) or 'critical'
        series.setdefault(label, []).append(row)
    caption = [f'bars: the final bracket of each search (width <= {fmt(options.tol)}); '
               f'hollow: the runs at the bracket warn (the footnote of its number)']
    for note in footnotes(rows):
        caption += textwrap.wrap(note, 150, subsequent_indent='    ')
    figure, axis = plt.subplots(figsize=(8.5, 5.2 + 0.14 * len(caption)))
    colours = plt.rcParams['axes.prop_cycle'].by_key()['color']
    special = False
    drawn = []                # the points as drawn, in the PNG's Description (what a test can read)
    for number, (label, members) in enumerate(series.items()):
        colour = colours[number % len(colours)]
        members.sort(key=lambda row: float(row['search'].fruit[x_name]) if x_name else 0)
        xs, ys = [], []
        for row in members:
            search = row['search']
            x = float(search.fruit[x_name]) * scale if x_name else 0.0
            if search.status == 'ok':
                xs.append(x)
                ys.append(search.critical)
                axis.errorbar([x], [search.critical], yerr=[[search.critical - search.low],
                                                           [search.high - search.critical]],
                              fmt='none', ecolor=colour, capsize=3, lw=1)
                hollow = bool(row['marks'])
                drawn.append(f'{label} x={fmt(x)} {name}={fmt(search.critical)} '
                             + (f'hollow {",".join(map(str, row["marks"]))}' if hollow else 'filled'))
                axis.plot([x], [search.critical], 'o', ms=8, mec=colour, mew=1.8,
                          mfc='white' if hollow else colour, zorder=3)
                if hollow:
                    axis.annotate(','.join(str(mark) for mark in row['marks']), (x, search.critical),
                                  textcoords='offset points', xytext=(7, 5), fontsize=9, color=colour,
                                  fontweight='bold')
            elif search.status in ('holds at both ends', 'holds at neither end'):
                special = True
                below = search.status == 'holds at both ends'
                drawn.append(f'{label} x={fmt(x)} ' + (f'below {fmt(low)}' if below else f'above {fmt(high)}'))
                axis.plot([x], [low if below else high], 'v' if below else '^', ms=9, mec=colour, mfc='white',
                          mew=1.8, zorder=3)
            else:
                special = True
                axis.plot([x], [low], 'x', ms=9, color=colour, mew=2, zorder=3)
        axis.plot(xs, ys, '-', color=colour, lw=2, label=label)
    axis.set_xlabel(options.x_label or (x_name if x_name else ''))
    axis.set_ylabel(options.y_label or f'critical {name}')
    axis.set_ylim(bottom=0)
    axis.grid(True, alpha=0.3)
    axis.set_title(options.title or f'{name} from which {key} {operator} {fmt(limit)}', fontsize=12)
    handles, labels = axis.get_legend_handles_labels()
    handles += [Line2D([], [], ls='none', marker='o', mfc='white', mec='0.3', mew=1.8, ms=8),
                Line2D([], [], ls='none', marker='o', mfc='0.3', mec='0.3', ms=8)]
    labels += ['warned (footnote)', 'no warning']
    if special:
        handles += [Line2D([], [], ls='none', marker='^', mfc='white', mec='0.3', ms=8),
                    Line2D([], [], ls='none', marker='v', mfc='white', mec='0.3', ms=8)]
        labels += [f'no onset up to {fmt(high)}', f'onset below {fmt(low)}']
    axis.legend(handles, labels, loc='best', fontsize=9, framealpha=0.9)
    figure.text(0.01, 0.01, '\n'.join(caption), fontsize=7.5, va='bottom', ha='left')
    figure.tight_layout(rect=(0, 0.025 * (len(caption) + 1) * 5.2 / (5.2 + 0.14 * len(caption)), 1, 1))
    figure.savefig(path, dpi=130, metadata={'Title': axis.get_title(), 'Description': '; '.join(drawn)})
    plt.close(figure)

