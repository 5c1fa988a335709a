#!/usr/bin/env python3
"""A finite-deformation peer reference of the Table 1 impact: CalculiX (ccx) with NLGEOM.

The elastic sphere of the paper's Table 1 (R 0.0366 m, E 18.11 MPa, nu 0.219,
rho 756.85 kg/m^3) dropped on a rigid frictionless plate from several heights,
so that the maximum approach alpha_m spans alpha/R ~ 0.02 to ~ 0.15, in four
models on one mesh (visco2d's MESH SPHERE, read from its results.h5):

  visco2d      visco2d's own small-strain run (Wilson theta 1.4)
  linear       CalculiX, *ELASTIC, no NLGEOM (small strain)
  svk          CalculiX, *ELASTIC with NLGEOM (St Venant-Kirchhoff)
  neohooke     CalculiX, *HYPERELASTIC, NEO HOOKE with NLGEOM, C10 = G/2, D1 = 2/K

Writes the inputs into OUT (default out/calculix_nlgeom/), runs them one at a
time (single-threaded ccx), parses the results and writes OUT/comparison.md,
OUT/results.json and OUT/small_strain_error.csv (doc/calculix_nlgeom.md reads them).

  PYTHONPATH=python python3 scripts/calculix_nlgeom_impact.py [OUT] [--level 2]
  PYTHONPATH=python python3 scripts/calculix_nlgeom_impact.py [OUT] --convergence

--convergence runs the neo-Hookean Table 1 drop at mesh levels 2, 3, 4 and at
level 2 (or --level) with the time step halved, and writes OUT/convergence.md.

Without ccx on PATH (or --ccx) the CalculiX runs are skipped with a message.
Not part of `make test` (tens of minutes).
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

from visco2d import case, hertz  # noqa: E402

sys.path.insert(0, HERE)
from calculix_common import (  # noqa: E402
    SECTOR, ccx_version, contact_cards, dat_blocks, gauss_point_index, gauss_weights, read_mesh, run_ccx,
    run_visco2d, sphere_mesh_cards, volume_mean_weights)

G_ACC = 9.8
#: the paper's Table 1 sphere (inputs/table1_elastic.inp)
TABLE1 = dict(R=0.0366, E=18.11e6, nu=0.219, rho=756.85, V=0.9982)
#: the targets of alpha_m / R (Hertz) besides Table 1's own drop
TARGETS = (0.02, 0.05, 0.08, 0.12, 0.16)
MODELS = ("linear", "svk", "neohooke")
MODEL_TEXT = {"visco2d": "visco2d small strain", "linear": "CalculiX linear (no NLGEOM)",
              "svk": "CalculiX St Venant-Kirchhoff (NLGEOM)", "neohooke": "CalculiX neo-Hookean (NLGEOM)"}


# ---------------------------------------------------------------- material and drops
def neo_hooke_constants(E, nu):
    """(C10, D1) of CalculiX's NEO HOOKE, U = C10 (I1bar - 3) + (J - 1)^2 / D1, with the same initial
    shear and bulk moduli as (E, nu): C10 = G/2, D1 = 2/K, G = E/(2(1 + nu)), K = E/(3(1 - 2 nu))."""
    G = E / (2.0 * (1.0 + nu))
    K = E / (3.0 * (1.0 - 2.0 * nu))
    return G / 2.0, 2.0 / K


def flesh_card(model, E, nu, rho):
    """The *MATERIAL lines of the flesh (name FLESH) in one of MODELS."""
    lines = ["*MATERIAL, NAME=FLESH"]
    if model == "neohooke":
        C10, D1 = neo_hooke_constants(E, nu)
        lines += ["*HYPERELASTIC, NEO HOOKE", f"{C10:.10g}, {D1:.10g}"]
    elif model in ("linear", "svk"):
        lines += ["*ELASTIC", f"{E:.10g}, {nu:.10g}"]
    else:
        raise ValueError(f"unknown model {model!r}: expected one of {', '.join(MODELS)}")
    lines += ["*DENSITY", f"{rho:.10g}"]
    return lines


def sphere_mass(R, rho):
    return rho * 4.0 / 3.0 * math.pi * R ** 3


def speed_for_alpha_ratio(ratio, E, nu, R, M):
    """The impact speed V at which Hertz's alpha_m (eq. [43]) is ratio R: the inverse of
    alpha_m = (15 (1 - nu^2) M V^2 / (16 E sqrt(R)))^0.4."""
    alpha = ratio * R
    return math.sqrt(alpha ** 2.5 * 16.0 * E * math.sqrt(R) / (15.0 * (1.0 - nu ** 2) * M))


def drop_table(p=TABLE1, targets=TARGETS):
    """The drops, sorted by speed: list of dict(name, V, h = V^2/2g, hertz_ratio = Hertz alpha_m / R);
    Table 1's own V and one drop per target ratio."""
    M = sphere_mass(p["R"], p["rho"])
    speeds = [("table1", p["V"])] + [(f"a{int(round(t * 1000)):03d}", speed_for_alpha_ratio(t, p["E"], p["nu"], p["R"], M))
                                     for t in targets]
    rows = []
    for name, V in speeds:
        a = hertz.alpha_max(p["E"], p["nu"], p["R"], M, V)
        rows.append(dict(name=name, V=V, h=V * V / (2 * G_ACC), hertz_ratio=a / p["R"]))
    return sorted(rows, key=lambda r: r["V"])


