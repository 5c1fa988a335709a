#!/usr/bin/env python3
"""A CalculiX (ccx) peer reference of a peach dropped on a 10 mm hyperfoam pad (visco2d issue 28).

The scene visco2d's `KINEMATICS LARGE` with a `PAD` is to be checked against
(doc/calculix_foam_pad.md):

  peach  sphere R 0.030 m, neo-Hookean (*HYPERELASTIC, NEO HOOKE) with the small-strain
         moduli of E 5 MPa, nu 0.35 (C10 = G/2, D1 = 2/K), rho 950 kg/m^3, gravity 9.81 m/s^2;
         visco2d's mesh `MESH SPHERE R=0.03 LEVEL=2` (read from its results.h5)
  drop   0.2 m: the pole touches the pad top z = 0 moving down at V = sqrt(2 g h) = 1.981 m/s
  pad    a disc 10 mm thick, radius 45 mm (1.5 R), *HYPERFOAM N=2 of doc/hyperfoam.md
         (set B: mu 0.74, 0.01 MPa, alpha 12, -2, nu 0, 0), rho 100 kg/m^3, its bottom bonded
         to a rigid ground (every dof fixed), its top in frictionless penalty contact
         with the peach; graded as visco2d's PAD grid (surface nodes under the peach's
         boundary nodes out to 0.4 R, columns growing by 1.2 beyond, rows growing by 1.2
         downward from the peach's pole element size)

CAX4 elements (expanded by ccx into C3D8 over a 2-degree sector), NLGEOM, *DYNAMIC, DIRECT
(HHT, alpha -0.05) at a fixed dt, face-to-face (SURFACE TO SURFACE) penalty contact. ccx 2.20's
*INITIAL CONDITIONS velocity does not move expanded CAX4 nodes, so step 1 lifts the peach by about
1 mm and accelerates it from rest to the impact speed by a uniform body force (a rigid translation);
step 2 switches to gravity and runs the impact to past separation (approach_step).

  PYTHONPATH=python python3 scripts/calculix_foam_pad.py [OUT]             # the whole study
  PYTHONPATH=python python3 scripts/calculix_foam_pad.py [OUT] --runs base # one run

Writes OUT (default out/calculix_foam_pad/): one folder per run, OUT/results.json,
OUT/report.md and OUT/history.csv (the finest run). Not part of `make test` (tens of minutes);
python/tests/test_calculix_foam_pad.py checks the parts that need no ccx.
"""
import argparse
import json
import math
import os
import shutil
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, ".."))
sys.path.insert(0, os.path.join(ROOT, "python"))
sys.path.insert(0, HERE)

from calculix_common import (  # noqa: E402
    SECTOR, body_mesh_cards, ccx_version, dat_blocks, gauss_point_index, gauss_weights, plate_node_base,
    read_mesh, run_ccx, run_visco2d, slave_nodes, volume_mean_weights)
from calculix_nlgeom_impact import flesh_card, max_shear_3d, neo_hooke_constants, parabola_vertex  # noqa: E402

G_ACC = 9.81
#: the peach of inputs/peach_drop.inp
PEACH = dict(R=0.030, E=5e6, nu=0.35, rho=950.0)
DROP_HEIGHT = 0.2
#: the pad: thickness (m), radius as a multiple of R, density
PAD = dict(thickness=0.010, width_factor=1.5, rho=100.0)
#: the example hyperfoam sets of doc/hyperfoam.md (mu in Pa)
FOAMS = {
    "A": dict(mu=(0.245e6, 0.005e6), alpha=(10.0, -2.0), nu=(0.0, 0.0)),
    "B": dict(mu=(0.74e6, 0.01e6), alpha=(12.0, -2.0), nu=(0.0, 0.0)),
    "C": dict(mu=(0.164861e6, 2.302e1), alpha=(8.88413, -4.81798), nu=(0.0, 0.0)),
}
#: the gap (m) between the pole and the pad's top centre that counts as separation
SEPARATION_GAP = 1e-6
#: the default penalty slope (Pa/m): 1e-5 m of overclosure at 1 MPa of contact pressure
PENALTY = 1e11


def impact_speed(h=DROP_HEIGHT, g=G_ACC):
    """V = sqrt(2 g h)."""
    return math.sqrt(2.0 * g * h)


def sphere_mass(R, rho):
    return rho * 4.0 / 3.0 * math.pi * R ** 3


# ---------------------------------------------------------------- the foam
def hyperfoam_card(foam):
    """The *HYPERFOAM lines (ccx/ABAQUS layout: mu_1, alpha_1, ..., mu_N, alpha_N, nu_1, ..., nu_N,
    eight values to a line; no temperature), units as given (Pa here)."""
    n = len(foam["mu"])
    values = [x for pair in zip(foam["mu"], foam["alpha"]) for x in pair] + list(foam["nu"])
    lines = [f"*HYPERFOAM, N={n}"]
    for i in range(0, len(values), 8):
        lines.append(", ".join(f"{v:.10g}" for v in values[i:i + 8]))
    return lines


def hyperfoam_moduli(foam):
    """(mu0, K0, E0) at small strain: mu0 = sum mu_i, K0 = sum 2 mu_i (1/3 + beta_i), beta = nu/(1 - 2 nu),
    E0 = 9 K0 mu0 / (3 K0 + mu0)."""
    mu0 = float(sum(foam["mu"]))
    K0 = float(sum(2.0 * m * (1.0 / 3.0 + n / (1.0 - 2.0 * n)) for m, n in zip(foam["mu"], foam["nu"])))
    return mu0, K0, 9.0 * K0 * mu0 / (3.0 * K0 + mu0)


