"""One picture per case (`make report`): the impact and the bruise of a visco2d run.

For every case folder (OUT/<case>/ holding a results.h5; all of OUT's
sub-folders by default, or the folders named) writes OUT/<case>/report.png
with the panels that apply to the run:

  alpha(t), F(t), q(t)   deformation, plate force and pole pressure against time
                         since first contact (dynamic runs with a plate that touched
                         it), maxima marked, the elastic Hertz impact dashed
  p(r)                   contact pressure over radius at the largest force and at
                         maximum deformation (/pressure, dynamic runs with contact)
  envelope               the time envelope of the BRUISE criterion (nodal, /bruise)
                         as a filled contour over the undeformed r-z half section,
                         the bruised region outlined (the threshold contour), the
                         envelope maximum marked: whole section and a zoom
  numbers                the key numbers of /summary (alpha_m, t_m, q_m, F_max,
                         bruise volume, depths, radius, susceptibility, ...)

A run with neither contact nor a BRUISE card has nothing to report: it is
listed as skipped. A folder named on the command line that is not a case (no
results.h5, or not a visco2d results file) stops the script with status 1.

usage: report.py [--out DIR] [CASE ...]   (CASE: a folder, or a case name under DIR)
"""
import argparse
import math
import os
import sys
import textwrap

import numpy as np

from . import figures  # the project's matplotlib style
from . import hertz
from .case import NotACase, read_results
from .figures import plt, mtri, MaxNLocator
from matplotlib.collections import PolyCollection

REPORT_NAME = "report.png"
DOTS_MAX = 600           # bruised Gauss points drawn as dots in the zoom up to this many (more hide the field)
TITLE_WIDTH = 140        # characters per title line (the figure is 17 inches wide at 11.5 pt)
# the BRUISE criterion -> (the /bruise measure, its label, display unit, factor from the file's unit)
MEASURES = {
    "MAXSHEAR": ("max_shear", "maximum shear (σ₁ − σ₃)/2", "MPa", 1e-6),
    "MISES": ("von_mises", "von Mises stress", "MPa", 1e-6),
    "OCTAHEDRAL": ("octahedral", "octahedral shear stress", "MPa", 1e-6),
    "ENERGY": ("energy_density", "strain-energy density", "J/cm³", 1e-6),
    # the failed flesh: the final equivalent plastic strain (its envelope: it never decreases)
    "PLASTIC": ("equivalent_plastic_strain", "equivalent plastic strain ε̄p", "%", 100.0),
}



def fail(message):
    """Print an error message on stderr and stop with status 1."""
    print(f"report: error: {message}", file=sys.stderr)
    sys.exit(1)


# ----------------------------------------------------------------------------- reading a case

def load_case(folder):
    """Read OUT/<case>/results.h5 (visco2d.case.read_results); NotACase with the reason if it is not a case."""
    return read_results(folder)


def number(case, key):
    """A summary key as a float, or None when it is missing or not a number."""
    value = case["summary"].get(key)
    if isinstance(value, (int, float, np.integer, np.floating)) and math.isfinite(float(value)):
        return float(value)
    return None


def has_contact(case):
    """True for a dynamic run with a plate whose body touched it (history t_ms, alpha_mm, force_N, q_MPa)."""
    history = case["history"]
    return (number(case, "time_first_contact_s") is not None
            and all(name in history for name in ("t_ms", "alpha_mm", "force_N", "q_MPa"))
            and np.count_nonzero(history["t_ms"] >= 0.0) >= 2)


def bruise_measure(case):
    """(criterion, measure, label, unit, factor) of the envelope to draw: the first criterion of
    bruise_criterion (a deck may give one per material); without a BRUISE card, the plastic strain
    of a PLASTIC run (which keeps no stress envelope then), else the largest shear stress's."""
    plastic_only = case.get("bruise") is not None and "max_shear_envelope" not in case["bruise"] \
        and "equivalent_plastic_strain" in case["bruise"]
    criteria = str(case["summary"].get("bruise_criterion", "PLASTIC" if plastic_only else "MAXSHEAR"))
    criteria = criteria.replace(" ", "").split(",")
    criterion = criteria[0].upper() if criteria[0].upper() in MEASURES else "MAXSHEAR"
    return (criterion,) + MEASURES[criterion] + (len(set(criteria)) > 1,)


