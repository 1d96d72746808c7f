r"""The regime map: the regions of the ``(gamma, delta)`` plane shaded, the boundaries on top.

The categories come from :mod:`groove_model.analysis.regimes`: four regions (double rolling and
rolling sliding, each clockwise or counter-clockwise) shaded in Paul Tol's colours, and the two
segments of the axis ``delta = 0`` drawn as thick lines. The boundaries traced by
:func:`groove_model.tracing.trace_boundaries` are drawn on top by
:func:`groove_model.plots.overlay.draw_boundaries`, and the seed points the paper names are
labelled.
"""

from __future__ import annotations

import logging
import math
from pathlib import Path

import numpy as np
from matplotlib.artist import Artist
from matplotlib.colors import to_rgba
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch, Polygon

from ..analysis.regimes import CATEGORIES, CATEGORY_CODE, OUTSIDE, check_resolution, classify_cells
from ..io.atomic import atomic_write_all
from ..model.lines import dr_limit_no_roll_point
from ..model.parameters import Parameters
from ..tracing import trace_boundaries
from .files import figure_files
from .labels import label_regions, region_label_positions
from .overlay import DIAGONAL_LABEL, MARKER_LABELS, STYLE_LABELS, draw_boundaries

__all__ = [
    "CATEGORY_COLOURS",
    "CATEGORY_LABELS",
    "MAP_RESOLUTION_MAX",
    "SEED_LEGEND",
    "draw_regime_map",
    "save_regime_map",
    "seed_points",
]

log = logging.getLogger(__name__)

#: most cells along each axis of a drawn map: the figure keeps about 110 bytes per cell while
#: it is drawn (1.8 GB at 4000), and a PNG shows no more than its own pixels (about 1000)
MAP_RESOLUTION_MAX = 5000

#: the legend's entry for the labelled points (open circles); ``, and the junction`` follows
#: where the junction is one of them
SEED_LEGEND = "labelled: the seed points of the boundaries"

CATEGORY_LABELS = {
    "double_rolling_clockwise": "double rolling, clockwise (down the steeper wall)",
    "double_rolling_counterclockwise": "double rolling, counter-clockwise (up the steeper wall)",
    "rolling_sliding_clockwise": "rolling sliding (steeper wall slides), clockwise",
    "rolling_sliding_counterclockwise": "rolling sliding (steeper wall slides), counter-clockwise",
    "double_sliding": r"double sliding ($\delta = 0$, $\gamma > \arctan k$)",
    "symmetric_no_rotation": r"symmetric, no rotation ($\delta = 0$, $\gamma \leq \arctan k$)",
    "no_rotation": r"no rotation ($\upsilon = 0$ exactly)",
}

#: Paul Tol's colour-blind-safe "light" scheme (made for shaded areas under black lines) for the
#: regions, and his "bright" scheme for the two segments of the axis.
CATEGORY_COLOURS = {
    "double_rolling_clockwise": "#77AADD",
    "double_rolling_counterclockwise": "#44BB99",
    "rolling_sliding_clockwise": "#EE8866",
    "rolling_sliding_counterclockwise": "#EEDD88",
    "double_sliding": "#AA3377",
    "symmetric_no_rotation": "#4477AA",
    "no_rotation": "#DDDDDD",
}

#: The two segments of the axis ``delta = 0``, drawn as lines rather than shaded.
_AXIS_SEGMENTS = ("symmetric_no_rotation", "double_sliding")
_HALF_PI = 0.5 * math.pi
_SQRT2 = math.sqrt(2.0)


def seed_points(k) -> dict:
    """The seed points the paper names, ``label -> (gamma, delta)`` in radians.

    ``(arctan(k/c), 0)`` (start of the double-rolling limit; ``(arctan k, 0)`` for the paper's
    compliance ``c = 1``), ``(arctan sqrt 2, 0)`` (branch point of the double-rolling
    ``upsilon = 0`` line), ``(pi/4, pi/4)`` (end of both ``upsilon = 0`` lines) and, for
    ``k > c sqrt 2``, the point of the double-rolling limit where ``upsilon = 0``. The labels
    are matplotlib mathtext.
    """
    return _seed_points(Parameters.coerce(k))


def _arctan(params: Parameters) -> str:
    """``arctan k`` in mathtext, ``arctan(k/c)`` for a compliance ratio ``c != 1``."""
    return r"\arctan k" if params.c == 1.0 else r"\arctan(k/c)"


def _category_label(name: str, params: Parameters) -> str:
    """The legend's text of region ``name`` (:data:`CATEGORY_LABELS`), with the axis segments
    split at ``arctan(k/c)`` where the compliance ratio ``c`` is not the paper's 1."""
    return CATEGORY_LABELS[name].replace(r"\arctan k", _arctan(params))


