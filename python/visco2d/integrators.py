"""The integrator family side by side: amplification matrices and the Table 1 impact.

    PYTHONPATH=python python3 -m visco2d.integrators [--out DIR] [--exe PATH] [--levels 1] [--dts-ms 0.04,0.02,0.01]
                                   [--integrators WILSON,NEWMARK,...] [--deck inputs/table1_elastic.inp]
                                   [--reference-mm 1.0388] [--table-only] [--reuse]

Part 1 (no runs, --table-only stops here): each integrator's amplification
matrix A on a single degree of freedom (u'' + omega^2 u = 0, state x = (u, v, a),
x_{n+1} = A x_n), written from the textbook definitions -- Wilson-theta as
Bathe and Wilson give it, Newmark, HHT-alpha and generalized-alpha as Chung
and Hulbert (1993) write the family, Bathe and Baig's (2005) composite
trapezoidal / 3-point backward Euler step -- independently of the solver.
From the principal eigenvalue pair lambda = r e^{+-i phi} at Omega = omega dt:
  period error          T_bar/T - 1 = Omega/phi - 1
  algorithmic damping   xi_bar = -ln(r)/phi
  spectral radius       rho(A) = max |lambda| (at dt/T = 0.1 and at Omega = 1e6, "infinity").

Part 2: the Table 1 impact (inputs/table1_elastic.inp: STICK, to maximum
deformation; --deck another impact deck with MESH SPHERE, e.g.
inputs/apple_center_accel.inp, the Fig. 2 accelerometer deck), OUTPUT EVERY=1
so that every step is in history.csv, with each
integrator at each DT and mesh level: alpha_m, t_m, q_m, the peak centre
acceleration, the CPU seconds of the solve (summary cpu_s) and two noise
measures over the contact phase (force > 0):
  noise(f) = RMS_n (f_{n+1} - 2 f_n + f_{n-1}) / max |f|
the root mean square of the step-to-step second difference of the history,
normalised by its peak, for the contact force (force_N) and the centre
acceleration (accel_center_g). A smooth history sampled at DT has a second
difference of order DT^2 f'' (small, and falling 4x per halving of DT);
ringing from period to period of the step is of the order of its own
amplitude. alpha errors are against the converged reference of the Table 1
impact (python/visco2d/study.py's f*, out of `make study`: 1.0388 mm, levels 3-5 at
DT 0.0025 ms), unless --reference-mm says otherwise (for another --deck:
no alpha error unless --reference-mm is given).

Writes OUT/integrators.md (and .csv) and prints the markdown.
"""
import argparse
import cmath
import csv
import math
import os
import re
import sys
import time

from . import runner
from .case import read_history, read_summary
from .deck import INTEGRATOR_CARDS, set_card_value, set_integrator
from .runner import ROOT, cpu_model

#: alpha_m (mm) of the Table 1 impact converged in mesh and DT: the reference f* of `make study`
#: (Richardson over levels 3-5 at DT 0.0025 ms plus the DT correction; README "What accuracy costs").
CONVERGED_ALPHA_MM = 1.0388

#: The integrators compared: name -> (INTEGRATOR card, parameters for the amplification matrix).
SCHEMES = {
    "WILSON": (INTEGRATOR_CARDS["WILSON"], {"kind": "wilson", "theta": 1.4}),
    "NEWMARK": (INTEGRATOR_CARDS["NEWMARK"], {"kind": "alpha", "beta": 0.25, "gamma": 0.5}),
    "HHT": (INTEGRATOR_CARDS["HHT"], {"kind": "alpha", "hht": 0.05}),
    "GENERALIZED_ALPHA": (INTEGRATOR_CARDS["GENERALIZED_ALPHA"], {"kind": "alpha", "rho_inf": 0.8}),
    "BATHE": (INTEGRATOR_CARDS["BATHE"], {"kind": "bathe"}),
}
LABELS = {
    "WILSON": "Wilson-θ, θ = 1.4 (paper)",
    "NEWMARK": "Newmark β = 1/4, γ = 1/2 (trapezoidal)",
    "HHT": "HHT-α, α = 0.05",
    "GENERALIZED_ALPHA": "generalized-α, ρ∞ = 0.8",
    "BATHE": "Bathe composite (γ = 1/2)",
}


# ---------------------------------------------------------------- amplification matrices

