#!/usr/bin/env python3
"""Peer-code check of visco2d's static plastic indentation on the plate against CalculiX (ccx).

A sphere (R 0.03 m, E 4 MPa, nu 0.32, rho 845, the sphere of the dynamic check) pressed onto the
rigid frictionless plate by its own weight under GRAVITY G=2000 (191 N), the load of
test_plastic_static's on_the_plate deck, followed in N equal load increments; flesh elastic and
elastic-plastic (bilinear isotropic hardening, Et 0.4 MPa, Y 0.3 MPa and optionally others).
Both codes use visco2d's own mesh (read from its results.h5); CalculiX has CAX4 elements,
node-to-surface penalty contact against a fixed C3D8 plate and *STATIC with *TIME POINTS at
every k/N (the modules of scripts/calculix_common.py, shared with
scripts/calculix_plastic_impact.py). visco2d's path point k is the run to k/N of the load in k
increments (the increments of the N-increment run, exactly).

  PYTHONPATH=python python3 scripts/calculix_plastic_static.py [OUT] [--level 3] [--increments 20]
      [--yields 0.3e6,0.1e6] [--penalty-factors 1,10] [--dry-run]

Writes the decks into OUT (default out/calculix_plastic_static/), runs both codes, and writes
OUT/comparison.md (doc/calculix_plastic_static.md reads it). --dry-run writes the inputs (it runs
visco2d, which takes seconds, for the mesh and the checkpoints) and no CalculiX job. Without ccx
on PATH (or --ccx) the CalculiX runs are skipped with a message. Not part of `make test`.
"""
import argparse
import math
import os
import shutil
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, ".."))
sys.path.insert(0, os.path.join(ROOT, "python"))
sys.path.insert(0, HERE)

from visco2d import case  # noqa: E402
from calculix_common import (  # noqa: E402
    SECTOR, ccx_version, contact_cards, dat_blocks, fmt, gauss_point_index, gauss_weights, hardening_modulus,
    gauss_field, material_cards, node_average, peeq_field, plastic_work, read_mesh, rel, run_ccx, run_visco2d, slave_nodes,
    sphere_mesh_cards, stored_energy, volume_mean_weights)

SPHERE = dict(R=0.03, E=4.0e6, nu=0.32, rho=845.0, Et=0.4e6, G=2000.0)
SLAVE_Z = 0.4   # the slave surface: boundary edges below 0.4 R (as the dynamic check)


# ---------------------------------------------------------------- Hertz
def hertz(F, R, E, nu):
    """Hertz's sphere on a rigid plane under a force F (Johnson, Contact Mechanics, 1985, eqs. 4.22-4.23):
    the contact radius a = (3 F R / 4 E*)^(1/3), E* = E/(1 - nu^2), the largest pressure
    p0 = 3 F / (2 pi a^2) and the approach of distant points delta = a^2 / R."""
    Es = E / (1 - nu ** 2)
    a = (3 * F * R / (4 * Es)) ** (1.0 / 3.0)
    return dict(a=a, p0=3 * F / (2 * math.pi * a ** 2), delta=a * a / R)


# ---------------------------------------------------------------- visco2d
def visco2d_deck(path, level, Y, fraction, increments, formulation):
    """visco2d's static deck on the plate at `fraction` of GRAVITY G: test_plastic_static's on_the_plate
    deck (frictionless PLATE Z=0 SLIP, GRAVITY), in `increments` load increments when plastic."""
    p = SPHERE
    # the elastic flesh through the plastic solver with a yield stress it never reaches: the same
    # increments, so its external_work_J is the path's trapezoidal work as CalculiX's (the exact
    # elastic path ends on the same contact set and values to 1e-9, test_plastic_static)
    analysis = f"ANALYSIS STATIC INCREMENTS={increments}"
    lines = [f"TITLE sphere R {p['R']:g} m on the plate, {'Y ' + format(Y, 'g') + ' Pa' if Y else 'elastic'}, "
             f"G {p['G'] * fraction:.10g} (CalculiX check)",
             analysis, "GEOMETRY AXISYMMETRIC", f"FORMULATION {formulation}",
             f"MATERIAL flesh ELASTIC E={p['E']:g} NU={p['nu']:g} RHO={p['rho']:g}"]
    lines.append(f"PLASTIC YIELD={Y:g} TANGENT={p['Et']:g}" if Y else "PLASTIC YIELD=1e12 TANGENT=0")
    lines += [f"MESH SPHERE R={p['R']:g} LEVEL={level}", "PLATE Z=0 SLIP", f"GRAVITY G={p['G'] * fraction:.12g}", "END"]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def visco2d_path(exe, folder, level, Y, increments, checkpoints, formulation="STANDARD"):
    """visco2d's summary at each checkpoint k (load k/N), from the run to k/N in k increments."""
    out = []
    for k in checkpoints:
        tag = "elastic" if not Y else f"Y{Y:g}"
        deck = os.path.join(folder, f"v_{tag}_{formulation.lower()}_{k:02d}of{increments}.inp")
        visco2d_deck(deck, level, Y, k / increments, k, formulation)
        vcase, wall = run_visco2d(exe, deck, folder)
        s = case.read_typed_summary(vcase)
        s["wall_s"] = wall
        s["case"] = vcase
        out.append(s)
    return out


