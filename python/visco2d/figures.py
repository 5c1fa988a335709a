"""Pictures of the paper's figures from visco2d's results.h5 files (`make figures`).

Reads out/<case>/results.h5 of the paper's impact decks (running the deck into
OUT first when the file is missing), runs the Table 1 deck once more on a fine
mesh (MESH SPHERE LEVEL=4 by default) and the Fig. 2 deck on the same mesh at
DT 5e-6 s into OUT/figures/runs/, and writes
OUT/figures/*.png:

  fig2_center_acceleration.png  Fig. 2: centre acceleration of the apple (25.4 mm drop): the 10 mm
                               accelerometer, the centre node and the centre of mass; the paper's grid
                               and step, and level --level at 5e-6 s
  fig3_deformation.png          Fig. 3: Table 1 elastic impact, alpha(t): FE, exact Hertz, Goldsmith [46]
  fig4_pressure.png             Fig. 4: the same, maximum surface pressure q(t)
  fig5_apple_0.7.png            apple at 0.7 m/s (Table 3): alpha(t) and q(t)
  fig6_apple_1.2.png            apple at 1.2 m/s (Table 3): alpha(t) and q(t)
  fig5_6_apple_velocities.png   the paper's layout of Figs. 5-6: both velocities, alpha and q
  max_shear_contour.png         maximum shear stress in the r-z section at maximum deformation

usage: figures.py [--out DIR] [--exe PATH] [--inputs DIR] [--level N]
"""
import argparse
import hashlib
import math
import os
import re
import sys

from . import hertz, runner
from .case import NotACase, read_results
from .deck import set_card_value, set_card_word

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.tri as mtri  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402

STANDARD_GRAVITY = 9.80665          # m/s^2, the unit "g" of accel_center_g
FINE_ACCEL_DT_S = 5e-6              # s, the step of the fine Fig. 2 run
PAPER_TABLE1 = {                    # the paper's Table 1: (t_m ms, alpha_m mm, q_m MPa)
    "dynamic finite element": (1.51, 1.096, 1.99),
    "Timoshenko & Goodier": (1.62, 1.097, 2.10),
}
LEVEL1_ELEMENTS = 88                # MESH SPHERE LEVEL=1; x4 per level

plt.rcParams.update({
    "font.size": 11, "axes.titlesize": 11, "axes.labelsize": 11, "legend.fontsize": 9,
    "xtick.labelsize": 10, "ytick.labelsize": 10, "axes.grid": True, "grid.alpha": 0.3,
    "savefig.dpi": 150,
})


# ----------------------------------------------------------------------------- runs and files

def fail(message):
    """Print an error message on stderr and stop with status 1."""
    print(f"figures: error: {message}", file=sys.stderr)
    sys.exit(1)


def run_deck(exe, deck, out_root):
    """Run `exe -q -o out_root deck`; stop with the solver's messages if it fails."""
    if not os.path.isfile(exe):
        fail(f"{exe} not found: build it first (make build) or pass --exe")
    if not os.path.isfile(deck):
        fail(f"deck {deck} not found")
    os.makedirs(out_root, exist_ok=True)
    print(f"figures: running {deck} into {out_root}/")
    done = runner.run(exe, [deck], out_root)
    if done.returncode != 0:
        fail(f"{exe} -q -o {out_root} {deck} exited with status {done.returncode}:\n"
             f"{done.stdout}{done.stderr}")


def case_results(case, args):
    """Path of OUT/<case>/results.h5; runs INPUTS/<case>.inp into OUT first when it is missing."""
    path = os.path.join(args.out, case, "results.h5")
    if not os.path.isfile(path):
        run_deck(args.exe, os.path.join(args.inputs, case + ".inp"), args.out)
        if not os.path.isfile(path):
            fail(f"{path} is still missing after running the deck")
    return path


