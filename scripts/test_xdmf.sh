#!/usr/bin/env bash
# results.xmf read by ParaView's own XDMF readers, every field checked against
# results.h5 (h5py), and the mesh warped by the displacement (Warp By Vector).
# Three cases: a dropped sphere with a BRUISE card (dynamic: velocity,
# acceleration, the envelopes), the static sphere under pressure and the
# plane-strain Lame cylinder. Readers (scripts/xdmf_read.py, one process per
# reader and case: a reader that aborts is a FAIL, not the end of the test):
#   - the `vtk` wheel (pip; scripts/setup.sh): vtkXdmfReader (its VTK has no XDMF3 reader)
#   - ParaView, when pvpython is installed (`bash scripts/setup.sh paraview`: Debian's
#     ParaView 5.11): the three reader proxies its File > Open offers for .xmf, XDMFReader
#     (vtkXdmfReader), Xdmf3ReaderS and Xdmf3ReaderT (vtkXdmf3Reader), and its Warp By Vector
# A reader that is not installed is a SKIP line (not a PASS).
# For every grid, each reader must give: the time of its /fields snapshot, the
# nodes (r, z, 0), the quads, the material, and every Attribute of results.xmf
# with the shape its Dimensions declare and the values of results.h5 (vectors
# (u_r, u_z, 0), the stress the 3x3 tensor [σ_r τ_rz 0; τ_rz σ_z 0; 0 0 σ_θ]);
# the warped points must be the nodes plus (u_r, u_z, 0). Values are compared
# exactly: each is the same double read from the same file.
# usage: scripts/test_xdmf.sh [EXE]   (prints PASS/FAIL/SKIP lines)
set -uo pipefail
cd "$(dirname "$0")/.."
exe=${1:-${VISCO2D:-build/install/bin/visco2d}}
tmp=build/test-tmp/xdmf
rm -rf "$tmp" && mkdir -p "$tmp"

pass() { echo "PASS $*"; }
fail() { echo "FAIL $*"; }

cp test/decks/bruise_drop.inp inputs/sphere_pressure.inp inputs/lame_plane_strain.inp "$tmp/"
cases="bruise_drop sphere_pressure lame_plane_strain"
if "$exe" -q -o "$tmp/out" "$tmp/bruise_drop.inp" "$tmp/sphere_pressure.inp" "$tmp/lame_plane_strain.inp" \
     > "$tmp/run.txt" 2>&1; then
  pass "xdmf_decks_ran"
else
  fail "xdmf_decks_ran: visco2d exited with status $? (see $tmp/run.txt)"
  exit 0
fi
if ! python3 -c "import h5py, numpy" > /dev/null 2>&1; then
  echo "SKIP xdmf readers: h5py is not installed (bash scripts/setup.sh)"
  exit 0
fi

