"""Draw the mesh of a case from its results.h5 (optionally the deformed mesh).

usage: plot_mesh.py out/<case>/results.h5 [more.h5 ...] [mesh.png] [--deformed SCALE] [--pole MM]

Several results.h5 files are drawn side by side (e.g. the same deck with
MESH SPHERE GRID=CONTACT and GRID=LEGACY). --pole MM adds, below each mesh,
the region within MM millimetres of the lowest node (the contact pole of a
sphere). Elements with an interior angle outside 90 +- 45 degrees are
shaded, and each title gives the mesh's angle range.
"""
import math
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402


def angles(polygon):
    """Interior angles (degrees) of a quadrilateral."""
    result = []
    for c in range(4):
        ax, ay = polygon[c - 1][0] - polygon[c][0], polygon[c - 1][1] - polygon[c][1]
        bx, by = polygon[(c + 1) % 4][0] - polygon[c][0], polygon[(c + 1) % 4][1] - polygon[c][1]
        result.append(math.degrees(math.atan2(abs(ax * by - ay * bx), ax * bx + ay * by)))
    return result


def read(path, scale):
    with h5py.File(path, "r") as f:
        nodes = f["/mesh/nodes"][...]
        elements = f["/mesh/elements"][...] - 1
        title = f.attrs["title"]
        title = title.decode() if isinstance(title, bytes) else str(title)
        if scale:
            last = sorted(f["/fields"].keys())[-1]
            nodes = nodes + scale * f[f"/fields/{last}/displacement"][...]
    return nodes, elements, title


def draw(ax, polygons, bad):
    ax.add_collection(PolyCollection(polygons, facecolors=["#f4a582" if b else "none" for b in bad],
                                     edgecolors="k", linewidths=0.4))
    ax.set_aspect("equal")
    ax.set_xlabel("r (mm)")
    ax.set_ylabel("z (mm)")


def main():
    args = sys.argv[1:]
    if not args:
        print(__doc__)
        return 2
    scale = 0.0
    pole = 0.0
    for flag in ("--deformed", "--pole"):
        if flag in args:
            k = args.index(flag)
            value = float(args[k + 1])
            del args[k:k + 2]
            if flag == "--deformed":
                scale = value
            else:
                pole = value
    inputs = [a for a in args if a.endswith(".h5")]
    outputs = [a for a in args if not a.endswith(".h5")]
    if not inputs:
        print(__doc__)
        return 2
    output = outputs[0] if outputs else inputs[0].replace("results.h5", "mesh.png")
    rows = 2 if pole else 1
    fig, axes = plt.subplots(rows, len(inputs), figsize=(4.2 * len(inputs), 7.5 if not pole else 10.5),
                             squeeze=False, gridspec_kw={"height_ratios": [2, 1] if pole else [1]})
    for column, path in enumerate(inputs):
        nodes, elements, title = read(path, scale)
        polygons = [nodes[e] * 1000.0 for e in elements]
        element_angles = [angles(p) for p in polygons]
        bad = [min(a) < 45.0 or max(a) > 135.0 for a in element_angles]
        low = min(min(a) for a in element_angles)
        high = max(max(a) for a in element_angles)
        ax = axes[0][column]
        draw(ax, polygons, bad)
        ax.autoscale()
        ax.set_title(f"{title}\n{len(elements)} elements, {len(nodes)} nodes, angles {low:.0f}-{high:.0f} deg",
                     fontsize=8)
        if pole:
            ax = axes[1][column]
            draw(ax, polygons, bad)
            z0 = float(nodes[:, 1].min()) * 1000.0
            ax.set_xlim(0.0, pole)
            ax.set_ylim(z0, z0 + pole)
            ax.set_title(f"within {pole:g} mm of the pole", fontsize=8)
    fig.tight_layout()
    fig.savefig(output, dpi=130)
    print(output)
    return 0


if __name__ == "__main__":
    sys.exit(main())
