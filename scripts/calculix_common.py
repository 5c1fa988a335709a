"""The parts shared by the CalculiX (ccx) peer-code checks of visco2d's plasticity.

Used by scripts/calculix_plastic_impact.py (the dynamic drop) and
scripts/calculix_plastic_static.py (the static indentation on the plate);
doc/calculix_plastic.md describes the model these functions write:

- visco2d's own mesh, read from its results.h5, as CalculiX CAX4 cards (CalculiX
  expands each into a C3D8 over a fixed 2-degree sector);
- the rigid plate as one fixed C3D8 brick under y = 0 (CalculiX's axial
  direction), its top face the master surface;
- the sphere's boundary edges near the contact pole as the slave surface of a
  frictionless node-to-surface penalty contact (*SURFACE BEHAVIOR,
  PRESSURE-OVERCLOSURE=LINEAR);
- the bilinear hardening curve as *PLASTIC pairs;
- the .dat file parsed into blocks, and the Gauss-point fields mapped back to
  visco2d's 2x2 points with their volumes.
"""
import math
import os
import re
import subprocess
import time

import numpy as np

GP = 1.0 / math.sqrt(3.0)
SECTOR = 180.0   # the whole ring over CalculiX's 2-degree sector of an expanded CAX4 model


# ---------------------------------------------------------------- materials
def hardening_modulus(E, Et):
    """H = E Et / (E - Et), the slope of the yield stress against the equivalent plastic strain."""
    return E * Et / (E - Et)


def ccx_plastic_card(Y, E, Et, eps_last=10.0):
    """*PLASTIC lines of the bilinear curve: (Y, 0) and (Y + H eps_last, eps_last)."""
    H = hardening_modulus(E, Et)
    return f"*PLASTIC\n{Y:.10g}, 0.0\n{Y + H * eps_last:.10g}, {eps_last:.10g}\n"


# ---------------------------------------------------------------- running
def ccx_version(ccx):
    """The version ccx -v prints, '?' if it prints none."""
    vtext = subprocess.run([ccx, "-v"], capture_output=True, text=True).stdout
    m = re.search(r"Version\s+(\S+)", vtext)
    return m.group(1) if m else "?"


def run_ccx(ccx, folder, job):
    """ccx -i job in folder; (seconds of wall clock, user+sys CPU of the child, log text)."""
    start = time.time()
    before = os.times()
    env = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_STIFFNESS="1", CCX_NPROC_EQUATION_SOLVER="1")
    with open(os.path.join(folder, job + ".log"), "w") as log:
        result = subprocess.run([ccx, "-i", job], cwd=folder, stdout=log, stderr=subprocess.STDOUT, env=env)
    after = os.times()
    cpu = (after.children_user - before.children_user) + (after.children_system - before.children_system)
    text = open(os.path.join(folder, job + ".log")).read()
    if result.returncode != 0 or "*ERROR" in text:
        tail = "\n".join(text.splitlines()[-15:])
        raise RuntimeError(f"ccx failed on {folder}/{job}.inp (exit {result.returncode}):\n{tail}")
    return time.time() - start, cpu, text


def run_visco2d(exe, deck, out):
    """visco2d -q -o out deck; (the case folder, seconds of wall clock)."""
    start = time.time()
    result = subprocess.run([exe, "-q", "-o", out, deck], capture_output=True, text=True)
    if result.returncode not in (0,):
        raise RuntimeError(f"visco2d failed on {deck}: {result.stderr.strip()}")
    name = os.path.splitext(os.path.basename(deck))[0]
    return os.path.join(out, name), time.time() - start


def dat_blocks(path):
    """Parse a ccx .dat file: list of (title, time, rows) with rows a list of float lists."""
    blocks = []
    head = re.compile(r"^\s*(.*?)\s*for set\s+(\S+)\s+and time\s+(\S+)")
    current = None
    with open(path) as handle:
        for line in handle:
            m = head.match(line)
            if m:
                current = (m.group(1).strip() + " " + m.group(2), float(m.group(3)), [])
                blocks.append(current)
                continue
            if current is None:
                continue
            parts = line.split()
            if not parts:
                continue
            try:
                current[2].append([float(p) for p in parts])
            except ValueError:
                current = None
    return blocks


# ---------------------------------------------------------------- the mesh
def read_mesh(vcase):
    """visco2d's mesh from a case folder's results.h5: (nodes (n, 2), elements (ne, 4) from 0, node ids)."""
    import h5py
    with h5py.File(os.path.join(vcase, "results.h5"), "r") as f:
        nodes = f["/mesh/nodes"][...]
        elements = f["/mesh/elements"][...] - 1
        ids = f["/mesh/node_ids"][...]
    return nodes, elements, ids