def gauss_to_nodes(values, elements, nnode):
    """Nodal mean over a node's elements of the value at their Gauss point nearest the node
    (Gauss point k is nearest corner k: the `_nodal` rule of /bruise)."""
    total = np.zeros(nnode)
    count = np.zeros(nnode)
    np.add.at(total, elements.ravel(), values.ravel())
    np.add.at(count, elements.ravel(), 1.0)
    return total / np.maximum(count, 1.0)


# ----------------------------------------------------------------------------- panels

def hertz_curves(case, t_end_ms):
    """The elastic Hertz impact of the summary's hertz_* keys: t (ms), alpha (mm), F (N), q (MPa); None if absent."""
    keys = ("hertz_young_Pa", "hertz_poisson", "hertz_radius_m", "hertz_mass_kg", "hertz_speed_m_s")
    values = [number(case, key) for key in keys]
    if any(value is None for value in values) or min(values[2:]) <= 0.0:
        return None
    young, poisson, radius, mass, speed = values
    t, alpha, q = hertz.exact(young, poisson, radius, mass, speed, t_end_ms * 1e-3, steps=1500)
    stiffness = 4.0 / 3.0 * young / (1.0 - poisson ** 2) * math.sqrt(radius)    # F = k alpha^1.5
    return t * 1e3, alpha * 1e3, stiffness * np.maximum(alpha, 0.0) ** 1.5, q * 1e-6


def time_panels(case, axes):
    """alpha(t), F(t), q(t) after first contact on three axes, maxima from the summary marked."""
    history = case["history"]
    keep = history["t_ms"] >= 0.0
    t = history["t_ms"][keep]
    end_of_time = str(case["summary"].get("stop_reason", "")) == "end of time"
    t_alpha = number(case, "t_alpha_max_ms")
    hertz = hertz_curves(case, max(t.max(), number(case, "hertz_t_alpha_max_ms") or 0.0) * 1.05)
    panels = (("alpha_mm", "deformation α (mm)", "mm", "alpha_max_mm", "t_alpha_max_ms", "C0", 1),
              ("force_N", "plate force F (N, whole body)", "N", "force_max_N", "t_force_max_ms", "C1", 2),
              ("q_MPa", "pole pressure q (MPa)", "MPa", "q_max_MPa", "t_q_max_ms", "C3", 3))
    for ax, (name, label, unit, key, tkey, colour, index) in zip(axes, panels):
        value = history[name][keep]
        ax.plot(t, value, "-", color=colour, lw=2.0, label="FE")
        if hertz is not None:
            ax.plot(hertz[0], hertz[index], "--", color="0.45", lw=1.2, label="Hertz, elastic (hertz_* keys)")
        peak, t_peak = number(case, key), number(case, tkey)
        if peak is None or t_peak is None:           # an older results.h5: the largest sample
            k = int(np.argmax(value))
            peak, t_peak = float(value[k]), float(t[k])
        what = "last sample" if (end_of_time and name == "alpha_mm") else "max"
        ax.plot([t_peak], [peak], "o", color=colour, ms=6, zorder=5)
        ax.text(0.03, 0.96, f"{what} {peak:.4g} {unit} at {t_peak:.2f} ms", transform=ax.transAxes, va="top",
                color=colour, fontsize=10, bbox=dict(boxstyle="round,pad=0.25", fc="w", ec=colour, alpha=0.9))
        if t_alpha is not None and name != "alpha_mm":
            ax.axvline(t_alpha, color="0.3", lw=0.8, ls=":", label=f"t of max α ({t_alpha:.2f} ms)")
        ax.set_xlim(0.0, max(t.max(), hertz[0].max() if hertz is not None else 0.0))
        top = max(value.max(), hertz[index].max() if hertz is not None else 0.0)
        ax.set_ylim(min(0.0, value.min() * 1.05), top * 1.3 if top > 0 else 1.0)
        ax.set_xlabel("time since first contact (ms)")
        ax.set_ylabel(label)
        ax.legend(loc="lower center", fontsize=8)
    axes[0].set_title("deformation α(t)" + (" (stop criterion not reached)" if end_of_time else ""))
    axes[1].set_title("plate force F(t)")
    axes[2].set_title("maximum surface pressure q(t)")


