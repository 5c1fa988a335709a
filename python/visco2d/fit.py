"""visco2d-fit: the flesh's constants from a measured curve (doc/calibration.md).

  visco2d-fit deck TEMPLATE --data CURVE.csv --param NAME=LOW:HIGH [--param NAME=LOW:GUESS:HIGH ...]
                                            [--set NAME=VALUE ...] [--model-x COL --x-scale F]
                                            [--model-y COL --y-scale F] -o OUT
        fit the ${name} placeholders of a template deck (visco2d-batch's syntax) so that visco2d's
        run reproduces the measured curve: least squares over forward runs of the program
  visco2d-fit relaxation --data RELAX.csv --terms N --strain EPS --nu NU [--area A | --diameter D]
                                            [--long-term] -o OUT
        fit E_i, alpha_i of the uniaxial relaxation modulus, the paper's eq. [47], in closed form
        (no FE run), then the shear constants G_m, beta_m by eq. [48] (`visco2d relax`)
  visco2d-fit sample OUT/fit.json --n N [--seed S] -o ROWS.csv [--run TEMPLATE --key KEY --batch-out DIR]
        N constant sets drawn from the fit's covariance (a visco2d-batch --table), and optionally
        run through visco2d-batch: the key's mean and standard deviation (a Monte Carlo)

The curve is a CSV file whose two columns carry their units in their names: the abscissa
time_s | time_ms | deformation_m | deformation_mm, the ordinate force_N | accel_m_s2 | accel_g |
stress_Pa | stress_MPa ('#' lines are comments). Every output goes into OUT/: fit.txt (the
constants, standard errors, correlations, residual, runs, warnings), cards.inp (the fitted
cards), fit.csv (data, fit, residual), fit.png (data against fit, residuals beneath), fit.json
(what `sample` reads). Exit status: 0 fitted (WARNING lines say what the data cannot
determine), 1 a forward run failed, 2 bad input (nothing written).
"""

import argparse
import csv
import json
import math
import os
import shutil
import string
import subprocess
import sys
import tempfile

import numpy as np

from . import runner
from .batch import UsageError, placeholders
from .case import read_history

PROGRAM = 'visco2d-fit'

#: Column names of a measured curve -> (quantity, factor to SI). The unit is the name's suffix.
ABSCISSAE = {'time_s': ('time', 1.0), 'time_ms': ('time', 1e-3),
             'deformation_m': ('deformation', 1.0), 'deformation_mm': ('deformation', 1e-3)}
ORDINATES = {'force_N': ('force', 1.0), 'accel_m_s2': ('accel', 1.0), 'accel_g': ('accel', 9.80665),
             'stress_Pa': ('stress', 1.0), 'stress_MPa': ('stress', 1e6)}
SI = {'time': 'time_s', 'deformation': 'deformation_m', 'force': 'force_N', 'accel': 'accel_m_s2',
      'stress': 'stress_Pa'}

#: |correlation| above which two constants are reported as not told apart by the data.
CORRELATION_LIMIT = 0.95
#: Condition number of the column-normalised J^T J above which the fit is reported near-singular
#: (a relative change of 1e-6 in the data can then move the constants by order one).
CONDITION_LIMIT = 1e6
#: Relative finite-difference step on a log-constant (or on a linear one's bound range): the FE
#: output is written with 10 significant digits and is smooth in the constants at a fixed mesh and
#: Delta t, so a 1e-4 step leaves a derivative error ~1e-6 relative from the round-off of the file.
DIFF_STEP = 1e-4


class FitError(Exception):
    """A forward run failed or the fit cannot proceed: exit 1."""


# ---------------------------------------------------------------- the measured curve

def read_curve(path, allowed_x=None):
    """(x name, y name, x array, y array, line numbers) of a measured curve, in SI units.

    Raises UsageError naming the file, line and column: no unit in a name, an unknown column,
    a value that is not a finite number, an abscissa that does not increase strictly."""
    try:
        with open(path, newline='') as handle:
            lines = handle.read().splitlines()
    except OSError as error:
        raise UsageError(f'{path}: cannot read the curve: {error.strerror}') from None
    except UnicodeDecodeError:
        raise UsageError(f'{path}: not a text file') from None
    rows = [(number, line) for number, line in enumerate(lines, start=1)
            if line.strip() and not line.lstrip().startswith('#')]
    if not rows:
        raise UsageError(f'{path}: no header line (expected e.g. "time_s,force_N")')
    head_line, head = rows[0]
    names = [name.strip() for name in next(csv.reader([head]))]
    if len(names) != 2:
        raise UsageError(f'{path}:{head_line}: expected two columns (abscissa, ordinate), found {len(names)}: '
                         f'{",".join(names)}')
    known = dict(ABSCISSAE, **ORDINATES)
    column = 1
    for name in names:
        if name not in known:
            if '_' not in name:
                hint = ', '.join(key for key in known if key.split('_')[0] == name.lower()) or ', '.join(known)
                raise UsageError(f'{path}:{head_line}:{column}: column "{name}" has no unit in its name '
                                 f'(write it after an underscore: {hint})')
            raise UsageError(f'{path}:{head_line}:{column}: unknown column "{name}" (known: '
                             f'{", ".join(ABSCISSAE)} for the abscissa; {", ".join(ORDINATES)} for the ordinate)')
        column += len(name) + 1
    xname, yname = names
    if xname not in ABSCISSAE:
        raise UsageError(f'{path}:{head_line}:1: the first column must be the abscissa '
                         f'({", ".join(ABSCISSAE)}), got "{xname}"')
    if yname not in ORDINATES:
        raise UsageError(f'{path}:{head_line}:{len(xname) + 2}: the second column must be the ordinate '
                         f'({", ".join(ORDINATES)}), got "{yname}"')
    if allowed_x and ABSCISSAE[xname][0] not in allowed_x:
        raise UsageError(f'{path}:{head_line}:1: this fit needs {" or ".join(allowed_x)} as the abscissa, got "{xname}"')
    xs, ys, where = [], [], []
    for number, line in rows[1:]:
        fields = next(csv.reader([line]))
        if len(fields) != 2:
            raise UsageError(f'{path}:{number}: expected 2 values, found {len(fields)}')
        values, column = [], 1
        for name, field in zip(names, fields):
            try:
                value = float(field)
            except ValueError:
                raise UsageError(f'{path}:{number}:{column}: {name}: "{field.strip()}" is not a number') from None
            if not math.isfinite(value):
                raise UsageError(f'{path}:{number}:{column}: {name}: {field.strip()} is not a finite number')
            values.append(value)
            column += len(field) + 1
        if xs and values[0] <= xs[-1]:
            what = 'repeats' if values[0] == xs[-1] else 'decreases'
            raise UsageError(f'{path}:{number}:1: {xname} {what} ({values[0]:.6g} after {xs[-1]:.6g} on line '
                             f'{where[-1]}): the abscissa must increase strictly (sort the curve)')
        xs.append(values[0])
        ys.append(values[1])
        where.append(number)
    x = np.array(xs) * ABSCISSAE[xname][1]
    y = np.array(ys) * ORDINATES[yname][1]
    return ABSCISSAE[xname][0], ORDINATES[yname][0], x, y, where


