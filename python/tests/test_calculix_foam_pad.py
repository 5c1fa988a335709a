"""The parts of scripts/calculix_foam_pad.py (the CalculiX reference of a peach dropped on a 10 mm
hyperfoam pad, doc/calculix_foam_pad.md) that need no ccx: the *HYPERFOAM card and its moduli, the
accelerated approach step, the pad's graded grid and its cards, the deck, and the parsing of a .dat
file written here (a rigid body pressing the pad's top with a known motion, force and stress). The
ccx runs themselves take minutes and stay out of `make test`."""
import math
import os
import sys

import numpy as np
import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
sys.path.insert(0, os.path.join(ROOT, "python"))

import calculix_foam_pad as fp  # noqa: E402
from calculix_common import plate_node_base  # noqa: E402


def test_hyperfoam_card_and_moduli():
    B = fp.FOAMS["B"]
    assert fp.hyperfoam_card(B) == ["*HYPERFOAM, N=2", "740000, 12, 10000, -2, 0, 0"]
    mu0, K0, E0 = fp.hyperfoam_moduli(B)
    assert (mu0, K0, E0) == pytest.approx((0.75e6, 0.5e6, 1.5e6), rel=1e-14)
    # doc/hyperfoam.md's table of set B: nominal stress at 5 / 20 / 40 / 60 / 80 % compression (MPa)
    for strain, stress in ((0.05, -0.0608), (0.2, -0.151), (0.4, -0.235), (0.6, -0.440), (0.8, -1.82)):
        # (the table's three digits)
        assert fp.hyperfoam_uniaxial_nominal(B, 1 - strain) / 1e6 == pytest.approx(stress, rel=3e-3)
    # small strain: T = E0 (lam - 1)
    assert fp.hyperfoam_uniaxial_nominal(B, 1 - 1e-6) == pytest.approx(-E0 * 1e-6, rel=1e-4)
    # three terms: eight values to a line, the ninth (nu_3) on the next
    three = dict(mu=(1.0, 2.0, 3.0), alpha=(4.0, 5.0, 6.0), nu=(0.1, 0.2, 0.3))
    assert fp.hyperfoam_card(three) == ["*HYPERFOAM, N=3", "1, 4, 2, 5, 3, 6, 0.1, 0.2", "0.3"]
    # one term with nu: K0 = 2 mu (1/3 + beta), E0 = 2 mu0 (1 + nu)
    one = dict(mu=(1e5,), alpha=(8.0,), nu=(0.25,))
    mu0, K0, E0 = fp.hyperfoam_moduli(one)
    assert K0 == pytest.approx(2e5 * (1 / 3 + 0.5), rel=1e-14)
    assert E0 == pytest.approx(2 * mu0 * 1.25, rel=1e-14)
    with pytest.raises(ValueError):
        fp.hyperfoam_uniaxial_nominal(three, 0.9)


def test_impact_speed_and_the_approach_step():
    V = fp.impact_speed()
    assert V == pytest.approx(math.sqrt(2 * 9.81 * 0.2), rel=1e-15)
    assert V == pytest.approx(1.981, abs=5e-4)
    a = fp.approach_step(V, 1e-5)
    # accelerated from rest over t1 to V1, then 2 dt V of gap closed under g reaches V
    assert a["g1"] * a["t1"] == pytest.approx(a["V1"], rel=1e-14)
    assert a["V1"] ** 2 + 2 * 9.81 * a["gap"] == pytest.approx(V ** 2, rel=1e-14)
    assert a["lift"] == pytest.approx(0.5 * a["V1"] * a["t1"] + 2e-5 * V, rel=1e-14)
    assert 1e-3 < a["lift"] < 1.1e-3


def test_graded_sizes_radii_and_depths():
    sizes = fp.graded_sizes(10.0, 0.4, 1.2)
    assert sum(sizes) == pytest.approx(10.0, rel=1e-14)
    assert all(b / a == pytest.approx(1.2, rel=1e-12) for a, b in zip(sizes[:-1], sizes[1:]))
    assert sizes[0] == pytest.approx(0.4, rel=0.1)
    # the body's boundary radii out to r_match, then growing by 1.2 to the width
    body = [0.0, 0.5, 1.2, 2.0, 3.0, 4.5, 7.0]
    r = fp.pad_radii(body, 3.0, 20.0)
    assert list(r[:5]) == [0.0, 0.5, 1.2, 2.0, 3.0]
    assert r[-1] == 20.0 and np.all(np.diff(r) > 0)
    d = np.diff(r[4:])
    assert all(b / a == pytest.approx(1.2, rel=1e-12) for a, b in zip(d[:-1], d[1:]))
    assert d[0] == pytest.approx(1.0 * 1.2, rel=0.15)
    z = fp.pad_depths(0.01, 4e-4)
    assert z[0] == 0.0 and z[-1] == -0.01 and np.all(np.diff(z) < 0)
    assert -np.diff(z)[0] == pytest.approx(4e-4, rel=0.1)
    u = fp.uniform_radii(1e-3, 0.018, 0.045)
    assert np.diff(u)[:18] == pytest.approx([1e-3] * 18, rel=1e-9) and u[-1] == 0.045
    assert list(fp.refine([0.0, 1.0, 3.0], 2)) == [0.0, 0.5, 1.0, 2.0, 3.0]