def neo_hooke_cauchy(C10, D1, stretches):
    """Principal Cauchy stresses of CalculiX's compressible neo-Hookean solid at principal stretches
    (l1, l2, l3): sigma = (2 C10 / J) dev(Bbar) + (2/D1)(J - 1) I, Bbar = J^(-2/3) B."""
    lam = np.asarray(stretches, dtype=float)
    J = float(np.prod(lam))
    bbar = J ** (-2.0 / 3.0) * lam ** 2
    return 2.0 * C10 / J * (bbar - bbar.mean()) + 2.0 / D1 * (J - 1.0)


def uniaxial_deck(path, model, E, nu, h=0.01, strain=-0.3):
    """One CAX4 element, h x h, r free, the top moved by strain h (NLGEOM for svk and neohooke)."""
    nl = ", NLGEOM" if model in ("svk", "neohooke") else ""
    lines = ["*HEADING", f"one CAX4 element, uniaxial {strain:g}, {model}", "*NODE", "1, 0.0, 0.0",
             f"2, {h:.10g}, 0.0", f"3, {h:.10g}, {h:.10g}", f"4, 0.0, {h:.10g}",
             "*ELEMENT, TYPE=CAX4, ELSET=EALL", "1, 1, 2, 3, 4",
             "*NSET, NSET=AXIS", "1, 4", "*NSET, NSET=BOT", "1, 2", "*NSET, NSET=TOP", "3, 4"]
    lines += flesh_card(model, E, nu, 1000.0)
    lines += ["*SOLID SECTION, ELSET=EALL, MATERIAL=FLESH", f"*STEP{nl}, INC=100", "*STATIC", "0.1, 1.0",
              "*BOUNDARY", "AXIS, 1, 1, 0.0", "BOT, 2, 2, 0.0", f"TOP, 2, 2, {strain * h:.10g}",
              "*EL PRINT, ELSET=EALL", "S", "*NODE PRINT, NSET=TOP", "U", "*END STEP", ""]
    with open(path, "w") as f:
        f.write("\n".join(lines))


def uniaxial_check(folder, ccx, p=TABLE1, h=0.01, strain=-0.3):
    """The neo-Hookean card and CalculiX's stress measure: one element compressed 30 %; its axial S
    against the closed-form Cauchy stress at the run's own lateral stretch (and the 2nd Piola-Kirchhoff
    stress, which it must not be)."""
    os.makedirs(folder, exist_ok=True)
    uniaxial_deck(os.path.join(folder, "uniaxial_neohooke.inp"), "neohooke", p["E"], p["nu"], h, strain)
    run_ccx(ccx, folder, "uniaxial_neohooke")
    blocks = dat_blocks(os.path.join(folder, "uniaxial_neohooke.dat"))
    S = np.array([b[2] for b in blocks if b[0].startswith("stresses")][-1])
    U = np.array([b[2] for b in blocks if b[0].startswith("displacements")][-1])
    lt = 1.0 + U[:, 1].max() / h
    la = 1.0 + strain
    C10, D1 = neo_hooke_constants(p["E"], p["nu"])
    cauchy = neo_hooke_cauchy(C10, D1, (lt, la, lt))
    J = la * lt * lt
    return dict(axial_stretch=la, lateral_stretch=lt, ccx_syy_Pa=float(S[:, 3].mean()),
                cauchy_syy_Pa=float(cauchy[1]), pk2_syy_Pa=float(J * cauchy[1] / la ** 2),
                cauchy_lateral_Pa=float(cauchy[0]))


# ---------------------------------------------------------------- visco2d
def visco2d_deck(path, V, level, dt, p=TABLE1):
    """Table 1's deck (inputs/table1_elastic.inp) at speed V, frictionless with release (SLIP RELEASE=YES)
    as the CalculiX contact, to 1.35 Hertz t_m (past the window CalculiX runs, 1.3 visco2d t_m), with
    field snapshots every 2 dt from 0.6 Hertz t_m (for the peak shear over time)."""
    M = sphere_mass(p["R"], p["rho"])
    t_h = hertz.maxima(p["E"], p["nu"], p["R"], M, V)[1]
    t_end = math.ceil(1.35 * t_h / dt) * dt
    times = np.arange(math.ceil(0.6 * t_h / dt), int(round(t_end / dt)), 2) * dt
    fields = ",".join(f"{t:.6g}" for t in times)
    with open(path, "w") as f:
        f.write(f"""TITLE Table 1 sphere, V = {V:.6g} m/s, frictionless, to maximum deformation (CalculiX NLGEOM check)
ANALYSIS DYNAMIC
GEOMETRY AXISYMMETRIC
MATERIAL apple ELASTIC E={p['E']:g} NU={p['nu']:g} RHO={p['rho']:g}
MESH SPHERE R={p['R']:g} LEVEL={level}
INITIAL VZ={-V:.10g} AZ={-G_ACC:g}
GRAVITY G={G_ACC:g}
WILSON THETA=1.4
TIME DT={dt:g} TEND={t_end:.6g}
PLATE Z=0 SLIP RELEASE=YES
OUTPUT EVERY=1 FIELDS={fields}
END
""")