def _seed_label(params: Parameters) -> str:
    return rf"$({_arctan(params)},\,0)$"


_JUNCTION_LABEL = r"$\upsilon = 0$ on the limit"
_BRANCH_LABEL = r"$(\arctan\sqrt{2},\,0)$"


def _seed_points(params: Parameters) -> dict:
    points = {
        _seed_label(params): (params.gamma_limit, 0.0),
        _BRANCH_LABEL: (math.atan(_SQRT2), 0.0),
        r"$(\pi/4,\,\pi/4)$": (0.25 * math.pi, 0.25 * math.pi),
    }
    junction = dr_limit_no_roll_point(params)
    if junction is not None:
        points[_JUNCTION_LABEL] = (float(junction[0]), float(junction[1]))
    return points


def _drawn_seed_points(params: Parameters) -> dict:
    """The seed points labelled on the map: :func:`seed_points` but for the branch point
    ``(arctan sqrt 2, 0)`` where the double-rolling ``upsilon = 0`` line has no physical part
    (``k < c sqrt 2``, no junction): nothing is drawn there, and a circle on the
    double-sliding segment read as a point of a boundary."""
    points = _seed_points(params)
    if _JUNCTION_LABEL not in points:
        del points[_BRANCH_LABEL]
    return points


def _label_offsets(params: Parameters, points: dict) -> dict:
    """Where each seed label goes, in points from the seed, chosen to keep labels apart (the
    junction's to the right of the seed's where the two points are within 0.15 rad, for
    ``c sqrt 2 < k < 1.26 c sqrt 2`` or so). ``points``: :func:`_seed_points`."""
    k_first = params.gamma_limit < math.atan(_SQRT2)
    junction = points.get(_JUNCTION_LABEL)
    close = junction is not None and math.hypot(junction[0] - params.gamma_limit,
                                                junction[1]) < 0.15
    return {
        _seed_label(params): (-45, 30) if k_first else (-18, 28),
        _BRANCH_LABEL: (45, 30) if k_first else (-62, 40),
        r"$(\pi/4,\,\pi/4)$": (-82, 10),
        _JUNCTION_LABEL: (78, 34) if close else (22, 26),
    }


def _seed_label_area(params: Parameters, points: dict) -> list:
    """Points (radians) covered by the seed points and their labels, which the regions' names
    keep clear of (offsets converted at about 0.0037 rad per point, the default figure's)."""
    offsets = _label_offsets(params, points)
    area = []
    for label, (g, d) in points.items():
        dx, dy = offsets[label]
        steps = np.linspace(0.0, 1.0, 6)
        area += [(g + t * 0.0037 * dx, d + t * 0.0037 * (dy + 6)) for t in steps]
    return area


def _rgba(codes: np.ndarray) -> np.ndarray:
    table = np.array([to_rgba(CATEGORY_COLOURS[name]) for name in CATEGORIES] + [(0, 0, 0, 0)])
    return table[np.where(codes == OUTSIDE, len(CATEGORIES), codes)]


def _drawn_entries(boundary_set) -> set:
    """Legend texts of :func:`~groove_model.plots.overlay.draw_boundaries` for what it draws."""
    entries = set()
    for name, curve in boundary_set.curves.items():
        physical = np.asarray(curve.physical, dtype=bool)
        if name not in STYLE_LABELS or not physical.any():
            continue
        entries.add(STYLE_LABELS[name])
        entries.update(MARKER_LABELS[p.kind] for p in curve.special_points
                       if physical[p.index] and p.kind in MARKER_LABELS)
    return entries


def draw_regime_map(ax, k, n: int = 600, boundaries: bool = True, degrees: bool = False,
                    boundary_set=None, legend: bool = True) -> dict:
    r"""Shade the regimes for friction ``k`` onto a matplotlib ``Axes`` and overlay the boundaries.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    k : float or Parameters
        Friction coefficient, finite and > 0.
    n : int
        Cells along each axis of ``[0, pi/2]`` (each cell is classified at its centre),
        ``2 <= n <= MAP_RESOLUTION_MAX = 5000``.
    boundaries : bool
        Overlay the traced boundaries and their special points.
    degrees : bool
        Axes in degrees instead of radians.
    boundary_set : groove_model.tracing.BoundarySet, optional
        Boundaries already traced for this ``k``; traced here when omitted.
    legend : bool
        Add a legend naming each regime in words, the line styles and the point markers.

    Returns
    -------
    dict
        The artists: ``"image"`` (the shaded regions, an ``AxesImage`` clipped to the triangle),
        ``"segments"`` (the two segments of ``delta = 0``), ``"boundaries"`` (from
        :func:`groove_model.plots.overlay.draw_boundaries`), ``"regions"`` (the names written
        in the regions), ``"seeds"`` (markers and labels of the seed points), ``"legend"``, and
        ``"boundary_set"``, the traced boundaries (or None).

    Raises
    ------
    ValueError
        If ``k`` or ``n`` is outside its allowed range.
    """
    params = Parameters.coerce(k)
    n = check_resolution(n, MAP_RESOLUTION_MAX)
    return _draw(ax, params, n, boundaries, degrees, boundary_set, legend)