def pressure_panel(case, ax):
    """p(r) at the largest plate force and at maximum deformation (/pressure), Hertz's p0 sqrt(1 - r²/a²)."""
    p = case["pressure"]
    edge_shown = False
    for rkey, pkey, tkey, colour, marker, what in (
            ("r_force_max_mm", "p_force_max_MPa", "t_force_max_ms", "C1", "o", "at maximum force"),
            ("r_alpha_max_mm", "p_alpha_max_MPa", "t_alpha_max_step_ms", "C0", "s", "at maximum deformation")):
        if rkey in p and pkey in p:
            t = number(case, tkey)
            r, pressure = np.asarray(p[rkey]), np.asarray(p[pkey])
            touching = np.flatnonzero(pressure > 0.0)
            edge = touching[-1] if touching.size > 1 else None     # the outermost node in contact
            inner = slice(0, edge) if edge is not None else slice(None)
            ax.plot(r[inner], pressure[inner], "-" + marker, color=colour, lw=1.6, ms=5,
                    mfc="none" if marker == "s" else colour,
                    label=f"FE {what}" + (f", t = {t:.2f} ms" if t is not None else ""))
            if edge is not None:
                ax.plot([r[edge]], [pressure[edge]], "D", color=colour, mfc="none", ms=7, mew=1.4)
                edge_shown = True
    if edge_shown:      # pressure.csv's last node in contact (doc/outputs.md): not drawn as a pressure
        ax.plot([], [], "D", color="0.3", mfc="none", ms=7, mew=1.4,
                label="outermost node in contact: its reaction carries the contact\n"
                      "out to the true edge, its area only the edge inside (reads high)")
    p0, a = number(case, "hertz_q_max_MPa"), number(case, "hertz_contact_radius_mm")
    if p0 is not None and a is not None and a > 0.0:
        r = np.linspace(0.0, a, 200)
        ax.plot(r, p0 * np.sqrt(1.0 - (r / a) ** 2), "--", color="0.45", lw=1.2,
                label=f"Hertz at its maximum: p₀ = {p0:.3g} MPa, a = {a:.3g} mm")
    ax.set_xlim(left=0.0)
    ax.set_ylim(0.0, ax.get_ylim()[1] * (1.75 if edge_shown else 1.35))   # room for the legend above the curves
    ax.set_xlabel("radius r (mm, deformed)")
    ax.set_ylabel("contact pressure p (MPa)")
    ax.set_title("contact pressure p(r)")
    ax.legend(loc="upper right", fontsize=7.5)