def file_digest(path):
    """sha256 of a file's bytes (hex)."""
    digest = hashlib.sha256()
    with open(path, "rb") as handle:
        for block in iter(lambda: handle.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def fine_table1_results(args, plate="STICK"):
    """Results of the Table 1 deck on MESH SPHERE LEVEL=args.level with PLATE ... `plate` (STICK or SLIP)."""
    def change(text):
        text = set_card_value(text, r"MESH\s+SPHERE", "LEVEL", args.level)
        return set_card_word(text, "PLATE", "STICK", plate)
    case = f"table1_elastic_level{args.level}" + ("" if plate == "STICK" else "_" + plate.lower())
    return variant_results(args, "table1_elastic", case, change, f"MESH SPHERE LEVEL={args.level}, PLATE {plate}")


def fine_accel_results(args):
    """Results of the Fig. 2 deck on MESH SPHERE LEVEL=args.level at TIME DT = FINE_ACCEL_DT_S (the sensor's
    peak is converged in the step there: doc/verification.md)."""
    def change(text):
        text = set_card_value(text, r"MESH\s+SPHERE", "LEVEL", args.level)
        return set_card_value(text, "TIME", "DT", f"{FINE_ACCEL_DT_S:g}")
    return variant_results(args, "apple_center_accel", f"apple_center_accel_level{args.level}", change,
                           f"MESH SPHERE LEVEL={args.level}, DT {FINE_ACCEL_DT_S:g} s")


def variant_results(args, source_case, case, change, label):
    """Results of a variant of inputs/<source_case>.inp made by `change` (text -> text).

    The deck is written to OUT/figures/decks/<case>.inp and run into
    OUT/figures/runs/<case>/, unless that run was made from the same deck
    text by the same executable (a stamp file holds both digests: `make
    build` touches the executable on every call).
    """
    source = os.path.join(args.inputs, source_case + ".inp")
    if not os.path.isfile(source):
        fail(f"deck {source} not found")
    with open(source) as handle:
        text = handle.read()
    try:
        text = change(text)
    except ValueError as problem:
        fail(f"{source}: {problem}")
    text = re.sub(r"(?im)^(\s*TITLE\s.*)$", lambda m: m.group(1) + f" [figures.py: {label}]", text, count=1)
    deck_dir = os.path.join(args.out, "figures", "decks")
    run_dir = os.path.join(args.out, "figures", "runs")
    os.makedirs(deck_dir, exist_ok=True)
    deck = os.path.join(deck_dir, case + ".inp")
    with open(deck, "w") as handle:
        handle.write(text)
    path = os.path.join(run_dir, case, "results.h5")
    stamp_path = os.path.join(run_dir, case, "figures.stamp")
    if not os.path.isfile(args.exe):
        fail(f"{args.exe} not found: build it first (make build) or pass --exe")
    stamp = f"deck {hashlib.sha256(text.encode()).hexdigest()}\nexe {file_digest(args.exe)}\n"
    old = open(stamp_path).read() if os.path.isfile(stamp_path) else None
    if old != stamp or not os.path.isfile(path):
        run_deck(args.exe, deck, run_dir)
        with open(stamp_path, "w") as handle:
            handle.write(stamp)
    return path




def load_run(path):
    """Read one results.h5 (visco2d.case.read_results); stops with the reason when it is not a dynamic run."""
    try:
        run = read_results(os.path.dirname(path) or ".")
    except NotACase as problem:
        fail(str(problem))
    if not run["has_fields"]:
        fail(f"{path} has no /fields group (not a dynamic visco2d run?)")
    return run


def summary_float(run, key):
    """A summary key as a float; stops with a clear message when it is missing."""
    if key not in run["summary"]:
        fail(f"{run['path']}: summary key {key} missing")
    return float(run["summary"][key])


def column(run, name):
    """A history column; stops with a clear message when it is missing."""
    if name not in run["history"]:
        fail(f"{run['path']}: history column {name} missing")
    return run["history"][name]


def after_contact(run, *names):
    """t_ms and the named history columns, restricted to t >= 0 (first contact)."""
    t = column(run, "t_ms")
    keep = t >= 0.0
    return (t[keep],) + tuple(column(run, name)[keep] for name in names)


def mesh_label(run):
    """'level L, E elements' for a generated sphere (88 x 4^(L-1) elements), else 'E elements'."""
    nelem = len(run["elements"])
    level = 1 + round(math.log(nelem / LEVEL1_ELEMENTS, 4)) if nelem >= LEVEL1_ELEMENTS else None
    if level is not None and LEVEL1_ELEMENTS * 4 ** (level - 1) == nelem:
        return f"level {level}, {nelem} elements"
    return f"{nelem} elements"


def snapshot(run, label):
    """The snapshot whose label contains `label` (labels join with '; ' when two coincide)."""
    for field in run["fields"]:
        if label in field["label"].split("; "):
            return field
    fail(f"{run['path']}: no snapshot labelled '{label}' "
         f"(found: {', '.join(repr(field['label']) for field in run['fields'])})")


# ----------------------------------------------------------------------------- Hertz and Goldsmith

def hertz_constants(run):
    """E, nu, R, M, V of the summary's Hertz reference (instantaneous moduli, mesh mass)."""
    return tuple(summary_float(run, key) for key in
                 ("hertz_young_Pa", "hertz_poisson", "hertz_radius_m", "hertz_mass_kg", "hertz_speed_m_s"))


# ----------------------------------------------------------------------------- stresses

def max_shear(stress):
    """tau_max = (sigma_1 - sigma_3)/2 of axisymmetric stresses (..., 4) = (sigma_r, sigma_z, sigma_theta, tau_rz):
    the in-plane principal pair from sigma_r, sigma_z, tau_rz and sigma_theta as the third."""
    sr, sz, st, trz = (stress[..., i] for i in range(4))
    centre = 0.5 * (sr + sz)
    radius = np.sqrt((0.5 * (sr - sz)) ** 2 + trz ** 2)
    principal = np.stack([centre + radius, centre - radius, st])
    return 0.5 * (principal.max(axis=0) - principal.min(axis=0))


def gauss_points(xy):
    """(nelem, 4, 2) positions of the 2x2 Gauss points of quads xy (nelem, 4, 2), ordered like the nodes:
    (-,-), (+,-), (+,+), (-,+) (visco2d_element)."""
    g = 1.0 / math.sqrt(3.0)
    xi = np.array([-g, g, g, -g])
    eta = np.array([-g, -g, g, g])
    node_xi = np.array([-1.0, 1.0, 1.0, -1.0])
    node_eta = np.array([-1.0, -1.0, 1.0, 1.0])
    shape = 0.25 * (1 + np.outer(xi, node_xi)) * (1 + np.outer(eta, node_eta))   # (gauss, node)
    return np.einsum("gn,enc->egc", shape, xy)


# ----------------------------------------------------------------------------- figures

def save(fig, path, written):
    """Save and close a figure; remember the path."""
    fig.savefig(path)
    plt.close(fig)
    written.append(path)


def mark_peak(ax, t_peak, peak, text, colour, offset=(-10, 10), ha="right"):
    """A dot at a maximum and its value in a small white box."""
    ax.plot([t_peak], [peak], "o", color=colour, ms=6, zorder=5)
    ax.annotate(text, (t_peak, peak), textcoords="offset points", xytext=offset, ha=ha, color=colour,
                fontsize=10, bbox=dict(boxstyle="round,pad=0.2", fc="w", ec="none", alpha=0.85), zorder=6)


def figure2(accel, accel_sep, fine, path, written):
    """Fig. 2: upward acceleration (g) against time since contact. Top: the decks as run (the paper's grid and
    step), the accelerometer (the sensor of PROBE accelerometer ... RADIUS=, a mass-weighted mean over a 10 mm
    ball), the node nearest the centre and the centre of mass. Bottom: the same on the fine grid at a step
    where the sensor is converged: the node rings, the sensor does not."""
    sensor = "accelerometer_sensor_az_m_s2"
    key = "probe_accelerometer_sensor_accel_max_g"
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(9, 10), sharex=True)
    runs = []
    if accel_sep is not None:
        runs.append((accel_sep, "C1", "SLIP + release, to separation"))
    runs.append((accel, "C0", "STICK, to maximum deformation"))
    for run, colour, what in runs:
        t, node, probe, cm = after_contact(run, "accel_center_g", sensor, "az_cm_m_s2")
        top.plot(t, node, "-", color=colour, lw=0.7, alpha=0.45, label=f"node nearest the centre, {what}")
        top.plot(t, probe / STANDARD_GRAVITY, "-", color=colour, lw=2.0, label=f"accelerometer (10 mm), {what}")
        top.plot(t, cm / STANDARD_GRAVITY, "--", color=colour, lw=1.6, label=f"centre of mass, {what}")
    peak, t_peak = summary_float(accel, key), summary_float(accel, "t_" + key[:-1] + "ms")
    mark_peak(top, t_peak, peak, f"accelerometer: {peak:.0f} g at {t_peak:.2f} ms", "C0", offset=(10, 6), ha="left")
    top.set_title(f"the decks as given (the paper's grid and step): {mesh_label(accel)}, Δt {summary_float(accel, 'dt_s') * 1e3:g} ms "
                  "", fontsize=10)
    t, node, probe, cm = after_contact(fine, "accel_center_g", sensor, "az_cm_m_s2")
    bottom.plot(t, node, "-", color="0.6", lw=0.6, label="node nearest the centre")
    bottom.plot(t, probe / STANDARD_GRAVITY, "-", color="C0", lw=2.0, label="accelerometer (10 mm)")
    bottom.plot(t, cm / STANDARD_GRAVITY, "--", color="k", lw=1.6, label="centre of mass")
    peak, t_peak = summary_float(fine, key), summary_float(fine, "t_" + key[:-1] + "ms")
    mark_peak(bottom, t_peak, peak, f"accelerometer: {peak:.0f} g", "C0", offset=(10, 6), ha="left")
    node_peak = summary_float(fine, "accel_center_max_g")
    bottom.set_title(f"STICK, {mesh_label(fine)}, Δt {summary_float(fine, 'dt_s') * 1e3:g} ms: the node peaks "
                     f"at {node_peak:.0f} g (off the scale: it rings), the centre of mass at "
                     f"{summary_float(fine, 'accel_cm_max_g'):.1f} g", fontsize=10)
    limit = 2.0 * max(peak, summary_float(accel, key))
    for ax in (top, bottom):
        ax.axhline(0.0, color="k", lw=0.6)
        ax.set_xlim(left=0.0)
        ax.set_ylim(-0.5 * limit, limit)
        ax.set_ylabel("upward acceleration a_z (g)")
        ax.grid(lw=0.3)
        ax.legend(fontsize=8, loc="upper left", ncol=1 if ax is bottom else 2, framealpha=0.9)
    bottom.set_xlabel("time since first contact t (ms)")
    fig.suptitle(f"Fig. 2: acceleration at the centre of a Golden Delicious apple, 25.4 mm drop\n"
                 f"(V = {summary_float(accel, 'impact_velocity_m_s'):.4f} m/s, Table 3 constants at 0.7 m/s); "
                 "accelerometer: mean a_z of the nodes within 5 mm\nof the centre (PROBE ... RADIUS=0.005, "
                 "a sensor 10 mm across); g = 9.80665 m/s²", fontsize=11)
    fig.tight_layout()
    save(fig, path, written)