def max_shear_2d(sig):
    """(sigma_1 - sigma_3)/2 of axisymmetric stresses (..., 4) = (sigma_r, sigma_z, sigma_theta, tau_rz)."""
    sr, sz, st, trz = sig[..., 0], sig[..., 1], sig[..., 2], sig[..., 3]
    c, d = 0.5 * (sr + sz), np.sqrt((0.5 * (sr - sz)) ** 2 + trz ** 2)
    p1, p2 = c + d, c - d
    hi = np.maximum(np.maximum(p1, p2), st)
    lo = np.minimum(np.minimum(p1, p2), st)
    return 0.5 * (hi - lo)


#: gauss_weights' point (k = i + 2 j) of visco2d's Gauss point 1..4 (counter-clockwise: (-,-), (+,-), (+,+), (-,+))
VISCO2D_POINT = (0, 1, 3, 2)


def largest_strain(sig, E, nu):
    """The largest principal-strain magnitude of axisymmetric elastic stresses (..., 4), as visco2d's
    small-strain warning measures it (visco2d_advice largest_strain): the strain from Hooke's law
    inverted, e = ((1 + nu) s - nu tr(s) I)/E, gamma_rz = 2 (1 + nu) tau_rz / E."""
    tr = sig[..., 0] + sig[..., 1] + sig[..., 2]
    er, ez, et = (((1 + nu) * sig[..., i] - nu * tr) / E for i in range(3))
    gamma = 2 * (1 + nu) * sig[..., 3] / E
    c, r = 0.5 * (er + ez), np.hypot(0.5 * (er - ez), 0.5 * gamma)
    return float(np.max(np.maximum(np.abs(c) + r, np.abs(et))))


def visco2d_results(vcase, R, p=TABLE1):
    """visco2d's impact maxima and its Gauss-point peak shear (the same recovery as CalculiX's below)."""
    import h5py
    s = case.read_typed_summary(vcase)
    nodes, elements, _ = read_mesh(vcase)
    _, xy, _ = gauss_weights(nodes, elements)
    best, at_alpha, strain = None, None, 0.0
    t_m = s["t_alpha_max_ms"] * 1e-3
    with h5py.File(os.path.join(vcase, "results.h5"), "r") as f:
        for name in f["fields"]:
            g = f["fields"][name]
            t = float(g.attrs.get("time_from_contact", -1.0))
            if t <= 0:
                continue
            sig = g["stress_gauss"][...]
            tau = max_shear_2d(sig)
            e, k = np.unravel_index(int(np.argmax(tau)), tau.shape)
            item = (float(tau[e, k]), t, xy[e, VISCO2D_POINT[k]], largest_strain(sig, p["E"], p["nu"]))
            if best is None or item[0] > best[0]:
                best = item
            if at_alpha is None or abs(t - t_m) < abs(at_alpha[1] - t_m):
                at_alpha = item
            strain = max(strain, item[3])
    res = dict(alpha_max_mm=s["alpha_max_mm"], t_alpha_max_ms=s["t_alpha_max_ms"], force_max_N=s["force_max_N"],
               contact_radius_mm=s["contact_radius_max_mm"], max_shear_nodal_MPa=s["max_shear_max_Pa"] / 1e6,
               hertz_alpha_max_mm=s["hertz_alpha_max_mm"], hertz_force_max_N=s["hertz_force_max_N"],
               hertz_contact_radius_mm=s["hertz_contact_radius_mm"], hertz_q_max_MPa=s["hertz_q_max_MPa"],
               mass_kg=s["mass_kg"], cpu_s=float(s["cpu_s"]))
    if best is not None:
        res.update(shear_max_MPa=best[0] / 1e6, t_shear_max_ms=best[1] * 1e3,
                   shear_depth_mm=best[2][1] * 1e3, shear_r_mm=best[2][0] * 1e3,
                   shear_at_alpha_MPa=at_alpha[0] / 1e6, shear_at_alpha_depth_mm=at_alpha[2][1] * 1e3,
                   t_snapshot_at_alpha_ms=at_alpha[1] * 1e3, strain_at_alpha=at_alpha[3], strain_max=strain)
    res["alpha_over_R"] = res["alpha_max_mm"] * 1e-3 / R
    return res


# ---------------------------------------------------------------- CalculiX
def near_elements(nodes, elements, R, r_cut=0.6, z_cut=0.45):
    """Indices (from 0) of the elements with every node at r < r_cut R and z < z_cut R: where the
    subsurface shear peaks (Hertz: on the axis at 0.48 a, a <= 0.4 R here)."""
    X = nodes[elements]
    keep = (X[:, :, 0].max(axis=1) < r_cut * R) & (X[:, :, 1].max(axis=1) < z_cut * R)
    return np.nonzero(keep)[0]


def free_fall_times(h, dt):
    """(t_f, t1): the free fall of h under g ends at t_f; CalculiX's first step ends at t1 = t_f - 2 dt."""
    t_f = math.sqrt(2 * h / G_ACC)
    return t_f, t_f - 2 * dt


