"""Mutation fuzzer of the visco2d card reader and solvers.

    PYTHONPATH=python python3 -m visco2d.fuzz [-n N] [--seed S] [-j JOBS] [--bound SECONDS] [--exe PATH] [--out DIR]
    PYTHONPATH=python python3 -m visco2d.fuzz --decks DECK...        run decks as they are (regression decks)
    PYTHONPATH=python python3 -m visco2d.fuzz --shrink DECK          minimize a failing deck (line delta debugging)

Takes the seed decks (inputs/*.inp and test/fuzz/*.inp; LEVEL=1 meshes and at most 1000
steps per TIME stage, so that most runs take well under a second), makes N mutated decks
from them (deterministically: deck i depends only on --seed, i and the seed decks, not on
--jobs), runs each with the visco2d executable into a fresh output root under a wall-time
bound and a 4 GB address-space limit (and VISCO2D_MAX_TIME = a quarter of the bound,
so a run estimated to be longer is refused up front; a tenth of the decks go to
'visco2d check DECK' instead), and classifies the run.  A run passes when it exits 0, 1, 2 or 3
(3: it ran, its outputs are written, and it missed one of its own EXPECT cards) and none of
these holds:

  CRASH       a signal, an exit status other than 0/1/2/3, or runtime-error text in
              stderr ('Fortran runtime error', 'Backtrace', 'Error termination',
              'Segmentation', UBSan's 'runtime error:', 'AddressSanitizer', ...)
  HANG        still running after --bound seconds (its process group is killed)
  PARTIAL     a '.partial.' or '.old.' folder left in the output root
  NONFINITE   NaN or Inf/Infinity in summary.txt, history.csv, listing.txt or
              results.h5 (every dataset and attribute, strings too); the deck's
              own text echoed back (title, input cards) is not counted
  UNREADABLE  a number no reader can parse in those files: a field of '*'
              (Fortran's overflowed edit descriptor) or an exponent without its
              letter (1.0000-300)
  UNLOCATED   exit 1 without an error line 'visco2d: error: <deck>:<line>[:<col>]: ...'
              (the errors without a column are counted by message form, as statistics)
  OUTPUT_ON_ERROR  exit 1 or 2 with the case folder OUT/<case>/ left behind
  MISSING_OUTPUT   exit 0 or 3 without each of listing.txt, summary.txt, history.csv, results.h5
  SILENT      a change that must not go unnoticed was accepted: a card padded with
              blanks past column 4096 or given a long comment (same meaning) ran to a
              different summary, or to an error that is not about the line's length; a
              keyword turned into a non-keyword (near miss) or a
              duplicated MESH/ELEMENT card ran with exit 0; a run with exit 0 whose
              summary reports fewer EXPECT results than the deck's EXPECT cards; a run
              whose summary has an EXPECT outside its RTOL (expect_*_within_rtol = no) with
              exit 0, or exit 3 without one or without its located 'EXPECT:' error line; a run with
              exit 0 whose energy-balance error (balance_error_max_rel) is above 10 % of the
              energy put in without a 'visco2d: warning:' about the energy

The report goes to OUT (default out/fuzz/): summary.md (counts per class and per
mutation kind, the error forms without a column), cases.csv (one row per deck),
and failures/<CLASS>/<id>.{inp,stderr,reason} for every failing deck.  The last
line of stdout is 'fuzz: N passed, N failed'; the exit status is 1 if any deck failed.

A regression deck (--decks) may say what it expects in '# fuzz:' comment lines:
  # fuzz: exit 1            the allowed exit statuses (default 0 1 2)
  # fuzz: summary KEY = V   when it exits 0, summary.txt must hold this line
"""

import argparse
import concurrent.futures
import csv
import glob
import math
import os
import random
import re
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

from . import case as case_folder
from .runner import ROOT

FAIL_CLASSES = ['CRASH', 'HANG', 'PARTIAL', 'NONFINITE', 'UNREADABLE', 'UNLOCATED',
                'OUTPUT_ON_ERROR', 'MISSING_OUTPUT', 'SILENT']

# Every keyword and field name of the card language (visco2d_deck.f90 and the *_cards.f90 readers).
KEYWORDS = set('''
ALPHA ANALYSIS ANGLE AR AT AXIS AXISYMMETRIC AZ BBAR BETA BOTTOM CORE CURVE DR DROP DT DYNAMIC
DZ E ELASTIC ELEMENT END EVERY EXPECT FIELDS FIX FORCE FORMULATION FR FZ G GEN GEOMETRY GRADE
GRAVITY HEIGHT INC INITIAL INNER K LEVEL MAT MATERIAL MAXDEFORMATION MESH NINC NO NODE NONE NR
NT NU NZ OUTER OUTPUT P PLANESTRAIN PLATE PRESSURE PROBE PRONY QUASISTATIC R R0 R1 RECT RELEASE
RHO RING RTOL RZ SEPARATION SLIP SPHERE STANDARD STATIC STEP STICK STOP TEND THETA TIME TITLE
TOP UNIAXIAL UR UZ VISCOELASTIC VR VZ WILSON YES Z Z0 Z1 ZR
INTEGRATOR NEWMARK HHT GENERALIZED_ALPHA BATHE GAMMA RHO_INF
'''.split())
# Cards whose second word is a user name (not a keyword), and TITLE (free text).
NAMED_CARDS = {'TITLE', 'MATERIAL', 'PROBE', 'CURVE', 'EXPECT'}

SPECIAL_NUMBERS = ['0', '-1', '1e308', '-1e308', '4.9e-324', '-4.9e-324', 'NaN', 'nan', 'Inf',
                   '-Infinity', '2147483647', '999999999', '4294967296', '-2147483648',
                   '9223372036854775808', '1e-308', '2.2250738585072014e-308', '1.8e308', '-0',
                   '1e999', '0.0', '1e-30', '1e30']
HUGE_INTEGERS = ['2147483647', '999999999', '4294967296', '-2147483648', '2147483648', '100000',
                 '3000', '700000000']

TEMPLATE_CARDS = [
    'PLATE Z=0 STICK', 'PLATE Z=0 SLIP RELEASE=YES', 'PLATE Z=0.01 SLIP', 'STOP AT=SEPARATION',
    'STOP AT=MAXDEFORMATION', 'STOP AT=TEND', 'FORMULATION BBAR', 'FORMULATION STANDARD',
    'GRAVITY G=9.8', 'GRAVITY', 'CURVE ramp 0 0 1e-3 1', 'CURVE held STEP', 'FORCE 1 FZ=-1 CURVE=ramp',
    'FORCE 3 FR=1e3 FZ=-1e3', 'FIX 1 RZ', 'FIX AXIS R', 'FIX BOTTOM Z', 'FIX TOP Z UZ=-1e-4 CURVE=ramp',
    'PROBE p NODE=1', 'PROBE q R=0 Z=0', 'EXPECT nodes 5', 'EXPECT steps 10 RTOL=0',
    'OUTPUT EVERY=1', 'OUTPUT EVERY=3 FIELDS=1e-4,2e-4', 'INITIAL VZ=-1', 'INITIAL AZ=0 AR=0',
    'DROP HEIGHT=0.05', 'TIME DT=1e-5 TEND=1e-4', 'WILSON THETA=1.4', 'WILSON THETA=1.0',
    'INTEGRATOR NEWMARK', 'INTEGRATOR NEWMARK BETA=0.1667 GAMMA=0.5', 'INTEGRATOR HHT ALPHA=0.1',
    'INTEGRATOR GENERALIZED_ALPHA RHO_INF=0.5', 'INTEGRATOR BATHE', 'INTEGRATOR WILSON THETA=1.4',
    'ANALYSIS STATIC', 'ANALYSIS DYNAMIC', 'ANALYSIS QUASISTATIC', 'GEOMETRY PLANESTRAIN',
    'GEOMETRY AXISYMMETRIC', 'NODE 1000 0 0', 'NODE 1 0 0', 'ELEMENT 1000 1 2 3 4 MAT=m',
    'MESH RECT R0=0 R1=0.01 Z0=0 Z1=0.01 NR=2 NZ=2', 'MESH SPHERE R=0.03 LEVEL=1',
    'MESH RING R0=0.01 R1=0.02 NR=2 NT=2', 'MATERIAL m ELASTIC E=1e6 NU=0.3 RHO=1000',
    'MATERIAL u UNIAXIAL NU=0.25', 'PRONY G=1e6 BETA=1', 'PRONY E=1e6 ALPHA=1', 'PRESSURE TOP P=1e5',
    'PRESSURE OUTER P=1e5 CURVE=ramp', 'TITLE inserted', 'END', '#', '!', '=', 'X=1']

NUMBER = re.compile(r'(?<![A-Za-z0-9_.])[+-]?(?:\d+\.?\d*|\.\d+)(?:[eEdD][+-]?\d+)?(?![A-Za-z0-9_.])')
WORD = re.compile(r'[A-Za-z][A-Za-z0-9_]*')
ERROR_LINE = re.compile(r'^visco2d: error: (.*)$', re.M)
NONFINITE_TOKEN = re.compile(r'(?<![A-Za-z0-9_])[-+]?(?:nan|inf|infinity)(?![A-Za-z0-9_])', re.I)
STARS = re.compile(r'\*{2,}')
NO_EXPONENT_LETTER = re.compile(r'(?<![A-Za-z0-9_.])[-+]?\d+\.\d+[-+]\d{2,}(?![\w.])')
CHECK_SHARE = 0.1     # the share of mutated decks given to 'visco2d check' instead of a run
BALANCE_LIMIT = 0.1   # balance_error_max_rel above this needs a warning that names the energy
CRASH_TEXT = ['Fortran runtime error', 'Backtrace', 'Error termination', 'Segmentation',
              'runtime error:', 'AddressSanitizer', 'LeakSanitizer', 'UndefinedBehaviorSanitizer',
              'Program received signal', 'Floating point exception', 'Illegal instruction',
              'Bus error', 'Aborted', 'Error allocating', 'Operating system error']


# ---------------------------------------------------------------------------- decks
def read_deck(path):
    with open(path, 'rb') as handle:
        return handle.read().decode('latin-1')


