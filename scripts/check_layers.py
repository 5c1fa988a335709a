#!/usr/bin/env python3
"""Check that the source tree keeps its floors.

src/ is grouped in floors, from the bottom up (see doc/architecture.md):

  core      kinds, errors, strings, the results record, timers, progress
  model     what the legacy program computes with: the material law and the
            relaxation, the parent quadrilateral, the mesh (mesh_t) and its
            bandwidth renumbering
  mesh      making a mesh: the generators (sphere, spheroid, rectangle,
            ring), the outline grid, the overlap tests
  cards     reading the input file: the card reader, the cards of every
            kind, the mesh built from its cards, the pad mesh, the deck
            (deck_t) and its checks, the estimate
  base      the legacy static program: element, viscoelastic law, banded
            matrices, assembly, static and quasi-static solution
  io        writing the results (text, CSV, HDF5, XDMF)
  bruise    bruise prediction from the stress and strain fields
  finite    finite deformation: hyperelastic laws (neo-Hookean, Mooney-Rivlin,
            hyperfoam), the large-deformation element and its Newton solution
  contact   the rigid plate: contact conditions, capacitance system, impact
  dynamics  the time integration (Wilson-theta and its family)
  (src/)    the driver, which runs a deck through all of them

A module may use modules of its own floor and of the floors below it, never
one above: the base imports nothing of the extensions. Every Fortran file
under src/ must be in one of the floors.

The reach: for every module of the base floor, the modules it depends on
at compile time (the transitive closure of its `use` statements) must all
be of the core, model and base floors (BASE_FLOORS): the legacy program
compiles against the model alone, never the reader (the mesh and cards
floors, deck_t) nor an extension. Their number must not outgrow the
budget in REACH below, and a base module not in REACH fails too. The
budgets are the reach measured when they were last lowered (lower a
budget when a module's reach shrinks; doc/architecture.md).

Prints one PASS/FAIL line per file and per base module, and exits 1 on any
violation.

usage: check_layers.py [SRC_DIR]
"""
import os
import re
import sys

# The largest reach (modules) of each base module.
REACH = {
    "visco2d_assembly": 10,
    "visco2d_banded": 2,
    "visco2d_cholmod": 3,
    "visco2d_constitutive": 5,
    "visco2d_element": 2,
    "visco2d_factor": 5,
    "visco2d_field_summary": 14,
    "visco2d_profile": 3,
    "visco2d_quasistatic": 23,
    "visco2d_solve_errors": 7,
    "visco2d_static": 20,
    "visco2d_stress_recovery": 5,
    "visco2d_viscoelastic": 2,
}

# The floors a base module may reach.
BASE_FLOORS = ("core", "model", "base")
FLOORS = ["core", "model", "mesh", "cards", "base", "plasticity", "finite", "io", "bruise", "contact", "dynamics", ""]
USE = re.compile(r"^\s*use\s+(visco2d_\w+)", re.IGNORECASE | re.MULTILINE)
MODULE = re.compile(r"^\s*module\s+(visco2d_\w+)\s*$", re.IGNORECASE | re.MULTILINE)


def main():
    src = sys.argv[1] if len(sys.argv) > 1 else "src"
    floor_of, uses, path_of = {}, {}, {}
    failures = 0
    for root, _, files in os.walk(src):
        floor = os.path.relpath(root, src)
        floor = "" if floor == "." else floor
        for name in sorted(files):
            if not name.endswith((".f90", ".F90")):
                continue
            path = os.path.join(root, name)
            if floor not in FLOORS:
                print(f"FAIL layers {path}: folder {floor!r} is not a floor ({', '.join(f for f in FLOORS if f)})")
                failures += 1
                continue
            text = open(path, encoding="utf-8").read()
            for module in MODULE.findall(text):
                floor_of[module.lower()] = floor
                path_of[module.lower()] = path
            uses[path] = (floor, sorted({u.lower() for u in USE.findall(text)}))
    for path, (floor, used) in sorted(uses.items()):
        level = FLOORS.index(floor)
        above = [u for u in used if u in floor_of and FLOORS.index(floor_of[u]) > level]
        unknown = [u for u in used if u not in floor_of]
        if above or unknown:
            failures += 1
            details = [f"uses {u} from floor {floor_of[u] or 'src'} above {floor or 'src'}" for u in above]
            details += [f"uses {u}, which no file under {src} defines" for u in unknown]
            print(f"FAIL layers {path}: " + "; ".join(details))
        else:
            print(f"PASS layers {path}")
    module_uses = {}
    for path, (floor, used) in uses.items():
        for module in MODULE.findall(open(path, encoding="utf-8").read()):
            module_uses[module.lower()] = [u for u in used if u != module.lower()]
    for module in sorted(m for m, f in floor_of.items() if f == "base"):
        reached = reach(module, module_uses)
        outside = sorted(m for m in reached if floor_of.get(m) not in BASE_FLOORS)
        if module not in REACH:
            failures += 1
            print(f"FAIL reach {module}: no budget in scripts/check_layers.py REACH (reaches {len(reached)} modules)")
            continue
        if outside:
            failures += 1
            print(f"FAIL reach {module}: reaches {len(outside)} module(s) outside the core, model and base floors: "
                  + ", ".join(f"{m} ({floor_of[m] or 'src'})" for m in outside))
        elif len(reached) > REACH[module]:
            failures += 1
            print(f"FAIL reach {module}: reaches {len(reached)} modules, budget {REACH[module]}; "
                  f"it now also depends on more of the code")
        else:
            print(f"PASS reach {module}: {len(reached)} modules (core, model and base only), budget {REACH[module]}")
    return 1 if failures else 0


def reach(module, module_uses):
    """The modules `module` depends on at compile time, transitively."""
    seen, stack = set(), [module]
    while stack:
        for used in module_uses.get(stack.pop(), []):
            if used not in seen:
                seen.add(used)
                stack.append(used)
    seen.discard(module)
    return seen


if __name__ == "__main__":
    sys.exit(main())