def ccx_deck(path, model, nodes, elements, ids, h, penalty, sigma_inf, t_end, dt, near, p=TABLE1, stress_every=1):
    """The CalculiX deck: visco2d's mesh lifted by h, falling from rest under gravity (step 1, 100
    increments, to 2 dt before contact; the *INITIAL CONDITIONS velocity does not move expanded CAX4
    nodes in ccx 2.20, doc/calculix_plastic.md), then the impact at the fixed dt (step 2) to t_end after
    step 1, printing U of the sphere, RF of the plate, and S in the elements `near` the contact.
    stress_every > 1 thins every print of step 2, not only S (ccx 2.20 applies an *EL PRINT's
    FREQUENCY to the *NODE PRINT too): ccx_results then cannot find first contact."""
    _, t1 = free_fall_times(h, dt)
    nl = ", NLGEOM" if model in ("svk", "neohooke") else ""
    lines = ["*HEADING", f"Table 1 sphere, {model}, drop {h:.6g} m, visco2d's mesh"]
    mesh, nslave = sphere_mesh_cards(nodes, elements, ids, h, 0.4 * p["R"])
    lines += mesh
    lines.append("*ELSET, ELSET=ENEAR")
    near = [int(e) + 1 for e in near]
    lines += [", ".join(str(e) for e in near[i:i + 10]) for i in range(0, len(near), 10)]
    lines += flesh_card(model, p["E"], p["nu"], p["rho"])
    lines += ["*MATERIAL, NAME=PLATE", "*ELASTIC", f"{1000 * p['E']:.10g}, 0.3", "*DENSITY", f"{p['rho']:.10g}",
              "*SOLID SECTION, ELSET=ESPHERE, MATERIAL=FLESH",
              "*SOLID SECTION, ELSET=EPLATE, MATERIAL=PLATE"]
    lines += contact_cards(penalty, sigma_inf)
    lines += ["*BOUNDARY", "AXIS, 1, 1, 0.0", "NPLATE, 1, 3, 0.0",
              f"*STEP{nl}, INC=1000000", "*DYNAMIC, DIRECT", f"{t1 / 100:.15g}, {t1:.15g}",
              "*DLOAD", f"ESPHERE, GRAV, {G_ACC:g}, 0., -1., 0.",
              "*EL PRINT, ELSET=ESPHERE, TOTALS=ONLY, FREQUENCY=100", "ELSE, ELKE",
              "*END STEP",
              f"*STEP{nl}, INC=1000000", "*DYNAMIC, DIRECT", f"{dt:.10g}, {t_end:.10g}",
              "*NODE PRINT, NSET=NSPHERE, FREQUENCY=1", "U",
              "*NODE PRINT, NSET=NPLATE, TOTALS=ONLY", "RF",
              f"*EL PRINT, ELSET=ENEAR, FREQUENCY={stress_every}", "S",
              "*END STEP", ""]
    with open(path, "w") as f:
        f.write("\n".join(lines))
    return nslave


def parabola_vertex(t, y):
    """The vertex of the parabola through the largest sample and its neighbours (visco2d's alpha_m)."""
    k = int(np.argmax(y))
    if k == 0 or k == len(y) - 1:
        return float(y[k]), float(t[k])
    A = np.array([[t[k + i] ** 2, t[k + i], 1.0] for i in (-1, 0, 1)])
    a, b, c = np.linalg.solve(A, y[k - 1:k + 2])
    return float(c - b * b / (4 * a)), float(-b / (2 * a))


def max_shear_3d(S):
    """(sigma_1 - sigma_3)/2 of rows (sxx, syy, szz, sxy, sxz, syz), the column order of ccx's .dat."""
    S = np.asarray(S, dtype=float)
    T = np.empty((len(S), 3, 3))
    T[:, 0, 0], T[:, 1, 1], T[:, 2, 2] = S[:, 0], S[:, 1], S[:, 2]
    T[:, 0, 1] = T[:, 1, 0] = S[:, 3]
    T[:, 0, 2] = T[:, 2, 0] = S[:, 4]
    T[:, 1, 2] = T[:, 2, 1] = S[:, 5]
    ev = np.linalg.eigvalsh(T)
    return 0.5 * (ev[:, 2] - ev[:, 0])


def contact_radius(r_def, y_def):
    """The radius where the deformed slave boundary leaves the plate y = 0: the zero of y, linear between
    the outermost node at y < 0 and the next node outward (nodes sorted by their undeformed radius)."""
    inside = np.nonzero(y_def < 0)[0]
    if len(inside) == 0:
        return 0.0
    j = int(inside.max())
    if j == len(r_def) - 1:
        return float(r_def[j])
    s = y_def[j] / (y_def[j] - y_def[j + 1])
    return float(r_def[j] + s * (r_def[j + 1] - r_def[j]))