def check_points(path, x, count):
    """At least count + 1 points for count constants (else the residual has no degree of freedom)."""
    if len(x) < count + 1:
        raise UsageError(f'{path}: {len(x)} data points for {count} constants: at least {count + 1} are needed '
                         f'(the residual needs n - p > 0 degrees of freedom)')


# ---------------------------------------------------------------- parameters

class Parameter:
    """A constant to fit: name, bounds, initial guess; fitted in log space when its bounds are positive."""

    def __init__(self, name, low, guess, high):
        self.name, self.low, self.guess, self.high = name, low, guess, high
        self.log = low > 0

    def to_theta(self, value):
        return math.log(value) if self.log else value

    def to_value(self, theta):
        return math.exp(theta) if self.log else theta

    @property
    def bounds(self):
        return (self.to_theta(self.low), self.to_theta(self.high))


def parse_param(text):
    """NAME=LOW:HIGH (guess: the geometric mean when both are positive, else the middle) or NAME=LOW:GUESS:HIGH."""
    name, sep, spec = text.partition('=')
    name = name.strip()
    if not sep or not name.isidentifier():
        raise UsageError(f'--param {text}: expected NAME=LOW:HIGH or NAME=LOW:GUESS:HIGH')
    parts = spec.split(':')
    try:
        values = [float(part) for part in parts]
    except ValueError:
        raise UsageError(f'--param {text}: the bounds must be numbers') from None
    if len(values) not in (2, 3) or not all(math.isfinite(v) for v in values):
        raise UsageError(f'--param {text}: expected NAME=LOW:HIGH or NAME=LOW:GUESS:HIGH (finite numbers)')
    low, high = values[0], values[-1]
    if not low < high:
        raise UsageError(f'--param {text}: LOW must be below HIGH')
    if len(values) == 3:
        guess = values[1]
        if not low < guess < high:
            raise UsageError(f'--param {text}: the guess must lie strictly between LOW and HIGH')
    else:
        guess = math.sqrt(low * high) if low > 0 else 0.5 * (low + high)
    return Parameter(name, low, guess, high)


def parse_set(text):
    name, sep, value = text.partition('=')
    if not sep or not name.strip().isidentifier() or not value.strip():
        raise UsageError(f'--set {text}: expected NAME=VALUE')
    return name.strip(), value.strip()


def fmt(value):
    """A constant as written into a deck: ten significant digits."""
    return format(value, '.10g')


# ---------------------------------------------------------------- uncertainty

def uncertainty(jacobian, residual, names, params_theta, logs):
    """Standard errors and correlations from the Jacobian at the optimum.

    jacobian: d(model)/d(theta) in the data's units (n x p), residual: model - data (n).
    cov(theta) = s^2 (J^T J)^-1 with s^2 = SSR / (n - p); a constant fitted in log space has
    the standard error value * se(theta) (the delta method). Directions of J^T J whose
    singular value is below 1e-12 of the largest are unidentifiable: their constants get an
    infinite standard error. Returns a dict (and the list of WARNING texts)."""
    n, p = jacobian.shape
    ssr = float(residual @ residual)
    dof = n - p
    s2 = ssr / dof
    norms = np.linalg.norm(jacobian, axis=0)
    warnings = []
    scale = np.where(norms > 0, norms, 1.0)
    normalised = jacobian / scale
    u, sv, vt = np.linalg.svd(normalised, full_matrices=False)
    dead = norms <= 1e-12 * (norms.max() if norms.max() > 0 else 1.0)
    condition = float((sv[0] / sv[-1]) ** 2) if sv[-1] > 0 else math.inf
    keep = sv > 1e-12 * sv[0] if sv[0] > 0 else np.zeros_like(sv, dtype=bool)
    inv = (vt[keep].T / sv[keep] ** 2) @ vt[keep]
    cov = s2 * inv / np.outer(scale, scale)
    free = np.ones(p, dtype=bool)
    for k in np.where(~keep)[0]:
        free &= np.abs(vt[k]) < 1e-6
    free &= ~dead
    se_theta = np.where(free, np.sqrt(np.maximum(np.diag(cov), 0.0)), np.inf)
    with np.errstate(invalid='ignore', divide='ignore'):
        sd = np.sqrt(np.maximum(np.diag(cov), 0.0))
        corr = cov / np.outer(sd, sd)
    corr[~np.isfinite(corr)] = np.nan
    for j in range(p):
        corr[j, j] = 1.0
    for j in np.where(dead)[0]:
        warnings.append(f'{names[j]} has no effect on the curve (its column of the Jacobian is zero): '
                        f'the data cannot determine it')
    for i in range(p):
        for j in range(i + 1, p):
            if np.isfinite(corr[i, j]) and abs(corr[i, j]) > CORRELATION_LIMIT and not (dead[i] or dead[j]):
                warnings.append(f'the data cannot tell apart {names[i]} and {names[j]} '
                                f'(correlation {corr[i, j]:+.4f}): only a combination of them is determined')
    if condition > CONDITION_LIMIT and not dead.any():
        weakest = vt[-1]
        order = np.argsort(-np.abs(weakest))
        combo = ' '.join(f'{weakest[k]:+.3f} {("ln " if logs[k] else "") + names[k]}' for k in order
                         if abs(weakest[k]) > 0.05)
        warnings.append(f'J^T J is near-singular (condition number {condition:.3g} of the column-normalised '
                        f'matrix > {CONDITION_LIMIT:g}): the data hardly determine the combination {combo}')
    values = np.array([math.exp(t) if lg else t for t, lg in zip(params_theta, logs)])
    se_value = np.where(np.array(logs), values * se_theta, se_theta)
    return {'n': n, 'p': p, 'ssr': ssr, 'rms': math.sqrt(ssr / n), 's': math.sqrt(s2), 'dof': dof,
            'cov_theta': cov, 'se_theta': se_theta, 'se': se_value, 'corr': corr, 'condition': condition,
            'values': values, 'warnings': warnings}