def envelope_data(case):
    """What the envelope panels draw: nodal envelope (display unit), nodal envelope/threshold ratio,
    the bruised Gauss points and the envelope maximum (all positions in mm, undeformed)."""
    bruise = case["bruise"]
    criterion, measure, label, unit, factor, mixed = bruise_measure(case)
    plastic = criterion == "PLASTIC"
    gauss_key = measure if plastic else f"{measure}_envelope"
    nodal_key = f"{gauss_key}_nodal"
    if nodal_key not in bruise or gauss_key not in bruise:
        raise NotACase(f"{case['path']}: /bruise has no {nodal_key} or {gauss_key}")
    envelope = bruise[gauss_key]
    threshold = bruise.get("threshold", np.zeros_like(envelope))
    if plastic:   # the strain threshold may be 0 (any plastic flow): the flesh assessed is /bruise/assessed
        assessed = bruise.get("assessed", np.ones_like(envelope)) > 0.0
        ratio = np.zeros_like(envelope)          # no ratio to outline: the bruised points are outlined
    else:
        assessed = threshold > 0.0
        ratio = np.where(assessed, envelope / np.where(assessed, threshold, 1.0), 0.0)
    nnode = len(case["nodes"])
    data = {"criterion": criterion, "measure": measure, "label": label, "unit": unit, "mixed": mixed or plastic,
            "nodal": bruise[nodal_key] * factor,
            # the outline: envelope/threshold = 1 (the element's own threshold; with one criterion)
            "ratio": gauss_to_nodes(ratio, case["elements"], nnode),
            "bruised_nodal": gauss_to_nodes(bruise["bruised"].astype(float), case["elements"], nnode)
            if "bruised" in bruise else None,
            "threshold": float(threshold[assessed].max()) * factor
            if assessed.any() and threshold[assessed].max() > 0.0 else None,
            "uniform_threshold": assessed.any() and np.ptp(threshold[assessed]) == 0.0,
            # elements no BRUISE card assesses (a PAD's): drawn grey, not in the colour scale
            "outside": ~assessed.any(axis=1) if assessed.any() else np.zeros(len(envelope), bool),
            "outside_label": "pad (not flesh: not assessed)" if "pad_compression_max_mm" in case["summary"]
            else "not assessed (no BRUISE card)"}
    gauss_r = bruise.get("gauss_r")
    gauss_z = bruise.get("gauss_z")
    if gauss_r is not None and gauss_z is not None:
        bruised = bruise.get("bruised", np.zeros_like(envelope)) > 0
        data["bruised_points"] = (gauss_r[bruised] * 1e3, gauss_z[bruised] * 1e3)
        # the maximum over the assessed flesh (a PAD's elements are not assessed), else everywhere
        searched = np.where(assessed, envelope, -np.inf) if assessed.any() else envelope
        k = np.unravel_index(int(np.argmax(searched)), envelope.shape)
        data["peak"] = (gauss_r[k] * 1e3, gauss_z[k] * 1e3, envelope[k] * factor)
    else:
        k = int(np.argmax(data["nodal"]))
        data["bruised_points"] = None
        data["peak"] = (case["nodes"][k, 0] * 1e3, case["nodes"][k, 1] * 1e3, data["nodal"][k])
    return data


def dots_drawn(data):
    """Whether the zoom marks the bruised Gauss points: some, and not so many that they hide the field."""
    return data["bruised_points"] is not None and 0 < data["bruised_points"][0].size <= DOTS_MAX


def zoom_box(case, data):
    """(width, height) in mm of the zoom on the contact region: the bruise and the contact with a margin."""
    nodes = case["nodes"] * 1e3
    size = [number(case, key) for key in ("bruise_radius_max_mm", "bruise_depth_bottom_mm",
                                          "contact_radius_max_mm", "contact_radius_mm")]
    peak_r, peak_z = data["peak"][0], data["peak"][1] - nodes[:, 1].min()
    extent = max([value for value in size if value is not None] + [peak_r, peak_z, 1e-9])
    side = min(1.35 * extent, nodes[:, 0].max() - nodes[:, 0].min(), nodes[:, 1].max() - nodes[:, 1].min())
    return side, side