def ccx_results(folder, job, nodes, elements, ids, h, dt, slave):
    """The impact maxima of a CalculiX run on visco2d's definitions (whole body)."""
    w, xy, shape = gauss_weights(nodes, elements)
    c = volume_mean_weights(nodes, elements, w, shape)
    index = {int(n): i for i, n in enumerate(ids)}
    _, t1 = free_fall_times(h, dt)
    blocks = dat_blocks(os.path.join(folder, job + ".dat"))

    def step_of(t):
        return int(round((t - t1) / dt))

    disp = {step_of(b[1]): b[2] for b in blocks if b[0].startswith("displacements") and b[0].endswith("NSPHERE")}
    frc = {step_of(b[1]): b[2][0] for b in blocks if b[0].endswith("NPLATE") and b[2]}
    stress = {step_of(b[1]): b[2] for b in blocks if b[0].startswith("stresses")}
    ks = sorted(k for k in disp if k >= 1)
    pole = int(np.argmin(np.hypot(nodes[:, 0], nodes[:, 1])))
    order = np.array(sorted(slave, key=lambda i: nodes[i, 0]))
    uz, upole, force, radius, U_all = [], [], [], [], {}
    for k in ks:
        rows = np.array(disp[k])
        u = np.zeros((len(nodes), 2))
        u[np.array([index[int(n)] for n in rows[:, 0]])] = rows[:, 1:3]
        U_all[k] = u
        uz.append(c @ u[:, 1])
        upole.append(u[pole, 1])
        force.append(frc.get(k, [0, 0, 0])[1])
        radius.append(contact_radius(nodes[order, 0] + u[order, 0], nodes[order, 1] + h + u[order, 1]))
    t_abs = t1 + np.array(ks) * dt
    uz, upole, radius = np.array(uz), np.array(upole), np.array(radius)
    vz = np.gradient(uz, t_abs)
    zp = h + upole
    j = int(np.nonzero(zp <= 0)[0][0])
    if j == 0:
        raise ValueError(f"{job}.dat: the pole is already on the plate at the first printed increment "
                         "(U must be printed at every increment from 2 dt before contact)")
    s_ = zp[j - 1] / (zp[j - 1] - zp[j])
    t_c = t_abs[j - 1] + s_ * dt
    uz_c = uz[j - 1] + s_ * (uz[j] - uz[j - 1])
    v0 = -(vz[j - 1] + s_ * (vz[j] - vz[j - 1]))
    t = t_abs - t_c
    alpha = uz_c - uz
    F = np.array(force) * SECTOR
    alpha_m, t_m = parabola_vertex(t, alpha)
    k_alpha = ks[int(np.argmin(np.abs(t - t_m)))]
    res = dict(alpha_max_mm=alpha_m * 1e3, t_alpha_max_ms=t_m * 1e3, force_max_N=float(F.max()),
               t_force_max_ms=float(t[int(np.argmax(F))] * 1e3), contact_radius_mm=float(radius[ks.index(k_alpha)] * 1e3),
               impact_velocity_m_s=float(v0), steps=len(ks), t_end_ms=float(t[-1] * 1e3),
               alpha_reached_end=bool(int(np.argmax(alpha)) == len(alpha) - 1))
    # the Gauss-point max shear (Cauchy stress with NLGEOM) in ENEAR at every printed increment
    best, at_alpha = None, None
    if stress:
        # the printed increment nearest alpha_m (S may be printed every few increments)
        k_alpha = min(stress, key=lambda k: abs(t1 + k * dt - t_c - t_m))
    for k in sorted(stress):
        S = np.array(stress[k])
        e, k2 = gauss_point_index(S)
        tau = max_shear_3d(S[:, 2:8])
        i = int(np.argmax(tau))
        item = (float(tau[i]), k, int(e[i]), int(k2[i]))
        if best is None or item[0] > best[0]:
            best = item
        if k == k_alpha:
            at_alpha = item
    if best is not None:
        res["shear_max_MPa"] = best[0] / 1e6
        res["t_shear_max_ms"] = float((t1 + best[1] * dt - t_c) * 1e3)
        res["shear_depth_mm"] = float(xy[best[2], best[3], 1] * 1e3)
        res["shear_r_mm"] = float(xy[best[2], best[3], 0] * 1e3)
        if best[1] in U_all:
            # the depth in the deformed body: the point's height above the plate
            u = U_all[best[1]][elements[best[2]], 1] @ shape[best[3]]
            res["shear_depth_deformed_mm"] = float((xy[best[2], best[3], 1] + h + u) * 1e3)
    if at_alpha is not None:
        res["shear_at_alpha_MPa"] = at_alpha[0] / 1e6
        res["shear_at_alpha_depth_mm"] = float(xy[at_alpha[2], at_alpha[3], 1] * 1e3)
    res["history"] = dict(t=t.tolist(), alpha=alpha.tolist(), F=F.tolist(), radius=radius.tolist())
    return res


# ---------------------------------------------------------------- one drop
def run_or_reuse(ccx, folder, job, reuse):
    """run_ccx, or with reuse a finished earlier run of the identical deck (its .dat and a log that
    ends with ccx's total time): (wall s, CPU s; the earlier run's from its .cpu file, else its log's
    total time)."""
    log = os.path.join(folder, job + ".log")
    if reuse and os.path.exists(os.path.join(folder, job + ".dat")) and os.path.exists(log):
        text = open(log).read()
        if "*ERROR" in text:
            # the earlier run of this deck failed: the same failure, not a second attempt
            tail = "\n".join(text.splitlines()[-15:])
            raise RuntimeError(f"ccx failed on {folder}/{job}.inp (an earlier run, reused):\n{tail}")
        if "Total CalculiX Time" in text:
            side = os.path.join(folder, job + ".cpu")
            if os.path.exists(side):
                wall, cpu = (float(x) for x in open(side).read().split())
                return wall, cpu
            total = float(text.split("Total CalculiX Time:")[1].split()[0])
            return total, total
    wall, cpu, _ = run_ccx(ccx, folder, job)
    with open(os.path.join(folder, job + ".cpu"), "w") as f:
        f.write(f"{wall:.3f} {cpu:.3f}\n")
    return wall, cpu