def alpha_row(params):
    """(beta, gamma, alpha_m, alpha_f) of the Chung-Hulbert family for NEWMARK / HHT / GENERALIZED_ALPHA."""
    if "hht" in params:                       # Hilber-Hughes-Taylor: alpha_f = alpha, alpha_m = 0
        a = params["hht"]
        return (1 + a) ** 2 / 4, 0.5 + a, 0.0, a
    if "rho_inf" in params:                   # Chung & Hulbert 1993, eqs. (25)-(27)
        rho = params["rho_inf"]
        am, af = (2 * rho - 1) / (rho + 1), rho / (rho + 1)
        return (1 - am + af) ** 2 / 4, 0.5 - am + af, am, af
    return params["beta"], params["gamma"], 0.0, 0.0


def step(params, x, w2, h):
    """One step of u'' + w2 u = 0 from x = (u, v, a) with step h, the textbook form of each method."""
    u, v, a = x
    kind = params["kind"]
    if kind == "wilson":                      # Bathe & Wilson: linear acceleration over tau = theta h
        theta = params["theta"]
        tau = theta * h
        u_tau = (6 / tau**2 * u + 6 / tau * v + 2 * a) / (w2 + 6 / tau**2)
        a_tau = 6 / tau**2 * (u_tau - u) - 6 / tau * v - 2 * a
        a1 = a + (a_tau - a) / theta
        return (u + h * v + h**2 / 6 * (2 * a + a1), v + h / 2 * (a + a1), a1)
    if kind == "alpha":                       # (1 - am) a1 + am a + w2 ((1 - af) u1 + af u) = 0
        beta, gamma, am, af = alpha_row(params)
        predictor = u + h * v + h**2 * (0.5 - beta) * a
        a1 = -(am * a + w2 * ((1 - af) * predictor + af * u)) / ((1 - am) + w2 * (1 - af) * beta * h**2)
        return (predictor + beta * h**2 * a1, v + h * ((1 - gamma) * a + gamma * a1), a1)
    if kind == "bathe":                       # Bathe & Baig 2005: trapezoidal over h/2, then 3-point Euler backward
        uh, vh, ah = step({"kind": "alpha", "beta": 0.25, "gamma": 0.5}, x, w2, h / 2)
        u1 = -((v - 4 * vh) / h + 3 * (u - 4 * uh) / h**2) / (9 / h**2 + w2)
        v1 = (u - 4 * uh + 3 * u1) / h
        a1 = (v - 4 * vh + 3 * v1) / h
        return (u1, v1, a1)
    raise ValueError(kind)


def amplification(params, omega_dt):
    """A (3 x 3, columns = the step of the unit states) at Omega = omega dt (omega = 1), in the state
    (u, dt v, dt^2 a): a similarity of the (u, v, a) matrix (the same eigenvalues) with entries of order 1."""
    columns = [step(params, unit, 1.0, omega_dt) for unit in ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))]
    scale = (1.0, omega_dt, omega_dt**2)
    return [[columns[j][i] * scale[i] / scale[j] for j in range(3)] for i in range(3)]


def eigenvalues(a):
    """The three eigenvalues of a 3 x 3 matrix (numpy)."""
    import numpy
    return list(numpy.linalg.eigvals(numpy.array(a)))


def properties(params, omega_dt):
    """Spectral radius, period error T_bar/T - 1 and damping ratio xi_bar at Omega (principal pair)."""
    roots = eigenvalues(amplification(params, omega_dt))
    radius = max(abs(z) for z in roots)
    pair = [z for z in roots if z.imag > 1e-14]
    if not pair:
        return radius, float("nan"), float("nan")
    z = max(pair, key=abs)
    phase = cmath.phase(z)
    return radius, omega_dt / phase - 1.0, -math.log(abs(z)) / phase


#: "Delta t / T -> infinity": Omega = omega dt = 1e12. The radius approaches its limit as Omega^-2
#: (Wilson, HHT), Omega^-1 (Bathe: 5/Omega) or Omega^(-2/3) (generalized-alpha, whose three eigenvalues
#: meet at -rho_inf: 0.78 Omega^(-2/3)), so at 1e12 all are within 1e-8 of the limit.
OMEGA_INFINITY = 1e12


