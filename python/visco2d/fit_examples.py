"""The synthetic 'measured' curves of inputs/examples/calibration/ (doc/calibration.md), and the
generators the tests of visco2d-fit use with other seeds.

    PYTHONPATH=python python3 -m visco2d.fit_examples [--exe PATH]

rewrites inputs/examples/calibration/apple_flesh_compression.csv (visco2d's own run of
flesh_compression.inp at the paper's Table 4 constants, 0.7 m/s, with Gaussian noise) and
relax_table4.csv (eq. [47] with Table 4's constants, in closed form, with noise). Neither is a
measurement: each file's header says how it was made.
"""

import argparse
import math
import os
import string
import sys
import tempfile

import numpy as np

from . import runner
from .case import read_history

#: The paper's Table 4 (uniaxial relaxation, eq. [47]) at 0.7 m/s: (E_i in Pa, alpha_i in 1/s).
TABLE4_V07 = [(1.703e6, 0.000311), (0.258e6, 0.0401), (0.461e6, 1.075), (0.212e6, 34.49)]
#: The cork-borer specimen of the examples: diameter 12.7 mm.
DIAMETER = 0.0127
AREA = math.pi * DIAMETER ** 2 / 4
FOLDER = os.path.join(runner.ROOT, 'inputs', 'examples', 'calibration')
COMPRESSION = os.path.join(FOLDER, 'flesh_compression.inp')


def relaxation_curve(seed, noise=0.002, strain=0.1, times=None, constants=TABLE4_V07):
    """(t, force_N) of a relaxation test at the held strain: eq. [47] times strain times AREA, plus
    Gaussian noise of `noise` times the initial force (seeded)."""
    t = np.logspace(-3, 4, 200) if times is None else times
    modulus = sum(e * np.exp(-a * t) for e, a in constants)
    force = strain * modulus * AREA
    rng = np.random.default_rng(seed)
    return t, force + rng.normal(0.0, noise * force[0], t.size)


def run_template(template_text, values, exe=None, folder=None):
    """history.csv of one visco2d run of a template with its ${name} values."""
    exe = exe or runner.default_exe()
    with tempfile.TemporaryDirectory(prefix='visco2d-fitex-', dir=folder) as work:
        deck = os.path.join(work, 'synthetic.inp')
        with open(deck, 'w') as handle:
            handle.write(string.Template(template_text).substitute(values))
        result = runner.run(exe, [deck], os.path.join(work, 'out'))
        if result.returncode != 0:
            raise RuntimeError(runner.located_error(result.stderr))
        return read_history(os.path.join(work, 'out', 'synthetic'))


def compression_curve(seed, values=None, noise=0.005, every=2, exe=None, template=COMPRESSION):
    """(deformation_m, force_N) of the compression template run by visco2d at `values` (default the
    Table 4 E1, E4), every `every`-th step, plus Gaussian noise of `noise` times the largest force."""
    values = values or {'E1': TABLE4_V07[0][0], 'E4': TABLE4_V07[3][0]}
    with open(template) as handle:
        text = handle.read()
    history = run_template(text, values, exe)
    deformation = -np.array(history['top_uz_m'])[every::every]
    force = -np.array(history['top_sz_Pa'])[every::every] * AREA
    rng = np.random.default_rng(seed)
    return deformation, force + rng.normal(0.0, noise * force.max(), force.size)


def write_curve(path, header, names, x, y, comments):
    with open(path, 'w') as handle:
        for line in comments:
            handle.write(f'# {line}\n')
        handle.write(f'{names}\n')
        for a, b in zip(x, y):
            handle.write(f'{a:.7g},{b:.7g}\n')


def main(argv=None):
    parser = argparse.ArgumentParser(prog='python3 -m visco2d.fit_examples', description=__doc__.split('\n')[0])
    parser.add_argument('--exe')
    options = parser.parse_args(argv)
    d, f = compression_curve(seed=2024, exe=options.exe)
    write_curve(os.path.join(FOLDER, 'apple_flesh_compression.csv'), None, 'deformation_m,force_N', d, f,
                ['SYNTHETIC, not a measurement: a "measured-looking" compression curve of apple flesh made by',
                 'python3 -m visco2d.fit_examples: visco2d run of flesh_compression.inp (12.7 mm x 10 mm',
                 'cylinder, frictionless platens, 5 mm/s to 1 mm) with the paper\'s Table 4 constants (0.7 m/s:',
                 'E1 = 1.703e6 Pa, E4 = 0.212e6 Pa, the others as in the deck), every second step (50',
                 'points), plus Gaussian noise of 0.5 % of the largest force (numpy default_rng seed 2024).'])
    t, force = relaxation_curve(seed=2024)
    write_curve(os.path.join(FOLDER, 'relax_table4.csv'), None, 'time_s,force_N', t, force,
                ['SYNTHETIC, not a measurement: a stress-relaxation curve made by python3 -m',
                 'visco2d.fit_examples from the paper\'s eq. [47] with its Table 4 constants at 0.7 m/s',
                 '(E_i = 1.703, 0.258, 0.461, 0.212 MPa; alpha_i = 0.000311, 0.0401, 1.075, 34.49 1/s), an',
                 'instantaneous step of 10 % strain held 1e-3 ... 1e4 s (200 log-spaced points), force =',
                 'strain x E(t) x the 12.7 mm specimen\'s section, plus Gaussian noise of 0.2 % of the',
                 'initial force (numpy default_rng seed 2024).'])
    print(f'wrote {FOLDER}/apple_flesh_compression.csv and relax_table4.csv')
    return 0


if __name__ == '__main__':
    sys.exit(main())