def table1_figure(coarse, fine, slip, quantity, path, written):
    """Figs. 3/4: Table 1 elastic impact, alpha (mm) or q (MPa) against time: FE on two meshes
    (and the fine mesh with SLIP), exact Hertz (mesh mass of each mesh), Goldsmith eq. [46], and the
    paper's Table 1 points. Returns the exact Hertz peak (t ms, value) of the fine mesh's mass."""
    young, poisson, radius, mass, speed = hertz_constants(fine)
    mass_coarse = hertz_constants(coarse)[3]
    t_m = summary_float(fine, "hertz_t_alpha_max_ms") * 1e-3
    last = max(column(run, "t_ms").max() for run in (coarse, fine, slip))
    t_end = max(1.25 * t_m, 1.05e-3 * last)
    is_alpha = quantity == "alpha"
    scale = 1e3 if is_alpha else 1e-6               # m -> mm, Pa -> MPa
    unit = "mm" if is_alpha else "MPa"
    fig, ax = plt.subplots(figsize=(9, 6.8))
    peak = None
    for mass_value, style, which in ((mass, "-", fine), (mass_coarse, ":", coarse)):
        t, alpha, q = hertz.exact(young, poisson, radius, mass_value, speed, t_end)
        value = (alpha if is_alpha else q) * scale
        ax.plot(t * 1e3, value, style, color="k", lw=1.6 if style == "-" else 1.2,
                label=f"exact Hertz, M = {mass_value:.4f} kg ({mesh_label(which).split(',')[0]} mesh mass)")
        if peak is None:
            peak = (t[np.argmax(value)] * 1e3, value.max())
    t = np.linspace(0.0, t_end, 600)
    alpha_g, q_g = hertz.goldsmith(young, poisson, radius, mass, speed, t)
    ax.plot(t * 1e3, (alpha_g if is_alpha else q_g) * scale, "--", color="0.5", lw=1.4,
            label=f"Goldsmith eq. [46], M = {mass:.4f} kg")
    name = "alpha_mm" if is_alpha else "q_MPa"
    key, tkey = ("alpha_max_mm", "t_alpha_max_ms") if is_alpha else ("q_max_MPa", "t_q_max_ms")
    for run, colour, lw, what in ((coarse, "C0", 2.0, "STICK"), (fine, "C3", 2.0, "STICK"),
                                  (slip, "C4", 1.3, "SLIP")):
        tt, value = after_contact(run, name)
        ax.plot(tt, value, "-", color=colour, lw=lw,
                label=f"FE, {mesh_label(run)}, {what}: max {summary_float(run, key):.3f} {unit} "
                      f"at {summary_float(run, tkey):.2f} ms")
        ax.plot([summary_float(run, tkey)], [summary_float(run, key)], "o", color=colour, ms=5)
    if not is_alpha:
        tt, value = after_contact(fine, "q_surface_MPa")
        ax.plot(tt, value, "-.", color="C3", lw=1.0,
                label=f"FE, {mesh_label(fine).split(',')[0]}, STICK: −σ_z extrapolated to the pole")
    for (who, (t_p, alpha_p, q_p)), marker in zip(PAPER_TABLE1.items(), ("s", "D")):
        ax.plot([t_p], [alpha_p if is_alpha else q_p], marker, mfc="none", mec="C2", mew=2, ms=9,
                label=f"paper's Table 1, {who}: {alpha_p if is_alpha else q_p} {unit} at {t_p} ms")
    ax.set_xlim(0.0, t_end * 1e3)
    ax.set_ylim(0.0, ax.get_ylim()[1] * 1.02)
    ax.set_xlabel("time since first contact t (ms)")
    if is_alpha:
        ax.set_ylabel("deformation α (mm)")
        title = "Fig. 3: deformation α (approach of the centre of mass since first contact)"
    else:
        ax.set_ylabel("maximum surface pressure q (MPa)")
        title = "Fig. 4: maximum surface pressure q (at the pole, from the nodal reaction)"
    ax.set_title(f"{title}\nTable 1 elastic sphere: V = {speed:g} m/s, E = {young / 1e6:g} MPa, ν = {poisson:g}, "
                 f"R = {radius * 1e3:g} mm\ndeck {coarse['case']}.inp (level 1 = the paper's 88 elements) "
                 f"and the same with LEVEL={args_level(fine)}", fontsize=10.5)
    ax.legend(loc="lower right", fontsize=8.5)
    fig.tight_layout()
    save(fig, path, written)
    return peak