def hyperfoam_uniaxial_nominal(foam, lam):
    """The nominal stress of uniaxial stress at the axial stretch lam, for one nu shared by every term:
    lateral stretch lam^(-nu), J = lam^(1 - 2 nu), T = (2/lam) sum mu_i/alpha_i (lam^alpha_i - J^(-alpha_i beta))."""
    nus = set(foam["nu"])
    if len(nus) != 1:
        raise ValueError("hyperfoam_uniaxial_nominal needs one nu for every term")
    nu = nus.pop()
    beta = nu / (1.0 - 2.0 * nu)
    J = lam ** (1.0 - 2.0 * nu)
    return 2.0 / lam * sum(m / a * (lam ** a - J ** (-a * beta)) for m, a in zip(foam["mu"], foam["alpha"]))


# ---------------------------------------------------------------- the pad grid
def graded_sizes(total, first, ratio=1.2):
    """Element sizes first, first ratio, first ratio^2, ... that fill `total` exactly: as many as bring
    the sum nearest to total, then all scaled by total / sum."""
    sizes = [first]
    while sum(sizes) < total:
        sizes.append(sizes[-1] * ratio)
    if len(sizes) > 1 and abs(sum(sizes[:-1]) - total) < abs(sum(sizes) - total):
        sizes.pop()
    scale = total / sum(sizes)
    return [s * scale for s in sizes]


def pad_radii(body_r, r_match, width, ratio=1.2):
    """The pad's surface node radii: the body's boundary node radii up to r_match (sorted, from 0), then
    columns growing by `ratio` from the last matched spacing out to `width` (visco2d's PAD rule)."""
    r = sorted(float(x) for x in body_r if x <= r_match + 1e-12)
    if r[0] > 1e-12:
        r = [0.0] + r
    last = r[-1] - r[-2]
    rest = graded_sizes(width - r[-1], last * ratio, ratio)
    for s in rest:
        r.append(r[-1] + s)
    r[-1] = width
    return np.array(r)


def uniform_radii(size, r_fine, width, ratio=1.2):
    """Surface radii at a uniform `size` out to r_fine (rounded to whole elements), then growing by ratio."""
    n = max(1, int(round(r_fine / size)))
    r = list(np.linspace(0.0, n * size, n + 1))
    for s in graded_sizes(width - r[-1], size * ratio, ratio):
        r.append(r[-1] + s)
    r[-1] = width
    return np.array(r)


def pad_depths(thickness, first, ratio=1.2):
    """The pad's row levels z, from the top z = 0 down to -thickness, rows growing by ratio downward."""
    z = [0.0]
    for s in graded_sizes(thickness, first, ratio):
        z.append(z[-1] - s)
    z[-1] = -thickness
    return np.array(z)


def pad_grid(r, z):
    """The r-z grid: nodes (n, 2) numbered row by row from the top (node k = j * len(r) + i at (r_i, z_j)),
    CAX4 elements (counter-clockwise in r-z: (i, j+1), (i+1, j+1), (i+1, j), (i, j) with z_j above z_j+1),
    so that face S3 (corners 3-4) of the top row is the pad's top surface."""
    nr, nz = len(r), len(z)
    nodes = np.array([(r[i], z[j]) for j in range(nz) for i in range(nr)])
    elements = []
    for j in range(nz - 1):
        for i in range(nr - 1):
            elements.append((( j + 1) * nr + i, (j + 1) * nr + i + 1, j * nr + i + 1, j * nr + i))
    return nodes, np.array(elements, dtype=int)


def element_area_signs(nodes, elements):
    """The signed areas of the elements (positive: counter-clockwise in r-z)."""
    X = nodes[elements]
    x, y = X[:, :, 0], X[:, :, 1]
    return 0.5 * ((x * np.roll(y, -1, axis=1)).sum(axis=1) - (np.roll(x, -1, axis=1) * y).sum(axis=1))


def pad_cards(r, z, base):
    """The pad's *NODE/*ELEMENT/*NSET/*SURFACE cards, node and element numbers from base + 1: sets NPAD,
    EPAD, PADBOT (the bottom row), PADTOP (the top row), PADAXIS (r = 0, not on the bottom), PADCTR (the
    top centre node); surface SPAD (the top row's S3 faces). Returns (lines, info dict)."""
    nodes, elements = pad_grid(r, z)
    nr, nz = len(r), len(z)
    lines = ["*NODE, NSET=NPAD"]
    lines += [f"{base + k + 1}, {x:.15g}, {y:.15g}" for k, (x, y) in enumerate(nodes)]
    lines.append("*ELEMENT, TYPE=CAX4, ELSET=EPAD")
    lines += [f"{base + e + 1}, " + ", ".join(str(base + n + 1) for n in conn) for e, conn in enumerate(elements)]

    def nset(name, ks):
        ks = [base + k + 1 for k in ks]
        return [f"*NSET, NSET={name}"] + [", ".join(str(k) for k in ks[i:i + 10]) for i in range(0, len(ks), 10)]

    bottom = [(nz - 1) * nr + i for i in range(nr)]
    top = list(range(nr))
    axis = [j * nr for j in range(nz - 1)]
    lines += nset("PADBOT", bottom) + nset("PADTOP", top) + nset("PADAXIS", axis) + nset("PADCTR", [0])
    lines.append("*SURFACE, NAME=SPAD, TYPE=ELEMENT")
    lines += [f"{base + e + 1}, S3" for e in range(nr - 1)]
    return lines, dict(nodes=nodes, elements=elements, top=top, bottom=bottom, centre=base + 1, r1=float(r[1]))


