"""The parts of scripts/calculix_nlgeom_impact.py (the finite-deformation CalculiX reference of the
Table 1 impact, doc/calculix_nlgeom.md) that need no ccx: the neo-Hookean card and its constants,
the drop-height table, the deck cards, and the parsing of a .dat file written here (a rigid-body
motion with a known approach, force and stress). The ccx runs themselves take minutes and stay
out of `make test`."""
import math
import os
import sys

import numpy as np
import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
sys.path.insert(0, os.path.join(ROOT, "python"))

import calculix_nlgeom_impact as nl  # noqa: E402
from visco2d import hertz  # noqa: E402

E, NU = 18.11e6, 0.219


def test_neo_hooke_constants_from_young_and_poisson():
    C10, D1 = nl.neo_hooke_constants(E, NU)
    G = E / (2 * (1 + NU))
    K = E / (3 * (1 - 2 * NU))
    assert C10 == pytest.approx(G / 2, rel=1e-15)
    assert D1 == pytest.approx(2 / K, rel=1e-15)
    # Table 1's flesh: G = 7.4282 MPa, K = 10.741 MPa
    assert C10 == pytest.approx(3.714110e6, rel=1e-6)
    assert D1 == pytest.approx(1.861955e-7, rel=1e-6)


def test_neo_hooke_stress_reduces_to_hooke_at_small_strain():
    # uniaxial stress at strain e: stretches (1 - nu e, 1 + e, 1 - nu e) give sigma = (0, E e, 0)
    # to first order; the second-order terms are ~ e^2 E, 1e-5 of E e at e = 1e-5
    C10, D1 = nl.neo_hooke_constants(E, NU)
    e = 1e-5
    s = nl.neo_hooke_cauchy(C10, D1, (1 - NU * e, 1 + e, 1 - NU * e))
    assert s[1] == pytest.approx(E * e, rel=1e-4)
    assert abs(s[0]) < 1e-4 * E * e and abs(s[2]) < 1e-4 * E * e
    # a pure volume change J: p = (2/D1)(J - 1), no deviator
    j = 1.01
    s = nl.neo_hooke_cauchy(C10, D1, (j ** (1 / 3),) * 3)
    assert s == pytest.approx([2 / D1 * (j - 1)] * 3, rel=1e-12)


def test_flesh_cards():
    C10, D1 = nl.neo_hooke_constants(E, NU)
    nh = nl.flesh_card("neohooke", E, NU, 756.85)
    assert nh == ["*MATERIAL, NAME=FLESH", "*HYPERELASTIC, NEO HOOKE", f"{C10:.10g}, {D1:.10g}",
                  "*DENSITY", "756.85"]
    assert nh[2] == "3714109.926, 1.861954721e-07"
    assert nl.flesh_card("linear", E, NU, 756.85) == ["*MATERIAL, NAME=FLESH", "*ELASTIC", "18110000, 0.219",
                                                      "*DENSITY", "756.85"]
    assert nl.flesh_card("svk", E, NU, 756.85) == nl.flesh_card("linear", E, NU, 756.85)
    with pytest.raises(ValueError, match="unknown model 'mooney'"):
        nl.flesh_card("mooney", E, NU, 756.85)


def test_drop_table_spans_the_target_approaches():
    p = nl.TABLE1
    M = nl.sphere_mass(p["R"], p["rho"])
    assert M == pytest.approx(0.15543, rel=1e-4)        # the Table 1 sphere's mass (visco2d: 0.1554 kg)
    rows = nl.drop_table()
    assert [r["V"] for r in rows] == sorted(r["V"] for r in rows)
    assert len(rows) == len(nl.TARGETS) + 1
    table1 = [r for r in rows if r["name"] == "table1"]
    assert len(table1) == 1 and table1[0]["V"] == 0.9982
    # Table 1's Hertz approach: 1.0974 mm (inputs/table1_elastic.inp), 0.0300 R
    assert table1[0]["hertz_ratio"] * p["R"] == pytest.approx(1.0974e-3, rel=1e-4)
    for r in rows:
        assert r["h"] == pytest.approx(r["V"] ** 2 / (2 * 9.8), rel=1e-14)
        # the speed inverts eq. [43], checked by the package's own Hertz formula
        a = hertz.alpha_max(p["E"], p["nu"], p["R"], M, r["V"])
        assert a / p["R"] == pytest.approx(r["hertz_ratio"], rel=1e-12)
    targets = sorted(r["hertz_ratio"] for r in rows if r["name"] != "table1")
    assert targets == pytest.approx(sorted(nl.TARGETS), rel=1e-12)
    assert min(targets) <= 0.02 + 1e-12 and max(targets) >= 0.15