def split_lines(text):
    return text.split('\n')


def is_card(line):
    stripped = line.strip()
    return bool(stripped) and stripped[0] not in '#!'


def card_part(line):
    """The line before its comment ('#' or '!')."""
    cut = len(line)
    for mark in '#!':
        position = line.find(mark)
        if position >= 0:
            cut = min(cut, position)
    return line[:cut]


def keyword(line):
    words = card_part(line).split()
    return words[0].upper() if words else ''


def end_index(lines):
    for index, line in enumerate(lines):
        if keyword(line) == 'END':
            return index
    return len(lines)


def card_indices(lines, before_end=True):
    last = end_index(lines) if before_end else len(lines)
    return [i for i, line in enumerate(lines[:last]) if is_card(line)]


def normalize_seed(text):
    """Make a seed cheap to run: mesh LEVEL=1, at most 1000 steps per TIME stage."""
    lines = split_lines(text)
    for index, line in enumerate(lines):
        body = card_part(line)
        word = keyword(line)
        if word == 'MESH':
            body = re.sub(r'(?i)\bLEVEL=\d+', 'LEVEL=1', body)
        elif word == 'TIME':
            dt = re.search(r'(?i)\bDT=(\S+)', body)
            tend = re.search(r'(?i)\bTEND=(\S+)', body)
            try:
                step, end = float(dt.group(1)), float(tend.group(1))
                if step > 0 and end / step > 1000:
                    body = body[:tend.start(1)] + ('%.6g' % (1000 * step)) + body[tend.end(1):]
            except (AttributeError, ValueError):
                pass
        lines[index] = body + line[len(card_part(line)):]
    return '\n'.join(lines)


def directives(text):
    """'# fuzz: exit 1' and '# fuzz: summary KEY = V' lines of a regression deck."""
    exits, summary = None, []
    for line in split_lines(text):
        match = re.match(r'\s*#\s*fuzz:\s*(\w+)\s*(.*?)\s*$', line)
        if not match:
            continue
        if match.group(1) == 'exit':
            exits = {int(word) for word in match.group(2).replace(',', ' ').split()}
        elif match.group(1) == 'summary':
            summary.append(re.sub(r'\s*=\s*', ' = ', match.group(2), count=1))
    return exits, summary


# ---------------------------------------------------------------------------- mutations
class Mutant:
    """A deck under mutation: its lines, the kinds applied, and the oracle flags."""

    def __init__(self, text, rng, seed_name, pool):
        self.lines = split_lines(text)
        self.rng = rng
        self.seed_name = seed_name
        self.pool = pool
        self.kinds = []
        self.notes = []
        self.must_fail = False      # the deck must be refused (exit 1)
        self.same_as_seed = False   # exit 0 must give the seed's summary

    def text(self):
        return '\n'.join(self.lines)

    def solo(self):
        """At most one mutation so far (rewriting MESH RECT as NODE/ELEMENT cards does not count)."""
        return len([kind for kind in self.kinds if kind != 'explicit']) <= 1

    def pick_card(self, predicate=None, before_end=True):
        indices = [i for i in card_indices(self.lines, before_end)
                   if predicate is None or predicate(self.lines[i])]
        return self.rng.choice(indices) if indices else None

    def replace_field(self, index, name, value):
        """Set NAME=value on card `index` (added if missing)."""
        line = self.lines[index]
        body, comment = card_part(line), line[len(card_part(line)):]
        pattern = re.compile(r'(?i)(?<![A-Za-z0-9_])' + re.escape(name) + r'=\S*')
        if pattern.search(body):
            body = pattern.sub(lambda _: name + '=' + value, body, count=1)
        else:
            body = body.rstrip() + ' ' + name + '=' + value
        self.lines[index] = body + comment


def mutate_delete_line(m):
    if not m.lines:
        return False
    index = m.pick_card() if m.rng.random() < 0.9 else m.rng.randrange(len(m.lines))
    if index is None:
        return False
    m.notes.append('deleted line %d: %.60s' % (index + 1, m.lines[index]))
    del m.lines[index]
    return True


def mutate_duplicate_line(m):
    index = m.pick_card()
    if index is None:
        return False
    line = m.lines[index]
    target = m.rng.choice([index + 1, m.rng.randrange(len(m.lines) + 1)])
    m.lines.insert(target, line)
    m.notes.append('duplicated line %d to %d: %.60s' % (index + 1, target + 1, line))
    if not m.kinds and keyword(line) in ('MESH', 'ELEMENT') and target <= end_index(m.lines):
        m.must_fail = True   # a second copy of the mesh or of an element: coincident elements
    return True


def mutate_swap_lines(m):
    cards = card_indices(m.lines)
    if len(cards) < 2:
        return False
    first, second = m.rng.sample(cards, 2)
    m.lines[first], m.lines[second] = m.lines[second], m.lines[first]
    m.notes.append('swapped lines %d and %d' % (first + 1, second + 1))
    return True


def number_spans(line):
    return [match.span() for match in NUMBER.finditer(card_part(line))]


def pick_number(m, predicate=None):
    candidates = []
    for index in card_indices(m.lines, before_end=m.rng.random() < 0.95):
        word = keyword(m.lines[index])
        if word == 'TITLE' and m.rng.random() < 0.9:
            continue
        if predicate is not None and not predicate(m.lines[index]):
            continue
        for span in number_spans(m.lines[index]):
            candidates.append((index, span))
    return m.rng.choice(candidates) if candidates else None


def set_number(m, where, value, note):
    index, (start, stop) = where
    line = m.lines[index]
    m.notes.append('%s line %d: %s -> %s' % (note, index + 1, line[start:stop], value))
    m.lines[index] = line[:start] + value + line[stop:]


def mutate_number_special(m):
    where = pick_number(m)
    if where is None:
        return False
    set_number(m, where, m.rng.choice(SPECIAL_NUMBERS + HUGE_INTEGERS), 'number')
    return True


def mutate_number_scale(m):
    where = pick_number(m)
    if where is None:
        return False
    index, (start, stop) = where
    text = m.lines[index][start:stop]
    try:
        value = float(text.replace('d', 'e').replace('D', 'e'))
    except ValueError:
        return False
    if not math.isfinite(value) or abs(value) > 1e300:
        return False
    choice = m.rng.random()
    if choice < 0.25:
        new = -value
    elif choice < 0.5 and re.fullmatch(r'[+-]?\d+', text):
        new = int(value) + m.rng.choice([-2, -1, 1, 2])
    else:
        new = value * 10.0 ** m.rng.choice([-6, -3, -2, -1, 1, 2, 3])
    if isinstance(new, int) or (re.fullmatch(r'[+-]?\d+', text) and math.isfinite(new) and new == int(new)):
        new_text = str(int(new))
    else:
        new_text = '%.6g' % new
    set_number(m, where, new_text, 'scaled')
    return True


JUNK = ['\x00', '\x07', '\t', '\r', '\x1b', '\xff\xfe', '\xc3\xa9', '\xe2\x80\x8b', '\xef\xbb\xbf',
        '=', ',', '"', "'", ';', '&', '(', ')', '\\', '#', '!', ' = ', '==', '.', '-', '+', 'e', 'E']


def mutate_junk(m):
    data = m.text()
    count = m.rng.choice([1, 1, 1, 2, 3, 8])
    for _ in range(count):
        position = m.rng.randrange(len(data) + 1)
        junk = m.rng.choice(JUNK) if m.rng.random() < 0.7 else ''.join(
            chr(m.rng.randrange(256)) for _ in range(m.rng.randint(1, 6)))
        data = data[:position] + junk + data[position:]
    m.notes.append('%d junk insertion(s)' % count)
    m.lines = split_lines(data)
    return True


def mutate_truncate(m):
    data = m.text()
    cards = card_indices(m.lines)
    if cards and m.rng.random() < 0.7:
        # cut inside a card line
        index = m.rng.choice(cards)
        offset = sum(len(line) + 1 for line in m.lines[:index]) + m.rng.randrange(len(m.lines[index]) + 1)
    else:
        offset = m.rng.randrange(len(data) + 1)
    m.notes.append('truncated at byte %d of %d' % (offset, len(data)))
    m.lines = split_lines(data[:offset])
    return True


def near_miss(rng, word):
    """A misspelling of `word` and whether it is a case-only change."""
    operation = rng.randrange(7)
    position = rng.randrange(len(word))
    letters = 'ABCDEFGHIJKLMNOPQRSTUVWXYZ'
    if operation == 0 and len(word) > 1:
        return word[:position] + word[position + 1:], False
    if operation == 1:
        return word[:position] + rng.choice(letters) + word[position:], False
    if operation == 2 and len(word) > 1:
        position = min(position, len(word) - 2)
        swapped = word[:position] + word[position + 1] + word[position] + word[position + 2:]
        return swapped, swapped == word
    if operation == 3:
        return word[:position] + rng.choice(letters) + word[position + 1:], False
    if operation == 4:
        return word + rng.choice(['S', '_', '1', 'X']), False
    if operation == 5:
        return word.lower() if rng.random() < 0.5 else word.capitalize(), True
    return word[:position] + word[position] + word[position:], False


def mutate_near_miss(m):
    """Misspell a keyword or field name (must be refused), or change its case (must not matter)."""
    candidates = []
    for index in card_indices(m.lines):
        body = card_part(m.lines[index])
        card = keyword(m.lines[index])
        for number, match in enumerate(WORD.finditer(body)):
            if card == 'TITLE' and number >= 1:
                continue
            if card in ('MATERIAL', 'PROBE', 'CURVE') and number == 1:
                continue
            if card == 'EXPECT' and number >= 1 and not body[match.end():].startswith('='):
                continue
            if match.group(0) in KEYWORDS:
                candidates.append((index, match.span()))
    if not candidates:
        return False
    index, (start, stop) = m.rng.choice(candidates)
    line = m.lines[index]
    word = line[start:stop]
    if m.rng.random() < 0.15 and line[stop:stop + 1] == '=':
        variant = m.rng.choice([' =', ' = ', '==', ':', '=='])
        m.lines[index] = line[:stop] + variant + line[stop + 1:]
        m.notes.append('line %d: %s= -> %s%s' % (index + 1, word, word, variant))
        return True
    new, case_only = near_miss(m.rng, word)
    if not new or new == word:
        return False
    m.lines[index] = line[:start] + new + line[stop:]
    m.notes.append('line %d: %s -> %s' % (index + 1, word, new))
    if not case_only and new.upper() not in KEYWORDS and not m.kinds:
        m.must_fail = True
    return True