# ---------------------------------------------------------------- the deck
def near_elements(nodes, elements, R, r_cut=0.2, z_cut=0.45):
    """Indices (from 0) of the peach's elements with every node at r < r_cut R and z < z_cut R."""
    X = nodes[elements]
    keep = (X[:, :, 0].max(axis=1) < r_cut * R) & (X[:, :, 1].max(axis=1) < z_cut * R)
    return np.nonzero(keep)[0]


def approach_step(V, dt, g=G_ACC, t1=1e-3):
    """The accelerated approach of step 1, dict(t1, g1, lift, gap, V1): ccx 2.20's *INITIAL CONDITIONS
    velocity does not move expanded CAX4 nodes (doc/calculix_plastic.md), and a free fall from h leaves
    the displacements near -h, whose 7 printed digits (1e-7 h) make the velocity and the contact force
    (differences of U; ccx 2.20 prints V = 0 for these nodes too) noisy. So the peach is lifted by
    `lift` (about 1 mm) and accelerated from rest by a uniform body force g1 over t1 (a rigid translation
    of a free body: no strain) to V1 = sqrt(V^2 - 2 g gap), with the pole `gap` = 2 dt V above the pad;
    step 2 switches to the real gravity g and meets the pad at V."""
    gap = 2.0 * dt * V
    V1 = math.sqrt(V * V - 2.0 * g * gap)
    g1 = V1 / t1
    return dict(t1=t1, g1=g1, lift=0.5 * g1 * t1 * t1 + gap, gap=gap, V1=V1)


CONTACT_KINDS = {"f2f": "SURFACE TO SURFACE", "n2s": "NODE TO SURFACE"}


def contact_cards(penalty, sigma_inf, kind="f2f", slave="SSLAVE", master="SPAD"):
    """Frictionless penalty contact of the slave surface on the master (default: the peach's SSLAVE on the
    pad's top SPAD), face-to-face (f2f, ccx's SURFACE TO SURFACE) or node-to-surface (n2s)."""
    return ["*SURFACE INTERACTION, NAME=FRICTIONLESS",
            "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
            f"{penalty:.6g}, {sigma_inf:.6g}",
            f"*CONTACT PAIR, INTERACTION=FRICTIONLESS, TYPE={CONTACT_KINDS[kind]}",
            f"{slave}, {master}"]


def controls_line(q_user):
    """The *CONTROLS, PARAMETERS=FIELD data line: ccx's defaults (R_n 0.005, C_n 0.01, q0 0.01, R_P 0.02,
    eps 1e-5, C_eps 1e-3, C_f 1e-8) with the user-defined average force q_u = q_user (N, of the 2-degree
    sector). ccx's own average force (the mean nodal force over the step's increments) is tiny before the
    impact (gravity on the peach's nodes), so the residual test 0.005 q cannot be met at first contact and
    ccx iterates without end; a fixed q_u = 0.02 N (the peak contact force is about 0.7 N over the sector)
    accepts residuals below 1e-4 N."""
    return f"0.005, 0.01, 0.01, {q_user:.6g}, 0.02, 1.e-5, 1.e-3, 1.e-8"


def ccx_deck(path, nodes, elements, ids, r_pad, z_pad, foam, penalty, t_end, dt, near, V=None,
             p=PEACH, pad=PAD, kind="f2f", pad_slave=False, contact_print=False, q_user=0.02):
    """The CalculiX deck: the peach lifted over the pad (top z = 0) and accelerated to the impact speed V
    (step 1, approach_step, 100 increments), step 2 the impact under gravity at the fixed dt to t_end,
    printing at every increment U of the peach and of the pad's top, RF of the pad's bottom, the energies
    of both bodies and S in the peach's elements `near` the contact. (ccx 2.20 refuses *CONTACT PRINT
    here, "no existing contact pair defined": the contact force is the rate of the peach's momentum
    plus its weight, from U.) Returns the pad's info (pad_cards)."""
    V = impact_speed() if V is None else V
    a = approach_step(V, dt)
    t1, h = a["t1"], a["lift"]
    base = plate_node_base(ids)
    lines = ["*HEADING", f"peach R {p['R']:g} m on a {pad['thickness'] * 1e3:g} mm hyperfoam pad at {V:.6g} m/s"]
    mesh, _ = body_mesh_cards(nodes, elements, ids, h, 0.4 * p["R"])
    lines += mesh
    padl, info = pad_cards(r_pad, z_pad, base)
    lines += padl
    lines.append("*ELSET, ELSET=ENEAR")
    near = [int(e) + 1 for e in near]
    lines += [", ".join(str(e) for e in near[i:i + 10]) for i in range(0, len(near), 10)]
    lines += flesh_card("neohooke", p["E"], p["nu"], p["rho"])
    lines += ["*MATERIAL, NAME=FOAM"] + hyperfoam_card(foam) + ["*DENSITY", f"{pad['rho']:.10g}",
              "*SOLID SECTION, ELSET=ESPHERE, MATERIAL=FLESH",
              "*SOLID SECTION, ELSET=EPAD, MATERIAL=FOAM"]
    lines += contact_cards(penalty, 1e3, kind, *(("SPAD", "SSLAVE") if pad_slave else ("SSLAVE", "SPAD")))
    lines += ["*AMPLITUDE, NAME=ONE, TIME=TOTAL TIME", "0., 1., 1000., 1.",
              "*BOUNDARY", "AXIS, 1, 1, 0.0", "PADAXIS, 1, 1, 0.0", "PADBOT, 1, 3, 0.0",
              "*STEP, NLGEOM, INC=1000000", "*DYNAMIC, DIRECT", f"{t1 / 100:.15g}, {t1:.15g}",
              "*DLOAD, AMPLITUDE=ONE", f"ESPHERE, GRAV, {a['g1']:.15g}, 0., -1., 0.",
              "*EL PRINT, ELSET=ESPHERE, TOTALS=ONLY, FREQUENCY=100", "ELSE, ELKE",
              "*END STEP",
              "*STEP, NLGEOM, INC=1000000", "*DYNAMIC, DIRECT", f"{dt:.10g}, {t_end:.10g}",
              "*CONTROLS, PARAMETERS=FIELD", controls_line(q_user),
              "*DLOAD, OP=NEW, AMPLITUDE=ONE", f"ESPHERE, GRAV, {G_ACC:g}, 0., -1., 0.",
              "*NODE PRINT, NSET=NSPHERE, FREQUENCY=1", "U",
              "*NODE PRINT, NSET=PADTOP", "U",
              "*NODE PRINT, NSET=PADBOT, TOTALS=ONLY", "RF",
              "*EL PRINT, ELSET=ESPHERE, TOTALS=ONLY", "ELSE, ELKE",
              "*EL PRINT, ELSET=EPAD, TOTALS=ONLY", "ELSE, ELKE",
              "*EL PRINT, ELSET=ENEAR", "S"]
    if contact_print:
        lines += ["*CONTACT PRINT, TOTALS=ONLY", "CF"]
    lines += ["*END STEP", ""]
    with open(path, "w") as f:
        f.write("\n".join(lines))
    return info