# ---------------------------------------------------------------- forward runs

class Forward:
    """visco2d runs of a template at given constants, in a temporary folder (removed by close()).

    model(thetas) runs one visco2d process for all the decks and returns the model curve of
    each on the data's abscissa."""

    def __init__(self, template_path, text, params, fixed, x_data, data_kind, x_column, x_scale, y_column,
                 y_scale, exe):
        self.template_path, self.text, self.params, self.fixed = template_path, text, params, fixed
        self.x_data, self.data_kind, self.exe = x_data, data_kind, exe
        self.x_column, self.x_scale, self.y_column, self.y_scale = x_column, x_scale, y_column, y_scale
        self.folder = tempfile.mkdtemp(prefix='visco2d-fit-')
        self.runs = 0
        self.processes = 0
        self.cache = {}
        self.last_history = None

    def close(self):
        shutil.rmtree(self.folder, ignore_errors=True)

    def deck_text(self, theta):
        values = dict(self.fixed)
        for parameter, t in zip(self.params, theta):
            values[parameter.name] = fmt(parameter.to_value(t))
        return string.Template(self.text).substitute(values)

    def describe(self, theta):
        return ', '.join(f'{p.name} = {fmt(p.to_value(t))}' for p, t in zip(self.params, theta))

    def model(self, thetas):
        keys = [tuple(float(t) for t in theta) for theta in thetas]
        todo = [key for key in dict.fromkeys(keys) if key not in self.cache]
        if todo:
            out = os.path.join(self.folder, 'out')
            decks = []
            for index, key in enumerate(todo):
                path = os.path.join(self.folder, f'run{self.runs + index + 1}.inp')
                with open(path, 'w') as handle:
                    handle.write(self.deck_text(key))
                decks.append(path)
            result = runner.run(self.exe, decks, out)
            self.processes += 1
            for key, deck in zip(todo, decks):
                case = os.path.splitext(os.path.basename(deck))[0]
                folder = os.path.join(out, case)
                if not os.path.isfile(os.path.join(folder, 'history.csv')):
                    raise FitError(f'the forward run at {self.describe(key)} failed: '
                                   f'{runner.located_error(result.stderr, os.path.basename(deck))}')
                history = read_history(folder)
                self.cache[key] = self.on_data(history, key)
                self.last_history = history
                shutil.rmtree(folder, ignore_errors=True)
                os.remove(deck)
            self.runs += len(todo)
        return [self.cache[key] for key in keys]

    def on_data(self, history, key):
        """The run's curve, history columns times their scales, interpolated at the data's abscissa."""
        for column in (self.x_column, self.y_column):
            if column not in history:
                raise UsageError(f'{self.template_path}: the run\'s history.csv has no column "{column}" '
                                 f'(its columns: {", ".join(history)})')
        x = np.array(history[self.x_column]) * self.x_scale
        y = np.array(history[self.y_column]) * self.y_scale
        if self.data_kind == 'deformation':
            top = int(np.argmax(x))         # the loading branch: up to the largest deformation
            x, y = x[:top + 1], y[:top + 1]
        if np.any(np.diff(x) <= 0):
            raise FitError(f'the run\'s {self.x_column} does not increase strictly (at {self.describe(key)}), '
                           f'so the curve cannot be interpolated on it')
        tolerance = 1e-9 * max(abs(x[-1]), abs(x[0]), 1e-300)
        if self.x_data[-1] > x[-1] + tolerance or self.x_data[0] < x[0] - tolerance:
            raise UsageError(f'the run covers {self.x_column} x {self.x_scale:g} = {x[0]:.6g} ... {x[-1]:.6g} '
                           f'(at {self.describe(key)}) but the data run from {self.x_data[0]:.6g} to '
                           f'{self.x_data[-1]:.6g}: the run is shorter than the curve (lengthen TEND, '
                           f'or STOP AT=TEND, or cut the curve)')
        return np.interp(self.x_data, x, y)


def default_columns(kind_x, kind_y, history, template):
    """The history column (and scale) compared with each data column, chosen from the names."""
    plate = 'force_N' in history and 't_ms' in history
    if kind_x == 'time':
        x = ('t_ms', 1e-3) if plate else ('t_s', 1.0)
    elif plate:
        x = ('alpha_mm', 1e-3)
    else:
        x = None
    sensors = [name for name in history if name.endswith('_sensor_az_m_s2')]
    if kind_y == 'force' and plate:
        y = ('force_N', 1.0)
    elif kind_y == 'accel':
        y = (sensors[0], 1.0) if len(sensors) == 1 else ('az_cm_m_s2', 1.0)
    else:
        y = None
    return x, y


# ---------------------------------------------------------------- least squares