def test_pad_grid_and_cards():
    r, z = np.array([0.0, 1.0, 3.0]), np.array([0.0, -1.0, -2.5])
    nodes, elements = fp.pad_grid(r, z)
    assert nodes.shape == (9, 2) and elements.shape == (4, 4)
    assert np.all(fp.element_area_signs(nodes, elements) > 0)            # counter-clockwise in r-z
    # the top row's face S3 joins corners 3 and 4: two nodes of the top surface z = 0
    for conn in elements[:2]:
        assert nodes[conn[2], 1] == 0.0 and nodes[conn[3], 1] == 0.0
    lines, info = fp.pad_cards(r, z, 1000)
    text = "\n".join(lines)
    assert "*NSET, NSET=PADBOT\n1007, 1008, 1009" in text
    assert "*NSET, NSET=PADTOP\n1001, 1002, 1003" in text
    assert "*NSET, NSET=PADAXIS\n1001, 1004\n" in text
    assert "*SURFACE, NAME=SPAD, TYPE=ELEMENT\n1001, S3\n1002, S3" in text
    assert "1001, 1004, 1005, 1002, 1001" in text                       # element 1: (0,-1) (1,-1) (1,0) (0,0)
    assert info["centre"] == 1001 and info["r1"] == 1.0


def small_mesh():
    """Four axisymmetric quadrilaterals, 2 x 2, 1 mm squares from the pole (0, 0)."""
    nodes = np.array([[x, z] for z in (0.0, 1e-3, 2e-3) for x in (0.0, 1e-3, 2e-3)])
    elements = np.array([[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6], [4, 5, 8, 7]])
    ids = np.arange(1, 10)
    return nodes, elements, ids


SMALL = dict(fp.PEACH, R=1e-3)
PAD_R, PAD_Z = np.array([0.0, 1e-3, 3e-3]), np.array([0.0, -1e-3, -2e-3])


def test_deck_cards(tmp_path):
    nodes, elements, ids = small_mesh()
    path = tmp_path / "pad.inp"
    info = fp.ccx_deck(str(path), nodes, elements, ids, PAD_R, PAD_Z, fp.FOAMS["B"], 1e11, 8e-3, 1e-5, [0, 1],
                       p=SMALL)
    text = path.read_text()
    a = fp.approach_step(fp.impact_speed(), 1e-5)
    assert info["centre"] == plate_node_base(ids) + 1 == 101
    assert "*MATERIAL, NAME=FOAM\n*HYPERFOAM, N=2\n740000, 12, 10000, -2, 0, 0\n*DENSITY\n100\n" in text
    assert "*HYPERELASTIC, NEO HOOKE" in text
    assert [line for line in text.splitlines() if line.startswith("*STEP")] == ["*STEP, NLGEOM, INC=1000000"] * 2
    assert f"*DLOAD, AMPLITUDE=ONE\nESPHERE, GRAV, {a['g1']:.15g}, 0., -1., 0.\n" in text
    assert "*DLOAD, OP=NEW, AMPLITUDE=ONE\nESPHERE, GRAV, 9.81, 0., -1., 0.\n" in text
    assert "*DYNAMIC, DIRECT\n1e-05, 0.008\n*CONTROLS, PARAMETERS=FIELD\n0.005, 0.01, 0.01, 0.02, 0.02," in text
    assert "*CONTACT PAIR, INTERACTION=FRICTIONLESS, TYPE=SURFACE TO SURFACE\nSSLAVE, SPAD\n" in text
    assert "PRESSURE-OVERCLOSURE=LINEAR\n1e+11, 1000\n" in text
    assert "PADBOT, 1, 3, 0.0" in text and "PADAXIS, 1, 1, 0.0" in text and "AXIS, 1, 1, 0.0" in text
    assert "*NODE PRINT, NSET=PADBOT, TOTALS=ONLY\nRF\n" in text
    assert "*ELSET, ELSET=ENEAR\n1, 2\n" in text and "*EL PRINT, ELSET=ENEAR\nS\n" in text
    # the peach lifted by the approach step's lift: the pole node at z = lift
    assert f"\n1, 0, {a['lift']:.15g}\n" in text
    # node-to-surface with the pad as slave
    fp.ccx_deck(str(path), nodes, elements, ids, PAD_R, PAD_Z, fp.FOAMS["A"], 1e12, 8e-3, 2e-5, [0], p=SMALL,
                kind="n2s", pad_slave=True)
    text = path.read_text()
    assert "TYPE=NODE TO SURFACE\nSPAD, SSLAVE\n" in text and "245000, 10, 5000, -2, 0, 0" in text