def run_drop(folder, exe, ccx, drop, level, dt, models, p=TABLE1, stress_every=1, reuse=False, near_cut=(0.6, 0.45),
             t_end_factor=1.3):
    """visco2d and the CalculiX models of one drop: {model: results}."""
    os.makedirs(folder, exist_ok=True)
    deck = os.path.join(folder, f"v_{drop['name']}.inp")
    visco2d_deck(deck, drop["V"], level, dt, p)
    vcase, _ = run_visco2d(exe, deck, folder)
    out = {"visco2d": visco2d_results(vcase, p["R"], p)}
    v = out["visco2d"]
    print(f"  visco2d: alpha_m {v['alpha_max_mm']:.4f} mm ({v['alpha_over_R']:.4f} R), F_m {v['force_max_N']:.2f} N, "
          f"tau {v.get('shear_max_MPa', float('nan')):.4f} MPa", flush=True)
    if not ccx:
        return out
    nodes, elements, ids = read_mesh(vcase)
    from calculix_common import slave_nodes
    slave = slave_nodes(nodes, elements, 0.4 * p["R"])
    near = near_elements(nodes, elements, p["R"], *near_cut)
    p0, aH = v["hertz_q_max_MPa"] * 1e6, v["hertz_alpha_max_mm"] * 1e-3
    penalty, sigma_inf = p0 / (1e-3 * aH), 0.0025 * p0
    # step 2 ends well after visco2d's maximum (St Venant-Kirchhoff is softer: later)
    t_end = math.ceil((t_end_factor * v["t_alpha_max_ms"] * 1e-3 + 4 * dt) / dt) * dt
    for model in models:
        job = f"ccx_{drop['name']}_{model}"
        inp = os.path.join(folder, job + ".inp")
        old = open(inp).read() if os.path.exists(inp) else None
        ccx_deck(inp, model, nodes, elements, ids, drop["h"], penalty, sigma_inf, t_end, dt, near, p, stress_every)
        reuse_this = reuse and old == open(inp).read()
        try:
            wall, cpu = run_or_reuse(ccx, folder, job, reuse_this)
        except RuntimeError as error:
            print(error, flush=True)
            out[model] = {"failed": str(error).splitlines()[0]}
            continue
        r = ccx_results(folder, job, nodes, elements, ids, drop["h"], dt, slave)
        r.update(cpu_s=cpu, wall_s=wall, penalty_Pa_m=penalty)
        r["alpha_over_R"] = r["alpha_max_mm"] * 1e-3 / p["R"]
        out[model] = r
        print(f"  {model}: alpha_m {r['alpha_max_mm']:.4f} mm, F_m {r['force_max_N']:.2f} N, a {r['contact_radius_mm']:.3f} mm, "
              f"tau {r.get('shear_max_MPa', float('nan')):.4f} MPa at {r.get('shear_depth_mm', float('nan')):.2f} mm, "
              f"cpu {cpu:.1f} s", flush=True)
        for f_ in (".dat", ".frd", ".sta", ".cvg"):
            # the .dat is parsed; the rest are not read (and the .frd is large)
            if f_ != ".dat" and os.path.exists(os.path.join(folder, job + f_)):
                os.remove(os.path.join(folder, job + f_))
    return out


# ---------------------------------------------------------------- tables
def relative(a, b):
    """(a - b)/|b| or None."""
    if a is None or b is None or b == 0:
        return None
    return (a - b) / abs(b)


ERROR_KEYS = (("alpha_max_mm", "alpha_m"), ("force_max_N", "F_m"), ("shear_at_alpha_MPa", "tau_alpha"),
              ("shear_max_MPa", "tau_max"))


def error_rows(results, reference="neohooke", compared=("visco2d", "linear", "svk")):
    """One row per drop: alpha_over_R (of the reference) and the relative error of each compared model
    against the reference in each of ERROR_KEYS (keys '<model>_<quantity>')."""
    rows = []
    for name, res in results:
        ref = res.get(reference)
        if not ref or "failed" in ref:
            continue
        row = dict(drop=name, alpha_over_R=ref["alpha_over_R"], strain_max=res.get("visco2d", {}).get("strain_at_alpha"))
        for m in compared:
            for key, short in ERROR_KEYS:
                row[f"{m}_{short}"] = relative(res.get(m, {}).get(key), ref.get(key))
        rows.append(row)
    return rows


def write_error_csv(path, rows, compared=("visco2d", "linear", "svk")):
    cols = ["alpha_over_R", "strain_max"] + [f"{m}_{s}" for m in compared for _, s in ERROR_KEYS]
    with open(path, "w") as f:
        f.write(",".join(cols) + "\n")
        for r in rows:
            f.write(",".join("" if r.get(c) is None else f"{r[c]:.5g}" for c in cols) + "\n")
    return cols


def f4(x, spec=".4g"):
    return "-" if x is None or (isinstance(x, float) and math.isnan(x)) else format(x, spec)


def pct(x):
    return "-" if x is None else f"{100 * x:+.2f} %"