def gauss_weights(nodes, elements):
    """(nelem, 4) whole-body volumes 2 pi r detJ of the 2x2 Gauss points, (nelem, 4, 2) their (r, z),
    and (nelem, 4, 4) the shape functions there; point k = i + 2 j with xi_i, eta_j = -g, +g."""
    pts = [(-GP, -GP), (GP, -GP), (-GP, GP), (GP, GP)]
    ne = len(elements)
    w = np.zeros((ne, 4))
    xy = np.zeros((ne, 4, 2))
    shape = np.zeros((4, 4))
    for k, (xi, eta) in enumerate(pts):
        N = 0.25 * np.array([(1 - xi) * (1 - eta), (1 + xi) * (1 - eta), (1 + xi) * (1 + eta), (1 - xi) * (1 + eta)])
        dxi = 0.25 * np.array([-(1 - eta), (1 - eta), (1 + eta), -(1 + eta)])
        deta = 0.25 * np.array([-(1 - xi), -(1 + xi), (1 + xi), (1 - xi)])
        X = nodes[elements]  # (ne, 4, 2)
        J11 = X[:, :, 0] @ dxi
        J12 = X[:, :, 1] @ dxi
        J21 = X[:, :, 0] @ deta
        J22 = X[:, :, 1] @ deta
        det = J11 * J22 - J12 * J21
        r = X[:, :, 0] @ N
        w[:, k] = 2 * math.pi * r * det
        xy[:, k, 0] = r
        xy[:, k, 1] = X[:, :, 1] @ N
        shape[k] = N
    return w, xy, shape


def volume_mean_weights(nodes, elements, w, shape):
    """c_i = int N_i dV / V: the consistent weights of node i in the volume mean (u_cm = c . u)."""
    c = np.zeros(len(nodes))
    for k in range(4):
        for a in range(4):
            np.add.at(c, elements[:, a], w[:, k] * shape[k, a])
    return c / w.sum()


def plate_node_base(ids):
    """The first node (and element) number of the plate brick: a power of ten above every mesh node."""
    return 10 ** (len(str(int(ids.max()))) + 1)


def sphere_mesh_cards(nodes, elements, ids, lift, slave_z):
    """The *NODE, *ELEMENT, *NSET and *SURFACE cards of visco2d's mesh lifted by `lift` and the plate.

    Sets: NSPHERE (the mesh's nodes), NPLATE (the brick's), ESPHERE (CAX4), EPLATE (one C3D8),
    AXIS (the nodes on r = 0); surfaces SSLAVE (the outer boundary edges, not on the axis, with
    both nodes at z <= slave_z) and SPLATE (the brick's top face y = 0). Returns (lines, slave faces).
    """
    lines = ["*NODE, NSET=NSPHERE"]
    for i, (r, z) in enumerate(nodes):
        lines.append(f"{ids[i]}, {r:.15g}, {z + lift:.15g}")
    # the rigid plate: one fixed C3D8 brick under y = 0 (CalculiX's axial direction), across the
    # 2-degree sector of the expansion
    rmax = nodes[:, 0].max()
    x0, x1, y0, y1, zz = -0.3 * rmax, 1.5 * rmax, -0.2 * rmax, 0.0, 0.2 * rmax
    base = plate_node_base(ids)
    plate = [(x0, y0, -zz), (x1, y0, -zz), (x1, y1, -zz), (x0, y1, -zz),
             (x0, y0, zz), (x1, y0, zz), (x1, y1, zz), (x0, y1, zz)]
    lines.append("*NODE, NSET=NPLATE")
    for k, (x, y, z) in enumerate(plate):
        lines.append(f"{base + k + 1}, {x:.15g}, {y:.15g}, {z:.15g}")
    lines.append("*ELEMENT, TYPE=CAX4, ELSET=ESPHERE")
    for e, conn in enumerate(elements):
        lines.append(f"{e + 1}, " + ", ".join(str(ids[n]) for n in conn))
    lines.append("*ELEMENT, TYPE=C3D8, ELSET=EPLATE")
    lines.append(f"{base + 1}, " + ", ".join(str(base + k + 1) for k in range(8)))
    axis = [ids[i] for i in range(len(nodes)) if abs(nodes[i, 0]) < 1e-12]
    lines.append("*NSET, NSET=AXIS")
    lines += [", ".join(str(a) for a in axis[i:i + 10]) for i in range(0, len(axis), 10)]
    # slave surface: the element edges on the outer boundary (not on the axis) below slave_z
    count = {}
    for e, conn in enumerate(elements):
        for f in range(4):
            a, b = conn[f], conn[(f + 1) % 4]
            count.setdefault(tuple(sorted((a, b))), []).append((e, f))
    lines.append("*SURFACE, NAME=SSLAVE, TYPE=ELEMENT")
    nslave = 0
    for (a, b), users in count.items():
        if len(users) != 1:
            continue
        if abs(nodes[a, 0]) < 1e-12 and abs(nodes[b, 0]) < 1e-12:
            continue
        if max(nodes[a, 1], nodes[b, 1]) > slave_z:
            continue
        e, f = users[0]
        lines.append(f"{e + 1}, S{f + 1}")
        nslave += 1
    # the plate's top face y = 0: the brick's face S5 (nodes 3-7-8-4), outward normal +y
    lines += ["*SURFACE, NAME=SPLATE, TYPE=ELEMENT", f"{base + 1}, S5"]
    return lines, nslave