def least_squares_fit(residual_of, jacobian_of, theta0, bounds, max_evaluations):
    from scipy.optimize import least_squares
    lows = [b[0] for b in bounds]
    highs = [b[1] for b in bounds]
    return least_squares(residual_of, theta0, jac=jacobian_of, bounds=(lows, highs), method='trf',
                         x_scale='jac', max_nfev=max_evaluations, xtol=1e-10, ftol=1e-10, gtol=1e-10)


def forward_jacobian(model_at, theta, params, f0=None):
    """Forward differences of the model curve in theta; every perturbed deck of one Jacobian runs in
    one visco2d process (model_at takes a list of points). The step is DIFF_STEP on a log constant,
    DIFF_STEP x the bound range on a linear one, taken backwards at an upper bound."""
    points, steps = [], []
    for j, parameter in enumerate(params):
        low, high = parameter.bounds
        h = DIFF_STEP if parameter.log else DIFF_STEP * (high - low)
        if theta[j] + h > high:
            h = -h
        point = np.array(theta, dtype=float)
        point[j] += h
        points.append(point)
        steps.append(point[j] - theta[j])
    curves = model_at([theta] + points)
    base = curves[0] if f0 is None else f0
    return np.column_stack([(curve - base) / step for curve, step in zip(curves[1:], steps)])


# ---------------------------------------------------------------- outputs

def summary_lines(title, names, values, uq, logs, extra=(), unit=''):
    lines = [f'# {title}', '']
    lines += list(extra)
    lines += ['', 'constants (value, standard error, relative standard error; log: fitted as ln of the value):']
    for k, name in enumerate(names):
        se = uq['se'][k]
        rel = se / abs(values[k]) if values[k] != 0 else math.inf
        lines.append(f'  {name:>12s} = {values[k]:.6g}  +- {se:.3g}  ({100 * rel:.3g} %)'
                     f'{"  log" if logs[k] else ""}')
    lines += ['', 'correlation matrix:', '  ' + ' ' * 12 + ''.join(f'{n:>10s}' for n in names)]
    for k, name in enumerate(names):
        lines.append(f'  {name:>12s}' + ''.join(f'{c:+10.4f}' if np.isfinite(c) else f'{"nan":>10s}'
                                              for c in uq['corr'][k]))
    lines += ['', f'points = {uq["n"]}', f'constants = {uq["p"]}', f'residual_rms = {uq["rms"]:.6g} {unit}',
              f'residual_s = {uq["s"]:.6g} {unit}  (sqrt(SSR / (n - p)))', f'condition_number = {uq["condition"]:.4g}  '
              f'(of the column-normalised J^T J)']
    return lines


def write_outputs(out, files, pictures=()):
    """Every output of a fit written at once, at the end: a failed fit writes nothing."""
    os.makedirs(out, exist_ok=True)
    for name, text in files.items():
        with open(os.path.join(out, name), 'w') as handle:
            handle.write(text)
    for name, draw in pictures:
        draw(os.path.join(out, name))


def csv_text(kind_x, kind_y, x, y, fit):
    lines = [f'{SI[kind_x]},{SI[kind_y]},fit_{SI[kind_y]},residual_{SI[kind_y]}']
    lines += [f'{a:.10g},{b:.10g},{c:.10g},{c - b:.10g}' for a, b, c in zip(x, y, fit)]
    return '\n'.join(lines) + '\n'


def picture(kind_x, kind_y, x, y, fit, title, logx=False):
    def draw(path):
        import matplotlib
        matplotlib.use('Agg')
        import matplotlib.pyplot as plt
        scale_x = {'time': (1e3, 'time (ms)'), 'deformation': (1e3, 'deformation (mm)')}[kind_x]
        if logx:
            scale_x = (1.0, 'time (s)')
        scale_y = {'force': (1.0, 'force (N)'), 'accel': (1.0, 'acceleration (m/s²)'),
                   'stress': (1e-3, 'stress (kPa)'), 'modulus': (1e-6, 'E(t) (MPa)')}[kind_y]
        figure, (top, bottom) = plt.subplots(2, 1, figsize=(7, 6), sharex=True,
                                             gridspec_kw={'height_ratios': [3, 1.3]})
        xs = x * scale_x[0]
        top.plot(xs, y * scale_y[0], 'o', ms=3, color='0.45', label='data')
        top.plot(xs, fit * scale_y[0], '-', color='C3', lw=1.6, label='fit')
        top.set_ylabel(scale_y[1])
        top.legend()
        top.set_title(title, fontsize=10)
        top.grid(alpha=0.3)
        bottom.plot(xs, (fit - y) * scale_y[0], 'o', ms=3, color='C0')
        bottom.axhline(0, color='k', lw=0.8)
        unit = scale_y[1][scale_y[1].index('('):] if '(' in scale_y[1] else ''
        bottom.set_ylabel(f'fit − data {unit}')
        bottom.set_xlabel(scale_x[1])
        bottom.grid(alpha=0.3)
        if logx:
            bottom.set_xscale('log')
        figure.tight_layout()
        figure.savefig(path, dpi=110)
        plt.close(figure)
    return draw


def template_cards(text, values):
    """The template's material cards (MATERIAL, PRONY, PLASTIC, HARDENING) with the values put in."""
    cards = []
    for line in text.splitlines():
        word = line.split('#', 1)[0].strip().split(' ', 1)[0].upper()
        if word in ('MATERIAL', 'PRONY', 'PLASTIC', 'HARDENING'):
            cards.append(string.Template(line.split('#', 1)[0].rstrip()).substitute(values))
    return cards


# ---------------------------------------------------------------- visco2d-fit deck