def envelope_panel(case, data, ax, box=None):
    """The envelope contour on the undeformed mesh (box: zoom (width, height) in mm from the pole)."""
    nodes = case["nodes"] * 1e3
    elements = case["elements"]
    triangles = np.vstack([elements[:, [0, 1, 2]], elements[:, [0, 2, 3]]])
    outside = data["outside"]
    grid = mtri.Triangulation(nodes[:, 0], nodes[:, 1], triangles, mask=np.concatenate([outside, outside]))
    flesh = np.unique(elements[~outside])
    top = max(float(data["nodal"][flesh].max()), data["peak"][2])
    levels = MaxNLocator(20).tick_values(0.0, top if top > 0 else 1.0)
    filled = ax.tricontourf(grid, data["nodal"], levels=levels, cmap="viridis")
    if outside.any():
        ax.add_collection(PolyCollection(nodes[elements[outside]], facecolor="0.82", edgecolor="0.6", lw=0.3))
    if box is not None:
        ax.triplot(grid, color="w", lw=0.25, alpha=0.35)
    outline = None
    if not data["mixed"] and data["ratio"].max() >= 1.0 and data["ratio"].min() < 1.0:
        outline = ax.tricontour(grid, data["ratio"], levels=[1.0], colors="r", linewidths=2.2)
    elif data["bruised_nodal"] is not None and data["bruised_nodal"].max() > 0.5 > data["bruised_nodal"].min():
        outline = ax.tricontour(grid, data["bruised_nodal"], levels=[0.5], colors="r", linewidths=2.2)
    if box is not None and dots_drawn(data):
        ax.plot(*data["bruised_points"], ".", color="r", ms=2.5, zorder=4)
    ax.plot([data["peak"][0]], [data["peak"][1]], "*", color="w", mec="k", mew=0.8, ms=16, zorder=6)
    plate = number(case, "plate_z_m")
    if plate is not None:
        ax.axhline(plate * 1e3, color="k", lw=2.0)
    z_low = nodes[:, 1].min()
    if box is None:
        ax.set_xlim(nodes[:, 0].min(), nodes[:, 0].max() * 1.02)
        ax.set_ylim(z_low - 0.02 * np.ptp(nodes[:, 1]), nodes[:, 1].max() + 0.01 * np.ptp(nodes[:, 1]))
    else:
        ax.set_xlim(nodes[:, 0].min(), nodes[:, 0].min() + box[0])
        ax.set_ylim(z_low - 0.03 * box[1], z_low + box[1])
    ax.set_aspect("equal")
    ax.grid(False)
    axial = case["geometry"].upper().startswith("AXI")
    ax.set_xlabel("r (mm)" if axial else "x (mm)")
    ax.set_ylabel("z (mm), undeformed" if axial else "y (mm), undeformed")
    return filled, outline


def envelope_panels(case, data, fig, whole_spec, zoom_spec, bar_spec):
    """Whole section (small) and zoom, one colour bar, a legend of the marks."""
    whole = fig.add_subplot(whole_spec)
    filled, _ = envelope_panel(case, data, whole)
    whole.set_title("envelope, whole section" if zoom_spec is not None
                    else f"envelope of the {data['label']}, whole section", fontsize=10)
    axes = [whole]
    if zoom_spec is not None:
        zoom = fig.add_subplot(zoom_spec)
        box = zoom_box(case, data)
        envelope_panel(case, data, zoom, box)
        nodes = case["nodes"] * 1e3
        whole.add_patch(plt.Rectangle((nodes[:, 0].min(), nodes[:, 1].min()), box[0], box[1],
                                      fill=False, ec="w", lw=1.2, ls="--"))
        zoom.set_title(f"envelope of the {data['label']}, contact region (dashed box)", fontsize=10)
        axes.append(zoom)
    bar = fig.colorbar(filled, cax=fig.add_subplot(bar_spec))
    bar.set_label(f"largest {data['label']} over the run ({data['unit']}, nodal)")
    if data["threshold"] is not None:
        bar.ax.axhline(data["threshold"], color="r", lw=2.2)
    outline = ("bruised region: envelope = threshold" if not data["mixed"]
               else "bruised region (bruised Gauss points, nodal mean 0.5)")
    if "bruise_criterion" not in case["summary"]:
        outline = "no BRUISE card (no outline)"
    elif data["bruised_points"] is not None and data["bruised_points"][0].size == 0:
        outline = "nothing bruised (no outline)"
    elif data["ratio"].min() >= 1.0:
        outline = "all the section bruised (no outline)"
    handles = [plt.Line2D([], [], color="r", lw=2.2, label=outline),
               plt.Line2D([], [], ls="none", marker="*", color="w", mec="k", ms=12,
                          label=f"envelope maximum {data['peak'][2]:.3g} {data['unit']}")]
    if data["outside"].any():
        handles.append(plt.Rectangle((0, 0), 1, 1, fc="0.82", ec="0.6", label=data["outside_label"]))
    if len(axes) > 1 and dots_drawn(data):
        handles.insert(1, plt.Line2D([], [], ls="none", marker=".", color="r", ms=6, label="bruised Gauss points"))
    axes[-1].legend(handles=handles, loc="upper right", fontsize=8.5, framealpha=0.9)