def slave_nodes(nodes, elements, slave_z):
    """Indices (from 0) of the nodes of the slave surface that sphere_mesh_cards writes."""
    count = {}
    for e, conn in enumerate(elements):
        for f in range(4):
            a, b = conn[f], conn[(f + 1) % 4]
            count.setdefault(tuple(sorted((a, b))), []).append(e)
    out = set()
    for (a, b), users in count.items():
        if len(users) != 1 or (abs(nodes[a, 0]) < 1e-12 and abs(nodes[b, 0]) < 1e-12):
            continue
        if max(nodes[a, 1], nodes[b, 1]) > slave_z:
            continue
        out.update((a, b))
    return sorted(out)


def material_cards(E, nu, rho, plastic, Y, Et):
    """FLESH (elastic, with the bilinear *PLASTIC curve if plastic) and the stiff PLATE, with their sections."""
    lines = ["*MATERIAL, NAME=FLESH", "*ELASTIC", f"{E:.10g}, {nu:.10g}", "*DENSITY", f"{rho:.10g}"]
    if plastic:
        lines.append(ccx_plastic_card(Y, E, Et).rstrip())
    lines += ["*MATERIAL, NAME=PLATE", "*ELASTIC", f"{1000 * E:.10g}, 0.3", "*DENSITY", f"{rho:.10g}",
              "*SOLID SECTION, ELSET=ESPHERE, MATERIAL=FLESH",
              "*SOLID SECTION, ELSET=EPLATE, MATERIAL=PLATE"]
    return lines


def contact_cards(penalty, sigma_inf):
    """The frictionless node-to-surface penalty contact of SSLAVE on SPLATE, slope K = penalty (Pa/m)."""
    return ["*SURFACE INTERACTION, NAME=FRICTIONLESS",
            "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
            f"{penalty:.6g}, {sigma_inf:.6g}",
            "*CONTACT PAIR, INTERACTION=FRICTIONLESS, TYPE=NODE TO SURFACE",
            "SSLAVE, SPLATE"]