def fmt(x):
    return f"{x: .6E}"


def write_dat(path, ids, pad_ids, t1, dt, uz, pad_uz, force, stress_rows):
    """A ccx-format .dat of step 2 (time t1 + k dt, k = 1..n): U of NSPHERE (every node u_z = uz[k]),
    U of PADTOP (the first two nodes u_z = pad_uz[k]), the total force of PADBOT and S of ENEAR."""
    lines = []
    for k in range(1, len(uz) + 1):
        t = t1 + k * dt
        lines += [f" displacements (vx,vy,vz) for set NSPHERE and time  {t:.7E}", ""]
        lines += [f"{int(i):10d} {fmt(0.0)} {fmt(uz[k - 1])} {fmt(0.0)}" for i in ids]
        lines += ["", f" displacements (vx,vy,vz) for set PADTOP and time  {t:.7E}", ""]
        lines += [f"{int(i):10d} {fmt(0.0)} {fmt(pad_uz[k - 1])} {fmt(0.0)}" for i in pad_ids]
        lines += ["", f" total force (fx,fy,fz) for set PADBOT and time  {t:.7E}", "",
                  f"        {fmt(0.0)} {fmt(force[k - 1])} {fmt(0.0)}", "",
                  f" stresses (elem, integ.pnt.,sxx,syy,szz,sxy,sxz,syz) for set ENEAR and time  {t:.7E}", ""]
        for e, pt, value in stress_rows(k):
            lines.append(f"{e:10d}{pt:4d} {fmt(-value)} {fmt(-2 * value)} {fmt(-value)} {fmt(0.0)} {fmt(0.0)} {fmt(0.0)}")
        lines.append("")
    path.write_text("\n".join(lines) + "\n")


