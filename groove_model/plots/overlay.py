"""Overlays of regime boundaries in the style of the paper's Figure 2.

``dr_limit`` solid (double rolling below, rolling sliding above), ``dr_no_roll`` dot-dashed and
``rs_no_roll`` dashed (clockwise rolling on the low-gamma side, counter-clockwise on the high);
``rs_limit`` coincides with ``dr_limit`` and is not drawn again. Friction coefficients are told
apart by line weight (thin to thick with increasing ``k``, as in the paper) and colour.
"""

from __future__ import annotations

import math
from pathlib import Path

import matplotlib
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from ..io.export import atomic_write
from ..tracing import BoundarySet

__all__ = ["LINESTYLES", "STYLE_LABELS", "draw_boundaries", "save_overlay"]

LINESTYLES = {"dr_limit": "-", "dr_no_roll": "-.", "rs_no_roll": "--"}
#: The legend's words for each line style.
STYLE_LABELS = {"dr_limit": "T = kN (DR | RS)", "dr_no_roll": r"$\upsilon = 0$ in DR",
                "rs_no_roll": r"$\upsilon = 0$ in RS"}
_MARKERS = {"start": "o", "end": "s", "junction": "D", "fold_gamma": "^", "branch_point": "*"}
# Okabe & Ito's colour-blind-safe palette.
_COLOURS = ("#000000", "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9")


def _frame(item):
    return item.to_frame() if isinstance(item, BoundarySet) else item


def draw_boundaries(ax, boundary_sets, degrees: bool = False, special_points: bool = True,
                    physical_only: bool = True):
    """Draw the boundaries of one or more ``k`` onto a matplotlib ``Axes``.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    boundary_sets : sequence of BoundarySet or pandas.DataFrame
        Traced boundaries (DataFrames with the CSV columns, e.g. read back from files).
    degrees : bool
        Axes in degrees instead of radians.
    special_points : bool
        Mark the special points (from the ``point`` column).
    physical_only : bool
        Skip rows flagged unphysical.

    Returns
    -------
    list of matplotlib artists
    """
    frames = [_frame(b) for b in boundary_sets]
    ks = sorted({float(f["k"].iloc[0]) for f in frames if len(f)})
    scale = (180.0 / math.pi) if degrees else 1.0
    unit = "deg" if degrees else "rad"
    artists = []
    top = 0.5 * math.pi * scale
    artists += ax.plot([0, top], [0, top], color="0.6", lw=0.8, ls=":", label=r"$\delta = \gamma$")
    for frame in frames:
        if not len(frame):
            continue
        k = float(frame["k"].iloc[0])
        rank = ks.index(k)
        width = 0.9 + 1.6 * rank / max(1, len(ks) - 1) if len(ks) > 1 else 1.5
        colour = _COLOURS[rank % len(_COLOURS)]
        first = True
        for name, style in LINESTYLES.items():
            rows = frame[frame["boundary"] == name]
            if physical_only:
                rows = rows[rows["physical"].astype(bool)]
            if not len(rows):
                continue
            label = f"k = {k:g}" if first else None
            first = False
            artists += ax.plot(rows["gamma"] * scale, rows["delta"] * scale, ls=style, lw=width,
                               color=colour, label=label)
            if special_points:
                marked = rows[rows["point"].astype(str) != ""]
                for kind, marker in _MARKERS.items():
                    sel = marked[marked["point"] == kind]
                    if len(sel):
                        artists.append(ax.scatter(
                            sel["gamma"] * scale, sel["delta"] * scale, marker=marker,
                            s=60 if kind == "branch_point" else 28, color=colour, zorder=3,
                            clip_on=False, edgecolors="white", linewidths=0.5))
    ax.set_xlim(0, top)
    ax.set_ylim(0, top * 0.55)
    ax.set_xlabel(rf"$\gamma = (\theta_L + \theta_R)/2$ ({unit})")
    ax.set_ylabel(rf"$\delta = (\theta_L - \theta_R)/2$ ({unit})")
    ax.set_aspect("equal")
    # Line styles and markers explained once, in black.
    handles, labels = ax.get_legend_handles_labels()
    for name, style in LINESTYLES.items():
        handles.append(Line2D([], [], color="0.2", ls=style))
        labels.append(STYLE_LABELS[name])
    if special_points:
        for kind, marker in _MARKERS.items():
            handles.append(Line2D([], [], color="0.2", marker=marker, ls=""))
            labels.append(kind.replace("_", " "))
    ax.legend(handles, labels, fontsize=7, loc="upper left", ncol=2, frameon=False)
    return artists


def save_overlay(boundary_sets, path, degrees: bool = False, formats=("png", "svg")) -> list:
    """Draw an overlay and write it atomically in each format.

    ``path`` may end in ``.png``, ``.svg`` or ``.pdf`` (replaced by each format) or have no
    such suffix (the format's is appended, so names like ``boundaries_k0.5`` stay whole).
    SVG output is deterministic (fixed ``svg.hashsalt``, no date).
    """
    path = Path(path)
    stem = path.with_suffix("") if path.suffix.lower() in (".png", ".svg", ".pdf") else path
    fig = Figure(figsize=(7.0, 4.6), layout="constrained")
    ax = fig.subplots()
    draw_boundaries(ax, boundary_sets, degrees=degrees)
    ks = sorted({float(_frame(b)["k"].iloc[0]) for b in boundary_sets if len(_frame(b))})
    ax.set_title("Regime boundaries of a ball in a groove, k = "
                 + ", ".join(f"{k:g}" for k in ks), fontsize=10)
    written = []
    for fmt in formats:
        target = stem.parent / f"{stem.name}.{fmt}"
        with matplotlib.rc_context({"svg.hashsalt": "groove"}):
            written.append(atomic_write(target, lambda tmp, f=fmt: fig.savefig(
                tmp, format=f, dpi=150, metadata={"Date": None} if f == "svg" else None)))
    return written
