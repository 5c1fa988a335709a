"""Longer convergence study of the elastic impact of Table 1 (not part of `make test`).

The sphere of Table 1 (R 36.6 mm, E 18.11 MPa, nu 0.219, rho 756.85,
V 0.9982 m/s, g 9.8, Wilson theta 1.4) on a rigid plate (PLATE Z=0, STICK,
stop at maximum deformation), run by the installed executable:

  * mesh levels 1..MAX_LEVEL at dt = 1e-5 s (level 5 takes seconds),
  * dt = 4e-5 .. 1.25e-6 s at level DT_LEVEL (default 3),

with the observed orders p = log2(|f1 - f2| / |f2 - f3|) of alpha_m and the
Richardson values f3 + (f3 - f2) / (2^p - 1). alpha_m is also refined by the
parabola through the three history samples around its largest sample (the
O(dt^2) sampling error of a maximum). Peak times and q are printed, not
extrapolated: they are sampled at dt and q jumps when a node ring joins.

Usage: PYTHONPATH=python python3 -m visco2d.convergence [--max-level 5] [--dt-level 3]
       [--exe build/install/bin/visco2d] [--out build/convergence_table1]
       [--integrator WILSON|NEWMARK|HHT|GENERALIZED_ALPHA|BATHE]
(--integrator: the card of python/visco2d/deck.py INTEGRATOR_CARDS in place
of WILSON THETA=1.4; the default is the paper's Wilson-theta.)
Writes OUT/table.md and prints it. Standard library only.
"""
import argparse
import math
import os
import sys
import time

from . import runner
from .case import number, read_history, read_summary
from .deck import INTEGRATOR_CARDS

KEYS = ["alpha_max_mm", "t_alpha_max_ms", "q_max_MPa", "t_q_max_ms", "q_surface_max_MPa", "force_max_N",
        "t_force_max_ms", "contact_nodes_max", "hertz_alpha_max_mm", "balance_error_J", "nodes", "elements"]


def deck_text(name, level, dt, integrator="WILSON"):
    return "\n".join([
        "TITLE " + name,
        "ANALYSIS DYNAMIC",
        "GEOMETRY AXISYMMETRIC",
        "MATERIAL apple ELASTIC E=18.11e6 NU=0.219 RHO=756.85",
        "MESH SPHERE R=0.0366 LEVEL=%d" % level,
        "INITIAL VZ=-0.9982 AZ=-9.8",
        "GRAVITY G=9.8",
        "WILSON THETA=1.4" if integrator == "WILSON" else INTEGRATOR_CARDS[integrator],
        "TIME DT=%g TEND=4e-3" % dt,
        "PLATE Z=0",
        "END", ""])


def run(exe, out, name, level, dt, integrator="WILSON"):
    decks = os.path.join(out, "decks")
    os.makedirs(decks, exist_ok=True)
    path = os.path.join(decks, name + ".inp")
    with open(path, "w") as handle:
        handle.write(deck_text(name, level, dt, integrator))
    start = time.time()
    result = runner.run(exe, [path], os.path.join(out, "runs"))
    seconds = time.time() - start
    if result.returncode != 0:
        sys.exit("visco2d failed on %s:\n%s" % (path, result.stderr))
    folder = os.path.join(out, "runs", name)
    summary = read_summary(folder)
    history = read_history(folder)
    t, alpha = history["t_ms"], history["alpha_mm"]
    record = {key: number(summary, key) for key in KEYS if key in summary}
    record["alpha_parabola_mm"] = parabola_peak(t, alpha)
    record["seconds"] = seconds
    return record


def parabola_peak(t, f):
    i = max(range(len(f)), key=lambda k: f[k])
    if i == 0 or i == len(f) - 1:
        return f[i]
    curvature = f[i - 1] - 2 * f[i] + f[i + 1]
    if curvature >= 0:
        return f[i]
    shift = 0.5 * (f[i - 1] - f[i + 1]) / curvature
    return f[i] - 0.25 * (f[i - 1] - f[i + 1]) * shift


def orders(values):
    """Observed orders and Richardson values of consecutive triples."""
    lines = []
    for k in range(len(values) - 2):
        f1, f2, f3 = values[k:k + 3]
        if f2 == f3 or f1 == f2:
            lines.append((k, float("nan"), float("nan")))
            continue
        p = math.log2(abs(f1 - f2) / abs(f2 - f3))
        richardson = f3 + (f3 - f2) / (2 ** p - 1) if p > 0 else float("nan")
        lines.append((k, p, richardson))
    return lines