def field_pattern(name):
    return re.compile(r'(?i)(?<![A-Za-z0-9_])(' + re.escape(name) + r')=(\S*)')


def mutate_degenerate_mesh(m):
    """Coincident nodes, zero-area and inverted elements, empty or collapsed generated meshes."""
    mesh = m.pick_card(lambda line: keyword(line) == 'MESH')
    elements = [i for i in card_indices(m.lines) if keyword(m.lines[i]) == 'ELEMENT']
    nodes = [i for i in card_indices(m.lines) if keyword(m.lines[i]) == 'NODE']
    options = []
    if mesh is not None:
        options.append('mesh')
    if elements:
        options.append('element')
    if nodes:
        options.append('node')
    if mesh is not None and 'RECT' in m.lines[mesh].upper():
        options.append('explicit')
    if not options:
        return False
    option = m.rng.choice(options)
    if option == 'mesh':
        line = m.lines[mesh].upper()
        if 'RECT' in line:
            change = m.rng.choice([('R1', 'R0'), ('Z1', 'Z0'), ('NR', '0'), ('NZ', '0'), ('R0', '-0.01'),
                                   ('R1', '-0.01'), ('Z1', '-1'), ('NR', '-1'), ('R0', '1e-300')])
        elif 'RING' in line:
            change = m.rng.choice([('R1', 'R0'), ('R0', '0'), ('ANGLE', '0'), ('ANGLE', '360'), ('ANGLE', '720'),
                                   ('ANGLE', '1e-12'), ('NT', '0'), ('R0', '-0.01'), ('ANGLE', '-90')])
        else:
            change = m.rng.choice([('R', '0'), ('R', '-0.03'), ('GRADE', '0'), ('GRADE', '1'), ('GRADE', '-1'),
                                   ('GRADE', '1e6'), ('CORE', '0'), ('CORE', '1'), ('CORE', '2'), ('LEVEL', '0'),
                                   ('R', '1e-300'), ('CORE', '-0.5')])
        name, value = change
        if value in ('R0', 'Z0'):
            match = field_pattern(value).search(card_part(m.lines[mesh]))
            value = match.group(2) if match else '0'
        m.replace_field(mesh, name, value)
        m.notes.append('MESH line %d: %s=%s' % (mesh + 1, name, value))
        return True
    if option == 'explicit':
        return explicit_mesh(m, mesh)
    if option == 'element':
        index = m.rng.choice(elements)
        words = card_part(m.lines[index]).split()
        if len(words) < 6:
            return False
        rest = words[6:]
        corners = words[2:6]
        choice = m.rng.randrange(5)
        if choice == 0:
            corners[m.rng.randrange(1, 4)] = corners[0]                # a repeated node: zero area
            note = 'repeated node'
        elif choice == 1:
            corners = corners[::-1]                                    # clockwise: negative area
            note = 'clockwise'
        elif choice == 2:
            corners[m.rng.randrange(4)] = m.rng.choice(['999999999', '0', '-1', '2147483647'])
            note = 'missing node'
        elif choice == 3:
            # a second element on the same nodes (coincident elements)
            number = m.rng.choice(['9999', '500', str(int(words[1]) + 1) if words[1].isdigit() else '2'])
            single = [w for w in rest if not w.upper().startswith(('GEN', 'INC', 'NINC'))]
            m.lines.insert(index + 1, ' '.join(['ELEMENT', number] + corners + single))
            m.notes.append('coincident element %s on line %d' % (number, index + 2))
            if not [kind for kind in m.kinds if kind != 'explicit']:
                m.must_fail = True
            return True
        else:
            corners = [corners[0], corners[2], corners[1], corners[3]]  # bow-tie (self-crossing)
            note = 'bow-tie'
        m.lines[index] = ' '.join(words[:2] + corners + rest)
        m.notes.append('ELEMENT line %d: %s' % (index + 1, note))
        return True
    # node: the same position as another node, or a huge number
    index = m.rng.choice(nodes)
    words = card_part(m.lines[index]).split()
    if len(words) < 4:
        return False
    other = card_part(m.lines[m.rng.choice(nodes)]).split()
    choice = m.rng.randrange(3)
    if choice == 0 and len(other) >= 4:
        words[2:4] = other[2:4]
        note = 'coincident with another node'
    elif choice == 1:
        words[1] = m.rng.choice(HUGE_INTEGERS)
        note = 'node number %s' % words[1]
    else:
        fields = [w for w in words[4:]]
        words = words[:4] + [re.sub(r'(?i)^(DR|DZ)=.*', r'\1=0', w) for w in fields]
        note = 'generation step 0 (coincident generated nodes)'
    m.lines[index] = ' '.join(words)
    m.notes.append('NODE line %d: %s' % (index + 1, note))
    return True


def explicit_mesh(m, mesh):
    """Replace MESH RECT by the same mesh in NODE and ELEMENT cards (then maybe degenerate it)."""
    body = card_part(m.lines[mesh])
    fields = {match.group(1).upper(): match.group(2) for match in re.finditer(r'([A-Za-z0-9]+)=(\S+)', body)}
    try:
        r0, r1, z0, z1 = (float(fields[k]) for k in ('R0', 'R1', 'Z0', 'Z1'))
        nr, nz = int(fields['NR']), int(fields['NZ'])
    except (KeyError, ValueError):
        return False
    if not (0 < nr <= 40 and 0 < nz <= 40):
        return False
    material = fields.get('MAT')
    if material is None:
        for line in m.lines:
            if keyword(line) == 'MATERIAL' and len(card_part(line).split()) > 1:
                material = card_part(line).split()[1]
                break
    if material is None:
        return False
    cards = []
    for j in range(nz + 1):
        cards.append('NODE %d %.10g %.10g GEN=%d INC=1 DR=%.10g' % (j * (nr + 1) + 1, r0, z0 + (z1 - z0) * j / nz,
                                                                  nr, (r1 - r0) / nr))
    for j in range(nz):
        first = j * (nr + 1) + 1
        cards.append('ELEMENT %d %d %d %d %d MAT=%s GEN=%d INC=1 NINC=1' % (j * nr + 1, first, first + 1,
                                                                           first + nr + 2, first + nr + 1,
                                                                           material, nr - 1))
    m.lines[mesh:mesh + 1] = cards
    m.notes.append('MESH RECT line %d as %d NODE/ELEMENT cards' % (mesh + 1, len(cards)))
    if m.rng.random() < 0.7:
        m.kinds.append('explicit')
        return mutate_degenerate_mesh(m) or True
    return True


def mutate_long_line(m):
    """Blank padding past column 4096, a long comment, a long name or number."""
    choice = m.rng.randrange(5)
    index = m.pick_card(lambda line: keyword(line) != 'TITLE')
    if index is None:
        return False
    line = m.lines[index]
    body, comment = card_part(line), line[len(card_part(line)):]
    if choice == 0:
        words = list(re.finditer(r'\S+', body))
        if len(words) < 2:
            return False
        cut = words[-1].start()
        width = m.rng.choice([4096, 4100, 5000, 8200, 70000])
        m.lines[index] = body[:cut] + ' ' * width + body[cut:] + comment
        m.notes.append('line %d: %d blanks before its last field' % (index + 1, width))
        if not m.kinds:
            m.same_as_seed = True
    elif choice == 1:
        width = m.rng.choice([4000, 4096, 5000, 100000])
        m.lines[index] = body + ' # ' + 'x' * width
        m.notes.append('line %d: a %d-character comment' % (index + 1, width))
        if not m.kinds:
            m.same_as_seed = True
    elif choice == 2:
        where = pick_number(m)
        if where is None:
            return False
        index, (start, stop) = where
        text = m.lines[index][start:stop]
        digits = m.rng.choice([100, 4000, 5000])
        value = '0.' + '0' * digits + '1' if m.rng.random() < 0.5 else '1' + '0' * digits
        m.lines[index] = m.lines[index][:start] + value + m.lines[index][stop:]
        m.notes.append('line %d: number %s with %d digits' % (index + 1, text, digits))
    elif choice == 3:
        # a long PROBE name, its EXPECT keys renamed alike: the summary keys must keep it whole
        probes = [i for i in card_indices(m.lines) if keyword(m.lines[i]) == 'PROBE'
                  and len(card_part(m.lines[i]).split()) > 1]
        if not probes:
            return False
        index = m.rng.choice(probes)
        name = card_part(m.lines[index]).split()[1]
        new = name + '_' + 'long' * m.rng.choice([10, 12, 20, 1100])
        for i, other in enumerate(m.lines):
            m.lines[i] = re.sub(r'\bprobe_' + re.escape(name) + r'_', 'probe_' + new + '_', other)
        m.lines[index] = m.lines[index].replace(name, new, 1)
        m.notes.append('PROBE %s renamed to a %d-character name' % (name, len(new)))
    else:
        # a long TITLE or material name
        title = m.pick_card(lambda text: keyword(text) in ('TITLE', 'MATERIAL'), before_end=True)
        if title is None:
            return False
        words = card_part(m.lines[title]).split()
        if len(words) < 2:
            return False
        width = m.rng.choice([100, 300, 4000])
        if words[0].upper() == 'TITLE':
            m.lines[title] = 'TITLE ' + 'T' * width
        else:
            old = words[1]
            new = old + 'm' * width
            for i, other in enumerate(m.lines):
                m.lines[i] = re.sub(r'(?i)(MAT=)' + re.escape(old) + r'\b', r'\g<1>' + new, other)
            m.lines[title] = m.lines[title].replace(old, new, 1)
        m.notes.append('line %d: a %d-character name' % (title + 1, width))
    return True