def fit_deck(options):
    params = [parse_param(text) for text in options.param]
    fixed = dict(parse_set(text) for text in options.set)
    names = [p.name for p in params]
    for name in names:
        if names.count(name) > 1 or name in fixed:
            raise UsageError(f'parameter "{name}" is given twice')
    template = options.template
    try:
        with open(template) as handle:
            text = handle.read()
    except OSError as error:
        raise UsageError(f'{template}: cannot read the template: {error.strerror}') from None
    uses = placeholders(template, text)
    given = set(names) | set(fixed)
    for name, where in uses.items():
        if name not in given:
            raise UsageError(f'{where}: ${{{name}}}: no value (give --param {name}=LOW:HIGH to fit it or '
                             f'--set {name}=VALUE to fix it)')
    for name in given:
        if name not in uses:
            raise UsageError(f'{template}: "{name}" is given but the template has no ${{{name}}} '
                             f'(its placeholders: {", ".join(uses) or "none"})')
    kind_x, kind_y, x, y, _ = read_curve(options.data)
    check_points(options.data, x, len(params))
    exe = runner.find_program(options.exe) if options.exe else runner.default_exe()
    if not exe or not os.path.isfile(exe):
        raise UsageError(f'no visco2d executable (make build, or --exe PATH)')
    theta0 = np.array([p.to_theta(p.guess) for p in params])
    forward = Forward(template, text, params, fixed, x, kind_x, None, 1.0, None, 1.0, exe)
    try:
        # The first run at the guess: it names the history's columns, so the compared ones are chosen
        # (or the given ones checked) before the optimiser starts.
        first = forward.deck_text(theta0)
        probe_dir = os.path.join(forward.folder, 'probe')
        os.makedirs(probe_dir)
        path = os.path.join(probe_dir, 'guess.inp')
        with open(path, 'w') as handle:
            handle.write(first)
        result = runner.run(exe, [path], os.path.join(probe_dir, 'out'))
        forward.runs += 1
        forward.processes += 1
        case = os.path.join(probe_dir, 'out', 'guess')
        if not os.path.isfile(os.path.join(case, 'history.csv')):
            raise FitError(f'the run at the initial guess ({forward.describe(theta0)}) failed: '
                           f'{runner.located_error(result.stderr)}')
        history = read_history(case)
        auto_x, auto_y = default_columns(kind_x, kind_y, history, template)
        if options.model_x:
            forward.x_column, forward.x_scale = options.model_x, options.x_scale
        elif auto_x:
            forward.x_column, forward.x_scale = auto_x
        else:
            raise UsageError(f'{options.data}: the run has no plate, so which history column is the '
                             f'{kind_x}? give --model-x COLUMN [--x-scale F] (columns: {", ".join(history)})')
        if options.model_y:
            forward.y_column, forward.y_scale = options.model_y, options.y_scale
        elif auto_y:
            forward.y_column, forward.y_scale = auto_y
        else:
            raise UsageError(f'{options.data}: which history column is the {kind_y}? give --model-y COLUMN '
                             f'[--y-scale F] (columns: {", ".join(history)})')
        forward.cache[tuple(float(t) for t in theta0)] = forward.on_data(history, theta0)
        yscale = float(np.max(np.abs(y))) or 1.0

        def residual_of(theta):
            return (forward.model([theta])[0] - y) / yscale

        def jacobian_of(theta):
            f0 = forward.model([theta])[0]
            return forward_jacobian(forward.model, theta, params, f0) / yscale

        result = least_squares_fit(residual_of, jacobian_of, theta0, [p.bounds for p in params],
                                   options.max_evaluations)
        theta = result.x
        fit = forward.model([theta])[0]
        jac = forward_jacobian(forward.model, theta, params, fit)
        residual = fit - y
        uq = uncertainty(jac, residual, names, theta, [p.log for p in params])
        at_bound = [p.name for p, t in zip(params, theta)
                    if min(abs(t - p.bounds[0]), abs(t - p.bounds[1])) < 1e-6 * max(1.0, abs(t))]
        for name in at_bound:
            uq['warnings'].append(f'{name} ends at a bound: widen its bounds (its standard error assumes an '
                                  f'interior optimum)')
        if not result.success:
            uq['warnings'].append(f'the optimiser stopped without converging: {result.message}')
        values = dict(fixed)
        for p, t in zip(params, theta):
            values[p.name] = fmt(p.to_value(t))
        cards = template_cards(text, values)
        extra = [f'template = {template}', f'data = {options.data} ({SI[kind_x]}, {SI[kind_y]}; {len(x)} points)',
                 f'compared: history {forward.x_column} x {forward.x_scale:g} -> {SI[kind_x]}, '
                 f'{forward.y_column} x {forward.y_scale:g} -> {SI[kind_y]}',
                 f'fixed = {", ".join(f"{k}={v}" for k, v in fixed.items()) or "none"}',
                 f'optimiser = scipy.optimize.least_squares (trf, x_scale=jac), {result.nfev} evaluations, '
                 f'{result.njev} Jacobians, status {result.status}: {result.message}',
                 f'forward_runs = {forward.runs} (in {forward.processes} visco2d processes)']
    finally:
        forward.close()
    return finish(options, names, [p.log for p in params], theta, uq, extra, cards,
                  csv_text(kind_x, kind_y, x, y, fit),
                  picture(kind_x, kind_y, x, y, fit, f'{os.path.basename(template)} fitted to '
                          f'{os.path.basename(options.data)}'),
                  bounds=[(p.low, p.high) for p in params], fixed=fixed, template=template,
                  title=f'visco2d-fit deck {template}', unit=SI[kind_y].split('_', 1)[1])


def finish(options, names, logs, theta, uq, extra, cards, table, draw, bounds, fixed, template, title,
           more_files=None, unit=''):
    warnings = uq['warnings']
    lines = summary_lines(title, names, uq['values'], uq, logs, extra, unit)
    lines.append(f'warnings = {len(warnings)}')
    lines += [f'WARNING: {w}' for w in warnings]
    lines += ['', 'cards (cards.inp):'] + ['  ' + c for c in cards]
    record = {'names': names, 'log': logs, 'theta': [float(t) for t in theta],
              'values': [float(v) for v in uq['values']], 'se': [float(s) for s in uq['se']],
              'cov_theta': uq['cov_theta'].tolist(), 'bounds': bounds, 'fixed': fixed,
              'template': template, 'residual_rms': uq['rms'], 'warnings': warnings}
    se_lines = [f'# {n} = {v:.6g} +- {s:.3g}' for n, v, s in zip(names, uq['values'], uq['se'])]
    files = {'fit.txt': '\n'.join(lines) + '\n',
             'cards.inp': '# visco2d-fit: fitted constants (standard errors in fit.txt)\n'
                          + '\n'.join(se_lines) + '\n' + '\n'.join(cards) + '\n',
             'fit.csv': table, 'fit.json': json.dumps(record, indent=1) + '\n'}
    files.update(more_files or {})
    write_outputs(options.out, files, [('fit.png', draw)])
    if not options.quiet:
        print('\n'.join(lines))
    for w in warnings:
        print(f'{PROGRAM}: WARNING: {w}', file=sys.stderr)
    return 0