def small_mesh():
    """Four axisymmetric quadrilaterals, 2 x 2, 1 mm squares from the pole (0, 0)."""
    nodes = np.array([[x, z] for z in (0.0, 1e-3, 2e-3) for x in (0.0, 1e-3, 2e-3)])
    elements = np.array([[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6], [4, 5, 8, 7]])
    ids = np.arange(1, 10)
    return nodes, elements, ids


def test_deck_nlgeom_only_on_the_finite_deformation_models(tmp_path):
    nodes, elements, ids = small_mesh()
    steps = {}
    for model in nl.MODELS:
        path = tmp_path / f"{model}.inp"
        nl.ccx_deck(str(path), model, nodes, elements, ids, 0.05, 1e11, 5e3, 2e-3, 1e-5, [0, 1], p=dict(nl.TABLE1, R=2e-3))
        text = path.read_text()
        steps[model] = [line for line in text.splitlines() if line.startswith("*STEP")]
        assert "*ELSET, ELSET=ENEAR\n1, 2\n" in text
        assert "*EL PRINT, ELSET=ENEAR, FREQUENCY=1\nS\n" in text
        assert "*DLOAD\nESPHERE, GRAV, 9.8, 0., -1., 0.\n" in text
        assert "*DYNAMIC, DIRECT\n1e-05, 0.002\n" in text
    assert steps["linear"] == ["*STEP, INC=1000000"] * 2
    assert steps["svk"] == steps["neohooke"] == ["*STEP, NLGEOM, INC=1000000"] * 2
    assert "*HYPERELASTIC, NEO HOOKE" in (tmp_path / "neohooke.inp").read_text()
    assert "*HYPERELASTIC" not in (tmp_path / "svk.inp").read_text()


def test_max_shear_and_contact_radius():
    # a tensor with principal stresses (-3, -1, 0.5) rotated: max shear 1.75, in both layouts
    c, s = math.cos(0.3), math.sin(0.3)
    Q = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    T = Q @ np.diag([-3.0, -1.0, 0.5]) @ Q.T
    row = [T[0, 0], T[1, 1], T[2, 2], T[0, 1], T[0, 2], T[1, 2]]
    assert nl.max_shear_3d([row])[0] == pytest.approx(1.75, rel=1e-12)
    # axisymmetric (sigma_r, sigma_z, sigma_theta, tau_rz) = the (x, y) plane and the hoop stress
    assert nl.max_shear_2d(np.array([T[0, 0], T[1, 1], 0.5, T[0, 1]])) == pytest.approx(1.75, rel=1e-12)
    # the boundary leaves the plate y = 0 between the 2nd and 3rd node: y from -1 to +1 over r 2 -> 4
    assert nl.contact_radius(np.array([0.0, 2.0, 4.0]), np.array([-2.0, -1.0, 1.0])) == pytest.approx(3.0)
    assert nl.contact_radius(np.array([0.0, 2.0]), np.array([1.0, 2.0])) == 0.0
    # uniaxial stress -E e in z: principal strains (-e, nu e, nu e); the largest magnitude e
    e = 0.01
    assert nl.largest_strain(np.array([[0.0, -E * e, 0.0, 0.0]]), E, NU) == pytest.approx(e, rel=1e-12)
    # pure shear tau_rz: strains +-(1 + nu) tau / E
    assert nl.largest_strain(np.array([[0.0, 0.0, 0.0, 1e5]]), E, NU) == pytest.approx((1 + NU) * 1e5 / E, rel=1e-12)