def _draw(ax, params: Parameters, n: int, boundaries: bool, degrees: bool, boundary_set,
          legend: bool) -> dict:
    scale = 180.0 / math.pi if degrees else 1.0
    top = _HALF_PI * scale
    codes = classify_cells(params, n)
    artists = {"image": _shade(ax, codes, top), "segments": _draw_axis(ax, params, scale),
               "boundaries": [], "seeds": [], "legend": None, "boundary_set": None}
    boundary_handles: list = []
    if boundaries:
        boundary_set = boundary_set if boundary_set is not None else trace_boundaries(params)
        if not boundary_set.ok:
            log.warning("k = %g: some boundaries failed and are drawn in part: %s", params.k,
                        "; ".join(boundary_set.failures))
        artists["boundary_set"] = boundary_set
        artists["boundaries"], boundary_handles = _overlay_boundaries(ax, boundary_set, degrees)
    points = _drawn_seed_points(params)
    artists["regions"] = label_regions(
        ax, region_label_positions([params], codes_list=[codes],
                                   avoid=_seed_label_area(params, points)),
        scale, color="0.1")
    artists["seeds"] = _label_seed_points(ax, params, points, scale)
    _frame_axes(ax, top, "deg" if degrees else "rad")
    if legend:
        artists["legend"] = _legend(ax, codes, boundary_handles, params,
                                    junction=_JUNCTION_LABEL in points)
    return artists


def _shade(ax, codes: np.ndarray, top: float):
    """The regions as an image clipped to the triangle ``0 <= delta <= gamma <= top``."""
    triangle = Polygon([(0.0, 0.0), (top, 0.0), (top, top)], closed=True,
                       transform=ax.transData, facecolor="none", edgecolor="none")
    image = ax.imshow(_rgba(codes), origin="lower", extent=(0.0, top, 0.0, top),
                      interpolation="nearest", aspect="equal", zorder=0)
    image.set_clip_path(triangle)
    return image


def _draw_axis(ax, params: Parameters, scale: float) -> list:
    """The triangle's edge and the two segments of ``delta = 0``, split at ``arctan(k/c)``."""
    top = _HALF_PI * scale
    lines = ax.plot([0.0, top, top, 0.0], [0.0, 0.0, top, 0.0], color="0.35", lw=0.8, zorder=1)
    g_lim = params.gamma_limit * scale
    for name, (a, b) in zip(_AXIS_SEGMENTS, ((0.0, g_lim), (g_lim, top)), strict=True):
        lines += ax.plot([a, b], [0.0, 0.0], color=CATEGORY_COLOURS[name], lw=4.5,
                         solid_capstyle="butt", zorder=2)
    return lines


def _overlay_boundaries(ax, boundary_set, degrees: bool) -> tuple[list, list]:
    """Draw the boundaries; return their artists and the ``(handle, text)`` legend entries of
    what is drawn: the line styles of the curves with a physical part and the markers of their
    special points (not the per-k colour entry)."""
    # a failed set is drawn in part, as the caller's warning says
    artists = draw_boundaries(ax, [boundary_set.to_frame(partial=True)], degrees=degrees)
    drawn = ax.get_legend()
    if drawn is None:
        return artists, []
    present = _drawn_entries(boundary_set)
    handles = [(h, t.get_text())
               for h, t in zip(drawn.legend_handles, drawn.get_texts(), strict=True)
               if t.get_text() in present]
    drawn.remove()
    return artists, handles


def _label_seed_points(ax, params: Parameters, points: dict, scale: float) -> list:
    artists = []
    offsets = _label_offsets(params, points)
    for label, (g, d) in points.items():
        xy = (g * scale, d * scale)
        # under the boundaries' markers (zorder 3), which it rings: an end square at the
        # corner (pi/4, pi/4) was hidden under it
        artists += ax.plot(*xy, marker="o", ms=8, mfc="none", mec="black", mew=1.2, ls="",
                           zorder=2.9)
        artists.append(ax.annotate(
            label, xy, xytext=offsets[label], textcoords="offset points", fontsize=8,
            ha="center", va="bottom", zorder=5,
            bbox=dict(boxstyle="round,pad=0.2", fc="white", ec="0.6", lw=0.5, alpha=0.9),
            arrowprops=dict(arrowstyle="-", color="0.2", lw=0.7, shrinkA=0, shrinkB=4)))
    return artists