# ---------------------------------------------------------------- Gauss-point fields
def gauss_point_index(block):
    """(element from 0, visco2d's 2D Gauss point k) of each row of an *EL PRINT block of the expanded
    C3D8 (columns element, point, ...): the 8 points are 4 pairs across the sector, k = i + 2 j."""
    rows = np.asarray(block)
    m = (rows[:, 1] - 1).astype(int)
    e = (rows[:, 0] - 1).astype(int)
    return e, (m % 2) + 2 * ((m // 2) % 2)


def stored_energy(S, w, E, nu):
    """The stored elastic energy sum w (p^2/2K + s:s/4G) of an *EL PRINT stress block (whole body;
    each 2D point appears twice, across the sector: half its weight each)."""
    e, k2 = gauss_point_index(S)
    S = np.asarray(S)
    Kb = E / (3 * (1 - 2 * nu))
    Gs = E / (2 * (1 + nu))
    sig = S[:, 2:8]
    pm = sig[:, :3].mean(axis=1)
    dev = sig[:, :3] - pm[:, None]
    ss = (dev ** 2).sum(axis=1) + 2 * (sig[:, 3:6] ** 2).sum(axis=1)
    dens = pm ** 2 / (2 * Kb) + ss / (4 * Gs)
    return float((0.5 * w[e, k2] * dens).sum())


def peeq_field(P, nelem):
    """(nelem, 4) PEEQ at visco2d's Gauss points from an *EL PRINT PEEQ block (the larger of a pair)."""
    e, k2 = gauss_point_index(P)
    pe = np.zeros((nelem, 4))
    np.maximum.at(pe, (e, k2), np.asarray(P)[:, 2])
    return pe


def gauss_field(block, column, nelem):
    """(nelem, 4) one column of an *EL PRINT block at visco2d's Gauss points (the mean of a pair)."""
    e, k2 = gauss_point_index(block)
    total = np.zeros((nelem, 4))
    count = np.zeros((nelem, 4))
    np.add.at(total, (e, k2), np.asarray(block)[:, column])
    np.add.at(count, (e, k2), 1.0)
    return total / np.maximum(count, 1.0)


def node_average(field, elements, node):
    """A Gauss-point field extrapolated bilinearly to the corners of each element (the 2x2 points as the
    corners of a square of half-side 1/sqrt(3)) and averaged over the elements at `node`, as visco2d's
    stress recovery (q_surface_MPa) does."""
    corners = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
    signs = [(-1, -1), (1, -1), (-1, 1), (1, 1)]       # point k = i + 2 j
    values = []
    for e in np.nonzero((elements == node).any(axis=1))[0]:
        a = int(np.nonzero(elements[e] == node)[0][0])
        xi, eta = corners[a]
        L = [0.25 * (1 + math.sqrt(3) * xi * sx) * (1 + math.sqrt(3) * eta * sy) for sx, sy in signs]
        values.append(float(np.dot(L, field[e])))
    return float(np.mean(values))


def plastic_work(pe, w, Y, H):
    """sum w (Y pe + H pe^2 / 2) = int sigma_y d(pe) dV, the plastic dissipation of J2 plasticity with
    linear isotropic hardening (exact for any path with that curve)."""
    return float((w * (Y * pe + 0.5 * H * pe ** 2)).sum())


# ---------------------------------------------------------------- tables
def fmt(x):
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "-"
    if isinstance(x, str):
        return x
    if x == 0:
        return "0"
    return f"{x:.4g}"


def rel(a, b):
    if a is None or b is None or isinstance(a, str) or isinstance(b, str):
        return "-"
    if b == 0:
        return "-"
    return f"{(a - b) / abs(b) * 100:+.1f} %"


# ---------------------------------------------------------------- a body on a deformable pad
def boundary_faces(nodes, elements, slave_z):
    """(element from 0, face from 0) of the outer boundary edges of visco2d's mesh, not on the axis, with
    both nodes at z <= slave_z: the faces of sphere_mesh_cards' SSLAVE surface (face f joins corners f, f + 1)."""
    count = {}
    for e, conn in enumerate(elements):
        for f in range(4):
            a, b = conn[f], conn[(f + 1) % 4]
            count.setdefault(tuple(sorted((a, b))), []).append((e, f))
    out = []
    for (a, b), users in count.items():
        if len(users) != 1:
            continue
        if abs(nodes[a, 0]) < 1e-12 and abs(nodes[b, 0]) < 1e-12:
            continue
        if max(nodes[a, 1], nodes[b, 1]) > slave_z:
            continue
        out.append(users[0])
    return out


def body_mesh_cards(nodes, elements, ids, lift, slave_z):
    """The *NODE, *ELEMENT, *NSET and *SURFACE cards of visco2d's mesh lifted by `lift`, without the rigid
    plate of sphere_mesh_cards: sets NSPHERE, ESPHERE, AXIS; surface SSLAVE (the same faces).
    Returns (lines, number of slave faces)."""
    lines = ["*NODE, NSET=NSPHERE"]
    for i, (r, z) in enumerate(nodes):
        lines.append(f"{ids[i]}, {r:.15g}, {z + lift:.15g}")
    lines.append("*ELEMENT, TYPE=CAX4, ELSET=ESPHERE")
    for e, conn in enumerate(elements):
        lines.append(f"{e + 1}, " + ", ".join(str(ids[n]) for n in conn))
    axis = [ids[i] for i in range(len(nodes)) if abs(nodes[i, 0]) < 1e-12]
    lines.append("*NSET, NSET=AXIS")
    lines += [", ".join(str(a) for a in axis[i:i + 10]) for i in range(0, len(axis), 10)]
    faces = boundary_faces(nodes, elements, slave_z)
    lines.append("*SURFACE, NAME=SSLAVE, TYPE=ELEMENT")
    lines += [f"{e + 1}, S{f + 1}" for e, f in faces]
    return lines, len(faces)