def args_level(run):
    """The MESH SPHERE level of a run, from its element count ('?' if it is not a generated sphere)."""
    label = mesh_label(run)
    return label.split(",")[0].split()[1] if label.startswith("level") else "?"


def apple_figure(run, figure_name, path, written):
    """Figs. 5/6 (one apple): alpha (mm) and q (MPa) against time, two panels, maxima marked,
    with the elastic Hertz curve at the instantaneous moduli as a reference."""
    t, alpha, q = after_contact(run, "alpha_mm", "q_MPa")
    young, poisson, radius, mass, speed = hertz_constants(run)
    t_end = max(t.max(), summary_float(run, "hertz_t_alpha_max_ms")) * 1.05
    th, alpha_h, q_h = hertz.exact(young, poisson, radius, mass, speed, t_end * 1e-3)
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8.5, 8), sharex=True)
    t_alpha, t_q = summary_float(run, "t_alpha_max_ms"), summary_float(run, "t_q_max_ms")
    for ax, value, reference, key, tkey, label, unit, colour in (
            (top, alpha, alpha_h * 1e3, "alpha_max_mm", "t_alpha_max_ms", "deformation α", "mm", "C0"),
            (bottom, q, q_h * 1e-6, "q_max_MPa", "t_q_max_ms", "maximum surface pressure q", "MPa", "C3")):
        ax.plot(t, value, "-", color=colour, lw=2.0, label=f"FE, viscoelastic (Table 3), {mesh_label(run)}")
        ax.plot(th * 1e3, reference, "--", color="0.4", lw=1.2,
                label=f"Hertz, elastic with E(0) = {young / 1e6:.3f} MPa, ν(0) = {poisson:.3f}")
        peak, t_peak = summary_float(run, key), summary_float(run, tkey)
        mark_peak(ax, t_peak, peak, f"max {peak:.3g} {unit} at {t_peak:.2f} ms", colour, offset=(-10, -22))
        ax.axvline(t_alpha, color="0.3", lw=0.9, ls=":", label=f"t of max α: {t_alpha:.2f} ms")
        ax.axvline(t_q, color="0.3", lw=0.9, ls="-.", label=f"t of max q: {t_q:.2f} ms")
        ax.set_ylabel(f"{label} ({unit})")
        ax.set_ylim(0.0, max(value.max(), reference.max()) * 1.12)
        ax.legend(loc="upper left", fontsize=8.5)
    bottom.set_xlim(0.0, t_end)
    bottom.set_xlabel("time since first contact t (ms)")
    top.set_title(f"{figure_name}: apple on a rigid plate, V = {speed:g} m/s (Table 3 constants at {speed:g} m/s)\n"
                  f"deck {run['case']}.inp, {mesh_label(run)}, R = {radius * 1e3:g} mm, STICK; "
                  f"max q comes {t_alpha - t_q:.2f} ms before max α")
    fig.tight_layout()
    save(fig, path, written)


