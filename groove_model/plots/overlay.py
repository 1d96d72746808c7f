"""Overlays of regime boundaries in the style of the paper's Figure 2.

``dr_limit`` solid (double rolling below, rolling sliding above), ``dr_no_roll`` dot-dashed and
``rs_no_roll`` dashed (clockwise rolling on the low-gamma side, counter-clockwise on the high);
``rs_limit`` coincides with ``dr_limit`` and is not drawn again. Friction coefficients are told
apart by line weight (thin to thick with increasing ``k``, as in the paper) and colour. The
legend says in words what each line and marker is; the regions are named where they are the
same for every ``k`` drawn; the axes reach from the domain's corner ``(0, 0)`` to ``pi/2`` in
``gamma`` and to the highest point drawn in ``delta``.
"""

from __future__ import annotations

import math
from pathlib import Path

from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from ..io.atomic import atomic_write_all
from ..model.parameters import Compliance, Parameters, k_text
from ..tracing import BoundarySet
from .files import figure_files
from .labels import label_regions, region_label_positions

__all__ = ["LINESTYLES", "MARKER_LABELS", "STYLE_LABELS", "draw_boundaries", "save_overlay"]

LINESTYLES = {"dr_limit": "-", "dr_no_roll": "-.", "rs_no_roll": "--"}
#: The legend's words for each line style.
STYLE_LABELS = {
    "dr_limit": "T = kN on the steeper wall: double rolling below, rolling sliding above",
    "dr_no_roll": r"no rotation ($\upsilon = 0$) in double rolling: clockwise to its left",
    "rs_no_roll": r"no rotation ($\upsilon = 0$) in rolling sliding: clockwise to its left",
}
#: The legend's words for each marker of a special point.
MARKER_LABELS = {
    "start": "start of a boundary",
    "end": "end of a boundary",
    "junction": "junction of the limit and a no-rotation line",
    "fold_gamma": r"turning point in $\gamma$",
    "fold_delta": r"highest point ($\delta$ turns back)",
    "branch_point": r"branch point on the axis $\delta = 0$",
}
DIAGONAL_LABEL = r"edge $\delta = \gamma$ (right wall horizontal)"
_MARKERS = {"start": "o", "end": "s", "junction": "D", "fold_gamma": "^", "fold_delta": "v",
            "branch_point": "*"}
# Okabe & Ito's colour-blind-safe palette.
_COLOURS = ("#000000", "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9")
_HALF_PI = 0.5 * math.pi


def _frame(item):
    return item.to_frame() if isinstance(item, BoundarySet) else item


def _key(frame) -> tuple[float, float]:
    """``(k, c)`` of a frame: what tells two traces apart (a file without the compliance
    column has the paper's ``c = 1``)."""
    c = float(frame["compliance"].iloc[0]) if "compliance" in frame.columns else 1.0
    return float(frame["k"].iloc[0]), c


def _key_text(key: tuple[float, float], with_c: bool) -> str:
    k, c = key
    return f"k = {k_text(k)}" + (f", c = {c:.4g}" if with_c else "")


def _drawn_rows(frame, name: str, physical_only: bool):
    rows = frame[frame["boundary"] == name]
    return rows[rows["physical"].astype(bool)] if physical_only else rows


def delta_top(frames, physical_only: bool = True) -> float:
    """The upper ``delta`` limit of the axes (radians): the highest point drawn plus a margin,
    at most ``pi/2`` (the domain's top); ``pi/4`` when nothing is drawn."""
    highest = max((float(_drawn_rows(f, name, physical_only)["delta"].max())
                   for f in frames if len(f) for name in LINESTYLES
                   if len(_drawn_rows(f, name, physical_only))), default=0.25 * math.pi)
    return min(_HALF_PI, 1.06 * highest + 0.02)