# ---------------------------------------------------------------- results
def axis_interpolation(nodes, z_at):
    """(i, j, s): the two axis nodes (indices from 0) around z = z_at and the weight s of j
    (u(z_at) = (1 - s) u_i + s u_j); the peach's centre (0, R) is not a node of MESH SPHERE."""
    axis = np.nonzero(np.abs(nodes[:, 0]) < 1e-12)[0]
    axis = axis[np.argsort(nodes[axis, 1])]
    z = nodes[axis, 1]
    k = int(np.searchsorted(z, z_at))
    k = min(max(k, 1), len(z) - 1)
    i, j = int(axis[k - 1]), int(axis[k])
    return i, j, float((z_at - z[k - 1]) / (z[k] - z[k - 1]))


def crossing(t, y, start=0):
    """The first time at or after index start where y changes sign from <= 0 to > 0 (linear), or None."""
    for k in range(max(start, 1), len(y)):
        if y[k - 1] <= 0 < y[k]:
            s = -y[k - 1] / (y[k] - y[k - 1])
            return float(t[k - 1] + s * (t[k] - t[k - 1])), k
    return None, None


def at_time(t, y, tq):
    """y linearly interpolated at tq."""
    return float(np.interp(tq, t, y))


def ccx_results(folder, job, nodes, elements, ids, pad_info, dt, V=None, p=PEACH, pad=PAD):
    """The impact of a run from its .dat: the histories from first contact and the maxima."""
    w, xy, shape = gauss_weights(nodes, elements)
    c = volume_mean_weights(nodes, elements, w, shape)
    M = sphere_mass(p["R"], p["rho"])
    index = {int(n): i for i, n in enumerate(ids)}
    V = impact_speed() if V is None else V
    a = approach_step(V, dt)
    t1, h = a["t1"], a["lift"]
    blocks = dat_blocks(os.path.join(folder, job + ".dat"))

    def step_of(t):
        return int(round((t - t1) / dt))

    def table(prefix, setname):
        return {step_of(b[1]): b[2] for b in blocks if b[0].startswith(prefix) and b[0].endswith(" " + setname)
                and b[1] > t1 + 0.5 * dt}

    U = table("displacements", "NSPHERE")
    UP = table("displacements", "PADTOP")
    RF = table("total force", "PADBOT")
    energy = {key: table(f"total {kind} energy", setname) for key, kind, setname in
              (("se_peach", "internal", "ESPHERE"), ("ke_peach", "kinetic", "ESPHERE"),
               ("se_pad", "internal", "EPAD"), ("ke_pad", "kinetic", "EPAD"))}
    S = table("stresses", "ENEAR")
    ks = sorted(k for k in U if k >= 1)
    pole = int(np.argmin(np.hypot(nodes[:, 0], nodes[:, 1])))
    ci, cj, cs = axis_interpolation(nodes, p["R"])
    centre_pad = pad_info["centre"]
    hist = {key: [] for key in ("uz_centre", "uz_pole", "uz_cm", "uz_pad", "uz_pad1", "F_ground")}
    energies = {key: [] for key in energy}
    for k in ks:
        rows = np.array(U[k])
        u = np.zeros((len(nodes), 2))
        u[np.array([index[int(n)] for n in rows[:, 0]])] = rows[:, 1:3]
        hist["uz_centre"].append((1 - cs) * u[ci, 1] + cs * u[cj, 1])
        hist["uz_pole"].append(u[pole, 1])
        hist["uz_cm"].append(c @ u[:, 1])
        pad_rows = {int(r[0]): r for r in UP[k]}
        hist["uz_pad"].append(pad_rows[centre_pad][2])
        hist["uz_pad1"].append(pad_rows[centre_pad + 1][2])
        hist["F_ground"].append(RF[k][0][1] * SECTOR)
        for key in energy:
            energies[key].append(energy[key][k][0][0] * SECTOR if k in energy[key] else float("nan"))
    hist = {key: np.array(x) for key, x in hist.items()}
    energies = {key: np.array(x) for key, x in energies.items()}
    t_abs = t1 + np.array(ks) * dt
    # velocities by central differences of U (ccx 2.20 prints V = 0 at the nodes of expanded CAX4)
    hist["vz_cm"] = np.gradient(hist["uz_cm"], t_abs)
    hist["vz_centre"] = np.gradient(hist["uz_centre"], t_abs)
    # first contact: the pole reaches the pad's undeformed top z = 0 (the pad is at rest before), linear
    # between increments (the pole's own z: after contact the pad's top follows it, so the gap to the
    # pad's top would stay near 0 and bias the interpolation by up to dt)
    zp = h + hist["uz_pole"]
    j = int(np.nonzero(zp <= 0)[0][0])
    if j == 0:
        raise ValueError(f"{job}.dat: the pole is already on the pad at the first printed increment")
    s_ = zp[j - 1] / (zp[j - 1] - zp[j])
    t_c = t_abs[j - 1] + s_ * dt
    t = t_abs - t_c
    ref = {key: at_time(t, hist[key], 0.0) for key in ("uz_centre", "uz_pole", "uz_cm")}
    v0 = -at_time(t, hist["vz_cm"], 0.0)
    alpha = -(hist["uz_centre"] - ref["uz_centre"])          # the centre's travel toward the ground
    alpha_cm = -(hist["uz_cm"] - ref["uz_cm"])
    pole_travel = -(hist["uz_pole"] - ref["uz_pole"])
    pad_top = hist["uz_pad"]
    pad_top1 = hist["uz_pad1"]         # the first surface node off the axis (see doc/calculix_foam_pad.md)
    # the contact force: the rate of the peach's momentum plus its weight (gravity and contact are the
    # only forces on it): F = M (dv_cm/dt + g), v_cm the consistent-mass mean of the velocities
    F_contact = M * (np.gradient(hist["vz_cm"], t_abs) + G_ACC)
    after = t > 0
    alpha_m, t_m = parabola_vertex(t[after], alpha[after])
    alpha_cm_m, t_cm_m = parabola_vertex(t[after], alpha_cm[after])
    k_m = int(np.argmin(np.abs(t - t_m)))
    kf = int(np.argmax(hist["F_ground"]))
    kc = int(np.argmax(np.where(after, F_contact, -np.inf)))
    kp = int(np.argmin(pad_top))
    kp1 = int(np.argmin(pad_top1))
    # separation: the pole leaves the pad's top centre after the maximum
    # (beyond a 1 micrometre tolerance: the printed digits of U, and a body resting on the pad)
    gap = h + hist["uz_pole"] - hist["uz_pad"]
    t_sep, k_sep = crossing(t, gap - SEPARATION_GAP, start=k_m)
    res = dict(
        V_first_contact_m_s=float(v0), t_first_contact_s=float(t_c), mass_kg=M,
        alpha_max_mm=alpha_m * 1e3, t_alpha_max_ms=t_m * 1e3,
        alpha_cm_max_mm=alpha_cm_m * 1e3, t_alpha_cm_max_ms=t_cm_m * 1e3,
        pole_travel_at_alpha_max_mm=at_time(t, pole_travel, t_m) * 1e3,
        pad_top_uz_at_alpha_max_mm=at_time(t, pad_top, t_m) * 1e3,
        body_approach_at_alpha_max_mm=(alpha_m - at_time(t, pole_travel, t_m)) * 1e3,
        pad_top_uz_min_mm=float(pad_top[kp] * 1e3), t_pad_top_uz_min_ms=float(t[kp] * 1e3),
        pad_compression_max=float(-pad_top[kp] / pad["thickness"]),
        pad_top1_uz_at_alpha_max_mm=at_time(t, pad_top1, t_m) * 1e3,
        pad_top1_uz_min_mm=float(pad_top1[kp1] * 1e3), t_pad_top1_uz_min_ms=float(t[kp1] * 1e3),
        pad_compression1_max=float(-pad_top1[kp1] / pad["thickness"]), pad_node1_r_mm=float(pad_info["r1"] * 1e3),
        ground_force_max_N=float(hist["F_ground"][kf]), t_ground_force_max_ms=float(t[kf] * 1e3),
        contact_force_max_N=float(F_contact[kc]), t_contact_force_max_ms=float(t[kc] * 1e3),
        t_end_ms=float(t[-1] * 1e3), steps=len(ks))
    if t_sep is not None:
        v_sep = at_time(t, hist["vz_cm"], t_sep)
        v_sep_c = at_time(t, hist["vz_centre"], t_sep)
        res.update(contact_duration_ms=t_sep * 1e3, rebound_speed_cm_m_s=v_sep, rebound_speed_centre_m_s=v_sep_c,
                   restitution_cm=v_sep / v0, restitution_centre=v_sep_c / v0)
        # the ground force's end: its last sign change from + to <= 0 before t_sep (the pad vibrates after)
        pos = np.nonzero((hist["F_ground"] > 0) & (t < t_sep + 1e-12))[0]
        res["t_ground_force_last_positive_ms"] = float(t[pos[-1]] * 1e3) if len(pos) else None
    # the contact force's end: its first fall to <= 0 after its peak
    t_fc, _ = crossing(t, -F_contact, start=kc)
    res["t_contact_force_zero_ms"] = t_fc * 1e3 if t_fc is not None else None
    # energies: kinetic + stored of both bodies + the peach's potential M g z_cm, against first contact
    total = energies["ke_peach"] + energies["se_peach"] + energies["ke_pad"] + energies["se_pad"] + M * G_ACC * hist["uz_cm"]
    e0 = at_time(t, total, 0.0)
    ke0 = 0.5 * M * v0 ** 2
    window = after & (t <= (t_sep if t_sep is not None else t[-1]))
    res["energy_error_max_rel"] = float(np.max(np.abs(total[window] - e0)) / ke0)
    res["energy_at_separation_rel"] = float((at_time(t, total, t_sep) - e0) / ke0) if t_sep is not None else None
    res["pad_energy_at_separation_rel"] = (float(at_time(t, energies["ke_pad"] + energies["se_pad"], t_sep) / ke0)
                                           if t_sep is not None else None)
    res["peach_vibration_energy_at_separation_rel"] = (float(
        (at_time(t, energies["ke_peach"] + energies["se_peach"], t_sep) - 0.5 * M * at_time(t, hist["vz_cm"], t_sep) ** 2) / ke0)
        if t_sep is not None else None)
    # the Gauss-point max shear (sigma_1 - sigma_3)/2 (Cauchy stress) in ENEAR, apart from the pole's own
    # element(s): the pole node pokes into the pad's axis node (doc/calculix_foam_pad.md), a spike that
    # decays within that element; its largest value is kept apart (shear_pole_element_max_MPa)
    pole_elements = set(int(x) for x in np.nonzero((elements == pole).any(axis=1))[0])
    best, at_alpha, pole_peak = None, None, 0.0
    k_alpha = min(S, key=lambda k: abs(t1 + k * dt - t_c - t_m)) if S else None
    for k in sorted(S):
        if not S[k]:
            continue
        rows = np.array(S[k])
        e, k2 = gauss_point_index(rows)
        tau = max_shear_3d(rows[:, 2:8])
        at_pole = np.isin(e, list(pole_elements))
        if at_pole.any():
            pole_peak = max(pole_peak, float(tau[at_pole].max()))
        tau = np.where(at_pole, -np.inf, tau)
        i = int(np.argmax(tau))
        item = (float(tau[i]), k, int(e[i]), int(k2[i]))
        if best is None or item[0] > best[0]:
            best = item
        if k == k_alpha:
            at_alpha = item
    if best is not None:
        res.update(shear_max_MPa=best[0] / 1e6, t_shear_max_ms=float((t1 + best[1] * dt - t_c) * 1e3),
                   shear_max_z_mm=float(xy[best[2], best[3], 1] * 1e3), shear_max_r_mm=float(xy[best[2], best[3], 0] * 1e3))
    res["shear_pole_element_max_MPa"] = pole_peak / 1e6
    if at_alpha is not None:
        res.update(shear_at_alpha_MPa=at_alpha[0] / 1e6, shear_at_alpha_z_mm=float(xy[at_alpha[2], at_alpha[3], 1] * 1e3))
    res["history"] = dict(t=t.tolist(), centre_uz=(-alpha).tolist(), pole_uz=(-pole_travel).tolist(),
                          pad_top_uz=pad_top.tolist(), pad_top1_uz=pad_top1.tolist(), ground_force=hist["F_ground"].tolist(),
                          contact_force=F_contact.tolist(), cm_uz=(-alpha_cm).tolist())
    return res