def apple_velocities_figure(slow, fast, path, written):
    """The paper's layout of Figs. 5 and 6: alpha (Fig. 5) and q (Fig. 6) of both apples on shared axes."""
    fig, (left, right) = plt.subplots(1, 2, figsize=(13, 5.4))
    for run, colour in ((slow, "C0"), (fast, "C3")):
        t, alpha, q = after_contact(run, "alpha_mm", "q_MPa")
        speed = summary_float(run, "impact_velocity_m_s")
        for ax, value, key, tkey, unit in ((left, alpha, "alpha_max_mm", "t_alpha_max_ms", "mm"),
                                           (right, q, "q_max_MPa", "t_q_max_ms", "MPa")):
            ax.plot(t, value, "-", color=colour, lw=2.0, label=f"V = {speed:g} m/s ({run['case']}.inp)")
            t_peak, peak = summary_float(run, tkey), summary_float(run, key)
            mark_peak(ax, t_peak, peak, f"{peak:.3g} {unit} at {t_peak:.2f} ms", colour, offset=(-8, 8))
    left.set_ylabel("deformation α (mm)")
    right.set_ylabel("maximum surface pressure q (MPa)")
    left.set_title("Fig. 5: effect of impact velocity on deformation")
    right.set_title("Fig. 6: effect of impact velocity on maximum surface pressure")
    for ax in (left, right):
        ax.set_xlabel("time since first contact t (ms)")
        ax.set_xlim(left=0.0)
        ax.set_ylim(0.0, ax.get_ylim()[1] * 1.12)
        ax.legend(loc="upper left")
    fig.suptitle(f"Viscoelastic apples (Table 3 constants of each velocity), R = 35 mm, STICK, "
                 f"to maximum deformation; {mesh_label(slow)}")
    fig.tight_layout()
    save(fig, path, written)