def mutate_insert_card(m):
    if m.rng.random() < 0.5:
        card = m.rng.choice(TEMPLATE_CARDS)
    else:
        card = m.rng.choice(m.pool)
    position = m.rng.choice([0, end_index(m.lines), m.rng.randrange(end_index(m.lines) + 1)])
    m.lines.insert(position, card)
    m.notes.append('inserted at line %d: %.60s' % (position + 1, card))
    return True


def mutate_field(m):
    index = m.pick_card(lambda line: '=' in card_part(line))
    if index is None:
        return False
    line = m.lines[index]
    body, comment = card_part(line), line[len(card_part(line)):]
    fields = list(re.finditer(r'([A-Za-z][A-Za-z0-9]*)=(\S*)', body))
    if not fields:
        return False
    field = m.rng.choice(fields)
    choice = m.rng.randrange(6)
    if choice == 0:
        body = body[:field.start()] + body[field.end():]
        note = 'deleted %s' % field.group(0)
    elif choice == 1:
        body = body.rstrip() + ' ' + field.group(1) + '=' + m.rng.choice([field.group(2), '1', '0'])
        note = 'duplicated field %s' % field.group(1)
    elif choice == 2:
        body = body.rstrip() + ' ' + m.rng.choice(['FOO=1', 'X=', '=1', 'NU', 'E=1=2', 'RTOL=0.1'])
        note = 'added a stray field'
    else:
        value = m.rng.choice(['', '=', '1,2', '1e', '.', '+', '-', '1.2.3', '0x10', '1d3', '1_dp', '1e+', 'e5',
                              '--1', '1e-3e', ',', '1 2', '"1"', 'YES', '1/2', '+-1', '1.e5', '.e5', '1E+308',
                              '1e-400', '4.9E-324', '0000000000000000000000000000001'])
        body = body[:field.start(2)] + value + body[field.end(2):]
        note = '%s=%s' % (field.group(1), value)
    m.lines[index] = body + comment
    m.notes.append('line %d: %s' % (index + 1, note))
    return True


def mutate_switch(m):
    """Change a mode word: analysis, geometry, plate mode, stop criterion, formulation."""
    swaps = {
        'ANALYSIS': ['STATIC', 'QUASISTATIC', 'DYNAMIC'],
        'GEOMETRY': ['AXISYMMETRIC', 'PLANESTRAIN'],
        'STOP': ['AT=MAXDEFORMATION', 'AT=SEPARATION', 'AT=TEND'],
        'PLATE': ['Z=0 STICK', 'Z=0 SLIP', 'Z=0 SLIP RELEASE=YES', 'Z=0 STICK RELEASE=YES', 'Z=0.001 SLIP',
                  'Z=-0.001 STICK'],
        'FORMULATION': ['STANDARD', 'BBAR'],
        'MATERIAL': None,
    }
    index = m.pick_card(lambda line: keyword(line) in swaps)
    if index is None:
        m.lines.insert(end_index(m.lines), 'FORMULATION BBAR')
        m.notes.append('FORMULATION BBAR added')
        return True
    word = keyword(m.lines[index])
    if word == 'MATERIAL':
        words = card_part(m.lines[index]).split()
        if len(words) < 3:
            return False
        words[2] = m.rng.choice(['ELASTIC', 'VISCOELASTIC', 'UNIAXIAL'])
        m.lines[index] = ' '.join(words)
    else:
        m.lines[index] = word + ' ' + m.rng.choice(swaps[word])
    m.notes.append('line %d: %s' % (index + 1, m.lines[index][:60]))
    return True


def mutate_whitespace(m):
    choice = m.rng.randrange(7)
    if choice == 0:
        m.lines = [line + '\r' for line in m.lines]
        note = 'CRLF line ends'
    elif choice == 1:
        index = m.pick_card()
        if index is None:
            return False
        m.lines[index] = m.lines[index].replace(' ', '\t')
        note = 'tabs on line %d' % (index + 1)
    elif choice == 2:
        index = m.pick_card()
        if index is None:
            return False
        m.lines[index] = '   ' + m.lines[index].lower()
        note = 'line %d in lower case, indented' % (index + 1)
    elif choice == 3:
        last = end_index(m.lines)
        m.lines = m.lines[:last]
        note = 'no END card'
    elif choice == 4:
        m.lines = [line for line in m.lines if line.strip()]
        data = m.text().rstrip('\n')
        m.lines = split_lines(data)
        note = 'no final newline'
    elif choice == 5:
        m.lines = ['', ' ', '\t'] + m.lines
        note = 'blank lines first'
    else:
        m.lines = []
        note = 'empty file'
    m.notes.append(note)
    return True


def mutate_physics(m):
    """The scenes of the issue: diverging integration, too large or tiny steps, near-incompressible, overloads."""
    word = {keyword(line) for line in m.lines}
    choice = m.rng.randrange(9)
    if choice == 0 and 'PLATE' in word and 'WILSON' in word:
        for i, line in enumerate(m.lines):
            if keyword(line) == 'WILSON':
                m.lines[i] = 'WILSON THETA=1.0'
            elif keyword(line) == 'PLATE':
                m.lines[i] = 'PLATE Z=0 SLIP RELEASE=YES'
            elif keyword(line) == 'TIME':
                m.lines[i] = 'TIME DT=2e-4 TEND=%s' % m.rng.choice(['4e-3', '6e-3'])
        note = 'theta = 1, SLIP RELEASE=YES, DT = 0.2 ms'
    elif choice in (1, 2) and 'TIME' in word:
        index = m.pick_card(lambda line: keyword(line) == 'TIME')
        if index is None:
            return False
        match = re.search(r'(?i)DT=(\S+)', m.lines[index])
        try:
            dt = float(match.group(1))
        except (AttributeError, ValueError):
            return False
        factor = m.rng.choice([100, 30, 1000]) if choice == 1 else m.rng.choice([1e-4, 1e-3, 1e-9 / dt])
        m.replace_field(index, 'DT', '%.6g' % (dt * factor))
        note = 'DT x %g' % factor
    elif choice == 3:
        index = m.pick_card(lambda line: keyword(line) == 'MATERIAL' and 'NU=' in line.upper())
        if index is None:
            return False
        m.replace_field(index, 'NU', m.rng.choice(['0.4999', '0.49999999', '0.5', '-0.9999', '0.49']))
        if m.rng.random() < 0.5:
            m.lines.insert(index, 'FORMULATION BBAR')
        note = 'near-incompressible'
    elif choice == 4:
        index = m.pick_card(lambda line: keyword(line) in ('INITIAL', 'DROP', 'GRAVITY', 'PRESSURE', 'FORCE'))
        if index is None:
            return False
        fields = re.findall(r'([A-Za-z]+)=', card_part(m.lines[index]))
        if not fields:
            return False
        m.replace_field(index, m.rng.choice(fields), m.rng.choice(['1e6', '-1e6', '1e12', '3e8', '1e150']))
        note = 'overload on line %d' % (index + 1)
    elif choice == 5 and 'MATERIAL' in word:
        index = m.pick_card(lambda line: keyword(line) in ('MATERIAL', 'PRONY'))
        if index is None:
            return False
        fields = re.findall(r'([A-Za-z]+)=', card_part(m.lines[index]))
        if not fields:
            return False
        m.replace_field(index, m.rng.choice(fields), m.rng.choice(['1e-300', '1e300', '1e-12', '1e20', '0']))
        note = 'extreme material constant on line %d' % (index + 1)
    elif choice == 6 and 'PLATE' in word:
        index = m.pick_card(lambda line: keyword(line) == 'PLATE')
        if index is None:
            return False
        m.replace_field(index, 'Z', m.rng.choice(['0.01', '0.0366', '-1', '1e-9', '0.1']))
        note = 'plate moved (initial penetration or no contact)'
    elif choice == 7:
        m.lines.insert(end_index(m.lines), m.rng.choice(['GRAVITY G=1e4', 'GRAVITY G=-9.8', 'GRAVITY G=1e300',
                                                         'GRAVITY G=0']))
        note = 'gravity'
    else:
        m.lines.insert(end_index(m.lines), 'OUTPUT EVERY=%s FIELDS=%s' % (
            m.rng.choice(['1', '0', '-1', '1000000', '2147483647']),
            m.rng.choice(['0', '1e-3', '-1', '1e308', '1e-3,1e-3', '2e-3,1e-3', 'NaN'])))
        note = 'OUTPUT card'
    m.notes.append(note)
    return True


def mutate_size(m):
    """Sizes that need a refusal up front: huge meshes, node numbers, step counts."""
    options = []
    for index in card_indices(m.lines):
        body = card_part(m.lines[index]).upper()
        word = keyword(m.lines[index])
        if word == 'MESH':
            options.append(('mesh', index))
        elif word in ('NODE', 'ELEMENT'):
            options.append(('id', index))
        elif word == 'TIME':
            options.append(('time', index))
        elif word == 'OUTPUT' and 'EVERY' in body:
            options.append(('output', index))
    if not options:
        return False
    option, index = m.rng.choice(options)
    if option == 'mesh':
        body = card_part(m.lines[index]).upper()
        if 'SPHERE' in body:
            m.replace_field(index, 'LEVEL', m.rng.choice(['7', '8', '10', '12', '30', '999999999', '2147483647']))
        else:
            names = ['NR', 'NZ'] if 'RECT' in body else ['NR', 'NT']
            value = m.rng.choice(['3000', '100000', '46341', '65536', '999999999', '2147483647'])
            for name in names if m.rng.random() < 0.6 else [m.rng.choice(names)]:
                m.replace_field(index, name, value)
    elif option == 'id':
        words = card_part(m.lines[index]).split()
        if len(words) < 2:
            return False
        if m.rng.random() < 0.5:
            words[1] = m.rng.choice(HUGE_INTEGERS)
        else:
            extra = {'GEN': m.rng.choice(HUGE_INTEGERS), 'INC': m.rng.choice(HUGE_INTEGERS + ['0', '-1'])}
            name = m.rng.choice(list(extra))
            words = [w for w in words if not w.upper().startswith(name + '=')] + [name + '=' + extra[name]]
        m.lines[index] = ' '.join(words)
    elif option == 'time':
        choice = m.rng.randrange(3)
        if choice == 0:
            m.replace_field(index, 'DT', m.rng.choice(['1e-9', '1e-12', '4.9e-324', '1e-300']))
        elif choice == 1:
            m.replace_field(index, 'TEND', m.rng.choice(['1e308', '1e6', '1e3', '3.1e7']))
        else:
            m.replace_field(index, 'DT', '1e-9')
            m.replace_field(index, 'TEND', '1e-3')
    else:
        m.replace_field(index, 'EVERY', m.rng.choice(['2147483647', '0', '-5', '999999999999']))
    m.notes.append('size: line %d -> %.80s' % (index + 1, m.lines[index]))
    return True