def weight_work(rows, N):
    """Add weight_work_J to each path point: the trapezoidal work of the weight (force_N at load k/N)
    along the centroid's approach, sum 1/2 (F_(k-1) + F_k)(alpha_k - alpha_(k-1)), the definition used
    for CalculiX (visco2d's external_work_J also books the plate reactions' trapezoidal work)."""
    work, a0, f0 = 0.0, 0.0, 0.0
    for s in rows:
        work += 0.5 * (f0 + s["force_N"]) * (s["alpha_mm"] - a0) * 1e-3
        a0, f0 = s["alpha_mm"], s["force_N"]
        s["weight_work_J"] = work


# ---------------------------------------------------------------- CalculiX
def ccx_static_deck(path, nodes, elements, ids, Y, penalty, sigma_inf, increments):
    """The CalculiX deck: visco2d's mesh, its pole on the plate (y = 0), the weight under G applied in
    *STATIC with *TIME POINTS at k/N (the increment is at most 1/N; automatic cut-backs allowed),
    every field printed at every time point. Returns the number of slave faces."""
    p = SPHERE
    lines = ["*HEADING", f"sphere R {p['R']} m on the plate, {'Y ' + str(Y) if Y else 'elastic'}, G {p['G']}, visco2d's mesh"]
    mesh, nslave = sphere_mesh_cards(nodes, elements, ids, 0.0, SLAVE_Z * p["R"])
    lines += mesh
    lines += material_cards(p["E"], p["nu"], p["rho"], bool(Y), Y, p["Et"])
    lines += contact_cards(penalty, sigma_inf)
    lines += ["*TIME POINTS, NAME=TP"]
    points = [f"{k / increments:.12g}" for k in range(1, increments + 1)]
    lines += [", ".join(points[i:i + 8]) for i in range(0, len(points), 8)]
    dt = 1.0 / increments
    lines += ["*BOUNDARY", "AXIS, 1, 1, 0.0", "NPLATE, 1, 3, 0.0",
              "*STEP, INC=10000",
              "*STATIC",
              f"{dt:.12g}, 1.0, {dt * 1e-4:.6g}, {dt:.12g}",
              "*DLOAD", f"ESPHERE, GRAV, {p['G']:.12g}, 0., -1., 0.",
              "*NODE PRINT, NSET=NSPHERE, TIME POINTS=TP", "U",
              "*NODE PRINT, NSET=NPLATE, TOTALS=ONLY, TIME POINTS=TP", "RF",
              "*EL PRINT, ELSET=ESPHERE, TIME POINTS=TP", "S, PEEQ",
              "*EL PRINT, ELSET=ESPHERE, TOTALS=ONLY, TIME POINTS=TP", "ELSE",
              "*END STEP", ""]
    with open(path, "w") as f:
        f.write("\n".join(lines))
    return nslave


def next_node_out(nodes, elements, radius_mm):
    """The undeformed radius (mm) of the first slave node beyond a contact radius: the contact edge
    lies between the two (both codes report the outermost node on the plate)."""
    r = np.sort(nodes[slave_nodes(nodes, elements, SLAVE_Z * SPHERE["R"]), 0]) * 1e3
    beyond = r[r > radius_mm + 1e-9]
    return float(beyond[0]) if len(beyond) else float("nan")


def penalty_pressure(d, K, sigma_inf):
    """CalculiX's linear pressure-overclosure law p(d) = K d (1/2 + atan(d/eps)/pi) with
    eps = pi sigma_inf / K (so that p -> -sigma_inf at large clearance d < 0)."""
    eps = math.pi * sigma_inf / K
    return K * d * (0.5 + np.arctan(d / eps) / math.pi)