def max_shear_numbers(run):
    """tau_max at maximum deformation: nodal field (MPa), its maximum and place (deformed and undeformed),
    the Gauss-point maximum, and the Hertz subsurface maximum on the axis for comparison."""
    field = snapshot(run, "maximum deformation")
    xy = run["nodes"] + field["displacement"]                  # deformed geometry, true scale (m)
    tau = max_shear(field["stress"]) * 1e-6                     # nodal averages -> MPa
    peak = int(np.argmax(tau))
    numbers = {"field": field, "xy": xy, "tau": tau, "peak": peak, "tau_max_MPa": tau[peak],
               "r_mm": xy[peak, 0] * 1e3, "z_mm": xy[peak, 1] * 1e3,
               "r0_mm": run["nodes"][peak, 0] * 1e3, "z0_mm": run["nodes"][peak, 1] * 1e3,
               "time_ms": field["time"] * 1e3, "alpha_mm": summary_float(run, "alpha_max_mm")}
    if field["stress_gauss"] is not None:
        tau_gauss = max_shear(field["stress_gauss"]) * 1e-6
        points = gauss_points(xy[run["elements"]]) * 1e3
        e, g = np.unravel_index(int(np.argmax(tau_gauss)), tau_gauss.shape)
        numbers.update(tau_gauss_MPa=tau_gauss[e, g], r_gauss_mm=points[e, g, 0], z_gauss_mm=points[e, g, 1])
    poisson = summary_float(run, "hertz_poisson")
    q0 = summary_float(run, "hertz_q_max_MPa") * 1e6
    a = summary_float(run, "hertz_contact_radius_mm") * 1e-3
    depths = np.linspace(1e-6, 3 * a, 3000)
    shear = hertz.subsurface_shear(poisson, q0, a, depths)
    numbers.update(hertz_tau_MPa=shear.max() * 1e-6, hertz_depth_mm=depths[np.argmax(shear)] * 1e3,
                   hertz_a_mm=a * 1e3, hertz_q0_MPa=q0 * 1e-6)
    return numbers