MUTATIONS = {
    'delete_line': (mutate_delete_line, 8),
    'duplicate_line': (mutate_duplicate_line, 6),
    'swap_lines': (mutate_swap_lines, 4),
    'number_special': (mutate_number_special, 20),
    'number_scale': (mutate_number_scale, 8),
    'junk_bytes': (mutate_junk, 5),
    'truncate': (mutate_truncate, 4),
    'near_miss': (mutate_near_miss, 8),
    'degenerate_mesh': (mutate_degenerate_mesh, 8),
    'long_line': (mutate_long_line, 5),
    'insert_card': (mutate_insert_card, 7),
    'field': (mutate_field, 6),
    'switch': (mutate_switch, 4),
    'whitespace': (mutate_whitespace, 3),
    'physics': (mutate_physics, 6),
    'size': (mutate_size, 3),
}


def make_mutant(seed, index, seeds, pool, kinds):
    """Deck `index` of campaign `seed`: a normalized seed deck with 1-4 mutations."""
    rng = random.Random('%d:%d' % (seed, index))
    seed_name, seed_text = seeds[rng.randrange(len(seeds))]
    m = Mutant(seed_text, rng, seed_name, pool)
    names = [name for name in kinds]
    weights = [MUTATIONS[name][1] for name in names]
    wanted = rng.choices([1, 2, 3, 4], weights=[60, 25, 10, 5])[0]
    attempts = 0
    while len(m.kinds) < wanted and attempts < 20:
        attempts += 1
        name = rng.choices(names, weights=weights)[0]
        before = (list(m.lines), m.must_fail, m.same_as_seed)
        if MUTATIONS[name][0](m):
            m.kinds.append(name)
        else:
            m.lines, m.must_fail, m.same_as_seed = before
    if not m.solo():              # the oracles hold only for a single mutation
        m.must_fail = m.same_as_seed = False
    m.command = 'check' if rng.random() < CHECK_SHARE else 'run'
    return m


# ---------------------------------------------------------------------------- running
class Case:
    def __init__(self, identifier, text, seed_name='', kinds=(), notes=(), must_fail=False, same_as_seed=False,
                 exits=None, summary_lines=(), file_name=None, command='run'):
        self.id = identifier
        self.text = text
        self.seed_name = seed_name
        self.kinds = list(kinds)
        self.notes = list(notes)
        self.must_fail = must_fail
        self.same_as_seed = same_as_seed
        self.exits = exits
        self.summary_lines = list(summary_lines)
        self.file_name = file_name or '%s.inp' % identifier
        self.command = command          # 'run' or 'check' (visco2d check DECK)
        self.disk_kb = 0                # > 0: the output root on a tmpfs of this size (--disk-full)
        # results
        self.status = None
        self.seconds = 0.0
        self.classes = []
        self.reasons = []
        self.signature = ''
        self.stderr = ''
        self.error_form = ''
        self.error_has_column = None
        self.reference = {}
        self.differing = []
        self.signatures = {}            # class -> its first signature


def limit_memory(megabytes):
    def apply():
        os.setsid()
        if megabytes > 0:
            limit = megabytes * 1024 * 1024
            resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    return apply