# ---------------------------------------------------------------- visco2d-fit relaxation (eq. [47])

def relaxation_model(theta, t, terms, long_term):
    """E(t) of eq. [47] and its Jacobian in theta = (ln E_1, ln alpha_1, ..., [ln E_inf])."""
    e = np.exp(theta)
    model = np.zeros_like(t)
    jac = np.zeros((len(t), len(theta)))
    for i in range(terms):
        decay = np.exp(-e[2 * i + 1] * t)
        model += e[2 * i] * decay
        jac[:, 2 * i] = e[2 * i] * decay
        jac[:, 2 * i + 1] = -e[2 * i] * e[2 * i + 1] * t * decay
    if long_term:
        model += e[-1]
        jac[:, -1] = e[-1]
    return model, jac


def relaxation_start(t, modulus, terms, long_term):
    """Starting rates spread over the data's decades and moduli by non-negative linear least squares.
    Several spreads are tried (the fit of each is kept if it is the best)."""
    from scipy.optimize import nnls
    positive = t[t > 0]
    t_low = positive.min() if positive.size else t.max() * 1e-6
    starts = []
    for shrink in (0.0, 0.5, 1.0):
        low, high = math.log(1 / t.max()) + shrink, math.log(1 / t_low) - shrink
        rates = np.exp(np.linspace(low, high, terms)) if terms > 1 else np.array([math.exp(0.5 * (low + high))])
        design = np.column_stack([np.exp(-a * t) for a in rates] + ([np.ones_like(t)] if long_term else []))
        moduli, _ = nnls(design, modulus)
        moduli = np.maximum(moduli, 1e-3 * max(modulus.max(), 1e-300))
        theta = []
        for i in range(terms):
            theta += [math.log(moduli[i]), math.log(rates[i])]
        if long_term:
            theta.append(math.log(moduli[-1]))
        starts.append(np.array(theta))
    return starts


def fit_relaxation_curve(t, modulus, terms, long_term=False):
    """Least squares of eq. [47] to E(t) samples: (theta, scipy result, sorted by increasing rate)."""
    from scipy.optimize import least_squares
    scale = float(np.max(np.abs(modulus)))
    positive = t[t > 0]
    t_low = positive.min() if positive.size else t.max() * 1e-6
    # Bounds in log space, wide enough never to bind a term the data see: a rate within 1e-3/t_max ...
    # 1e3/t_min (a faster or slower term is invisible in the curve), a modulus within 1e-8 ... 10
    # times the largest E(t) sample.
    low_e, high_e = math.log(1e-8 * scale), math.log(10 * scale)
    low_a, high_a = math.log(1e-3 / t.max()), math.log(1e3 / t_low)
    lows = [v for _ in range(terms) for v in (low_e, low_a)] + ([low_e] if long_term else [])
    highs = [v for _ in range(terms) for v in (high_e, high_a)] + ([high_e] if long_term else [])
    best = None
    for start in relaxation_start(t, modulus, terms, long_term):
        start = np.clip(start, np.array(lows) + 1e-9, np.array(highs) - 1e-9)
        result = least_squares(lambda th: (relaxation_model(th, t, terms, long_term)[0] - modulus) / scale,
                               start, jac=lambda th: relaxation_model(th, t, terms, long_term)[1] / scale,
                               bounds=(lows, highs), method='trf', x_scale='jac',
                               xtol=1e-14, ftol=1e-14, gtol=1e-14, max_nfev=20000)
        if best is None or result.cost < best.cost:
            best = result
    theta = best.x.copy()
    order = np.argsort(theta[1:2 * terms:2])
    sorted_theta = np.concatenate([theta[2 * k:2 * k + 2] for k in order] + ([theta[-1:]] if long_term else []))
    return sorted_theta, best


def relax_program(exe, nu, pairs):
    """The program's eq. [48] (`visco2d relax`): K and [(G_m, beta_m)] for uniaxial [(E_i, alpha_i)]."""
    command = [exe, 'relax', '--nu', repr(nu)] + [repr(float(v)) for pair in pairs for v in pair]
    result = subprocess.run(command, capture_output=True, text=True, env=dict(os.environ, **runner.ONE_THREAD))
    if result.returncode != 0:
        raise FitError(f'visco2d relax failed: {result.stderr.strip() or result.stdout.strip()}')
    lines = result.stdout.strip().splitlines()
    bulk = float(lines[0].split('=')[1].replace('D', 'E'))
    terms = [tuple(float(v.replace('D', 'E')) for v in line.split()) for line in lines[1:]]
    return bulk, terms


def shear_uncertainty(exe, nu, pairs, cov_values):
    """K, G_m, beta_m by eq. [48] and their standard errors: the program's conversion differentiated by
    forward differences (relative step 1e-6; it prints 12 digits) and the delta method on cov."""
    bulk, shear = relax_program(exe, nu, pairs)
    base = np.array([bulk] + [v for term in shear for v in term])
    flat = np.array([v for pair in pairs for v in pair], dtype=float)
    jac = np.zeros((len(base), len(flat)))
    for j in range(len(flat)):
        if flat[j] == 0:            # the alpha = 0 of a long-term E_inf: not a fitted constant
            continue
        step = 1e-6 * flat[j]
        moved = flat.copy()
        moved[j] += step
        b, s = relax_program(exe, nu, [tuple(moved[2 * i:2 * i + 2]) for i in range(len(pairs))])
        jac[:, j] = (np.array([b] + [v for term in s for v in term]) - base) / step
    cov = jac @ cov_values @ jac.T
    return bulk, shear, np.sqrt(np.maximum(np.diag(cov), 0.0))