HISTORY_COLUMNS = ("t_s", "centre_uz_m", "pole_uz_m", "pad_top_uz_m", "ground_force_N", "contact_force_N",
                   "pad_top_r1_uz_m")


def write_history(path, hist):
    """The history CSV from first contact (t >= 0): displacements relative to first contact (the pad's
    top centre: from rest), forces in N of the whole ring."""
    keys = ("t", "centre_uz", "pole_uz", "pad_top_uz", "ground_force", "contact_force", "pad_top1_uz")
    with open(path, "w") as f:
        f.write(",".join(HISTORY_COLUMNS) + "\n")
        for row in zip(*(hist[k] for k in keys)):
            if row[0] < 0:
                continue
            f.write(",".join(f"{x:.7g}" for x in row) + "\n")


# ---------------------------------------------------------------- runs
def visco2d_mesh(exe, folder, level, p=PEACH):
    """visco2d's MESH SPHERE of the peach: a deck of a few steps run into folder; (nodes, elements, ids)."""
    os.makedirs(folder, exist_ok=True)
    deck = os.path.join(folder, f"peach_mesh_L{level}.inp")
    with open(deck, "w") as f:
        f.write(f"""TITLE The peach's mesh for the CalculiX foam-pad reference (scripts/calculix_foam_pad.py)
ANALYSIS DYNAMIC
MATERIAL flesh ELASTIC E={p['E']:g} NU={p['nu']:g} RHO={p['rho']:g}
MESH SPHERE R={p['R']:g} LEVEL={level}
INITIAL VZ={-impact_speed():.10g} AZ={-G_ACC:g}
GRAVITY G={G_ACC:g}
TIME DT=1e-5 TEND=2e-5
PLATE Z=0 SLIP RELEASE=YES
STOP AT=TEND
END
""")
    vcase, _ = run_visco2d(exe, deck, folder)
    return read_mesh(vcase)