def max_shear_figure(run, plate, path, written, zoom=(12.0, 10.0), vmax=None):
    """tau_max (MPa) in the r-z section at maximum deformation on the deformed mesh (true scale):
    the whole section and a zoom on the contact region; the maximum marked. Returns its numbers."""
    n = max_shear_numbers(run)
    xy, tau = n["xy"], n["tau"]
    elements = run["elements"]
    triangles = np.vstack([elements[:, [0, 1, 2]], elements[:, [0, 2, 3]]])   # each quad -> two triangles
    grid = mtri.Triangulation(xy[:, 0] * 1e3, xy[:, 1] * 1e3, triangles)
    top = vmax if vmax is not None else tau.max()
    levels = MaxNLocator(24).tick_values(0.0, top)
    fig = plt.figure(figsize=(13, 6.6))
    whole = fig.add_axes([0.05, 0.09, 0.25, 0.76])
    close = fig.add_axes([0.35, 0.09, 0.52, 0.76])
    bar_axes = fig.add_axes([0.89, 0.12, 0.018, 0.70])
    for ax in (whole, close):
        filled = ax.tricontourf(grid, np.minimum(tau, top), levels=levels, cmap="viridis")
        ax.tricontour(grid, tau, levels=levels[::3], colors="w", linewidths=0.4, alpha=0.6)
        ax.axhline(0.0, color="k", lw=2.0)                      # the plate
        ax.plot([n["r_mm"]], [n["z_mm"]], "r*", ms=15, mec="w", mew=0.8, zorder=5)
        ax.set_aspect("equal")
        ax.set_xlabel("r (mm)")
        ax.set_ylabel("z (mm)")
        ax.grid(False)
    whole.set_xlim(0.0, xy[:, 0].max() * 1e3 * 1.02)
    whole.set_ylim(-1.0, xy[:, 1].max() * 1e3 * 1.01)
    whole.add_patch(plt.Rectangle((0, 0), zoom[0], zoom[1], fill=False, ec="r", lw=1.2, ls="--"))
    whole.set_title("whole section; red box: zoom", fontsize=10)
    close.set_xlim(0.0, zoom[0])
    close.set_ylim(-0.4, zoom[1])
    close.annotate(f"max τ (red star) = {n['tau_max_MPa']:.3f} MPa\nat r = {n['r_mm']:.2f} mm, z = {n['z_mm']:.2f} mm\n"
                   f"(undeformed: r = {n['r0_mm']:.2f} mm, z = {n['z0_mm']:.2f} mm)",
                   (n["r_mm"], n["z_mm"]), textcoords="axes fraction", xytext=(0.36, 0.45), color="w", fontsize=10,
                   arrowprops=dict(arrowstyle="->", color="w"),
                   bbox=dict(boxstyle="round", fc="0.15", ec="none", alpha=0.75))
    hertz_depth = n["hertz_depth_mm"]
    close.plot([0.0], [hertz_depth], "wo", mfc="none", ms=11, mew=1.8, zorder=5)
    close.annotate(f"Hertz (white circle; frictionless half-space):\nmax τ = {n['hertz_tau_MPa']:.3f} MPa "
                   f"on the axis at depth {hertz_depth:.2f} mm\n(contact radius a = {n['hertz_a_mm']:.2f} mm)",
                   (0.0, hertz_depth), textcoords="axes fraction", xytext=(0.36, 0.72), color="w", fontsize=10,
                   arrowprops=dict(arrowstyle="->", color="w"),
                   bbox=dict(boxstyle="round", fc="0.15", ec="none", alpha=0.75))
    close.set_title(f"contact region, r < {zoom[0]:g} mm, z < {zoom[1]:g} mm (plate: black line z = 0)",
                    fontsize=10)
    bar = fig.colorbar(filled, cax=bar_axes)
    bar.set_label(r"maximum shear stress $\tau_\mathrm{max}$ = (σ₁ − σ₃)/2 (MPa)")
    fig.suptitle(f"Maximum shear stress at maximum deformation (t = {n['time_ms']:.2f} ms, "
                 f"α = {n['alpha_mm']:.3f} mm): deformed mesh at true scale, nodal (averaged) stresses\n"
                 f"Table 1 elastic sphere, V = {summary_float(run, 'impact_velocity_m_s'):g} m/s, PLATE {plate}; "
                 f"deck {run['case']}.inp, {mesh_label(run)}", fontsize=11.5)
    save(fig, path, written)
    return n