def main():
    parser = argparse.ArgumentParser(prog="python3 -m visco2d.convergence", description=__doc__.splitlines()[0])
    parser.add_argument("--max-level", type=int, default=5)
    parser.add_argument("--dt-level", type=int, default=3)
    parser.add_argument("--exe", default=os.environ.get("VISCO2D", "build/install/bin/visco2d"))
    parser.add_argument("--out", default="build/convergence_table1")
    parser.add_argument("--integrator", default="WILSON", choices=list(INTEGRATOR_CARDS))
    args = parser.parse_args()
    if not os.path.exists(args.exe):
        sys.exit("no executable %s: run `make build` first" % args.exe)
    lines = []

    def emit(text=""):
        print(text, flush=True)
        lines.append(text)

    suffix = "" if args.integrator == "WILSON" else "_" + args.integrator.lower()
    emit("## Table 1 elastic impact: convergence (PLATE Z=0 STICK, stop at maximum deformation; %s)"
         % ("WILSON THETA=1.4" if args.integrator == "WILSON" else INTEGRATOR_CARDS[args.integrator]))
    emit()
    emit("Mesh refinement, dt = 1e-5 s:")
    emit()
    emit("| level | elements | nodes | alpha_max mm | alpha (parabola) mm | t_alpha ms | q_max MPa | t_q ms |"
         " q_surface_max MPa | force_max N | t_force ms | contact nodes | Hertz alpha mm | run s |")
    emit("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    mesh = []
    for level in range(1, args.max_level + 1):
        r = run(args.exe, args.out, "table1_level%d%s" % (level, suffix), level, 1e-5, args.integrator)
        mesh.append(r)
        emit("| %d | %d | %d | %.5f | %.5f | %.3f | %.3f | %.3f | %.3f | %.2f | %.3f | %d | %.4f | %.1f |" % (
            level, r["elements"], r["nodes"], r["alpha_max_mm"], r["alpha_parabola_mm"], r["t_alpha_max_ms"],
            r["q_max_MPa"], r["t_q_max_ms"], r["q_surface_max_MPa"], r["force_max_N"], r["t_force_max_ms"],
            r["contact_nodes_max"], r["hertz_alpha_max_mm"], r["seconds"]))
    emit()
    emit("| levels | observed order p of alpha_m | Richardson alpha_m mm |")
    emit("|---|---|---|")
    values = [r["alpha_max_mm"] for r in mesh]
    for k, p, richardson in orders(values):
        emit("| %d, %d, %d | %.2f | %.5f |" % (k + 1, k + 2, k + 3, p, richardson))
    if len(values) >= 3:
        best = orders(values)[-1][2]
        emit()
        emit("Level 1 (the paper's 88 elements) vs the last Richardson value: %.2f %%" %
             (100 * (values[0] / best - 1)))

    dts = [4e-5, 2e-5, 1e-5, 5e-6, 2.5e-6, 1.25e-6]
    emit()
    emit("Time-step refinement, level %d:" % args.dt_level)
    emit()
    emit("| dt s | alpha_max mm | alpha (parabola) mm | t_alpha ms | q_max MPa | t_q ms | force_max N |"
         " balance_error J/rad | run s |")
    emit("|---|---|---|---|---|---|---|---|---|")
    steps = []
    for dt in dts:
        r = run(args.exe, args.out, "table1_level%d_dt%g%s" % (args.dt_level, dt, suffix), args.dt_level, dt,
                args.integrator)
        steps.append(r)
        emit("| %.3g | %.6f | %.6f | %.4f | %.3f | %.4f | %.2f | %.3e | %.1f |" % (
            dt, r["alpha_max_mm"], r["alpha_parabola_mm"], r["t_alpha_max_ms"], r["q_max_MPa"], r["t_q_max_ms"],
            r["force_max_N"], r["balance_error_J"], r["seconds"]))
    emit()
    emit("| dt triple | p (parabola) | Richardson (parabola) mm | p (raw maxima) |")
    emit("|---|---|---|---|")
    par = orders([r["alpha_parabola_mm"] for r in steps])
    raw = orders([r["alpha_max_mm"] for r in steps])
    for (k, p, richardson), (_, p_raw, _) in zip(par, raw):
        emit("| %.3g, %.3g, %.3g | %.2f | %.6f | %.2f |" % (dts[k], dts[k + 1], dts[k + 2], p, richardson, p_raw))

    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "table.md"), "w") as handle:
        handle.write("\n".join(lines) + "\n")
    print("\nwritten: %s" % os.path.join(args.out, "table.md"))


if __name__ == "__main__":
    main()