#: the runs of the study: name -> (mesh level, dt, penalty factor, pad refinement, foam set; the region
#: r < near_r R, z < near_z R where S is printed, default 0.2 and 0.45; t_end, default --t-end)
RUNS = {
    "base": dict(level=2, dt=2e-5, penalty=1.0, pad_refine=1, foam="B"),
    "dt_half": dict(level=2, dt=1e-5, penalty=1.0, pad_refine=1, foam="B"),
    "penalty_x10": dict(level=2, dt=2e-5, penalty=10.0, pad_refine=1, foam="B"),
    "pad_fine": dict(level=2, dt=2e-5, penalty=1.0, pad_refine=2, foam="B"),
    # level 3: S printed in r < 0.06 R only (the peak is on the axis, ~1 mm from it at level 2), not to
    # print 800 elements at every increment; dt 1e-5 (at 2e-5 ccx diverged at first contact, the pad's
    # top row 0.2 mm thick), to 4.2 ms only (past the maxima at 3.4 ms; CPU)
    "level3": dict(level=3, dt=1e-5, penalty=1.0, pad_refine=1, foam="B", near_r=0.06, t_end=4.2e-3),
    "foam_A": dict(level=2, dt=2e-5, penalty=1.0, pad_refine=1, foam="A"),
}


