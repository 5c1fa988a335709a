#!/usr/bin/env python3
"""Draw the source floors of src/ (doc/floors.png for doc/architecture.md).

One box per floor, bottom up as scripts/check_layers.py stacks them, with
its modules and lines, and, per floor, how many of its `use` statements go
to each floor below (the arrows: a module uses its own floor and the floors
below, never one above). The base's floors (core, model, base: all a base
module may reach) are shaded.

usage: floors_picture.py [SRC_DIR] [PNG]      (defaults: src doc/floors.png)
"""
import collections
import os
import re
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from check_layers import BASE_FLOORS, FLOORS, MODULE, USE  # noqa: E402  (beside this script: sys.path[0])

WHAT = {
    "core": "kinds, errors, strings, the record, sorting",
    "model": "material law, relaxation, quadrilateral, mesh_t",
    "mesh": "generators, outline grid, overlap tests",
    "cards": "the reader, the cards, the deck, the pad mesh",
    "base": "the legacy static program: element, assembly, factors, solution",
    "plasticity": "J2 return mapping, the static plastic Newton solve",
    "io": "summary, CSV, HDF5, XDMF, listing",
    "bruise": "bruise prediction from the fields",
    "contact": "the rigid plate, capacitance system, impact, pad",
    "dynamics": "Wilson-θ and its family, the energy balance",
    "": "the driver: a deck through every stage",
}


def survey(src):
    """Per floor: modules, lines, and the count of its uses of each floor."""
    floor_of, files = {}, collections.defaultdict(list)
    for root, _, names in os.walk(src):
        floor = os.path.relpath(root, src)
        floor = "" if floor == "." else floor
        for name in sorted(names):
            if name.endswith((".f90", ".F90")) and floor in FLOORS:
                path = os.path.join(root, name)
                text = open(path, encoding="utf-8").read()
                files[floor].append(text)
                for module in MODULE.findall(text):
                    floor_of[module.lower()] = floor
    modules = {f: sum(len(MODULE.findall(t)) for t in files[f]) for f in FLOORS}
    lines = {f: sum(t.count("\n") for t in files[f]) for f in FLOORS}
    uses = {f: collections.Counter() for f in FLOORS}
    for floor in FLOORS:
        for text in files[floor]:
            for used in {u.lower() for u in USE.findall(text)}:
                if used in floor_of and floor_of[used] != floor:
                    uses[floor][floor_of[used]] += 1
    return modules, lines, uses


def draw(src, png):
    modules, lines, uses = survey(src)
    fig, ax = plt.subplots(figsize=(13.5, 0.62 * len(FLOORS) + 1.2))
    height, gap = 0.8, 0.22
    for level, floor in enumerate(FLOORS):
        y = level * (height + gap)
        shade = "#d6e6f5" if floor in BASE_FLOORS else "#f2f2f2"
        ax.add_patch(plt.Rectangle((0, y), 7.9, height, fc=shade, ec="0.35", lw=1.0))
        name = f"src/{floor}/" if floor else "src/ (top)"
        ax.text(0.12, y + height / 2, name, va="center", ha="left", fontsize=10.5, family="monospace",
                weight="bold")
        ax.text(2.25, y + height / 2, WHAT.get(floor, ""), va="center", ha="left", fontsize=9)
        ax.text(8.05, y + height / 2, f"{modules[floor]} module{'s' if modules[floor] != 1 else ''}, {lines[floor]} lines", va="center",
                ha="left", fontsize=9)
        below = sorted(uses[floor].items(), key=lambda item: -FLOORS.index(item[0]))
        if below:
            ax.text(10.3, y + height / 2, "uses " + ", ".join(f"{f or 'top'} ({n})" for f, n in below),
                    va="center", ha="left", fontsize=7.5, color="0.3")
    top = len(FLOORS) * (height + gap)
    ax.annotate("", xy=(-0.25, 0.0), xytext=(-0.25, top - gap), arrowprops=dict(arrowstyle="->", lw=1.5))
    ax.text(-0.4, top / 2, "a module uses its own floor and those below", rotation=90, va="center", ha="right",
            fontsize=9)
    ax.set_xlim(-0.9, 17.2)
    ax.set_ylim(-0.2, top)
    ax.axis("off")
    ax.set_title("visco2d's source floors, bottom up (shaded: all that the base may reach; "
                 "scripts/check_layers.py checks both rules)", fontsize=10.5)
    fig.tight_layout()
    fig.savefig(png, dpi=130)
    print(f"floors_picture: wrote {png}")


if __name__ == "__main__":
    draw(sys.argv[1] if len(sys.argv) > 1 else "src", sys.argv[2] if len(sys.argv) > 2 else "doc/floors.png")