def numbers_text(case, data):
    """The key numbers of the summary, one per line."""
    s = lambda key: number(case, key)  # noqa: E731
    lines = []
    if has_contact(case):
        v = s("impact_velocity_m_s")
        if v is not None:
            lines.append(f"impact velocity V = {v:.4g} m/s")
        alpha, t_alpha = s("alpha_max_mm"), s("t_alpha_max_ms")
        if alpha is not None:
            stopped = str(case["summary"].get("stop_reason", ""))
            what, when = ("α at the last sample", "t") if stopped == "end of time" else ("α_m", "t_m")
            lines.append(f"{what} = {alpha:.4g} mm at {when} = {t_alpha:.3g} ms")
            if stopped == "end of time":
                lines.append("  (TEND reached before the stop criterion)")
        for key, tkey, name, unit in (("q_max_MPa", "t_q_max_ms", "q_m", "MPa"),
                                      ("force_max_N", "t_force_max_ms", "F_max", "N")):
            if s(key) is not None:
                lines.append(f"{name} = {s(key):.4g} {unit} at {s(tkey):.3g} ms")
        if s("contact_radius_max_mm") is not None:
            lines.append(f"largest contact radius {s('contact_radius_max_mm'):.3g} mm")
        if s("contact_duration_ms") is not None:
            lines.append(f"contact {s('contact_duration_ms'):.3g} ms, restitution "
                         f"{s('coefficient_of_restitution'):.3f}")
        if s("energy_absorbed_J") is not None:
            lines.append(f"energy absorbed {s('energy_absorbed_J') * 1e3:.4g} mJ")
        if s("plastic_dissipation_J") is not None:          # a PLASTIC flesh (doc/plasticity.md)
            lines.append(f"plastic work {s('plastic_dissipation_J') * 1e3:.4g} mJ, largest ε̄p "
                         f"{100 * s('equivalent_plastic_strain_max'):.3g} %")
        if s("residual_flattening_mm") is not None:
            lines.append(f"residual flattening of the pole {s('residual_flattening_mm'):.3g} mm")
    elif s("force_N") is not None:                    # a static run on the plate
        lines.append(f"static, plate force {s('force_N'):.4g} N")
        for key, name, unit in (("alpha_mm", "approach α", "mm"), ("q_MPa", "pole pressure q", "MPa"),
                                ("contact_radius_mm", "contact radius", "mm")):
            if s(key) is not None:
                lines.append(f"{name} = {s(key):.4g} {unit}")
    if data is not None:
        if lines:
            lines.append("")
        suffix = "cm³" if case["geometry"].upper().startswith("AXI") else "cm³/m"
        key_suffix = "cm3" if suffix == "cm³" else "cm3_per_m"
        threshold = s("bruise_threshold_Pa")
        threshold_text = (f"{threshold * 1e-6:.3g} MPa" if threshold is not None else
                          f"{s('bruise_threshold_J_m3') * 1e-6:.3g} J/cm³" if s("bruise_threshold_J_m3") is not None
                          else f"ε̄p > {100 * s('bruise_threshold_strain'):.3g} %"
                          if s("bruise_threshold_strain") is not None else "per material")
        if "bruise_criterion" in case["summary"]:
            lines.append(f"BRUISE {case['summary']['bruise_criterion']}, threshold {threshold_text}")
        else:
            lines.append("no BRUISE card: no region assessed")
        volume = s(f"bruise_volume_{key_suffix}")
        if volume is not None:
            assessed = s(f"bruise_assessed_volume_{key_suffix}")
            share = f" ({100 * volume / assessed:.3g} % of the flesh)" if assessed else ""
            lines.append(f"bruise volume {volume:.4g} {suffix}{share}")
        top, bottom = s("bruise_depth_top_mm"), s("bruise_depth_bottom_mm")
        if top is not None and bottom is not None:
            below = "the pole" if number(case, "plate_z_m") is not None or s("force_N") is not None \
                else "the lowest point"
            lines.append(f"depth {top:.3g} to {bottom:.3g} mm below {below}")
        if s("bruise_radius_max_mm") is not None:
            lines.append(f"largest radius {s('bruise_radius_max_mm'):.3g} mm "
                         f"(diameter {2 * s('bruise_radius_max_mm'):.3g} mm)")
        first = s("bruise_time_first_s")
        if first is not None and has_contact(case):
            lines.append(f"first failure at {(first - s('time_first_contact_s')) * 1e3:.3g} ms after contact")
        index = 1
        while any(s(f"bruise_threshold_{index}_{unit}") is not None for unit in ("Pa", "J_m3", "strain")):
            value = s(f"bruise_threshold_{index}_Pa")
            text = (f"{value * 1e-6:.3g} MPa" if value is not None
                    else f"{s(f'bruise_threshold_{index}_J_m3') * 1e-6:.3g} J/cm³"
                    if s(f"bruise_threshold_{index}_J_m3") is not None
                    else f"ε̄p > {100 * s(f'bruise_threshold_{index}_strain'):.3g} %")
            extra = s(f"bruise_volume_threshold_{index}_{key_suffix}")
            lines.append(f"  at {text}: {extra:.4g} {suffix}" if extra is not None else f"  at {text}")
            index += 1
        if s("bruise_susceptibility_cm3_per_J") is not None:
            lines.append(f"susceptibility {s('bruise_susceptibility_cm3_per_J'):.4g} cm³/J")
        r_peak, z_peak, value = data["peak"]
        # below the body's lowest point; on a PAD (its nodes lie lower) that is the pad's top, the plate's z
        on_pad = s("pad_compression_max_mm") is not None and s("plate_z_m") is not None
        lowest = s("plate_z_m") if on_pad else case["nodes"][:, 1].min()
        depth = z_peak - lowest * 1e3
        lines.append(f"envelope max {value:.3g} {data['unit']}")
        radial = "r" if case["geometry"].upper().startswith("AXI") else "x"
        lines.append(f"  at {radial} = {r_peak:.3g} mm, depth {depth:.3g} mm")
    elif lines:
        lines += ["", "no BRUISE card in the deck: no envelope"]
    warnings = s("warnings")
    if warnings:
        lines.append("")
        lines.append(f"warnings: {warnings:.0f} (see summary.txt)")
    return "\n".join(lines)