def refine(values, times):
    """Each interval of a sorted coordinate list split into `times` equal parts."""
    out = [values[0]]
    for a, b in zip(values[:-1], values[1:]):
        out += [a + (b - a) * k / times for k in range(1, times + 1)]
    return np.array(out)


def pad_mesh_for(nodes, elements, p=PEACH, pad=PAD, refine_by=1):
    """The pad's (radii, depths) for the peach's mesh: visco2d's PAD rule, each interval split refine_by times."""
    s = slave_nodes(nodes, elements, 0.4 * p["R"])
    r = pad_radii(nodes[s, 0], 0.4 * p["R"], pad["width_factor"] * p["R"])
    axis = np.sort(nodes[np.abs(nodes[:, 0]) < 1e-12, 1])
    first = float(axis[1] - axis[0])                      # the pole element's height
    z = pad_depths(pad["thickness"], first)
    if refine_by > 1:
        r, z = refine(r, refine_by), refine(z, refine_by)
    return r, z


def run_one(name, spec, out, exe, ccx, t_end, reuse=False):
    folder = os.path.join(out, name)
    os.makedirs(folder, exist_ok=True)
    nodes, elements, ids = visco2d_mesh(exe, os.path.join(folder, "visco2d"), spec["level"])
    r, z = pad_mesh_for(nodes, elements, refine_by=spec["pad_refine"])
    near = near_elements(nodes, elements, PEACH["R"], spec.get("near_r", 0.2), spec.get("near_z", 0.45))
    job = "pad"
    inp = os.path.join(folder, job + ".inp")
    old = open(inp).read() if os.path.exists(inp) else None
    info = ccx_deck(inp, nodes, elements, ids, r, z, FOAMS[spec["foam"]], PENALTY * spec["penalty"], t_end,
                    spec["dt"], near)
    same = old == open(inp).read()
    cpu_file = os.path.join(folder, job + ".cpu")
    if reuse and same and os.path.exists(os.path.join(folder, job + ".dat")) and os.path.exists(cpu_file):
        wall, cpu = (float(x) for x in open(cpu_file).read().split())
    else:
        wall, cpu, _ = run_ccx(ccx, folder, job)
        with open(cpu_file, "w") as f:
            f.write(f"{wall:.3f} {cpu:.3f}\n")
    res = ccx_results(folder, job, nodes, elements, ids, info, spec["dt"])
    res.update(cpu_s=cpu, wall_s=wall, penalty_Pa_m=PENALTY * spec["penalty"], nodes_peach=len(nodes),
               elements_peach=len(elements), elements_pad=(len(r) - 1) * (len(z) - 1),
               pad_surface_first_mm=float((r[1] - r[0]) * 1e3), pad_row_first_mm=float((z[0] - z[1]) * 1e3), **spec)
    for ext in (".frd", ".sta", ".cvg"):
        if os.path.exists(os.path.join(folder, job + ext)):
            os.remove(os.path.join(folder, job + ext))
    return res


def fmt(x, spec=".4g"):
    return "-" if x is None or (isinstance(x, float) and math.isnan(x)) else format(x, spec)