# read CASE with READER under PYTHON (a command); then compare with results.h5
check_reader() {
  local label=$1 reader=$2 case=$3
  shift 3
  local npz="$tmp/${label}_${reader}_${case}.npz" log="$tmp/${label}_${reader}_${case}.log"
  "$@" scripts/xdmf_read.py "$reader" "$tmp/out/$case" "$npz" > "$log" 2>&1
  local status=$?
  if [ $status -eq 2 ]; then
    echo "SKIP xdmf_${label}_${reader}: $(grep 'xdmf_read:' "$log" | head -1)"
    return 1
  elif [ $status -ne 0 ]; then
    fail "xdmf_${label}_${reader}_${case}_reads: exit $status: $(grep -v -E '^ |HDF5-DIAG|^\[|^[0-9]+ ' "$log" \
      | grep -i -E 'assert|error|abort|signal' | head -2 | tr '\n' ' ')"
    return 0
  fi
  pass "xdmf_${label}_${reader}_${case}_reads"
  python3 - "$label" "$reader" "$tmp/out/$case" "$npz" <<'EOF'
import os, sys
import xml.etree.ElementTree as ET
import h5py, numpy as np

label, reader, folder, npz = sys.argv[1:]
name = f"xdmf_{label}_{reader}_{os.path.basename(folder)}"
got = np.load(npz)
problems = {"steps": [], "times": [], "mesh": [], "shapes": [], "values": [], "warp": []}


def expected(group, bruise, field):
    """The nodal field `field` of results.xmf, from the /fields and /bruise datasets."""
    if field in ("displacement", "velocity", "acceleration"):
        values = group[field][()]
        return np.column_stack([values, np.zeros(len(values))])
    if field == "stress":   # sigma_r, sigma_z, sigma_theta, tau_rz -> the 3x3 tensor row by row
        s = group["stress"][()]
        zero = np.zeros(len(s))
        return np.column_stack([s[:, 0], s[:, 3], zero, s[:, 3], s[:, 1], zero, zero, zero, s[:, 2]])
    if field in group:
        return group[field][()]
    return bruise[field + "_nodal"][()]


grids = ET.parse(os.path.join(folder, "results.xmf")).getroot().findall("./Domain/Grid/Grid")
with h5py.File(os.path.join(folder, "results.h5"), "r") as f:
    names = sorted(f["/fields"])
    nodes = f["/mesh/nodes"][()]
    elements = f["/mesh/elements_0based"][()]
    material = f["/mesh/element_material"][()]
    bruise = f["/bruise"] if "/bruise" in f else None
    reported = int(got["steps_reported"])
    if not (reported == len(names) or (len(names) == 1 and reported == 0)) or len(grids) != len(names):
        problems["steps"].append(f"{reported} time steps, {len(grids)} grids, {len(names)} /fields snapshots")
    for k, snapshot in enumerate(names):
        if f"time_{k}" not in got:
            problems["steps"].append(f"no step {k} read")
            break
        group = f["/fields"][snapshot]
        if float(got[f"time_{k}"]) != float(group.attrs["time"]) and len(names) > 1:
            problems["times"].append(f"step {k}: {float(got[f'time_{k}'])} s, {snapshot} {float(group.attrs['time'])} s")
        points = got[f"points_{k}"]
        if not (points.shape == (len(nodes), 3) and np.array_equal(points[:, :2], nodes) and not points[:, 2].any()):
            problems["mesh"].append(f"step {k}: points {points.shape} not the nodes (r, z, 0)")
        if not (np.all(got[f"types_{k}"] == 9) and np.array_equal(got[f"offsets_{k}"], 4 * np.arange(len(elements) + 1))
                and np.array_equal(got[f"cells_{k}"], elements.ravel())):
            problems["mesh"].append(f"step {k}: cells not the quads of /mesh/elements_0based")
        if not np.array_equal(got.get(f"cell_material_{k}", np.array([])), material):
            problems["mesh"].append(f"step {k}: cell data 'material' missing or not /mesh/element_material")
        grid = grids[k]
        if grid.get("Name") != snapshot:
            problems["steps"].append(f"grid {k} is {grid.get('Name')}, not {snapshot}")
        for attribute in grid.findall("Attribute"):
            field = attribute.get("Name")
            if attribute.get("Center") != "Node":
                continue
            declared = tuple(int(n) for n in attribute.find("DataItem").get("Dimensions").split())
            key = f"point_{field}_{k}"
            if key not in got:
                problems["shapes"].append(f"{snapshot}/{field}: not read")
                continue
            if got[key].shape != declared:
                problems["shapes"].append(f"{snapshot}/{field}: read {got[key].shape}, declared {declared}")
                continue
            want = expected(group, bruise, field)
            if not np.array_equal(got[key], want):
                worst = np.max(np.abs(got[key] - want)) if got[key].shape == want.shape else None
                problems["values"].append(f"{snapshot}/{field}: {got[key].shape} differs from results.h5 "
                                          f"{want.shape} (largest difference {worst})")
        for field in group:   # every nodal field of /fields is shown (stress_gauss is per Gauss point)
            if field != "stress_gauss" and f"point_{field}_{k}" not in got:
                problems["values"].append(f"{snapshot}/{field}: in results.h5, not read from results.xmf")
        warped = got[f"warped_{k}"]
        want = np.column_stack([nodes + group["displacement"][()], np.zeros(len(nodes))])
        if not (warped.shape == want.shape and np.array_equal(warped, want)):
            problems["warp"].append(f"step {k}: warped points {warped.shape} not nodes + (u_r, u_z, 0)")
version = str(got["vtk_version"]) if "vtk_version" in got else "?"
for what, found in problems.items():
    verdict = "FAIL" if found else "PASS"
    print(f"{verdict} {name}_{what}" + (f": {'; '.join(found[:3])}" if found else "") + f" (VTK {version})")
EOF
  return 0
}

if python3 -c "import vtkmodules.vtkIOXdmf2" > /dev/null 2>&1; then
  for case in $cases; do
    check_reader wheel vtkXdmfReader "$case" python3
  done
  for case in $cases; do
    check_reader wheel vtkXdmf3Reader "$case" python3 || break
  done
else
  echo "SKIP xdmf_wheel: the vtk wheel is not installed (bash scripts/setup.sh installs it): VTK's readers not tried"
fi
if command -v pvpython > /dev/null 2>&1; then
  for reader in XDMFReader Xdmf3ReaderS Xdmf3ReaderT; do
    for case in $cases; do
      check_reader paraview "$reader" "$case" pvpython --force-offscreen-rendering || break
    done
  done
else
  echo "SKIP xdmf_paraview: no pvpython (bash scripts/setup.sh paraview installs ParaView 5.11): its readers not tried"
fi