def ccx_static_results(folder, job, nodes, elements, ids, Y, penalty, sigma_inf, increments):
    """visco2d's static contact and plastic keys from a CalculiX run, at each k/N (whole body)."""
    p = SPHERE
    w, xy, shape = gauss_weights(nodes, elements)
    volume = w.sum()
    mass = p["rho"] * volume
    c = volume_mean_weights(nodes, elements, w, shape)
    index = {int(n): i for i, n in enumerate(ids)}
    blocks = dat_blocks(os.path.join(folder, job + ".dat"))

    def k_of(t):
        return int(round(t * increments))

    def by_k(prefix, setname):
        return {k_of(b[1]): b[2] for b in blocks if b[0].startswith(prefix) and b[0].endswith(setname)}

    disp = by_k("displacements", "NSPHERE")
    rf = by_k("total force", "NPLATE")
    stress = by_k("stresses", "ESPHERE")
    peeq = by_k("equivalent plastic strain", "ESPHERE")
    else_ = {k: v for k, v in by_k("total internal energy", "ESPHERE").items() if v}
    slaves = np.array(slave_nodes(nodes, elements, SLAVE_Z * p["R"]))
    pole = int(np.argmin(np.hypot(nodes[:, 0], nodes[:, 1])))
    H = hardening_modulus(p["E"], p["Et"]) if Y else 0.0
    rows = []
    alpha_prev, lam_prev, work = 0.0, 0.0, 0.0
    for k in sorted(disp):
        u = np.zeros((len(nodes), 2))
        d = np.array(disp[k])
        u[np.array([index[int(n)] for n in d[:, 0]])] = d[:, 1:3]
        lam = k / increments
        alpha = -(c @ u[:, 1])
        # the trapezoidal work of the weight M g lam along the centroid's approach (visco2d's
        # external_work_J: with its exact contact the plate's reactions do no work)
        work += 0.5 * (lam_prev + lam) * mass * p["G"] * (alpha - alpha_prev)
        alpha_prev, lam_prev = alpha, lam
        over = -(nodes[slaves, 1] + u[slaves, 1])            # overclosure of the slave nodes
        inside = slaves[over > 0]
        r = dict(k=k, load=lam, weight_N=mass * p["G"] * lam, alpha_mm=alpha * 1e3,
                 force_N=(rf[k][0][1] * SECTOR) if k in rf else float("nan"),
                 pole_overclosure_um=float(over[slaves == pole][0]) * 1e6,
                 q_penalty_MPa=float(penalty_pressure(over[slaves == pole][0], penalty, sigma_inf)) / 1e6,
                 contact_radius_mm=nodes[inside, 0].max() * 1e3 if len(inside) else 0.0,
                 contact_nodes=len(inside), weight_work_J=work)
        if k in stress:
            r["q_MPa"] = r["q_penalty_MPa"]
            r["strain_energy_J"] = stored_energy(stress[k], w, p["E"], p["nu"])
            # -sigma_y (CalculiX's axial stress) extrapolated to the pole: visco2d's q_surface_MPa
            r["q_surface_MPa"] = -node_average(gauss_field(stress[k], 3, len(elements)), elements, pole) / 1e6
        if k in else_:
            r["internal_energy_J"] = else_[k][0][0] * SECTOR
        if Y and k in peeq:
            pe = peeq_field(peeq[k], len(elements))
            r["equivalent_plastic_strain_max"] = float(pe.max())
            r["yielded_volume_m3"] = float(w[pe > 0].sum())
            r["yielded_volume_1e-6_m3"] = float(w[pe > 1e-6].sum())
            r["plastic_dissipation_J"] = plastic_work(pe, w, Y, H)
            kmax = np.unravel_index(np.argmax(pe), pe.shape)
            r["peeq_max_at_mm"] = tuple(float(v) * 1e3 for v in xy[kmax[0], kmax[1]])
        elif not Y:
            r["plastic_dissipation_J"] = 0.0
        rows.append(r)
    last = max(stress) if stress else None
    check = {}
    if last is not None:
        e, k2 = gauss_point_index(stress[last])
        check["points"] = len(e)
    check["mass_kg"] = mass
    return rows, check