def test_results_parsed_from_a_dat_file(tmp_path):
    # a rigid peach reaches the pad at V at t_c and presses it as alpha = A sin(w (t - t_c)) (A w = V),
    # its pole and the pad's top moving together; after half a period the pad is back at rest and the
    # peach leaves at V (restitution 1). Ground force 180 times the sector's k alpha; the stress
    # uniaxial -2 s in y, -s in x and z: max shear s/2, s = 1e6 alpha/A at element 3, ccx point 3
    nodes, elements, ids = small_mesh()
    dt, V, A = 1e-5, fp.impact_speed(), 2e-3
    w = V / A
    a = fp.approach_step(V, dt)
    t1, h = a["t1"], a["lift"]
    n = int(1.4 * math.pi / w / dt)
    t = t1 + np.arange(1, n + 1) * dt
    t_c = t1 + 2.4 * dt
    s = t - t_c
    alpha = np.where(s < 0, V * s, np.where(s < math.pi / w, A * np.sin(w * s), -V * (s - math.pi / w)))
    uz = -h - alpha                                  # every node; the pole reaches z = 0 at t_c
    pad_uz = -np.clip(alpha, 0, None)
    k_stiff = 5e4
    force = np.clip(alpha, 0, None) * k_stiff / fp.SECTOR
    base = plate_node_base(ids)

    def stress_rows(k):
        q = 1e6 * max(alpha[k - 1], 0.0) / A
        # element 1 holds the pole node: its spike (3 s) is kept apart
        return [(e, pt, 3 * q if e == 1 else q if (e, pt) == (3, 3) else 0.5 * q) for e in (1, 2, 3, 4)
                for pt in range(1, 9)]

    write_dat(tmp_path / "pad.dat", ids, [base + 1, base + 2], t1, dt, uz, pad_uz, force, stress_rows)
    info = dict(centre=base + 1, r1=1e-3)
    r = fp.ccx_results(str(tmp_path), "pad", nodes, elements, ids, info, dt, p=SMALL)
    wdt = w * dt
    assert r["V_first_contact_m_s"] == pytest.approx(V, rel=1e-3)
    assert r["t_first_contact_s"] == pytest.approx(t_c, abs=1e-3 * dt)
    assert r["alpha_max_mm"] == pytest.approx(A * 1e3, rel=wdt ** 2)
    assert r["t_alpha_max_ms"] == pytest.approx(math.pi / (2 * w) * 1e3, abs=0.05 * dt * 1e3)
    assert r["alpha_cm_max_mm"] == pytest.approx(A * 1e3, rel=wdt ** 2)
    # the pole and the pad's top move with the body: no own approach, compression alpha / thickness
    assert r["pole_travel_at_alpha_max_mm"] == pytest.approx(A * 1e3, rel=wdt ** 2)
    assert r["body_approach_at_alpha_max_mm"] == pytest.approx(0.0, abs=1e-6)
    assert r["pad_top_uz_min_mm"] == pytest.approx(-A * 1e3, rel=wdt ** 2)
    assert r["pad_compression_max"] == pytest.approx(A / fp.PAD["thickness"], rel=wdt ** 2)
    assert r["pad_top1_uz_min_mm"] == r["pad_top_uz_min_mm"]
    assert r["ground_force_max_N"] == pytest.approx(k_stiff * A, rel=wdt ** 2)
    # the contact force from the momentum: M (A w^2 sin + g), its peak M (A w^2 + g) (two central
    # differences over 2 dt: 4/3 (w dt)^2 low, and the sample nearest the peak)
    M = fp.sphere_mass(SMALL["R"], SMALL["rho"])
    assert r["mass_kg"] == M
    assert r["contact_force_max_N"] == pytest.approx(M * (A * w * w + 9.81), rel=4 * wdt ** 2)
    # separation at half a period, at V up
    # (the pole 1 micrometre above the pad, 1e-6 / V later; the gap is linear between increments, and the
    # kink of the pad's stop falls inside one: within dt)
    assert r["contact_duration_ms"] == pytest.approx((math.pi / w + fp.SEPARATION_GAP / V) * 1e3, abs=dt * 1e3)
    assert r["rebound_speed_cm_m_s"] == pytest.approx(V, rel=1e-3)
    assert r["restitution_cm"] == pytest.approx(1.0, rel=1e-3)
    assert r["restitution_centre"] == pytest.approx(1.0, rel=1e-3)
    assert r["shear_max_MPa"] == pytest.approx(0.5, rel=wdt ** 2)
    assert r["shear_at_alpha_MPa"] == pytest.approx(0.5, rel=wdt ** 2)
    assert r["shear_pole_element_max_MPa"] == pytest.approx(1.5, rel=wdt ** 2)
    assert r["t_shear_max_ms"] == pytest.approx(math.pi / (2 * w) * 1e3, abs=dt * 1e3)
    g = 1 / math.sqrt(3)
    assert r["shear_max_r_mm"] == pytest.approx(0.5 * (1 - g), rel=1e-12)
    assert r["shear_max_z_mm"] == pytest.approx(1 + 0.5 * (1 + g), rel=1e-12)
    # no energies printed: the energy check is not a number
    assert math.isnan(r["energy_error_max_rel"])
    # the history from first contact: the columns and the first rows
    fp.write_history(tmp_path / "history.csv", r["history"])
    rows = (tmp_path / "history.csv").read_text().splitlines()
    assert rows[0] == ",".join(fp.HISTORY_COLUMNS)
    first = [float(x) for x in rows[1].split(",")]
    assert 0 <= first[0] < dt
    assert first[1] == pytest.approx(-V * first[0], rel=1e-3)
    assert len(rows) - 1 == int(np.sum(np.array(r["history"]["t"]) >= 0))


def test_first_contact_before_the_first_sample_is_an_error(tmp_path):
    nodes, elements, ids = small_mesh()
    dt = 1e-5
    a = fp.approach_step(fp.impact_speed(), dt)
    uz = -a["lift"] - 1e-6 * np.arange(1, 11)
    base = plate_node_base(ids)
    write_dat(tmp_path / "pad.dat", ids, [base + 1, base + 2], a["t1"], dt, uz, np.zeros(10), np.zeros(10), lambda k: [])
    with pytest.raises(ValueError, match="already on the pad at the first printed increment"):
        fp.ccx_results(str(tmp_path), "pad", nodes, elements, ids, dict(centre=base + 1, r1=1e-3), dt, p=SMALL)


def test_axis_interpolation_and_crossing():
    nodes = np.array([[0.0, 0.0], [0.0, 1.0], [0.0, 3.0], [1.0, 2.0]])
    i, j, s = fp.axis_interpolation(nodes, 2.5)
    assert (i, j) == (1, 2) and s == pytest.approx(0.75)
    t = np.array([0.0, 1.0, 2.0, 3.0])
    assert fp.crossing(t, np.array([1.0, -1.0, -1.0, 1.0]), start=1) == (2.5, 3)
    assert fp.crossing(t, np.array([-1.0, -1.0, -1.0, -1.0])) == (None, None)