def _frame_axes(ax, top: float, unit: str) -> None:
    margin = 0.02 * top
    ax.set_xlim(-margin, top + margin)
    ax.set_ylim(-margin, top + margin)
    ax.set_aspect("equal")
    ax.set_xlabel(rf"$\gamma = (\theta_L + \theta_R)/2$ ({unit})")
    ax.set_ylabel(rf"$\delta = (\theta_L - \theta_R)/2$ ({unit})")


def _legend(ax, codes: np.ndarray, boundary_handles: list, params: Parameters,
            junction: bool):
    """Each region present in words, the two axis segments, then the boundaries' entries and
    the labelled points' (``junction``: the junction is one of them)."""
    present = set(np.unique(codes[codes != OUTSIDE]).tolist())
    present |= {CATEGORY_CODE[name] for name in _AXIS_SEGMENTS}
    handles: list[Artist] = []
    labels: list[str] = []
    for code, name in enumerate(CATEGORIES):
        if code not in present:
            continue
        if name in _AXIS_SEGMENTS:
            handles.append(Line2D([], [], color=CATEGORY_COLOURS[name], lw=4.5))
        else:
            handles.append(Patch(facecolor=CATEGORY_COLOURS[name], edgecolor="0.5", lw=0.5))
        labels.append(_category_label(name, params))
    for handle, text in boundary_handles:
        if text == DIAGONAL_LABEL:
            continue
        handles.append(handle)
        labels.append(text)
    # the open circles of _label_seed_points (a new user took them for points of a boundary)
    handles.append(Line2D([], [], marker="o", ms=7, mfc="none", mec="black", mew=1.2, ls=""))
    labels.append(SEED_LEGEND + (", and the junction" if junction else ""))
    return ax.legend(handles, labels, loc="upper left", fontsize=7, frameon=False,
                     borderaxespad=0.3)


def save_regime_map(k, path, n: int = 600, degrees: bool = False, formats=("png", "svg"),
                    boundary_set=None, boundaries: bool = True, dpi: int = 150) -> list:
    """Draw the regime map for ``k`` and write it atomically in each format.

    Parameters
    ----------
    k : float or Parameters
    path : path-like
        Target file; its suffix is replaced by each format's (``map_k10.png`` ->
        ``map_k10.png`` and ``map_k10.svg``). Its directory is created if missing (and
        removed again if nothing is written).
    n : int
        Cells along each axis (see :func:`draw_regime_map`).
    degrees : bool
        Axes in degrees.
    formats : sequence of str
        Any of ``"png"``, ``"svg"``, ``"pdf"``.
    boundary_set : groove_model.tracing.BoundarySet, optional
        Boundaries already traced for this ``k``; traced here when omitted.
    boundaries : bool
        Overlay the boundaries (False: the shaded regions and seed points only).
    dpi : int
        Resolution of raster output.

    Returns
    -------
    list of pathlib.Path
        The files written.

    Raises
    ------
    ValueError
        For an unknown format or an argument outside its range.

    Notes
    -----
    Each file is written to a temporary name in the target directory and moved into place with
    ``os.replace`` (:func:`groove_model.io.export.atomic_write`), so no reader sees a partial file.
    """
    params = Parameters.coerce(k)
    n = check_resolution(n, MAP_RESOLUTION_MAX)
    formats = tuple(formats)
    bad = [f for f in formats if f not in ("png", "svg", "pdf")]
    if bad or not formats:
        raise ValueError(f"format = {bad[0] if bad else formats!r} is not one of png, svg, pdf")
    path = Path(path)
    fig = Figure(figsize=(7.2, 6.6), layout="constrained")
    ax = fig.subplots()
    _draw(ax, params, n, boundaries, degrees, boundary_set, legend=True)
    compliance = "" if params.c == 1.0 else f", compliance ratio c = {params.c:.4g}"
    ax.set_title(f"Regimes of a ball in a groove, friction coefficient k = {params.k:g}"
                 + compliance, fontsize=10)
    files = []
    for fmt in formats:
        # the path as given for its own format (x.PNG stays x.PNG)
        target = path if path.suffix.lower() == "." + fmt else path.with_suffix("." + fmt)
        files.append((target, fmt))
    return atomic_write_all(figure_files(fig, files, dpi=dpi))  # every format or none
