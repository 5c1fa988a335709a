#!/usr/bin/env python3
"""Draw the mesh of a case from its results.h5 (optionally the deformed mesh).

usage: plot_mesh.py out/<case>/results.h5 [mesh.png] [--deformed SCALE]
"""
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402


def main():
    args = sys.argv[1:]
    if not args:
        print(__doc__)
        return 2
    scale = 0.0
    if "--deformed" in args:
        k = args.index("--deformed")
        scale = float(args[k + 1])
        del args[k:k + 2]
    path = args[0]
    output = args[1] if len(args) > 1 else path.replace("results.h5", "mesh.png")
    with h5py.File(path, "r") as f:
        nodes = f["/mesh/nodes"][...]
        elements = f["/mesh/elements"][...] - 1
        title = f.attrs["title"]
        title = title.decode() if isinstance(title, bytes) else str(title)
        if scale:
            last = sorted(f["/fields"].keys())[-1]
            nodes = nodes + scale * f[f"/fields/{last}/displacement"][...]
    fig, ax = plt.subplots(figsize=(5, 8))
    polygons = [nodes[e] * 1000.0 for e in elements]
    ax.add_collection(PolyCollection(polygons, facecolors="none", edgecolors="k", linewidths=0.4))
    ax.autoscale()
    ax.set_aspect("equal")
    ax.set_xlabel("r (mm)")
    ax.set_ylabel("z (mm)")
    ax.set_title(f"{title}\n{len(elements)} elements, {len(nodes)} nodes", fontsize=9)
    fig.tight_layout()
    fig.savefig(output, dpi=150)
    print(output)
    return 0


if __name__ == "__main__":
    sys.exit(main())