# ----------------------------------------------------------------------------- one case

def wrapped(text, width):
    """text in lines of at most `width` characters: at spaces, and a longer word (a case name,
    a path) at its last _ or / that fits, else at the width."""
    lines = []
    for piece in textwrap.wrap(text, width, break_long_words=False, break_on_hyphens=False) or [""]:
        while len(piece) > width:
            cut = max(piece.rfind("_", 0, width), piece.rfind("/", 0, width)) + 1 or width
            lines.append(piece[:cut])
            piece = piece[cut:]
        lines.append(piece)
    return lines


def title_lines(name, setting, path, width=TITLE_WIDTH):
    """The report's title: case and title, the setting, the results file, each wrapped to `width`."""
    return "\n".join(wrapped(name, width) + wrapped(setting, width) + wrapped(f"({path})", width))


def report(case, path):
    """Draw the report of one case into path (written whole: a temporary file, then renamed).
    Returns False (nothing written) when no panel applies."""
    contact = has_contact(case)
    data = envelope_data(case) if case["bruise"] is not None else None
    if not contact and data is None and number(case, "force_N") is None:
        return False
    pressure = contact and case["pressure"] is not None and len(case["pressure"].get("r_mm", [])) > 0
    plate = number(case, "plate_z_m") is not None or number(case, "force_N") is not None   # dynamic, static
    if contact:
        fig = plt.figure(figsize=(17, 10.5 if data is not None else 9.5))
        if data is not None:
            spec = fig.add_gridspec(2, 5, width_ratios=[1, 1, 1, 0.9, 0.04], height_ratios=[1, 1.35],
                                    left=0.05, right=0.95, bottom=0.06, top=0.88, wspace=0.3, hspace=0.25)
            time_axes = [fig.add_subplot(spec[0, k]) for k in range(3)]
            pressure_ax = fig.add_subplot(spec[1, 0]) if pressure else None
            envelope_panels(case, data, fig, spec[1, 3], spec[1, 1:3], spec[1, 4])
            text_ax = fig.add_subplot(spec[0, 3:])
        else:
            spec = fig.add_gridspec(2, 3, left=0.06, right=0.98, bottom=0.07, top=0.88, wspace=0.28, hspace=0.3)
            time_axes = [fig.add_subplot(spec[0, k]) for k in range(3)]
            pressure_ax = fig.add_subplot(spec[1, 0]) if pressure else None
            text_ax = fig.add_subplot(spec[1, 1])
        time_panels(case, time_axes)
        if pressure_ax is not None:
            pressure_panel(case, pressure_ax)
    else:
        fig = plt.figure(figsize=(17, 7.5))
        if data is not None:
            if plate:
                spec = fig.add_gridspec(1, 4, width_ratios=[1.0, 1.5, 0.9, 0.04], left=0.02, right=0.94,
                                        bottom=0.09, top=0.86, wspace=0.25)
                envelope_panels(case, data, fig, spec[0, 2], spec[0, 1], spec[0, 3])
            else:                                   # no contact region to zoom on: the whole section, larger
                spec = fig.add_gridspec(1, 3, width_ratios=[1.0, 1.5, 0.04], left=0.02, right=0.94,
                                        bottom=0.09, top=0.86, wspace=0.25)
                envelope_panels(case, data, fig, spec[0, 1], None, spec[0, 2])
            text_ax = fig.add_subplot(spec[0, 0])
        else:
            text_ax = fig.add_subplot(1, 1, 1)
    text_ax.axis("off")
    text_ax.text(0.0, 1.0, numbers_text(case, data), va="top", ha="left", fontsize=10, linespacing=1.45,
                 transform=text_ax.transAxes,
                 bbox=dict(boxstyle="round,pad=0.5", fc="0.96", ec="0.7"))
    stop = case["summary"].get("stop_reason")
    setting = (f"{case['summary'].get('analysis', '')} {case['geometry'].lower()}, {figures.mesh_label(case)}"
               + (f", plate {case['summary'].get('plate', '')}" if "plate" in case["summary"] else "")
               + (f", stopped at {stop}" if stop else ""))
    fig.suptitle(title_lines(f"{case['case']}: {case['title']}", setting, case["path"]), fontsize=11.5)
    temporary = path + ".part.png"
    try:
        fig.savefig(temporary)
        os.replace(temporary, path)
    finally:
        plt.close(fig)
        if os.path.exists(temporary):
            os.remove(temporary)
    return True