def draw_boundaries(ax, boundary_sets, degrees: bool = False, special_points: bool = True,
                    physical_only: bool = True):
    """Draw the boundaries of one or more ``k`` onto a matplotlib ``Axes``.

    The axes get limits from the domain and the data (``0 <= gamma <= pi/2``,
    ``0 <= delta <=`` :func:`delta_top`), labels, and a legend in words below them.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    boundary_sets : sequence of BoundarySet or pandas.DataFrame
        Traced boundaries (DataFrames with the CSV columns, e.g. read back from files). A
        failed ``BoundarySet`` raises ``TraceError``; ``b.to_frame(partial=True)`` draws what
        it traced.
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
    ks = sorted({_key(f) for f in frames if len(f)})
    scale = (180.0 / math.pi) if degrees else 1.0
    unit = "deg" if degrees else "rad"
    top = _HALF_PI * scale
    artists = ax.plot([0, top], [0, top], color="0.6", lw=0.8, ls=":", label=DIAGONAL_LABEL)
    for frame in frames:
        if len(frame):
            artists += _draw_frame(ax, frame, ks, scale, special_points, physical_only)
    ax.set_xlim(0, top)
    ax.set_ylim(0, delta_top(frames, physical_only) * scale)
    ax.set_xlabel(rf"$\gamma = (\theta_L + \theta_R)/2$ ({unit})")
    ax.set_ylabel(rf"$\delta = (\theta_L - \theta_R)/2$ ({unit})")
    ax.set_aspect("equal")
    _legend(ax, special_points)
    return artists


def _draw_frame(ax, frame, ks: list, scale: float, special_points: bool,
                physical_only: bool) -> list:
    """The curves of one ``(k, c)``, its weight and colour from its rank among ``ks``."""
    key = _key(frame)
    rank = ks.index(key)
    width = 0.9 + 1.6 * rank / max(1, len(ks) - 1) if len(ks) > 1 else 1.5
    colour = _COLOURS[rank % len(_COLOURS)]
    artists: list = []
    label: str | None = _key_text(key, any(c != 1.0 for _, c in ks))
    for name, style in LINESTYLES.items():
        rows = _drawn_rows(frame, name, physical_only)
        if not len(rows):
            continue
        artists += ax.plot(rows["gamma"] * scale, rows["delta"] * scale, ls=style, lw=width,
                           color=colour, label=label)
        label = None
        if not special_points:
            continue
        for kind, marker in _MARKERS.items():
            sel = rows[rows["point"].astype(str) == kind]
            if len(sel):
                artists.append(ax.scatter(
                    sel["gamma"] * scale, sel["delta"] * scale, marker=marker,
                    s=60 if kind == "branch_point" else 28, color=colour, zorder=3,
                    clip_on=False, edgecolors="white", linewidths=0.5))
    return artists


def _legend(ax, special_points: bool) -> None:
    """One entry per k, then the line styles and markers explained once, in black, below the
    axes where they cover nothing."""
    handles, labels = ax.get_legend_handles_labels()
    for name, style in LINESTYLES.items():
        handles.append(Line2D([], [], color="0.2", ls=style))
        labels.append(STYLE_LABELS[name])
    if special_points:
        for kind, marker in _MARKERS.items():
            handles.append(Line2D([], [], color="0.2", marker=marker, ls=""))
            labels.append(MARKER_LABELS[kind])
    ax.legend(handles, labels, fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14),
              ncol=2, frameon=False)


def save_overlay(boundary_sets, path, degrees: bool = False, formats=("png", "svg"),
                 regions: bool = True) -> list:
    """Draw an overlay, with a title and the regions named, and write it atomically in each
    format.

    ``path`` may end in ``.png``, ``.svg`` or ``.pdf`` (replaced by each format) or have no
    such suffix (the format's is appended, so names like ``boundaries_k0.5`` stay whole).
    ``regions`` names the regions that are the same for every ``k`` (classified with the point
    solver for each ``k``, the paper's compliance). SVG output is deterministic (fixed
    ``svg.hashsalt``, no date).
    """
    path = Path(path)
    stem = path.with_suffix("") if path.suffix.lower() in (".png", ".svg", ".pdf") else path
    frames = [_frame(b) for b in boundary_sets]
    # The axes' height follows the data (equal aspect, 6.3 in for pi/2); legend, title and
    # axis labels need about 2.1 in.
    fig = Figure(figsize=(7.0, 2.1 + 6.3 * delta_top(frames) / _HALF_PI), layout="constrained")
    ax = fig.subplots()
    draw_boundaries(ax, boundary_sets, degrees=degrees)
    params = [b.params or Parameters(b.k) if isinstance(b, BoundarySet)
              else Parameters(_key(b)[0], Compliance(_key(b)[1]))
              for b in boundary_sets if len(_frame(b))]
    keys = sorted({(p.k, p.c) for p in params})
    if regions:
        scale = (180.0 / math.pi) if degrees else 1.0
        label_regions(ax, region_label_positions(params, top=delta_top(frames)), scale)
    if all(c == 1.0 for _, c in keys):
        title = "friction coefficient k = " + ", ".join(k_text(k) for k, _ in keys)
    else:
        title = "; ".join(_key_text(key, True) for key in keys) + " (c: compliance ratio)"
    ax.set_title("Regime boundaries of a ball in a groove, " + title, fontsize=10)
    files = []
    for fmt in formats:
        # the path as given for its own format (x.PNG stays x.PNG), the stem + suffix else
        own = path.suffix.lower() == f".{fmt}"
        target = path if own else stem.parent / f"{stem.name}.{fmt}"
        files.append((target, fmt))
    return atomic_write_all(figure_files(fig, files, dpi=150))  # every format or none