def fit_relaxation(options):
    kind_x, kind_y, t, y, _ = read_curve(options.data, allowed_x=('time',))
    if kind_y == 'force':
        if options.area:
            area = options.area
        elif options.diameter:
            area = math.pi * options.diameter ** 2 / 4
        else:
            raise UsageError(f'{options.data}: the curve is a force: give the specimen\'s --area (m^2) or '
                             f'--diameter (m) to make it a stress')
        stress = y / area
    elif kind_y == 'stress':
        stress = y
        area = None
    else:
        raise UsageError(f'{options.data}: a relaxation curve is force_N or stress_Pa against time, not {kind_y}')
    if not options.strain > 0:
        raise UsageError('--strain: the held strain must be a positive number (its magnitude)')
    if not -1 < options.nu < 0.5:
        raise UsageError('--nu must lie in (-1, 0.5)')
    terms, long_term = options.terms, options.long_term
    p = 2 * terms + (1 if long_term else 0)
    check_points(options.data, t, p)
    modulus = np.abs(stress) / options.strain        # eq. [47]: E(t) = sigma(t) / eps0 at a held strain
    theta, result = fit_relaxation_curve(t, modulus, terms, long_term)
    model, jac = relaxation_model(theta, t, terms, long_term)
    names = [n for i in range(terms) for n in (f'E{i + 1}', f'alpha{i + 1}')] + (['E_inf'] if long_term else [])
    uq = uncertainty(jac, model - modulus, names, theta, [True] * p)
    values = uq['values']
    pairs = [(values[2 * i], values[2 * i + 1]) for i in range(terms)] + ([(values[-1], 0.0)] if long_term else [])
    cov_values = uq['cov_theta'] * np.outer(values, values)     # delta method: d value = value d theta
    exe = runner.find_program(options.exe) if options.exe else runner.default_exe()
    if not exe or not os.path.isfile(exe):
        raise UsageError('no visco2d executable for eq. [48] (make build, or --exe PATH)')
    if long_term:
        # E_inf is the pair (E_inf, 0): its alpha is not a fitted constant (no variance)
        index = list(range(2 * terms)) + [2 * terms]
        full = np.zeros((2 * terms + 2, 2 * terms + 2))
        full[np.ix_(index, index)] = cov_values
        cov_values = full
    if np.all(np.isfinite(uq['se'])):
        bulk, shear, shear_se = shear_uncertainty(exe, options.nu, pairs, cov_values)
    else:
        bulk, shear = relax_program(exe, options.nu, pairs)
        shear_se = np.full(1 + 2 * len(shear), np.inf)
    rho = f' RHO={options.rho:g}' if options.rho else ''
    cards = ['# eq. [47]: the uniaxial relaxation modulus as fitted',
             f'MATERIAL {options.name} UNIAXIAL NU={options.nu:g}{rho}']
    cards += [f'PRONY E={fmt(e)} ALPHA={fmt(a)}' for e, a in pairs]
    cards += ['# or, the same material through eq. [48] (visco2d relax): the shear series and K',
              f'# MATERIAL {options.name} VISCOELASTIC K={fmt(bulk)}{rho}']
    cards += [f'# PRONY G={fmt(g)} BETA={fmt(b)}' for g, b in shear]
    extra = [f'data = {options.data} ({SI[kind_x]}, {SI[kind_y]}; {len(t)} points, t = {t[0]:.4g} ... {t[-1]:.4g} s)',
             f'held strain = {options.strain:g}' + (f', area = {area:.6g} m^2' if area else ''),
             f'model: E(t) = {"E_inf + " if long_term else ""}sum_i E_i exp(-alpha_i t), eq. [47], '
             f'{terms} terms; sigma(t) = eps0 E(t) (an instantaneous step)',
             f'optimiser = scipy.optimize.least_squares (trf, analytic Jacobian), {result.nfev} evaluations, '
             f'best of {3} starts', 'forward_runs = 0 (closed form)',
             '', f'eq. [48] with nu = {options.nu:g} (visco2d relax): K = {bulk:.6g} +- {shear_se[0]:.3g} Pa']
    for m, (g, b) in enumerate(shear):
        extra.append(f'  G{m + 1} = {g:.6g} +- {shear_se[1 + 2 * m]:.3g} Pa   beta{m + 1} = {b:.6g} +- '
                     f'{shear_se[2 + 2 * m]:.3g} 1/s')
    record_extra = {'shear': {'K': bulk, 'K_se': float(shear_se[0]),
                              'G': [g for g, _ in shear], 'beta': [b for _, b in shear],
                              'G_se': [float(s) for s in shear_se[1::2]],
                              'beta_se': [float(s) for s in shear_se[2::2]]}}
    status = finish(options, names, [True] * p, theta, uq, extra, cards,
                    csv_text('time', 'stress', t, modulus * options.strain, model * options.strain),
                    picture('time', 'modulus', t, modulus, model, f'eq. [47], {terms} terms, fitted to '
                            f'{os.path.basename(options.data)}', logx=True),
                    bounds=[(0.0, math.inf)] * p, fixed={}, template=None,
                    title=f'visco2d-fit relaxation {options.data}', unit='Pa (of E(t))')
    path = os.path.join(options.out, 'fit.json')
    with open(path) as handle:
        record = json.load(handle)
    record.update(record_extra)
    with open(path, 'w') as handle:
        json.dump(record, handle, indent=1)
    return status


# ---------------------------------------------------------------- visco2d-fit sample (Monte Carlo)