# ----------------------------------------------------------------------------- main

def case_folders(args):
    """The folders to report: those named (a folder, or a name under --out), else every sub-folder of
    --out with a results.h5."""
    if args.cases:
        folders = []
        for name in args.cases:
            folder = name if os.path.isdir(name) else os.path.join(args.out, name)
            folders.append(folder if os.path.isdir(folder) else name)
        return folders
    if not os.path.isdir(args.out):
        fail(f"output root {args.out} not found: run the decks first (make run) or pass --out")
    folders = sorted(os.path.join(args.out, name) for name in os.listdir(args.out)
                     if os.path.isfile(os.path.join(args.out, name, "results.h5")))
    if not folders:
        fail(f"no case folder (a sub-folder with results.h5) in {args.out}: run the decks first (make run)")
    return folders


def main():
    """Parse the options, draw every case's report and print the files written."""
    parser = argparse.ArgumentParser(prog="visco2d-report", description=__doc__.split("\n\n")[0],
                                     epilog="writes <case folder>/report.png")
    parser.add_argument("--out", default="out", help="output root of the runs (default: out)")
    parser.add_argument("cases", nargs="*", metavar="CASE",
                        help="case folders (or case names under --out); default: every case in --out")
    args = parser.parse_args()
    folders = case_folders(args)
    try:
        cases = [load_case(folder) for folder in folders]      # every folder checked before any drawing
    except NotACase as problem:
        fail(str(problem))
    written, skipped = [], []
    for case in cases:
        path = os.path.join(case["folder"], REPORT_NAME)
        try:
            drawn = report(case, path)
        except NotACase as problem:
            fail(str(problem))
        (written if drawn else skipped).append(path if drawn else case["folder"])
    for folder in skipped:
        print(f"report: {folder}: skipped (no plate contact, no BRUISE card: no panel applies)")
    print(f"report: {len(written)} files written:")
    for path in written:
        print(f"  {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