def run_case(case, options, work_root, seed_summaries):
    work = tempfile.mkdtemp(prefix='c', dir=work_root)
    deck = os.path.join(work, case.file_name)
    with open(deck, 'wb') as handle:
        handle.write(case.text.encode('latin-1'))
    out_root = os.path.join(work, 'out')
    mounted = None
    if case.disk_kb:   # a full disk: the output root on a tmpfs of that size
        mounted = os.path.join(work, 'disk')
        os.makedirs(mounted)
        if subprocess.run(['mount', '-t', 'tmpfs', '-o', 'size=%dk' % case.disk_kb, 'tmpfs', mounted],
                          stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode != 0:
            mounted = None
            case.disk_kb = 0
        else:
            out_root = os.path.join(mounted, 'out')
    with open(os.path.join(work, 'stdout'), 'wb') as out, open(os.path.join(work, 'stderr'), 'wb') as err:
        start = time.monotonic()
        arguments = ['check', case.file_name] if case.command == 'check' else [
            '-q', '-o', os.path.relpath(out_root, work), case.file_name]
        process = subprocess.Popen([options.exe] + arguments, cwd=work, stdout=out,
                                   stderr=err, stdin=subprocess.DEVNULL, preexec_fn=limit_memory(options.mem_mb),
                                   env=options.env)
        hung = False
        try:
            process.wait(timeout=options.bound)
        except subprocess.TimeoutExpired:
            hung = True
            try:
                os.killpg(process.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            process.wait()
        case.seconds = time.monotonic() - start
    case.status = process.returncode
    with open(os.path.join(work, 'stderr'), 'rb') as handle:
        case.stderr = handle.read(200000).decode('latin-1')
    classify(case, hung, work, out_root, options, seed_summaries)
    if mounted:
        subprocess.run(['umount', '-l', mounted], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    if not options.keep_work:
        shutil.rmtree(work, ignore_errors=True)
    return case


def sign(case, signature):
    """Record a failure signature ('CLASS what where'): the first one per class is kept."""
    case.signatures.setdefault(signature.split(' ', 1)[0], signature)
    case.signature = case.signature or signature


def add(case, name, reason):
    if name not in case.classes:
        case.classes.append(name)
    case.reasons.append('%s: %s' % (name, reason))


def crash_signature(stderr):
    """Where a crash happened, from the runtime's or the sanitizer's report: 'file:line | what'."""
    # gfortran's run-time warnings (array temporaries) come as 'At line N of file F' too: drop them
    text = re.sub(r'At line \d+ of file [^\n]*\nFortran runtime warning:[^\n]*\n?', '', stderr)
    frame = r'((?:src|app|test)/[\w./-]+\.f90:\d+)'
    what, where = '', ''
    runtime = re.search(r'(?:At line (\d+) of file ([^\s(]+)[^\n]*\n)?(Fortran runtime error: [^\n]*)', text)
    sanitizer = re.search(r'ERROR: (\w+Sanitizer: [\w-]+)', text)
    undefined = re.search(r'([\w./-]+\.f90:\d+):\d+: runtime error: ([^\n]*)', text)
    if undefined:
        where, what = undefined.group(1), 'runtime error: ' + undefined.group(2)
    elif sanitizer:
        what = sanitizer.group(1)
        found = re.search(frame, text[sanitizer.end():])
        where = found.group(1) if found else ''
    elif runtime:
        what = runtime.group(3)
        where = '%s:%s' % (runtime.group(2), runtime.group(1)) if runtime.group(1) else ''
        if not where:
            found = re.search(frame, text)
            where = found.group(1) if found else ''
    elif re.search(r"In file '([^']+)', around line (\d+): (Error allocating)", text):
        match = re.search(r"In file '([^']+)', around line (\d+): (Error allocating)", text)
        where, what = '%s:%s' % (match.group(1), match.group(2)), match.group(3)
    else:
        match = re.search(r'(Error allocating \d+ bytes|Program received signal \w+|Operating system error[^\n]*)',
                          text)
        if match:
            what = match.group(1)
            found = re.search(frame, text)
            where = found.group(1) if found else ''
    if not what:
        return ''
    where = re.sub(r'^(\./)+', '', where.replace('/./', '/'))
    what = re.sub(r"'\d+'|\b\d+\b", 'N', what)[:100]
    return '%s | %s' % (where, what) if where else what


def message_form(message, deck):
    """An error message with its location, numbers and quoted text replaced: its form."""
    text = message.replace(deck, '<deck>')
    text = re.sub(r'^<deck>(:\d+)?(:\d+)?: ', '', text)
    text = re.sub(r'"[^"]*"', '"…"', text)
    text = NUMBER.sub('#', text)
    text = re.sub(r'\b[A-Za-z_]*\d[\w.+-]*', '#', text)
    return text[:140]


def classify(case, hung, work, out_root, options, seed_summaries):
    status = case.status
    stderr = case.stderr
    if hung:
        add(case, 'HANG', 'still running after %g s' % options.bound)
        sign(case, 'HANG %s %s' % (case.seed_name, '+'.join(case.kinds)))
    elif status < 0 or status not in (0, 1, 2, 3):
        add(case, 'CRASH', 'exit status %d%s' % (status, ' (signal %d)' % -status if status < 0 else ''))
    found = [text for text in CRASH_TEXT if text in stderr]
    if found:
        add(case, 'CRASH', 'stderr holds %s' % ', '.join(repr(t) for t in found[:3]))
    if 'CRASH' in case.classes:
        sign(case, 'CRASH ' + (crash_signature(stderr) or 'exit %d' % status))
    if case.exits is not None and not hung and status not in case.exits and 'CRASH' not in case.classes:
        add(case, 'SILENT', 'exit status %d, this deck expects %s' % (status, sorted(case.exits)))
        sign(case, 'SILENT exit %d' % status)
    # leftovers in the output root
    if os.path.isdir(out_root) and not hung:   # a run killed at the bound cannot clean up
        leftovers = [name for name in os.listdir(out_root) if '.partial.' in name or '.old.' in name]
        if leftovers:
            add(case, 'PARTIAL', 'left in the output root: %s' % ', '.join(leftovers[:3]))
            sign(case, 'PARTIAL')
    case_name = os.path.splitext(case.file_name)[0]
    case_dir = os.path.join(out_root, case_name)
    if hung:
        return
    if status in (1, 2) and os.path.isdir(case_dir):
        add(case, 'OUTPUT_ON_ERROR', 'exit %d with %s/ left behind' % (status, case_name))
        sign(case, 'OUTPUT_ON_ERROR ' + message_form(first_error(stderr), case.file_name))
    if status == 1 and 'CRASH' not in case.classes and case.disk_kb and ERROR_LINE.search(stderr):
        pass   # a write failure names the output file, not a line of the deck
    elif status == 1 and 'CRASH' not in case.classes:
        locate(case, stderr)
        reference = seed_summaries.get(case.seed_name) if case.same_as_seed else None
        message = first_error(stderr)
        if reference and not re.search(r'long|characters|column', message):
            add(case, 'SILENT', 'a change of layout only (%s) of a deck that runs made it fail with another '
                'error: %.200s' % ('; '.join(case.notes), message))
            sign(case, 'SILENT layout change misread: ' + message_form(message, case.file_name))
    if case.command == 'check':
        if os.path.exists(out_root):
            add(case, 'OUTPUT_ON_ERROR', '"visco2d check" wrote into the output root')
            sign(case, 'OUTPUT_ON_ERROR check wrote output')
        return
    if status in (0, 3):
        missing = [name for name in ('listing.txt', 'summary.txt', 'history.csv', 'results.h5')
                   if not (os.path.isfile(os.path.join(case_dir, name))
                           and os.path.getsize(os.path.join(case_dir, name)) > 0)]
        if missing:
            add(case, 'MISSING_OUTPUT', 'exit %d without %s' % (status, ', '.join(missing)))
            sign(case, 'MISSING_OUTPUT ' + ','.join(missing))
    if os.path.isdir(case_dir):
        check_outputs(case, case_dir)
        if status in (0, 3):
            check_oracles(case, case_dir, seed_summaries)
            check_expect_status(case, case_dir, status)


def first_error(stderr):
    match = ERROR_LINE.search(stderr)
    return match.group(1) if match else stderr.strip().split('\n')[0][:200] if stderr.strip() else ''


def locate(case, stderr):
    match = ERROR_LINE.search(stderr)
    deck = case.file_name
    if not match:
        add(case, 'UNLOCATED', 'exit 1 without a "visco2d: error:" line: %.120s' % stderr.strip().replace('\n', '|'))
        sign(case, 'UNLOCATED no error line')
        return
    message = match.group(1)
    case.error_form = message_form(message, deck)
    where = re.match(re.escape(deck) + r':(\d+)(?::(\d+))?: ', message)
    if not where:
        add(case, 'UNLOCATED', 'the error names no line of %s: %.160s' % (deck, message))
        sign(case, 'UNLOCATED ' + case.error_form)
        return
    case.error_has_column = where.group(2) is not None


def generic_key(key):
    """A summary key or column name with the deck's own names and numbers taken out."""
    key = re.sub(r'^expect_.*_(value|rel_error|within_rtol)$', r'expect_*_\1', key)
    key = re.sub(r'^probe_[^ ]*?_(ur|uz|vr|vz|ar|az|sr|sz|st|trz|r|z)(_\w+)?$', r'probe_*_\1\2', key)
    return re.sub(r'\d+', 'N', key)


def where_in(text, position, name):
    """The summary key, the history column or the listing section at a position of a text output."""
    start = text.rfind('\n', 0, position) + 1
    line = text[start:text.find('\n', position) if text.find('\n', position) >= 0 else len(text)]
    if '=' in line and not line.lstrip().startswith(('-', '+')) and ' = ' in line:
        return line, generic_key(line.split('=')[0].strip())
    if name == 'history.csv':
        header = text.split('\n', 1)[0].split(',')
        column = text[start:position].count(',')
        return line, 'column ' + generic_key(header[column].strip()) if column < len(header) else 'row'
    sections = re.findall(r'^ ([A-Z][A-Z0-9 (),./-]{3,})$', text[:start], re.M)
    return line, 'section ' + (sections[-1].split('(')[0].strip() if sections else 'head')


def scan_text(text, case, where):
    """Non-finite and unreadable numbers in a text output (not its echo of the deck)."""
    bad = NONFINITE_TOKEN.search(text)
    if bad:
        line, key = where_in(text, bad.start(), where)
        add(case, 'NONFINITE', '%s: %.160s' % (where, line.strip()))
        sign(case, 'NONFINITE %s %s' % (where, key))
    for pattern, what in ((STARS, 'a field of *'), (NO_EXPONENT_LETTER, 'an exponent without its letter')):
        bad = pattern.search(text)
        if bad:
            line, key = where_in(text, bad.start(), where)
            add(case, 'UNREADABLE', '%s: %s (%s): %.160s' % (where, what, bad.group(0), line.strip()))
            sign(case, 'UNREADABLE %s %s: %s' % (where, key, what))


def listing_without_echo(text):
    """listing.txt without the lines that repeat the deck (title, deck path, INPUT CARDS)."""
    kept, echo = [], False
    for line in text.split('\n'):
        if line.startswith(' INPUT CARDS'):
            echo = True
            continue
        if echo:
            if line.strip() == '':
                echo = False
            continue
        if re.match(r'\s*(title|deck|case)\s*[:=]', line):
            continue
        kept.append(line)
    return '\n'.join(kept)


def check_outputs(case, case_dir):
    for name in ('summary.txt', 'history.csv', 'listing.txt'):
        path = os.path.join(case_dir, name)
        if not os.path.isfile(path):
            continue
        with open(path, 'rb') as handle:
            text = handle.read().decode('latin-1')
        if name == 'summary.txt':
            text = '\n'.join(line for line in text.split('\n') if not line.startswith(('title =', 'case =')))
        elif name == 'listing.txt':
            text = listing_without_echo(text)
        scan_text(text, case, name)
    path = os.path.join(case_dir, 'results.h5')
    if os.path.isfile(path):
        check_hdf5(case, path)


def check_hdf5(case, path):
    try:
        import h5py
        import numpy
    except ImportError:
        return
    problems = []

    def value_problem(name, value):
        if isinstance(value, (bytes, numpy.bytes_)):
            value = value.decode('latin-1')
        if isinstance(value, str):
            if NONFINITE_TOKEN.search(value):
                return 'NONFINITE', '%s = %.60s' % (name, value)
            return None
        array = numpy.asarray(value)
        if array.dtype.kind in 'fc' and not numpy.all(numpy.isfinite(array)):
            return 'NONFINITE', '%s holds %d non-finite value(s)' % (name, int(numpy.size(array) - numpy.sum(
                numpy.isfinite(array))))
        if array.dtype.kind in 'SUO':
            for item in array.ravel():
                problem = value_problem(name, item)
                if problem:
                    return problem
        return None

    def visit(name, item):
        for key, value in item.attrs.items():
            if key == 'title':
                continue
            problem = value_problem('%s@%s' % (name, key), value)
            if problem:
                problems.append(problem)
        if isinstance(item, h5py.Dataset):
            if name.rsplit('/', 1)[-1] == 'title':
                return
            problem = value_problem(name, item[()])
            if problem:
                problems.append(problem)

    try:
        with h5py.File(path, 'r') as handle:
            for key, value in handle.attrs.items():
                if key not in ('title',):
                    problem = value_problem('@' + key, value)
                    if problem:
                        problems.append(problem)
            handle.visititems(visit)
    except Exception as error:  # an unreadable file after exit 0 is a broken output
        if case.status in (0, 3):
            add(case, 'MISSING_OUTPUT', 'results.h5 unreadable: %s' % error)
            sign(case, 'MISSING_OUTPUT results.h5 unreadable')
        return
    for kind, text in problems[:1]:
        add(case, kind, 'results.h5: %s' % text)
        sign(case, '%s results.h5 %s' % (kind, re.sub(r'\d+', 'N', text.split(' ')[0])))


def read_summary(case_dir):
    """The case's summary ({} when it has none)."""
    path = os.path.join(case_dir, 'summary.txt')
    return case_folder.read_summary(path) if os.path.isfile(path) else {}


def expect_keys(text):
    keys = set()
    lines = split_lines(text)
    for line in lines[:end_index(lines)]:
        words = card_part(line).split()
        if len(words) >= 2 and words[0].upper() == 'EXPECT':
            keys.add(words[1])
    return keys


def check_expect_status(case, case_dir, status):
    """Exit 3 if and only if the summary holds an EXPECT outside its RTOL, with a located EXPECT error line."""
    missed = [key for key, value in read_summary(case_dir).items()
              if key.startswith('expect_') and key.endswith('_within_rtol') and value.strip() == 'no']
    if status == 0 and missed:
        add(case, 'SILENT', 'exit 0 with an EXPECT outside its RTOL: %s' % ', '.join(missed[:3]))
        sign(case, 'SILENT EXPECT missed, exit 0')
    elif status == 3 and not missed:
        add(case, 'SILENT', 'exit 3 with every EXPECT within its RTOL')
        sign(case, 'SILENT exit 3 without a miss')
    elif status == 3 and not re.search(r'^visco2d: error: ' + re.escape(case.file_name) + r':\d+:\d+: EXPECT: ',
                                       case.stderr, re.M):
        add(case, 'UNLOCATED', 'exit 3 without a located "EXPECT:" error line')
        sign(case, 'UNLOCATED EXPECT miss')


def check_oracles(case, case_dir, seed_summaries):
    summary = read_summary(case_dir)
    given = expect_keys(case.text)
    reported = {key for key in summary if key.startswith('expect_') and key.endswith('_within_rtol')}
    if given and len(reported) < len(given):
        add(case, 'SILENT', 'the deck has %d EXPECT key(s), summary.txt reports %d' % (len(given), len(reported)))
        sign(case, 'SILENT EXPECT count')
    try:
        balance = float(summary.get('balance_error_max_rel', '0'))
    except ValueError:
        balance = 0.0
    energy_warning = re.search(r'^visco2d: warning:.*energ', case.stderr, re.M | re.I)
    if balance > BALANCE_LIMIT and not energy_warning:
        add(case, 'SILENT', 'exit 0 with an energy-balance error %.3g times the energy put in and no warning '
            'about it' % balance)
        sign(case, 'SILENT energy balance unwarned')
    if case.must_fail:
        add(case, 'SILENT', 'accepted (exit 0) a deck that must be refused: %s' % '; '.join(case.notes))
        sign(case, 'SILENT accepted %s' % case.kinds[0])
    if case.same_as_seed and case.seed_name in seed_summaries:
        reference = seed_summaries[case.seed_name]
        ignore = ('cpu_s', 'case', 'title')
        differing = sorted(key for key in set(reference) | set(summary) if key not in ignore
                           and without_deck_name(reference.get(key)) != without_deck_name(summary.get(key)))
        case.reference, case.differing = reference, differing
        if reference and differing:
            add(case, 'SILENT', 'a change of layout only (%s) changed the summary: %s' % (
                '; '.join(case.notes), ', '.join(differing[:4])))
            sign(case, 'SILENT layout changed the summary')
    for line in case.summary_lines:
        key, value = line.split(' = ', 1)
        if summary.get(key) != value:
            add(case, 'SILENT', 'summary.txt has %s = %s, this deck expects %s' % (key, summary.get(key), value))
            sign(case, 'SILENT summary ' + key)


def without_deck_name(value):
    """A summary value with a warning's leading deck path (`d000017.inp:19: PAD: ...`) cut to its
    line (`:19: PAD: ...`): a mutant and its seed are different files with the same cards."""
    if value is None:
        return None
    return re.sub(r'^\S*?\.inp:', ':', value)


# ---------------------------------------------------------------------------- campaign
def load_seeds(patterns):
    seeds = []
    for pattern in patterns:
        for path in sorted(glob.glob(os.path.join(ROOT, pattern) if not os.path.isabs(pattern) else pattern)):
            name = os.path.splitext(os.path.basename(path))[0]
            seeds.append((name, normalize_seed(read_deck(path))))
    return seeds


def card_pool(seeds):
    pool = []
    for _, text in seeds:
        lines = split_lines(text)
        pool.extend(card_part(line).strip() for line in lines if is_card(line))
    return sorted(set(pool))


def seed_reference_summaries(seeds, options, work_root):
    """The summary of every seed as it is (for the oracle of layout-only changes)."""
    summaries = {}
    for name, text in seeds:
        case = Case('seed_' + re.sub(r'\W', '_', name), text, seed_name=name)
        work = tempfile.mkdtemp(prefix='s', dir=work_root)
        path = os.path.join(work, case.file_name)
        with open(path, 'wb') as handle:
            handle.write(text.encode('latin-1'))
        try:
            status = subprocess.run([options.exe, '-q', '-o', 'out', case.file_name], cwd=work,
                                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                    timeout=options.bound, env=options.env).returncode
        except subprocess.TimeoutExpired:
            status = None
        summaries[name] = read_summary(os.path.join(work, 'out', os.path.splitext(case.file_name)[0])) \
            if status == 0 else {}
        shutil.rmtree(work, ignore_errors=True)
    return summaries


def oracle_directives(case):
    """'# fuzz:' lines that carry a mutant's oracle into the saved deck (for --decks and --shrink)."""
    lines = []
    if case.must_fail:
        lines.append('# fuzz: exit 1 2')
    if case.same_as_seed and case.reference:
        lines.append('# fuzz: exit 0 1 2')
        for key in case.differing[:6]:
            if key in case.reference:
                lines.append('# fuzz: summary %s = %s' % (key, case.reference[key]))
    return ''.join(line + '\n' for line in lines)


def save_failure(case, out):
    for name in case.classes:
        folder = os.path.join(out, 'failures', name)
        os.makedirs(folder, exist_ok=True)
        stem = os.path.join(folder, case.id)
        with open(stem + '.inp', 'wb') as handle:
            handle.write((oracle_directives(case) + case.text).encode('latin-1'))
        with open(stem + '.stderr', 'wb') as handle:
            handle.write(case.stderr.encode('latin-1'))
        with open(stem + '.reason', 'w') as handle:
            handle.write('%s (seed %s; mutations %s; %s; exit %s; %.2f s)\n' % (
                '; '.join(case.reasons), case.seed_name, '+'.join(case.kinds) or 'none',
                'visco2d check' if case.command == 'check' else 'run', case.status, case.seconds))
            for note in case.notes:
                handle.write('  %s\n' % note)
            handle.write('signature: %s\n' % case.signatures.get(name, case.signature))


def write_report(cases, out, options, elapsed):
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, 'cases.csv'), 'w', newline='') as handle:
        writer = csv.writer(handle)
        writer.writerow(['id', 'command', 'seed', 'mutations', 'exit', 'seconds', 'classes', 'signature', 'error_form',
                         'column', 'notes', 'signatures'])
        for case in cases:
            writer.writerow([case.id, case.command, case.seed_name, '+'.join(case.kinds), case.status,
                             '%.3f' % case.seconds,
                             ' '.join(case.classes), case.signature, case.error_form,
                             '' if case.error_has_column is None else int(case.error_has_column),
                             ' | '.join(case.notes)[:400],
                             ' || '.join(case.signatures.get(name, name) for name in case.classes)])
    failing = [c for c in cases if c.classes]
    lines = ['# visco2d fuzz report', '',
             'exe `%s`, %d decks, seed %s, bound %g s, %d jobs, %.1f s wall' % (
                 options.exe, len(cases), options.seed, options.bound, options.jobs, elapsed), '']
    counts = {name: sum(1 for c in cases if name in c.classes) for name in FAIL_CLASSES}
    checks = [c for c in cases if c.command == 'check']
    exits = {}
    for case in cases:
        exits[case.status] = exits.get(case.status, 0) + 1
    lines += ['## Classes', '', '| class | decks |', '|---|---|']
    lines += ['| %s | %d |' % (name, counts[name]) for name in FAIL_CLASSES]
    lines += ['| (passed) | %d |' % (len(cases) - len(failing)), '',
              '%d of the decks ran as "visco2d check DECK" (%d failing), the others as runs.' % (
                  len(checks), sum(1 for c in checks if c.classes)), '',
              'exit statuses: ' + ', '.join('%s: %d' % (k, v) for k, v in sorted(exits.items(),
                                                                                  key=lambda kv: str(kv[0]))),
              '']
    kinds = sorted({k for c in cases for k in c.kinds})
    if kinds:
        lines += ['## Per mutation kind (a deck counts under each of its kinds)', '',
                  '| kind | decks | exit 0 | exit 1 | ' + ' | '.join(FAIL_CLASSES) + ' |',
                  '|---|---|---|---|' + '---|' * len(FAIL_CLASSES)]
        for kind in kinds:
            group = [c for c in cases if kind in c.kinds]
            lines.append('| %s | %d | %d | %d | %s |' % (
                kind, len(group), sum(1 for c in group if c.status == 0), sum(1 for c in group if c.status == 1),
                ' | '.join(str(sum(1 for c in group if n in c.classes)) for n in FAIL_CLASSES)))
        lines.append('')
    signatures = {}
    for case in failing:
        signatures.setdefault(case.signature, []).append(case)
    lines += ['## Distinct failures (by signature)', '', '| decks | signature | example | reason |',
              '|---|---|---|---|']
    for signature, group in sorted(signatures.items(), key=lambda kv: -len(kv[1])):
        example = group[0]
        lines.append('| %d | `%s` | %s/%s | %s |' % (len(group), signature.replace('|', '/'), example.classes[0],
                                                    example.id, example.reasons[0].replace('|', '/')[:200]))
    located = [c for c in cases if c.error_has_column is not None]
    no_column = [c for c in located if not c.error_has_column]
    forms = {}
    for case in no_column:
        forms[case.error_form] = forms.get(case.error_form, 0) + 1
    lines += ['', '## Errors without a column (statistics, not failures)', '',
              '%d of %d located errors give no column, in %d message forms:' % (len(no_column), len(located),
                                                                                  len(forms)), '']
    lines += ['- %d × `%s`' % (n, form) for form, n in sorted(forms.items(), key=lambda kv: -kv[1])[:60]]
    seconds = sorted(c.seconds for c in cases)
    if seconds:
        lines += ['', '## Run times', '', 'median %.3f s, 90%% %.3f s, 99%% %.3f s, max %.3f s' % (
            seconds[len(seconds) // 2], seconds[int(0.9 * (len(seconds) - 1))], seconds[int(0.99 * (len(seconds) - 1))],
            seconds[-1])]
    with open(os.path.join(out, 'summary.md'), 'w') as handle:
        handle.write('\n'.join(lines) + '\n')
    return counts, signatures


def progress(done, total, failed, start, quiet):
    if quiet:
        return
    if done == total or done % max(1, total // 20) == 0:
        print('  %d/%d decks, %d failing, %.0f s' % (done, total, failed, time.monotonic() - start), flush=True)


def run_all(cases, options, seed_summaries):
    work_root = tempfile.mkdtemp(prefix='visco2d_fuzz.')
    start = time.monotonic()
    done = failed = 0
    lock = threading.Lock()
    try:
        with concurrent.futures.ThreadPoolExecutor(max_workers=options.jobs) as pool:
            futures = [pool.submit(run_case, case, options, work_root, seed_summaries) for case in cases]
            for future in concurrent.futures.as_completed(futures):
                case = future.result()
                with lock:
                    done += 1
                    if case.classes:
                        failed += 1
                        save_failure(case, options.out)
                        if options.verbose:
                            print('FAIL %s%s: %s (%s)' % (options.label, case.id, '; '.join(case.reasons)[:300],
                                                          case.signature[:200]), flush=True)
                    elif options.verbose:
                        print('PASS %s%s' % (options.label, case.id), flush=True)
                    progress(done, len(cases), failed, start, options.quiet or options.verbose)
    finally:
        shutil.rmtree(work_root, ignore_errors=True)
    return time.monotonic() - start


# ---------------------------------------------------------------------------- shrinking
def shrink(path, options):
    """Delta debugging over lines: the smallest deck with the same failure signature."""
    text = read_deck(path)
    exits, summary_lines = directives(text)
    work_root = tempfile.mkdtemp(prefix='visco2d_shrink.')
    file_name = re.sub(r'[^\w.-]', '_', os.path.basename(path))
    if not file_name.endswith('.inp'):
        file_name += '.inp'

    def run(candidate):
        case = Case('shrink', candidate, exits=exits, summary_lines=summary_lines, file_name=file_name)
        return run_case(case, options, work_root, {})

    try:
        target = run(text)
        if not target.classes:
            print('shrink: %s does not fail (exit %s); nothing to shrink' % (path, target.status))
            return 1
        signature = target.signature
        if 'SILENT' in target.classes:
            print('shrink: %s fails as SILENT (%s): not shrunk, that oracle holds for the mutation, not for '
                  'a smaller deck' % (path, target.reasons[0]))
            return 1
        print('shrink: target signature: %s' % signature)
        tests = [0]

        def failing(lines):
            tests[0] += 1
            return run('\n'.join(lines) + '\n').signature == signature

        lines = split_lines(text.rstrip('\n'))
        kept = [line for line in lines if re.match(r'\s*#\s*fuzz:', line)]   # '# fuzz:' lines stay
        lines = [line for line in lines if line not in kept]
        run_plain = run
        run = lambda candidate: run_plain(''.join(line + '\n' for line in kept) + candidate)  # noqa: E731
        # first drop comment and blank lines at once, then each line
        stripped = [line for line in lines if is_card(line)]
        if failing(stripped):
            lines = stripped
        granularity = 2
        while len(lines) >= 2:
            chunk = max(1, len(lines) // granularity)
            reduced = False
            for start in range(0, len(lines), chunk):
                candidate = lines[:start] + lines[start + chunk:]
                if candidate and failing(candidate):
                    lines = candidate
                    granularity = max(granularity - 1, 2)
                    reduced = True
                    break
            if not reduced:
                if chunk == 1:
                    break
                granularity = min(len(lines), granularity * 2)
        # shorten long lines: cut trailing comments
        for index, line in enumerate(lines):
            body = card_part(line).rstrip()
            if body != line and body and failing(lines[:index] + [body] + lines[index + 1:]):
                lines[index] = body
        output = options.shrink_out or re.sub(r'\.inp$', '', path) + '.min.inp'
        with open(output, 'wb') as handle:
            handle.write(('\n'.join(kept + lines) + '\n').encode('latin-1'))
        print('shrink: %d -> %d lines in %d runs: %s' % (len(split_lines(text.rstrip('\n'))), len(lines), tests[0],
                                                          output))
        return 0
    finally:
        shutil.rmtree(work_root, ignore_errors=True)


# ---------------------------------------------------------------------------- main
def main():
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)   # quiet when piped into head
    parser = argparse.ArgumentParser(prog="python3 -m visco2d.fuzz", description=__doc__.split('\n\n')[0], epilog=__doc__.split('\n\n', 2)[2],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('-n', '--count', type=int, default=1000, help='number of mutated decks (default 1000)')
    parser.add_argument('--seed', type=int, default=1, help='campaign seed: deck i depends only on it (default 1)')
    parser.add_argument('-j', '--jobs', type=int, default=os.cpu_count() or 1,
                        help='parallel runs (default: the number of cores, %(default)s)')
    parser.add_argument('--bound', type=float, default=20.0, help='wall-time bound per run, s (default 20)')
    parser.add_argument('--exe', default=os.path.join(ROOT, 'build', 'install', 'bin', 'visco2d'),
                        help='the visco2d executable (default build/install/bin/visco2d)')
    parser.add_argument('--out', default=os.path.join(ROOT, 'out', 'fuzz'),
                        help='report folder, emptied first (default out/fuzz)')
    parser.add_argument('--seeds', nargs='+', default=['inputs/*.inp', 'test/fuzz/*.inp'],
                        help='seed deck globs, relative to the repository (default inputs/*.inp test/fuzz/*.inp)')
    parser.add_argument('--kinds', default=','.join(MUTATIONS),
                        help='mutation kinds to use, comma-separated (default all: %(default)s)')
    parser.add_argument('--only', type=int, nargs='+', help='run only these deck numbers of the campaign')
    parser.add_argument('--decks', nargs='+', help='run these decks as they are (no mutation), e.g. test/fuzz/*.inp')
    parser.add_argument('--expect-exit', type=int, nargs='+', metavar='STATUS',
                        help='with --decks: the allowed exit statuses of decks without a "# fuzz: exit" line '
                        '(default 0 1 2; inputs/ decks must exit 0)')
    parser.add_argument('--label', default='', help='prefix of the deck names in PASS/FAIL lines (with -v)')
    parser.add_argument('--shrink', metavar='DECK', help='minimize a failing deck by deleting lines, keeping '
                        'its failure signature; writes DECK.min.inp (or --shrink-out)')
    parser.add_argument('--shrink-out', help='where --shrink writes the minimized deck')
    parser.add_argument('--mem-mb', type=int, default=None,
                        help='address-space limit per run in MB, 0 for none (default 4096, none for an '
                        'AddressSanitizer build)')
    parser.add_argument('--disk-full', type=float, default=0, metavar='SHARE',
                        help='that share of the runs (0-1) write into a tmpfs of 16-400 kB, a full disk '
                        '(needs root: mount -t tmpfs; not used by make test)')
    parser.add_argument('--write', metavar='DIR', help='only write the mutated decks into DIR, run nothing')
    parser.add_argument('--keep-work', action='store_true', help='keep each run folder (for debugging)')
    parser.add_argument('-v', '--verbose', action='store_true', help='a PASS/FAIL line per deck')
    parser.add_argument('-q', '--quiet', action='store_true', help='no progress lines')
    options = parser.parse_args()
    options.exe = os.path.abspath(options.exe)
    options.out = os.path.abspath(options.out)
    if options.mem_mb is None:   # no address-space limit under AddressSanitizer (it reserves terabytes)
        with open(options.exe, 'rb') as handle:
            options.mem_mb = 0 if b'libasan' in handle.read() else 4096
    options.env = dict(os.environ, VISCO2D_PROGRESS_DELAY='1e9')
    # A run whose estimated time exceeds a quarter of the bound (the estimate is
    # within a factor of 2, and jobs share the cores) is refused up front with a
    # located error (visco2d --max-time): what is then still running at the
    # bound is a hang, not an announced long run.
    options.env.setdefault('VISCO2D_MAX_TIME', '%g' % (options.bound/4.0))
    options.env.setdefault('ASAN_OPTIONS', 'halt_on_error=1:detect_leaks=1:exitcode=86:max_allocation_size_mb=4096')
    options.env.setdefault('UBSAN_OPTIONS', 'halt_on_error=1:print_stacktrace=1:exitcode=87')
    kinds = [k for k in options.kinds.split(',') if k]
    unknown = [k for k in kinds if k not in MUTATIONS]
    if unknown:
        parser.error('unknown mutation kind(s) %s; known: %s' % (', '.join(unknown), ', '.join(MUTATIONS)))
    if not options.write and not (os.path.isfile(options.exe) and os.access(options.exe, os.X_OK)):
        parser.error('no executable %s (make build, or --exe)' % options.exe)

    if options.shrink:
        return shrink(options.shrink, options)

    if os.path.isdir(options.out):
        shutil.rmtree(options.out)
    os.makedirs(options.out)
    if options.decks:
        cases = []
        for path in options.decks:
            text = read_deck(path)
            exits, summary_lines = directives(text)
            name = re.sub(r'[^\w.-]', '_', os.path.splitext(os.path.basename(path))[0])
            if exits is None and options.expect_exit:
                exits = set(options.expect_exit)
            cases.append(Case(name, text, seed_name=os.path.relpath(path, ROOT), exits=exits,
                              summary_lines=summary_lines))
        seed_summaries = {}
    else:
        seeds = load_seeds(options.seeds)
        if not seeds:
            parser.error('no seed decks match %s' % ' '.join(options.seeds))
        pool = card_pool(seeds)
        numbers = options.only or range(options.count)
        cases = []
        for number in numbers:
            m = make_mutant(options.seed, number, seeds, pool, kinds)
            cases.append(Case('d%06d' % number, m.text() + ('\n' if m.lines and m.lines[-1] != '' else ''),
                              seed_name=m.seed_name, kinds=m.kinds, notes=m.notes, must_fail=m.must_fail,
                              same_as_seed=m.same_as_seed and m.command == 'run', command=m.command))
        for case in cases:
            rng = random.Random('disk:%d:%s' % (options.seed, case.id))
            if case.command == 'run' and rng.random() < options.disk_full:
                case.disk_kb = rng.choice([16, 32, 64, 100, 200, 300, 400])
                case.kinds.append('disk_full')
                case.notes.append('output root on a %d kB tmpfs' % case.disk_kb)
                case.same_as_seed = False
        if options.write:
            os.makedirs(options.write, exist_ok=True)
            for case in cases:
                with open(os.path.join(options.write, case.file_name), 'wb') as handle:
                    handle.write(case.text.encode('latin-1'))
            print('fuzz: %d decks written to %s' % (len(cases), options.write))
            return 0
        work_root = tempfile.mkdtemp(prefix='visco2d_seeds.')
        try:
            seed_summaries = seed_reference_summaries(
                [s for s in seeds if any(c.same_as_seed and c.seed_name == s[0] for c in cases)], options, work_root)
        finally:
            shutil.rmtree(work_root, ignore_errors=True)
    if not options.quiet:
        print('fuzz: %d decks, %d jobs, bound %g s, exe %s' % (len(cases), options.jobs, options.bound, options.exe),
              flush=True)
    elapsed = run_all(cases, options, seed_summaries)
    counts, signatures = write_report(cases, options.out, options, elapsed)
    failed = sum(1 for c in cases if c.classes)
    print(' '.join('%s %d' % (name, counts[name]) for name in FAIL_CLASSES))
    if signatures and not options.quiet:
        print('distinct failures:')
        for signature, group in sorted(signatures.items(), key=lambda kv: -len(kv[1]))[:30]:
            print('  %5d  %s  (e.g. %s)' % (len(group), signature[:150], group[0].id))
    print('report: %s' % os.path.join(options.out, 'summary.md'))
    print('fuzz: %d passed, %d failed' % (len(cases) - failed, failed))
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main())