def amplification_table():
    """Markdown: the integrators' period error, damping and spectral radius at dt/T = 0.1 and infinity."""
    omega = 2 * math.pi * 0.1
    lines = ["| integrator | INTEGRATOR card | period error T̄/T − 1 at Δt/T = 0.1 | damping ratio ξ̄ at 0.1 "
             "| ρ(A) at 0.1 | ρ(A) at 1 | ρ(A) at Δt/T → ∞ (Ω = 1e12) | period error at 0.05 |",
             "|---|---|---|---|---|---|---|---|"]
    for name, (card, params) in SCHEMES.items():
        radius, period, xi = properties(params, omega)
        radius_inf = properties(params, OMEGA_INFINITY)[0]
        period_half = properties(params, omega / 2)[1]
        radius_one = properties(params, 2 * math.pi)[0]
        lines.append("| %s | `%s` | %+.2f %% | %.4f | %.5f | %.3f | %.4f | %+.2f %% |" % (
            LABELS[name], card, 100 * period, xi, radius, radius_one, radius_inf, 100 * period_half))
    return "\n".join(lines)


# ---------------------------------------------------------------- the Table 1 impact


def noise(values, active):
    """RMS over the active steps of the second difference f_{n+1} - 2 f_n + f_{n-1}, over max |f| there."""
    indices = [n for n in range(1, len(values) - 1) if active[n - 1] and active[n] and active[n + 1]]
    peak = max((abs(values[n]) for n in range(len(values)) if active[n]), default=0.0)
    if not indices or peak == 0.0:
        return float("nan")
    total = sum((values[n + 1] - 2 * values[n] + values[n - 1]) ** 2 for n in indices)
    return math.sqrt(total / len(indices)) / peak


def impact_deck(source_text, card, level, dt_ms):
    """Table 1 with LEVEL=, DT=, OUTPUT EVERY=1 and the integrator card (in place of WILSON THETA=)."""
    text = set_card_value(source_text, r"MESH\s+SPHERE", "LEVEL", level)
    text = set_card_value(text, "TIME", "DT", "%.10g" % (dt_ms * 1e-3))
    text = set_card_value(text, "OUTPUT", "EVERY", 1)
    text = set_integrator(text, card)
    text = re.sub(r"(?im)^\s*PROBE\b[^\n]*\n", "", text)
    return text


def run_impact(exe, out, name, level, dt_ms, source_text, reuse, case="table1_elastic"):
    card = SCHEMES[name][0]
    tag = "%s_%s_L%d_dt%dns" % (case, name.lower(), level, round(dt_ms * 1e6))
    decks, runs = os.path.join(out, "decks"), os.path.join(out, "runs")
    os.makedirs(decks, exist_ok=True)
    deck_path = os.path.join(decks, tag + ".inp")
    text = impact_deck(source_text, card, level, dt_ms)
    summary_path = os.path.join(runs, tag, "summary.txt")
    row = {"integrator": name, "level": level, "dt_ms": dt_ms, "status": "failed"}
    same = reuse and os.path.isfile(deck_path) and os.path.isfile(summary_path) and open(deck_path).read() == text
    if not same:
        with open(deck_path, "w") as handle:
            handle.write(text)
        result = runner.run(exe, [deck_path], runs)
        if result.returncode != 0 or not os.path.isfile(summary_path):
            row["detail"] = ((result.stderr or result.stdout).strip().splitlines() or ["no output"])[-1]
            return row
    summary = read_summary(summary_path)
    history = read_history(os.path.join(runs, tag, "history.csv"))
    active = [f > 0.0 for f in history["force_N"]]
    row.update({
        "alpha_max_mm": float(summary["alpha_max_mm"]), "t_alpha_max_ms": float(summary["t_alpha_max_ms"]),
        "q_max_MPa": float(summary["q_max_MPa"]), "accel_center_max_g": float(summary["accel_center_max_g"]),
        "accel_cm_max_g": float(summary["accel_cm_max_g"]), "force_max_N": float(summary["force_max_N"]),
        "steps": int(summary["steps"]), "cpu_s": float(summary["cpu_s"]),
        "noise_force": noise(history["force_N"], active), "noise_accel": noise(history["accel_center_g"], active),
        "status": "ok"})
    return row


def percent_error(value, reference):
    return "—" if reference is None else "%+.2f" % (100 * (value / reference - 1))