def fmt(x):
    return f"{x: .6E}"


def write_dat(path, nodes, ids, h, dt, t1, motion, force, stress_rows):
    """A ccx-format .dat: U of NSPHERE, the plate's total force and S of ENEAR at increments k = 1..n of
    step 2 (time t1 + k dt), the body moving rigidly down by motion(t)."""
    lines = []
    for k in range(1, len(motion) + 1):
        t = t1 + k * dt
        lines += [f" displacements (vx,vy,vz) for set NSPHERE and time  {t:.7E}", ""]
        lines += [f"{int(i):10d} {fmt(0.0)} {fmt(motion[k - 1])} {fmt(0.0)}" for i in ids]
        lines += ["", f" total force (fx,fy,fz) for set NPLATE and time  {t:.7E}", "",
                  f"        {fmt(0.0)} {fmt(force[k - 1])} {fmt(0.0)}", "",
                  f" stresses (elem, integ.pnt.,sxx,syy,szz,sxy,sxz,syz) for set ENEAR and time  {t:.7E}", ""]
        for e, pt, value in stress_rows(k):
            lines.append(f"{e:10d}{pt:4d} {fmt(-value)} {fmt(-2 * value)} {fmt(-value)} {fmt(0.0)} {fmt(0.0)} {fmt(0.0)}")
        lines.append("")
    path.write_text("\n".join(lines) + "\n")


def test_results_parsed_from_a_dat_file(tmp_path):
    # the body falls at V until its pole reaches the plate at t_c, then alpha = A sin(w (t - t_c))
    # (velocity continuous: A w = V); the plate force is 180 times the sector's k alpha; the stress is
    # uniaxial -2 s in y with -s in x and z: max shear s/2, s = 1e6 alpha/A at the point (element 3, ccx
    # point 3, i.e. 2D point k = 2 at (-g, +g)) and half that elsewhere
    nodes, elements, ids = small_mesh()
    h, dt, V, A = 0.05, 1e-5, 1.0, 1e-3
    w = V / A
    _, t1 = nl.free_fall_times(h, dt)
    n = 250
    t = t1 + np.arange(1, n + 1) * dt
    t_c = t1 + 2.4 * dt
    alpha = np.where(t < t_c, V * (t - t_c), A * np.sin(w * (t - t_c)))
    motion = -h - alpha                     # every node: u_y = -(h + alpha), the pole at z = 0
    k_stiff = 2e5
    force = np.maximum(alpha, 0) * k_stiff / nl.SECTOR

    def stress_rows(k):
        s = 1e6 * max(alpha[k - 1], 0.0) / A
        return [(e, pt, s if (e, pt) == (3, 3) else 0.5 * s) for e in (1, 2, 3, 4) for pt in range(1, 9)]

    write_dat(tmp_path / "job.dat", nodes, ids, h, dt, t1, motion, force, stress_rows)
    slave = [0, 1, 2]
    r = nl.ccx_results(str(tmp_path), "job", nodes, elements, ids, h, dt, slave)
    t_peak = math.pi / (2 * w)
    # the parabola through three samples of a sine at w dt = 0.01: vertex within (w dt)^2/8 of A
    assert r["alpha_max_mm"] == pytest.approx(A * 1e3, rel=2e-5)
    assert r["t_alpha_max_ms"] == pytest.approx(t_peak * 1e3, abs=0.05 * dt * 1e3)
    assert r["impact_velocity_m_s"] == pytest.approx(V, rel=1e-3)
    # the force's largest sample: within the sine's drop over half a step of its maximum
    assert r["force_max_N"] == pytest.approx(k_stiff * A, rel=(w * dt) ** 2)
    assert r["shear_max_MPa"] == pytest.approx(0.5, rel=(w * dt) ** 2)
    assert r["shear_at_alpha_MPa"] == pytest.approx(0.5, rel=(w * dt) ** 2)
    # the point: element 3 (from 0: 2), 2D point (-g, +g), r = 0.5 mm (1 - g), z = 1 mm + 0.5 mm (1 + g)
    g = 1 / math.sqrt(3)
    assert r["shear_r_mm"] == pytest.approx(0.5 * (1 - g), rel=1e-12)
    assert r["shear_depth_mm"] == pytest.approx(1 + 0.5 * (1 + g), rel=1e-12)
    # every slave node is at z = 0 undeformed: all penetrate, the radius is the outermost's (2 mm)
    assert r["contact_radius_mm"] == pytest.approx(2.0, rel=1e-12)
    assert not r["alpha_reached_end"]