def draw_samples(record, count, seed):
    """count constant sets from the multivariate normal of the fit (in its log / linear parameters),
    clipped to the bounds: [{name: value}]."""
    theta = np.array(record['theta'])
    cov = np.array(record['cov_theta'])
    if not np.all(np.isfinite(cov)) or not np.all(np.isfinite(record['se'])):
        raise UsageError('the fit has constants the data do not determine (infinite standard error): '
                         'no covariance to sample')
    generator = np.random.default_rng(seed)
    draws = generator.multivariate_normal(theta, cov, size=count, method='eigh')
    rows = []
    for draw in draws:
        row = {}
        for name, lg, t, (low, high) in zip(record['names'], record['log'], draw, record['bounds']):
            value = math.exp(t) if lg else t
            row[name] = min(max(value, low), high)
        rows.append(row)
    return rows


def sample(options):
    try:
        with open(options.fit) as handle:
            record = json.load(handle)
    except (OSError, ValueError) as error:
        raise UsageError(f'{options.fit}: not a fit.json of visco2d-fit ({error})') from None
    if options.n < 2:
        raise UsageError('--n: at least 2 samples')
    rows = draw_samples(record, options.n, options.seed)
    names = record['names']
    lines = [','.join(['case'] + names)]
    for k, row in enumerate(rows):
        lines.append(','.join([f'mc_{k + 1:03d}'] + [fmt(row[n]) for n in names]))
    with open(options.output, 'w') as handle:
        handle.write('\n'.join(lines) + '\n')
    print(f'{options.output}: {len(rows)} constant sets of {", ".join(names)} (seed {options.seed})')
    if not options.run:
        return 0
    from . import batch
    argv = ['run', options.run, '--table', options.output, '-o', options.batch_out, '-q',
            '--keys', options.key]
    for text in options.set:
        argv += ['--param', text]
    if options.jobs:
        argv += ['-j', str(options.jobs)]
    if options.exe:
        argv += ['--exe', options.exe]
    status = batch.main(argv)
    values = []
    with open(os.path.join(options.batch_out, 'table.csv'), newline='') as handle:
        for row in csv.DictReader(handle):
            try:
                values.append(float(row[options.key]))
            except (KeyError, ValueError):
                pass
    if len(values) < 2:
        raise FitError(f'{options.batch_out}/table.csv: fewer than 2 cases report {options.key}')
    values = np.array(values)
    print(f'{options.key}: mean = {values.mean():.6g}, sd = {values.std(ddof=1):.3g}, '
          f'min = {values.min():.6g}, max = {values.max():.6g} ({len(values)} of {len(rows)} cases)')
    return status


# ---------------------------------------------------------------- command line

def build_parser():
    parser = argparse.ArgumentParser(prog=PROGRAM, description=__doc__.split('\n\n')[0].split('\n', 1)[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog='doc/calibration.md')
    sub = parser.add_subparsers(dest='command', required=True)
    deck = sub.add_parser('deck', help='fit a template deck\'s ${name} constants to a curve by forward runs')
    deck.add_argument('template')
    deck.add_argument('--data', required=True, help='the measured curve (CSV, units in the column names)')
    deck.add_argument('--param', action='append', default=[], required=True,
                      help='NAME=LOW:HIGH or NAME=LOW:GUESS:HIGH, a constant to fit (repeatable)')
    deck.add_argument('--set', action='append', default=[], help='NAME=VALUE, a placeholder held fixed')
    deck.add_argument('--model-x', help='the history column compared with the abscissa (default from the names)')
    deck.add_argument('--x-scale', type=float, default=1.0, help='factor on --model-x (to SI, sign)')
    deck.add_argument('--model-y', help='the history column compared with the ordinate')
    deck.add_argument('--y-scale', type=float, default=1.0, help='factor on --model-y (e.g. minus an area)')
    deck.add_argument('--max-evaluations', type=int, default=60, help='least_squares max_nfev (default 60)')
    relax = sub.add_parser('relaxation', help='eq. [47] in closed form, then eq. [48] and the cards')
    relax.add_argument('--data', required=True)
    relax.add_argument('--terms', type=int, required=True, help='the number of exponential terms')
    relax.add_argument('--long-term', action='store_true', help='also a constant E_inf (alpha = 0)')
    relax.add_argument('--strain', type=float, required=True, help='the held strain (its magnitude)')
    relax.add_argument('--area', type=float, help='specimen cross-section (m^2) for a force curve')
    relax.add_argument('--diameter', type=float, help='specimen diameter (m) for a force curve')
    relax.add_argument('--nu', type=float, required=True, help="Poisson's ratio at t = 0 (eq. [48]'s K)")
    relax.add_argument('--rho', type=float, help='density for the cards (kg/m^3)')
    relax.add_argument('--name', default='flesh', help='the material id of the cards')
    for command in (deck, relax):
        command.add_argument('-o', '--out', required=True, help='output folder')
        command.add_argument('--exe', help='the visco2d executable')
        command.add_argument('-q', '--quiet', action='store_true', help='no summary on stdout')
    mc = sub.add_parser('sample', help='constant sets from a fit\'s covariance (a visco2d-batch --table)')
    mc.add_argument('fit', help='OUT/fit.json of a fit')
    mc.add_argument('--n', type=int, required=True)
    mc.add_argument('--seed', type=int, default=1)
    mc.add_argument('-o', '--output', required=True, help='the rows CSV to write')
    mc.add_argument('--run', help='a template to run through visco2d-batch with the rows')
    mc.add_argument('--key', default='bruise_volume_cm3', help='the summary key to report (mean, sd)')
    mc.add_argument('--batch-out', default='out/fit_mc', help='visco2d-batch output root')
    mc.add_argument('--set', action='append', default=[], help='NAME=VALUE for the template\'s other placeholders')
    mc.add_argument('-j', '--jobs', type=int)
    mc.add_argument('--exe')
    return parser


def main(argv=None):
    options = build_parser().parse_args(argv)
    try:
        if options.command == 'deck':
            return fit_deck(options)
        if options.command == 'relaxation':
            return fit_relaxation(options)
        return sample(options)
    except UsageError as error:
        print(f'{PROGRAM}: error: {error}', file=sys.stderr)
        return 2
    except FitError as error:
        print(f'{PROGRAM}: error: {error}', file=sys.stderr)
        return 1


if __name__ == '__main__':
    sys.exit(main())