def impact_table(rows, reference):
    lines = ["| integrator | level | Δt (ms) | steps | α_m (mm) | α error % | t_m (ms) | q_m (MPa) "
             "| centre accel. max (g) | CM decel. max (g) | force noise | accel. noise | CPU s |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if r["status"] != "ok":
            lines.append("| %s | %d | %g | FAILED: %s | | | | | | | | | |" % (
                r["integrator"], r["level"], r["dt_ms"], r.get("detail", "")))
            continue
        lines.append("| %s | %d | %g | %d | %.4f | %s | %.4f | %.3f | %.0f | %.1f | %.2e | %.2e | %.3f |" % (
            r["integrator"], r["level"], r["dt_ms"], r["steps"], r["alpha_max_mm"],
            percent_error(r["alpha_max_mm"], reference), r["t_alpha_max_ms"], r["q_max_MPa"],
            r["accel_center_max_g"], r["accel_cm_max_g"], r["noise_force"], r["noise_accel"], r["cpu_s"]))
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(prog="python3 -m visco2d.integrators", description=__doc__.split("\n")[0])
    parser.add_argument("--out", default=os.path.join(ROOT, "out", "integrators"))
    parser.add_argument("--exe", default=os.path.join(ROOT, "build/install/bin/visco2d"))
    parser.add_argument("--levels", default="1")
    parser.add_argument("--dts-ms", default="0.04,0.02,0.01")
    parser.add_argument("--integrators", default=",".join(SCHEMES))
    parser.add_argument("--deck", default=os.path.join("inputs", "table1_elastic.inp"),
                        help="the impact deck (MESH SPHERE ... LEVEL=, TIME DT=, OUTPUT EVERY=, one WILSON card)")
    parser.add_argument("--reference-mm", type=float,
                        help="converged alpha_m (default for Table 1: make study's f*, %g mm)" % CONVERGED_ALPHA_MM)
    parser.add_argument("--table-only", action="store_true", help="the amplification table only (no runs)")
    parser.add_argument("--reuse", action="store_true", help="do not rerun an identical deck already run in OUT")
    args = parser.parse_args()
    names = [n.strip().upper() for n in args.integrators.split(",") if n.strip()]
    unknown = [n for n in names if n not in SCHEMES]
    if unknown:
        sys.exit("integrators: unknown integrator(s) %s (known: %s)" % (", ".join(unknown), ", ".join(SCHEMES)))
    text = ["# The integrator family on one degree of freedom and on the Table 1 impact", "",
            "## Amplification matrices (single degree of freedom)", "", amplification_table(), ""]
    if not args.table_only:
        exe = os.path.abspath(args.exe)
        if not os.access(exe, os.X_OK):
            sys.exit("integrators: no executable %s (run `make build`)" % exe)
        deck_path = args.deck if os.path.isabs(args.deck) else os.path.join(ROOT, args.deck)
        with open(deck_path) as handle:
            source = handle.read()
        case = os.path.splitext(os.path.basename(deck_path))[0]
        reference = args.reference_mm
        if reference is None and case == "table1_elastic":
            reference = CONVERGED_ALPHA_MM
        levels = [int(v) for v in args.levels.split(",")]
        dts = sorted((float(v) for v in args.dts_ms.split(",")), reverse=True)
        rows = []
        for level in levels:
            for name in names:
                for dt in dts:
                    start = time.perf_counter()
                    row = run_impact(exe, args.out, name, level, dt, source, args.reuse, case)
                    print("integrators: %s level %d DT %g ms: %s (%.1f s)" % (
                        name, level, dt, row["status"], time.perf_counter() - start), file=sys.stderr, flush=True)
                    rows.append(row)
        text += ["## The impact: %s" % os.path.relpath(deck_path, ROOT), "",
                 "CPU: %s; one run at a time. α error against the converged α_m = %s mm. Noise: RMS of the "
                 "step-to-step second difference f(n+1) − 2 f(n) + f(n−1) over the contact phase (force > 0), "
                 "divided by the peak of |f| there." % (cpu_model(), "—" if reference is None else "%g" % reference),
                 "", impact_table(rows, reference), ""]
        os.makedirs(args.out, exist_ok=True)
        with open(os.path.join(args.out, "integrators.csv"), "w", newline="") as handle:
            columns = ["integrator", "level", "dt_ms", "steps", "alpha_max_mm", "t_alpha_max_ms", "q_max_MPa",
                       "accel_center_max_g", "accel_cm_max_g", "force_max_N", "noise_force", "noise_accel",
                       "cpu_s", "status"]
            writer = csv.DictWriter(handle, fieldnames=columns, extrasaction="ignore")
            writer.writeheader()
            writer.writerows(rows)
        with open(os.path.join(args.out, "integrators.md"), "w") as handle:
            handle.write("\n".join(text) + "\n")
        if any(r["status"] != "ok" for r in rows):
            print("\n".join(text))
            return 1
    print("\n".join(text))
    return 0


if __name__ == "__main__":
    sys.exit(main())