def test_first_contact_before_the_first_sample_is_an_error(tmp_path):
    # the pole already on the plate at the first printed increment: no first-contact time to interpolate
    nodes, elements, ids = small_mesh()
    h, dt = 0.05, 1e-5
    _, t1 = nl.free_fall_times(h, dt)
    motion = -h - 1e-6 * np.arange(1, 11)
    write_dat(tmp_path / "job.dat", nodes, ids, h, dt, t1, motion, np.zeros(10), lambda k: [])
    with pytest.raises(ValueError, match="already on the plate at the first printed increment"):
        nl.ccx_results(str(tmp_path), "job", nodes, elements, ids, h, dt, [0, 1, 2])


def test_error_rows_and_csv(tmp_path):
    ref = dict(alpha_over_R=0.1, alpha_max_mm=2.0, force_max_N=100.0, shear_at_alpha_MPa=0.8, shear_max_MPa=1.0)
    res = [("d1", {"neohooke": ref,
                   "visco2d": dict(alpha_max_mm=2.02, force_max_N=99.0, shear_at_alpha_MPa=0.76, shear_max_MPa=0.9,
                                   strain_at_alpha=0.12),
                   "linear": dict(alpha_max_mm=1.98, force_max_N=101.0, shear_at_alpha_MPa=0.78, shear_max_MPa=0.95),
                   "svk": {"failed": "diverged"}})]
    rows = nl.error_rows(res)
    assert rows[0]["strain_max"] == 0.12
    assert rows[0]["visco2d_alpha_m"] == pytest.approx(0.01)
    assert rows[0]["linear_F_m"] == pytest.approx(0.01)
    assert rows[0]["visco2d_tau_alpha"] == pytest.approx(-0.05)
    assert rows[0]["visco2d_tau_max"] == pytest.approx(-0.1)
    assert rows[0]["svk_alpha_m"] is None
    cols = nl.write_error_csv(str(tmp_path / "e.csv"), rows)
    text = (tmp_path / "e.csv").read_text().splitlines()
    assert text[0].split(",") == cols and cols[:3] == ["alpha_over_R", "strain_max", "visco2d_alpha_m"]
    assert len(cols) == 2 + 3 * 4
    assert text[1].split(",")[:6] == ["0.1", "0.12", "0.01", "-0.01", "-0.05", "-0.1"]
    assert text[1].endswith(",,,,")


def test_visco2d_deck(tmp_path):
    path = tmp_path / "v.inp"
    nl.visco2d_deck(str(path), 0.9982, 2, 1e-5)
    lines = path.read_text().splitlines()
    assert "INITIAL VZ=-0.9982 AZ=-9.8" in lines and "MESH SPHERE R=0.0366 LEVEL=2" in lines
    assert "PLATE Z=0 SLIP RELEASE=YES" in lines
    assert "MATERIAL apple ELASTIC E=1.811e+07 NU=0.219 RHO=756.85" in lines
    # to 1.35 Hertz t_m (1.6179 ms), snapshots every 2 dt from 0.6 t_m
    assert "TIME DT=1e-05 TEND=0.00219" in lines
    fields = [x for x in lines if x.startswith("OUTPUT")][0].split("FIELDS=")[1].split(",")
    times = np.array([float(x) for x in fields])
    assert times[0] == pytest.approx(0.98e-3) and times[-1] < 2.19e-3
    assert np.diff(times) == pytest.approx(2e-5)