QUANT = [("alpha_max_mm", "alpha_m (mm)"), ("t_alpha_max_ms", "t at alpha_m (ms)"), ("force_max_N", "F_m (N)"),
         ("contact_radius_mm", "contact radius at alpha_m (mm)"), ("shear_at_alpha_MPa", "max shear at alpha_m (MPa)"),
         ("shear_max_MPa", "max shear, over time (MPa)"), ("shear_depth_mm", "its depth, undeformed (mm)"),
         ("shear_depth_deformed_mm", "its height above the plate, deformed (mm)"),
         ("strain_at_alpha", "largest principal strain at alpha_m (visco2d's warning measure)"),
         ("strain_max", "largest principal strain, over time"), ("cpu_s", "CPU (s)")]


def hertz_shear_peak(nu, q0, a):
    """(largest (sigma_z - sigma_r)/2 on the axis under Hertz's pressure, its depth): hertz.subsurface_shear
    sampled at depths 0.001 a .. 2 a (every 0.001 a)."""
    depths = np.arange(1, 2001) * 1e-3 * a
    tau = hertz.subsurface_shear(nu, q0, a, depths)
    i = int(np.argmax(tau))
    return float(tau[i]), float(depths[i])


def drop_report(drop, res, level):
    names = ["visco2d"] + [m for m in MODELS if m in res]
    v = res["visco2d"]
    tau_h, z_h = hertz_shear_peak(TABLE1["nu"], v["hertz_q_max_MPa"] * 1e6, v["hertz_contact_radius_mm"] * 1e-3)
    lines = [f"### {drop['name']}: V = {drop['V']:.4f} m/s (h = {drop['h']:.4g} m), Hertz alpha_m/R = {drop['hertz_ratio']:.4f}\n",
             f"Hertz (eqs. [43]-[45], the mesh's mass): alpha_m {v['hertz_alpha_max_mm']:.4f} mm, F_m {v['hertz_force_max_N']:.2f} N, "
             f"a {v['hertz_contact_radius_mm']:.3f} mm, q_m {v['hertz_q_max_MPa']:.4f} MPa; its largest subsurface shear "
             f"(sigma_z - sigma_r)/2 on the axis {tau_h / 1e6:.4f} MPa at depth {z_h * 1e3:.3f} mm. Mesh level {level}; visco2d's "
             f"shear is the largest over its field snapshots after contact (at and just after alpha_m).\n",
             "| quantity | " + " | ".join(MODEL_TEXT[n] for n in names) + " |",
             "|---|" + "---:|" * len(names)]
    for key, text in QUANT:
        lines.append(f"| {text} | " + " | ".join(f4(res[n].get(key)) if "failed" not in res[n] else "failed" for n in names) + " |")
    lines.append("")
    return lines


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", nargs="?", default=os.path.join(ROOT, "out", "calculix_nlgeom"))
    ap.add_argument("--level", type=int, default=2, help="MESH SPHERE LEVEL of the error table (default 2)")
    ap.add_argument("--dt", type=float, default=1e-5, help="time step of both codes (s)")
    ap.add_argument("--convergence", action="store_true", help="the neo-Hookean Table 1 drop at levels 2, 3, 4 and dt/2")
    ap.add_argument("--levels", default="2,3,4", help="levels of --convergence")
    ap.add_argument("--drops", default="", help="comma list of drop names to run (default all)")
    ap.add_argument("--models", default=",".join(MODELS))
    ap.add_argument("--reuse", action="store_true", help="parse a finished earlier ccx run of an identical deck instead of rerunning it")
    ap.add_argument("--no-halving", action="store_true", help="--convergence without the dt/2 run")
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "install", "bin", "visco2d"))
    ap.add_argument("--ccx", default=shutil.which("ccx"))
    args = ap.parse_args()
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    ccx = args.ccx
    if not ccx:
        print("ccx not found (apt-get install -y calculix-ccx): the CalculiX runs are skipped")
    models = [m for m in args.models.split(",") if m]
    drops = drop_table()
    version = ccx_version(ccx) if ccx else "-"
    if args.convergence:
        table1 = [d for d in drops if d["name"] == "table1"][0]
        runs = [(f"level {lv}, dt {args.dt:g}", int(lv), args.dt) for lv in args.levels.split(",")]
        if not args.no_halving:
            runs.append((f"level {args.level}, dt {args.dt / 2:g}", args.level, args.dt / 2))
        conv = []
        for label, lv, dt in runs:
            print(f"convergence: {label}", flush=True)
            folder = os.path.join(out, "convergence", f"L{lv}_dt{dt:g}")
            # level 4: S in a smaller region (r < 0.3 R, z < 0.2 R: the peak is at 0.09 R depth, 0.02 R
            # from the axis) and to 1.1 t_m, not 1.3 (the .dat of level 3 with S in r < 0.6 R, z < 0.45 R
            # is 190 MB); a FREQUENCY on *EL PRINT would apply to the U of *NODE PRINT too (ccx 2.20)
            fine = lv >= 4
            conv.append((label, run_drop(folder, args.exe, ccx, table1, lv, dt, ["neohooke"], reuse=args.reuse,
                                         near_cut=(0.3, 0.2) if fine else (0.6, 0.45), t_end_factor=1.1 if fine else 1.3)))
        with open(os.path.join(out, "convergence.json"), "w") as f:
            json.dump([(l, {m: {k: x for k, x in r.items() if k != "history"} for m, r in res.items()}) for l, res in conv],
                      f, indent=1)
        lines = [f"# Convergence of the neo-Hookean NLGEOM Table 1 drop (ccx {version})\n",
                 "| run | alpha_m (mm) | t at alpha_m (ms) | F_m (N) | a at alpha_m (mm) | max shear at alpha_m (MPa) | "
                 "its depth (mm) | max shear over time (MPa) | visco2d alpha_m (mm) | visco2d F_m (N) | "
                 "visco2d shear at alpha_m (MPa) | ccx CPU (s) |",
                 "|---|" + "---:|" * 11]
        for label, res in conv:
            r, v = res.get("neohooke", {}), res["visco2d"]
            if "failed" in r:
                lines.append(f"| {label} | failed: {r['failed']} |" + " |" * 10)
                continue
            lines.append(f"| {label} | " + " | ".join(f4(r.get(k), s) for k, s in (
                ("alpha_max_mm", ".5g"), ("t_alpha_max_ms", ".4g"), ("force_max_N", ".5g"), ("contact_radius_mm", ".4g"),
                ("shear_at_alpha_MPa", ".4g"), ("shear_at_alpha_depth_mm", ".3g"), ("shear_max_MPa", ".4g"))) + " | " +
                " | ".join(f4(v.get(k), s) for k, s in (("alpha_max_mm", ".5g"), ("force_max_N", ".5g"),
                                                        ("shear_at_alpha_MPa", ".4g")))
                + f" | {f4(r.get('cpu_s'), '.1f')} |")
        text = "\n".join(lines) + "\n"
        with open(os.path.join(out, "convergence.md"), "w") as f:
            f.write(text)
        print(text)
        return
    wanted = set(d for d in args.drops.split(",") if d)
    results = []
    for drop in drops:
        if wanted and drop["name"] not in wanted:
            continue
        print(f"drop {drop['name']}: V {drop['V']:.4f} m/s, h {drop['h']:.4g} m, Hertz alpha/R {drop['hertz_ratio']:.4f}", flush=True)
        results.append((drop["name"], run_drop(os.path.join(out, drop["name"]), args.exe, ccx, drop, args.level, args.dt, models,
                                               reuse=args.reuse)))
        with open(os.path.join(out, "results.json"), "w") as f:
            json.dump([(n, {m: {k: x for k, x in r.items() if k != "history"} for m, r in res.items()}) for n, res in results],
                      f, indent=1)
    report = [f"# CalculiX NLGEOM peer reference of the Table 1 impact (ccx {version}, mesh level {args.level}, dt {args.dt:g} s)\n"]
    if ccx:
        u = uniaxial_check(os.path.join(out, "uniaxial"), ccx)
        C10, D1 = neo_hooke_constants(TABLE1["E"], TABLE1["nu"])
        report.append(f"Neo-Hookean card check (one CAX4 element, NLGEOM, axial stretch {u['axial_stretch']:.3g}, lateral "
                      f"{u['lateral_stretch']:.6g} from the run; C10 = {C10:.7g} Pa, D1 = {D1:.7g} 1/Pa): ccx S_yy "
                      f"{u['ccx_syy_Pa']:.7g} Pa, closed-form Cauchy {u['cauchy_syy_Pa']:.7g} Pa "
                      f"({relative(u['ccx_syy_Pa'], u['cauchy_syy_Pa']):+.1e}), 2nd Piola-Kirchhoff {u['pk2_syy_Pa']:.7g} Pa: "
                      f"ccx prints the Cauchy stress.\n")
        with open(os.path.join(out, "uniaxial.json"), "w") as f:
            json.dump(u, f, indent=1, default=float)
    report.append("| drop | V (m/s) | h (m) | Hertz alpha_m/R |")
    report.append("|---|---:|---:|---:|")
    report += [f"| {d['name']} | {d['V']:.4f} | {d['h']:.4g} | {d['hertz_ratio']:.4f} |" for d in drops]
    report.append("")
    for name, res in results:
        report += drop_report([d for d in drops if d["name"] == name][0], res, args.level)
    rows = error_rows(results)
    if rows:
        report.append("## Relative error against CalculiX neo-Hookean NLGEOM\n")
        head = "| alpha_m/R | visco2d largest strain |"
        for m in ("visco2d", "linear", "SVK"):
            head += f" {m} alpha_m | {m} F_m | {m} shear at alpha_m | {m} shear over time |"
        report.append(head)
        report.append("|---:|" + "---:|" * 13)
        for r in rows:
            report.append(f"| {r['alpha_over_R']:.4f} | {f4(r['strain_max'], '.3f')} | " + " | ".join(
                pct(r[f"{m}_{s}"]) for m in ("visco2d", "linear", "svk") for _, s in ERROR_KEYS) + " |")
        write_error_csv(os.path.join(out, "small_strain_error.csv"), rows)
    text = "\n".join(report) + "\n"
    with open(os.path.join(out, "comparison.md"), "w") as f:
        f.write(text)
    print(text)
    print(f"written {os.path.join(out, 'comparison.md')}")


if __name__ == "__main__":
    main()