REPORT_KEYS = (
    ("alpha_max_mm", "alpha_m: the centre's travel toward the ground (mm)", ".4f"),
    ("t_alpha_max_ms", "t at alpha_m (ms)", ".3f"),
    ("pole_travel_at_alpha_max_mm", "the pole's travel at alpha_m (mm)", ".4f"),
    ("pad_top_uz_at_alpha_max_mm", "the pad's top centre u_z at alpha_m (mm)", ".4f"),
    ("body_approach_at_alpha_max_mm", "the peach's own approach at alpha_m (centre minus pole travel, mm)", ".4f"),
    ("alpha_cm_max_mm", "the centre of mass's largest travel (mm)", ".4f"),
    ("pad_top_uz_min_mm", "the pad's top centre, largest u_z (mm)", ".4f"),
    ("t_pad_top_uz_min_ms", "its time (ms)", ".3f"),
    ("pad_compression_max", "the largest pad compression (top centre u_z / thickness)", ".4f"),
    ("pad_top1_uz_at_alpha_max_mm", "the pad's first surface node off the axis, u_z at alpha_m (mm)", ".4f"),
    ("pad_top1_uz_min_mm", "the same node, largest u_z (mm)", ".4f"),
    ("pad_compression1_max", "the largest pad compression at that node", ".4f"),
    ("ground_force_max_N", "F_m, ground reaction of the pad's bottom (N)", ".2f"),
    ("t_ground_force_max_ms", "its time (ms)", ".3f"),
    ("contact_force_max_N", "the contact force M (dv_cm/dt + g), its peak (N)", ".2f"),
    ("t_contact_force_max_ms", "its time (ms)", ".3f"),
    ("contact_duration_ms", "contact duration: the pole leaves the pad's top centre (ms)", ".3f"),
    ("t_contact_force_zero_ms", "the contact force's return to zero (ms)", ".3f"),
    ("rebound_speed_cm_m_s", "rebound speed, centre of mass, at separation (m/s)", ".4f"),
    ("restitution_cm", "coefficient of restitution (centre of mass)", ".4f"),
    ("rebound_speed_centre_m_s", "rebound speed, centre node, at separation (m/s)", ".4f"),
    ("restitution_centre", "coefficient of restitution (centre node)", ".4f"),
    ("shear_max_MPa", "largest max shear (sigma_1 - sigma_3)/2 in the flesh, apart from the pole element (MPa)", ".4f"),
    ("t_shear_max_ms", "its time (ms)", ".3f"),
    ("shear_max_z_mm", "its undeformed height above the pole (mm)", ".2f"),
    ("shear_max_r_mm", "its undeformed radius (mm)", ".2f"),
    ("shear_at_alpha_MPa", "the same at alpha_m (MPa)", ".4f"),
    ("shear_pole_element_max_MPa", "the pole element's largest max shear (the axis-contact spike, MPa)", ".4f"),
    ("energy_error_max_rel", "largest energy error to separation / first-contact kinetic energy", ".2e"),
    ("pad_energy_at_separation_rel", "energy left in the pad at separation / kinetic energy", ".3g"),
    ("peach_vibration_energy_at_separation_rel", "the peach's vibration energy at separation / kinetic energy", ".3g"),
    ("V_first_contact_m_s", "the speed at first contact (m/s)", ".4f"),
    ("cpu_s", "ccx CPU (s)", ".0f"),
)


def report(results, version):
    names = [n for n in results]
    lines = [f"# CalculiX reference: a peach dropped 0.2 m on a 10 mm hyperfoam pad (ccx {version})\n",
             "| run | level | dt (s) | penalty (Pa/m) | pad refine | foam | peach elements | pad elements |",
             "|---|---:|---:|---:|---:|---|---:|---:|"]
    for n in names:
        r = results[n]
        if "failed" in r:
            lines.append(f"| {n} | failed: {r['failed']} |" + " |" * 6)
            continue
        lines.append(f"| {n} | {r['level']} | {r['dt']:g} | {r['penalty_Pa_m']:.3g} | {r['pad_refine']} | {r['foam']} | "
                     f"{r['elements_peach']} | {r['elements_pad']} |")
    ok = [n for n in names if "failed" not in results[n]]
    lines += ["", "| quantity | " + " | ".join(ok) + " |", "|---|" + "---:|" * len(ok)]
    for key, text, spec in REPORT_KEYS:
        lines.append(f"| {text} | " + " | ".join(fmt(results[n].get(key), spec) for n in ok) + " |")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", nargs="?", default=os.path.join(ROOT, "out", "calculix_foam_pad"))
    ap.add_argument("--runs", default="base,dt_half,penalty_x10,pad_fine", help=f"comma list of {', '.join(RUNS)}")
    ap.add_argument("--t-end", type=float, default=8e-3, help="step 2's length (s): past separation")
    ap.add_argument("--reuse", action="store_true", help="parse a finished earlier run of an identical deck")
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "install", "bin", "visco2d"))
    ap.add_argument("--ccx", default=shutil.which("ccx"))
    args = ap.parse_args()
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    if not args.ccx:
        print("ccx not found (apt-get install -y calculix-ccx): nothing to run")
        return
    version = ccx_version(args.ccx)
    path = os.path.join(out, "results.json")
    results = json.load(open(path)) if os.path.exists(path) else {}
    for name in [n for n in args.runs.split(",") if n]:
        spec = RUNS[name]
        print(f"run {name}: {spec}", flush=True)
        try:
            res = run_one(name, spec, out, args.exe, args.ccx, spec.get("t_end", args.t_end), reuse=args.reuse)
        except (RuntimeError, ValueError, IndexError) as error:
            print(error, flush=True)
            results[name] = {"failed": str(error).splitlines()[0], **spec}
            continue
        write_history(os.path.join(out, name, "history.csv"), res.pop("history"))
        results[name] = res
        print("  " + ", ".join(f"{k} {fmt(res.get(k), s)}" for k, _, s in REPORT_KEYS[:16:3]) + f", cpu {res['cpu_s']:.0f} s",
              flush=True)
        with open(path, "w") as f:
            json.dump(results, f, indent=1)
    finest = [n for n in ("dt_half", "base") if n in results and "failed" not in results[n]]
    if finest:
        shutil.copy(os.path.join(out, finest[0], "history.csv"), os.path.join(out, "history.csv"))
    text = report(results, version)
    with open(os.path.join(out, "report.md"), "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