# ----------------------------------------------------------------------------- main

def main():
    """Parse the options, gather the runs, draw every figure and print the files written."""
    parser = argparse.ArgumentParser(prog="python3 -m visco2d.figures", description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default="out", help="output root of `make run` (default: out)")
    parser.add_argument("--exe", default="build/install/bin/visco2d", help="the visco2d executable")
    parser.add_argument("--inputs", default="inputs", help="folder of the paper's decks (default: inputs)")
    parser.add_argument("--level", type=int, default=4,
                        help="MESH SPHERE LEVEL of the fine Table 1 runs (default 4: 5632 elements)")
    args = parser.parse_args()
    if args.level < 1:
        fail("--level must be at least 1")
    figures = os.path.join(args.out, "figures")
    os.makedirs(figures, exist_ok=True)

    accel = load_run(case_results("apple_center_accel", args))
    accel_sep = load_run(case_results("apple_center_accel_separation", args))
    coarse = load_run(case_results("table1_elastic", args))
    slow = load_run(case_results("apple_v0.7", args))
    fast = load_run(case_results("apple_v1.2", args))
    fine = load_run(fine_table1_results(args, "STICK"))
    slip = load_run(fine_table1_results(args, "SLIP"))

    written = []
    figure2(accel, accel_sep, load_run(fine_accel_results(args)), os.path.join(figures, "fig2_center_acceleration.png"),
            written)
    hertz_peak = table1_figure(coarse, fine, slip, "alpha", os.path.join(figures, "fig3_deformation.png"), written)
    table1_figure(coarse, fine, slip, "q", os.path.join(figures, "fig4_pressure.png"), written)
    apple_figure(slow, "Figs. 5-6 at 0.7 m/s", os.path.join(figures, "fig5_apple_0.7.png"), written)
    apple_figure(fast, "Figs. 5-6 at 1.2 m/s", os.path.join(figures, "fig6_apple_1.2.png"), written)
    apple_velocities_figure(slow, fast, os.path.join(figures, "fig5_6_apple_velocities.png"), written)
    stick = max_shear_numbers(fine)
    shear = {"STICK": max_shear_figure(fine, "STICK", os.path.join(figures, "max_shear_contour.png"), written),
             "SLIP": max_shear_figure(slip, "SLIP", os.path.join(figures, "max_shear_contour_slip.png"), written,
                                      vmax=stick["tau_max_MPa"])}

    mass = hertz_constants(fine)[3]
    print(f"figures: Table 1, Hertz (M = {mass:.4f} kg): summary alpha_m {summary_float(fine, 'hertz_alpha_max_mm'):.4f} mm "
          f"at {summary_float(fine, 'hertz_t_alpha_max_ms'):.3f} ms, q_m {summary_float(fine, 'hertz_q_max_MPa'):.3f} MPa; "
          f"integrated curve peaks at {hertz_peak[1]:.4f} mm at {hertz_peak[0]:.3f} ms")
    for run, plate in ((coarse, "STICK"), (fine, "STICK"), (slip, "SLIP")):
        print(f"figures: Table 1, FE {mesh_label(run)}, {plate}: alpha_m {summary_float(run, 'alpha_max_mm'):.3f} mm "
              f"at {summary_float(run, 't_alpha_max_ms'):.3f} ms, q_m {summary_float(run, 'q_max_MPa'):.3f} MPa at "
              f"{summary_float(run, 't_q_max_ms'):.3f} ms")
    for plate, n in shear.items():
        gauss = (f"; Gauss points {n['tau_gauss_MPa']:.3f} MPa at r = {n['r_gauss_mm']:.2f}, "
                 f"z = {n['z_gauss_mm']:.2f} mm" if "tau_gauss_MPa" in n else "")
        print(f"figures: max shear at maximum deformation, {plate} (t = {n['time_ms']:.2f} ms): nodal "
              f"{n['tau_max_MPa']:.3f} MPa at r = {n['r_mm']:.2f} mm, z = {n['z_mm']:.2f} mm{gauss}; "
              f"Hertz {n['hertz_tau_MPa']:.3f} MPa on the axis at depth {n['hertz_depth_mm']:.2f} mm")
    print(f"figures: {len(written)} files written:")
    for path in written:
        print(f"  {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