# ---------------------------------------------------------------- the report
QUANTITIES = [
    ("alpha_mm", "approach α (mm)"),
    ("contact_radius_mm", "contact radius (mm, outermost node)"),
    ("q_surface_MPa", "pole pressure −σ_z extrapolated (MPa)"),
    ("q_MPa", "pole contact pressure, each code's own (MPa)"),
    ("weight_work_J", "work of the weight along α, W (J)"),
    ("strain_energy_J", "stored elastic energy U (J)"),
    ("plastic_dissipation_J", "plastic dissipation D (J)"),
    ("equivalent_plastic_strain_max", "largest ε̄_p"),
    ("yielded_volume_m3", "yielded volume (m³)"),
]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", nargs="?", default=os.path.join(ROOT, "out", "calculix_plastic_static"))
    ap.add_argument("--level", type=int, default=3, help="MESH SPHERE LEVEL (default 3)")
    ap.add_argument("--increments", type=int, default=20, help="load increments N of both codes (default 20)")
    ap.add_argument("--checkpoints", default="5,10,15,20",
                    help="the increments k (of N) at which the codes are compared (default 5,10,15,20)")
    ap.add_argument("--yields", default="0.3e6,0.1e6", help="yield stresses of the plastic runs, Pa (default 0.3e6,0.1e6)")
    ap.add_argument("--penalty-rule", type=float, default=1e-3,
                    help="penalty slope K = Hertz p0 / (this x Hertz delta) at the full load (default 1e-3)")
    ap.add_argument("--penalty-factors", default="1,10", help="CalculiX runs at these multiples of K (default 1,10)")
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "install", "bin", "visco2d"))
    ap.add_argument("--ccx", default=shutil.which("ccx"))
    ap.add_argument("--dry-run", action="store_true", help="write the inputs, run no CalculiX job")
    args = ap.parse_args()
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    if not os.access(args.exe, os.X_OK):
        sys.exit(f"{args.exe}: no visco2d executable (make build)")
    ccx = args.ccx
    if not ccx and not args.dry_run:
        print("ccx (CalculiX) is not installed (apt-get install -y calculix-ccx): the CalculiX runs are skipped")
    N = args.increments
    checkpoints = [int(k) for k in args.checkpoints.split(",")]
    if any(k < 1 or k > N for k in checkpoints) or N not in checkpoints:
        sys.exit(f"--checkpoints must lie in 1..{N} and include {N}")
    yields = [None] + [float(y) for y in args.yields.split(",") if y]
    factors = [float(f) for f in args.penalty_factors.split(",")]
    p = SPHERE

    # visco2d along the path (a second, B-bar column at the full load only)
    vis = {}
    for Y in yields:
        vis[(Y, "STANDARD")] = visco2d_path(args.exe, out, args.level, Y, N, range(1, N + 1))
        weight_work(vis[(Y, "STANDARD")], N)
        vis[(Y, "BBAR")] = visco2d_path(args.exe, out, args.level, Y, N, [N], "BBAR")
        s = vis[(Y, "STANDARD")][-1]
        print(f"visco2d {'elastic' if not Y else 'Y ' + format(Y, 'g')}: alpha {s['alpha_mm']:.4f} mm, "
              f"q {s['q_MPa']:.4f} MPa, a {s['contact_radius_mm']:.3f} mm, cpu {s['cpu_s']} s", flush=True)
    base = vis[(None, "STANDARD")][-1]
    nodes, elements, ids = read_mesh(base["case"])
    F_full = base["force_N"]
    hz = hertz(F_full, p["R"], p["E"], p["nu"])
    K = hz["p0"] / (args.penalty_rule * hz["delta"])
    sigma_inf = 0.0025 * hz["p0"]
    version = ccx_version(ccx) if ccx else None

    ccx_rows, ccx_meta = {}, {}
    for Y in yields:
        for fac in factors:
            tag = "elastic" if not Y else f"Y{Y:g}"
            job = f"ccx_{tag}_K{fac:g}"
            nslave = ccx_static_deck(os.path.join(out, job + ".inp"), nodes, elements, ids, Y, fac * K, sigma_inf, N)
            if not ccx or args.dry_run:
                print(f"written {os.path.join(out, job + '.inp')} ({len(elements)} CAX4, {nslave} slave faces, "
                      f"K = {fac * K:.4g} Pa/m)")
                continue
            print(f"ccx {job}: {len(elements)} CAX4, {nslave} slave faces, K = {fac * K:.4g} Pa/m ...", flush=True)
            start = time.time()
            try:
                wall, cpu, log = run_ccx(ccx, out, job)
            except RuntimeError as error:
                # reported, never retried with other settings
                print(error)
                lines = str(error).splitlines()
                ccx_meta[(Y, fac)] = {"failed": " ".join(
                    [lines[0]] + [l.strip() for l in lines[1:] if "*ERROR" in l or "diverge" in l or "program stops" in l])}
                continue
            rows, check = ccx_static_results(out, job, nodes, elements, ids, Y, fac * K, sigma_inf, N)
            check.update(cpu_s=cpu, wall_s=wall, increments=log.count("increment ") or None,
                         iterations=log.count("iteration "))
            ccx_rows[(Y, fac)] = rows
            ccx_meta[(Y, fac)] = check
            r = rows[-1]
            print(f"ccx {job}: alpha {r['alpha_mm']:.4f} mm, q {r['q_MPa']:.4f} MPa, a {r['contact_radius_mm']:.3f} mm, "
                  f"F {r['force_N']:.3f} N (weight {r['weight_N']:.3f}), cpu {cpu:.1f} s ({time.time() - start:.0f} s)",
                  flush=True)
    if args.dry_run or not ccx:
        return

    # ---------------------------------------------------------------- comparison.md
    rep = [f"# CalculiX check of visco2d's static indentation on the plate\n",
           f"Written by scripts/calculix_plastic_static.py; CalculiX {version}; MESH SPHERE LEVEL={args.level} "
           f"({len(nodes)} nodes, {len(elements)} elements, used by both codes); {N} load increments; "
           f"GRAVITY G={p['G']:g} (weight {F_full:.6g} N at the full load); E_t = {p['Et']:g} Pa; "
           f"CalculiX penalty K = {K:.4g} Pa/m (Hertz p0 {hz['p0'] / 1e6:.4g} MPa over {args.penalty_rule:g} x Hertz "
           f"delta {hz['delta'] * 1e3:.4g} mm at the full load), sigma_inf = {sigma_inf:.4g} Pa.\n"]
    for Y in yields:
        name = "elastic flesh" if not Y else f"Y = {Y / 1e6:g} MPa, E_t = {p['Et'] / 1e6:g} MPa"
        rep.append(f"## {name}\n")
        vrows = vis[(Y, "STANDARD")]
        for fac in factors:
            meta = ccx_meta.get((Y, fac), {})
            if "failed" in meta:
                rep.append(f"CalculiX at {fac:g} K FAILED: {meta['failed']}\n")
        good = [f for f in factors if (Y, f) in ccx_rows]
        rep.append("### The force–approach curve (the plate force is the weight, M G k/N, in both codes)\n")
        rep.append("| k/N | force (N) | visco2d α (mm) | " + " | ".join(f"CalculiX {f:g} K α (mm)" for f in good)
                   + " | " + " | ".join(f"{f:g} K vs visco2d" for f in good) + " |")
        rep.append("|---|" + "---:|" * (2 + 2 * len(good)))
        for v in vrows:
            k = int(round(v["load_increments"]))
            cvals = [next((r["alpha_mm"] for r in ccx_rows[(Y, f)] if r["k"] == k), None) for f in good]
            rep.append(f"| {k}/{N} | {v['force_N']:.4g} | {v['alpha_mm']:.4f} | " + " | ".join(
                "-" if x is None else f"{x:.4f}" for x in cvals)
                       + " | " + " | ".join(rel(x, v["alpha_mm"]) for x in cvals) + " |")
        rep.append("")
        tag = "elastic" if not Y else f"Y{Y:g}"
        with open(os.path.join(out, f"curve_{tag}.csv"), "w") as f:
            f.write("k,force_N,visco2d_alpha_mm," + ",".join(f"ccx_K{x:g}_alpha_mm" for x in good) + "\n")
            for v in vrows:
                k = int(round(v["load_increments"]))
                cvals = [next((r["alpha_mm"] for r in ccx_rows[(Y, x)] if r["k"] == k), float("nan")) for x in good]
                f.write(f"{k},{v['force_N']:.10g},{v['alpha_mm']:.10g}," + ",".join(f"{x:.10g}" for x in cvals) + "\n")
        for k in checkpoints:
            v = vrows[k - 1]
            head = f"### load {k}/{N} (weight {v['force_N']:.4g} N)\n"
            rep.append(head)
            cols = ["visco2d"] + [f"CalculiX {f:g} K" for f in good]
            if not Y:
                cols.append("Hertz")
            line = "| quantity | " + " | ".join(cols) + " | " + " | ".join(f"{f:g} K vs visco2d" for f in good)
            if not Y:
                line += " | visco2d vs Hertz"
            rep.append(line + " |")
            rep.append("|---|" + "---:|" * (len(cols) + len(good) + (1 if not Y else 0)))
            hk = hertz(v["force_N"], p["R"], p["E"], p["nu"])
            hvals = {"contact_radius_mm": hk["a"] * 1e3, "q_MPa": hk["p0"] / 1e6, "q_surface_MPa": hk["p0"] / 1e6}
            for key, text in QUANTITIES:
                if not Y and key in ("equivalent_plastic_strain_max", "yielded_volume_m3", "plastic_dissipation_J"):
                    continue
                vv = v.get(key)
                cvals = [next((r.get(key) for r in ccx_rows[(Y, f)] if r["k"] == k), None) for f in good]
                line = f"| {text} | {fmt(vv)} | " + " | ".join(fmt(x) for x in cvals)
                if not Y:
                    line += f" | {fmt(hvals.get(key))}"
                line += " | " + " | ".join(rel(x, vv) for x in cvals)
                if not Y:
                    line += f" | {rel(vv, hvals.get(key))}"
                rep.append(line + " |")
            extra = []
            for f in good:
                r = next(r for r in ccx_rows[(Y, f)] if r["k"] == k)
                extra.append(f"CalculiX {f:g} K: plate force {r['force_N']:.6g} N (weight {r['weight_N']:.6g} N), "
                             f"pole overclosure {r['pole_overclosure_um']:.3g} µm, {r['contact_nodes']} nodes in contact "
                             f"(visco2d {int(v['contact_nodes'])}), internal energy ELSE {fmt(r.get('internal_energy_J'))} J, "
                             f"W − U − D {fmt(r['weight_work_J'] - r.get('strain_energy_J', float('nan')) - r.get('plastic_dissipation_J', 0.0))} J"
                             + (f", largest ε̄_p at (r, z) = ({r['peeq_max_at_mm'][0]:.2f}, {r['peeq_max_at_mm'][1]:.2f}) mm, "
                                f"yielded volume with PEEQ > 1e-6 {fmt(r.get('yielded_volume_1e-6_m3'))} m³"
                                if 'peeq_max_at_mm' in r else ""))
            rep.append("\n" + "; ".join(extra) + (
                f". visco2d: W − U − D {fmt(v['weight_work_J'] - v['strain_energy_J'] - v.get('plastic_dissipation_J', 0.0))} J; "
                f"its external_work_J (with the reactions' work) {fmt(v['external_work_J'])} J, "
                f"external_work_J − U − D {fmt(v['external_work_J'] - v['strain_energy_J'] - v.get('plastic_dissipation_J', 0.0))} J; "
                f"first slave node out of contact at r = {fmt(next_node_out(nodes, elements, v['contact_radius_mm']))} mm.\n"))
        b = vis[(Y, "BBAR")][-1]
        rep.append(f"visco2d with FORMULATION BBAR at the full load: α {fmt(b['alpha_mm'])} mm, contact radius "
                   f"{fmt(b['contact_radius_mm'])} mm, q {fmt(b['q_MPa'])} MPa"
                   + (f", D {fmt(b['plastic_dissipation_J'])} J, largest ε̄_p {fmt(b['equivalent_plastic_strain_max'])}, "
                      f"yielded volume {fmt(b['yielded_volume_m3'])} m³" if Y else "") + ".\n")
        cpu = [f"visco2d {float(vrows[-1]['cpu_s']):.2f} s for the full load in {N} increments "
               f"({sum(float(s['cpu_s']) for s in vrows):.1f} s for its {len(vrows)} path runs)"]
        cpu += [f"CalculiX {f:g} K {ccx_meta[(Y, f)]['cpu_s']:.1f} s" for f in good]
        rep.append("CPU: " + ", ".join(cpu) + ".\n")
    text = "\n".join(rep) + "\n"
    with open(os.path.join(out, "comparison.md"), "w") as f:
        f.write(text)
    print(text)
    print(f"written {os.path.join(out, 'comparison.md')}")


if __name__ == "__main__":
    main()
