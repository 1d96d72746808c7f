r"""The regime map: every point of the ``(gamma, delta)`` plane classified and shaded.

Each point of the domain ``0 <= delta <= gamma <= pi/2`` is classified with the vectorised point
solver :func:`groove_model.equilibrium.solve_equilibrium` into one of

=====================================  =====================================================
category                               where
=====================================  =====================================================
``double_rolling_clockwise``           ``T/N <= k`` on both walls, ``upsilon < 0``
``double_rolling_counterclockwise``    ``T/N <= k`` on both walls, ``upsilon > 0``
``rolling_sliding_clockwise``          steeper (left) wall slides, ``upsilon < 0``
``rolling_sliding_counterclockwise``   steeper (left) wall slides, ``upsilon > 0``
``double_sliding``                     the segment ``delta = 0``, ``gamma > arctan k``
``symmetric_no_rotation``              the segment ``delta = 0``, ``gamma <= arctan k``
``no_rotation``                        ``upsilon = 0`` exactly off the axis (measure zero)
=====================================  =====================================================

(``upsilon = R phi / Z``, negative clockwise, i.e. rolling down the steeper wall; paper,
"Rolling solutions"). The map shades the four regions, draws the two segments of the axis
``delta = 0`` as thick lines, overlays the boundaries traced by
:func:`groove_model.tracer.trace_boundaries` (drawn by :func:`groove_model.plotting.draw_boundaries`)
and labels the seed points the paper names.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy import optimize
from scipy.optimize import elementwise

from ..model.boundaries import boundary_system
from ..model.equilibrium import double_rolling_state, solve_equilibrium
from ..model.parameters import Parameters

__all__ = [
    "CATEGORIES",
    "CATEGORY_COLOURS",
    "CATEGORY_LABELS",
    "OUTSIDE",
    "RegimeGrid",
    "classify_grid",
    "classify_points",
    "dr_limit_no_roll_point",
    "dr_no_roll_line",
    "draw_regime_map",
    "save_regime_map",
    "seed_points",
]

log = logging.getLogger(__name__)

CATEGORIES = (
    "double_rolling_clockwise",
    "double_rolling_counterclockwise",
    "rolling_sliding_clockwise",
    "rolling_sliding_counterclockwise",
    "double_sliding",
    "symmetric_no_rotation",
    "no_rotation",
)
#: Code of a grid node outside the domain ``0 <= delta <= gamma <= pi/2``.
OUTSIDE = -1

CATEGORY_LABELS = {
    "double_rolling_clockwise": "double rolling, clockwise (down the steeper wall)",
    "double_rolling_counterclockwise": "double rolling, counter-clockwise (up the steeper wall)",
    "rolling_sliding_clockwise": "rolling-sliding (steeper wall slides), clockwise",
    "rolling_sliding_counterclockwise": "rolling-sliding (steeper wall slides), counter-clockwise",
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

_CODE = {name: i for i, name in enumerate(CATEGORIES)}
_HALF_PI = 0.5 * math.pi
_SQRT2 = math.sqrt(2.0)


def _readonly(array: np.ndarray) -> np.ndarray:
    array.setflags(write=False)
    return array


@dataclass(frozen=True)
class RegimeGrid:
    """Classification of the nodes of a regular grid over ``[0, pi/2]^2``.

    Attributes
    ----------
    k : float
        Friction coefficient.
    gamma : ndarray, shape (n + 1,)
        Node abscissae ``gamma_i = i h``, ``h = (pi/2)/n`` (radians).
    delta : ndarray, shape (n + 1,)
        Node ordinates ``delta_j = j h`` (radians).
    category : ndarray of int8, shape (n + 1, n + 1)
        ``category[j, i]`` is the index into :data:`CATEGORIES` of the node
        ``(gamma_i, delta_j)``, or :data:`OUTSIDE` where ``delta_j > gamma_i``.
    upsilon : ndarray, shape (n + 1, n + 1)
        Rolling ``R phi / Z`` at each node (NaN outside the domain).
    """

    k: float
    gamma: np.ndarray = field(repr=False)
    delta: np.ndarray = field(repr=False)
    category: np.ndarray = field(repr=False)
    upsilon: np.ndarray = field(repr=False)

    @property
    def step(self) -> float:
        """Grid step ``h`` in radians."""
        return float(self.gamma[1] - self.gamma[0])

    @property
    def inside(self) -> np.ndarray:
        """Boolean mask of the nodes in the domain."""
        return self.category != OUTSIDE

    def counts(self) -> dict:
        """Number of nodes in each category (every category present, zeros included)."""
        return {name: int(np.count_nonzero(self.category == code)) for name, code in _CODE.items()}

    def names(self) -> np.ndarray:
        """The category of each node as a string array (``"outside"`` outside the domain)."""
        table = np.array([*CATEGORIES, "outside"], dtype=object)
        return table[np.where(self.category == OUTSIDE, len(CATEGORIES), self.category)]


def classify_points(gamma, delta, k) -> np.ndarray:
    """Category code (index into :data:`CATEGORIES`) of each point ``(gamma, delta)``.

    Parameters
    ----------
    gamma, delta : array_like
        Points of the domain ``0 <= delta <= gamma <= pi/2``, radians, broadcastable shapes.
    k : float or Parameters
        Friction coefficient, finite and > 0.

    Returns
    -------
    ndarray of int8
        Codes of the broadcast shape.

    Raises
    ------
    ValueError
        If ``k`` or a point is outside its allowed range (from the point solver).

    Notes
    -----
    The regime is the point solver's (double rolling where ``T/N <= k`` on both walls, double
    sliding on ``delta = 0`` beyond ``arctan k``, rolling sliding elsewhere); the rotation sense
    is the sign of ``upsilon``. On ``delta = 0`` the double-rolling state is the symmetric one,
    ``beta_L = beta_R = pi/2 - gamma``, ``upsilon = 0`` (paper, "Rolling solutions").
    """
    gamma, delta = np.broadcast_arrays(np.asarray(gamma, float), np.asarray(delta, float))
    eq = solve_equilibrium(np.atleast_1d(gamma), np.atleast_1d(delta), k)  # checks k, domain
    regime = np.asarray(eq.regime, dtype=object).reshape(gamma.shape)
    upsilon = np.asarray(eq.upsilon, dtype=float).reshape(gamma.shape)
    axis = delta == 0.0
    code = np.full(gamma.shape, _CODE["no_rotation"], dtype=np.int8)
    for name, regime_name in (("double_rolling", "double_rolling"),
                              ("rolling_sliding", "rolling_sliding")):
        here = (regime == regime_name) & ~axis
        code[here & (upsilon < 0.0)] = _CODE[f"{name}_clockwise"]
        code[here & (upsilon > 0.0)] = _CODE[f"{name}_counterclockwise"]
    # On the axis the category follows gamma against arctan(k/c) alone: exactly there the
    # solver's T/N = tan gamma may round either way.
    params = Parameters.coerce(k)
    below = gamma <= params.gamma_limit
    code[axis & below] = _CODE["symmetric_no_rotation"]
    code[axis & ~below] = _CODE["double_sliding"]
    return code


def classify_grid(k, n: int = 400) -> RegimeGrid:
    """Classify the nodes of an ``(n + 1) x (n + 1)`` grid over the domain.

    Parameters
    ----------
    k : float or Parameters
        Friction coefficient, finite and > 0.
    n : int
        Number of grid steps along each axis of ``[0, pi/2]``, ``2 <= n <= 20000``; the step is
        ``h = (pi/2)/n``. Nodes with ``delta > gamma`` are marked :data:`OUTSIDE`.

    Returns
    -------
    RegimeGrid

    Raises
    ------
    ValueError
        If ``n`` or ``k`` is outside its allowed range.
    """
    params = Parameters.coerce(k)
    n = _check_resolution(n)
    axis = np.linspace(0.0, _HALF_PI, n + 1)
    G, D = np.meshgrid(axis, axis)
    inside = D <= G
    category = np.full(G.shape, OUTSIDE, dtype=np.int8)
    upsilon = np.full(G.shape, np.nan)
    category[inside] = classify_points(G[inside], D[inside], params)
    upsilon[inside] = solve_equilibrium(G[inside], D[inside], params).upsilon
    return RegimeGrid(params.k, _readonly(axis.copy()), _readonly(axis.copy()),
                      _readonly(category), _readonly(upsilon))


def _check_resolution(n) -> int:
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)):
        raise TypeError(f"grid resolution n must be an integer, got {n!r}")
    if not 2 <= n <= 20000:
        raise ValueError(f"grid resolution n = {n} is outside the allowed range 2 <= n <= 20000")
    return int(n)


def _dr_upsilon(gamma, delta):
    """Double-rolling ``upsilon(gamma, delta)`` (independent of ``k``) for root finding in gamma."""
    return double_rolling_state(gamma, delta, Parameters(1.0))["upsilon"]


def dr_no_roll_line(delta):
    r"""The double-rolling ``upsilon = 0`` line on rows ``delta`` in ``(0, pi/4)``.

    Parameters
    ----------
    delta : array_like
        Rows, radians, ``0 < delta < pi/4``.

    Returns
    -------
    gamma, beta_L : ndarray
        The line's ``gamma`` on each row and its ``beta_L`` (the double-rolling state does not
        depend on ``k``).

    Notes
    -----
    The line leaves the symmetric family at the branch point ``(arctan sqrt 2, 0)`` as
    ``gamma ~ arctan sqrt 2 - O(delta^2)`` and ends at ``(pi/4, pi/4)``, so it is a graph over
    ``delta`` but not over ``gamma`` near the branch point. On each row ``upsilon < 0`` at
    ``gamma = pi/4`` and ``upsilon > 0`` at ``gamma = arctan sqrt 2 + 0.05`` (where it is
    ``O(delta)``, well above round-off; at ``arctan sqrt 2`` itself it is only ``O(delta^3)``),
    so the root is bracketed (Chandrupatla, scipy ``elementwise.find_root``).
    """
    delta = np.asarray(delta, dtype=float)
    res = elementwise.find_root(_dr_upsilon, (np.full_like(delta, 0.25 * math.pi),
                                              np.full_like(delta, math.atan(_SQRT2) + 0.05)),
                                args=(delta,),
                                tolerances=dict(xatol=0.0, xrtol=4.0 * np.finfo(float).eps,
                                                fatol=0.0, frtol=0.0))
    gamma = np.where(res.success, res.x, np.nan)
    return gamma, double_rolling_state(gamma, delta, Parameters(1.0))["beta_L"]


def dr_limit_no_roll_point(k):
    r"""The point of ``dr_limit`` where ``upsilon = 0``, or ``None`` when ``k <= sqrt 2``.

    Parameters
    ----------
    k : float or Parameters

    Returns
    -------
    ndarray, shape (4,), or None
        ``x = (gamma, delta, beta_L, upsilon)`` with ``upsilon = 0`` to round-off.

    Notes
    -----
    With ``upsilon = 0`` the double-rolling ratios are ``T/N_L = c cot beta_L``,
    ``T/N_R = c cot beta_R`` (paper Eq. rollt with Eq. prop), so the point is where the
    ``upsilon = 0`` line of double rolling (:func:`dr_no_roll_line`) reaches
    ``c cot beta_L = k``. Along the line ``beta_L`` falls from ``arctan(1/sqrt 2)`` at the branch
    point to 0 at ``(pi/4, pi/4)``; it is sampled on rows ``delta`` (densely towards both ends),
    the crossing is bracketed, and the point is polished by Newton's method on the four
    equations ``dr_limit`` and ``upsilon = 0`` with the analytic Jacobian of
    :mod:`groove_model.boundaries`; Brent's method on the line is the fallback.
    """
    params = Parameters.coerce(k)
    if params.k / params.c <= _SQRT2:
        return None
    target = math.atan2(params.c, params.k)  # beta_L with c cot beta_L = k
    quarter = 0.25 * math.pi
    # Below delta ~ 1e-7 the line's gamma = arctan sqrt 2 - O(delta^2) is lost in round-off.
    deltas = np.unique(np.concatenate([np.geomspace(1e-7, 1e-2, 26),
                                       np.linspace(0.0, quarter, 65)[1:-1],
                                       quarter - np.geomspace(1e-10, 1e-2, 33)]))
    gammas, beta_L = dr_no_roll_line(deltas)
    system = boundary_system("dr_limit", params)

    def equations(x):
        H, J = system.residual_and_jacobian(x)
        return np.append(H, x[3]), np.vstack([J, [0.0, 0.0, 0.0, 1.0]])

    def newton(x0, lo, hi):
        sol = optimize.root(equations, x0, jac=True, method="hybr", options=dict(xtol=1e-15))
        good = (sol.success and lo <= sol.x[1] <= hi
                and np.max(np.abs(equations(sol.x)[0])) <= 1e-13 * (1.0 + params.k))
        return sol.x if good else None

    below = beta_L < target
    if not below.any():
        log.warning("k = %g: the upsilon = 0 point of dr_limit is within 1e-10 of the corner "
                    "(pi/4, pi/4) and was not located", params.k)
        return None
    if below.all():
        # Within 1e-7 of the branch point (k just above sqrt 2): beta_L ~ beta* - delta there.
        beta_star = math.atan(1.0 / _SQRT2)
        x = newton(np.array([math.atan(_SQRT2), beta_star - target, target, 0.0]), 0.0, 1e-6)
        if x is None:
            log.warning("k = %g: the upsilon = 0 point of dr_limit is too close to the branch "
                        "point (arctan sqrt 2, 0) to be located", params.k)
        return x
    i = int(np.argmax(below))  # first row past the crossing: bracket rows (i - 1, i)
    w = (target - beta_L[i - 1]) / (beta_L[i] - beta_L[i - 1])
    x0 = np.array([gammas[i - 1] + w * (gammas[i] - gammas[i - 1]),
                   deltas[i - 1] + w * (deltas[i] - deltas[i - 1]), target, 0.0])
    x = newton(x0, deltas[i - 1], deltas[i])
    if x is not None:
        return x

    def excess(delta):
        return float(dr_no_roll_line(np.array([delta]))[1][0]) - target

    delta = optimize.brentq(excess, deltas[i - 1], deltas[i], xtol=1e-16,
                            rtol=4.0 * np.finfo(float).eps)
    gamma, beta = dr_no_roll_line(np.array([delta]))
    return np.array([float(gamma[0]), delta, float(beta[0]), 0.0])


def seed_points(k) -> dict:
    """The seed points the paper names, ``label -> (gamma, delta)`` in radians.

    ``(arctan k, 0)`` (start of the double-rolling limit), ``(arctan sqrt 2, 0)`` (branch point
    of the double-rolling ``upsilon = 0`` line), ``(pi/4, pi/4)`` (end of both ``upsilon = 0``
    lines) and, for ``k > sqrt 2``, the point of the double-rolling limit where ``upsilon = 0``.
    """
    params = Parameters.coerce(k)
    points = {
        r"$(\arctan k,\,0)$": (params.gamma_limit, 0.0),
        r"$(\arctan\sqrt{2},\,0)$": (math.atan(_SQRT2), 0.0),
        r"$(\pi/4,\,\pi/4)$": (0.25 * math.pi, 0.25 * math.pi),
    }
    junction = dr_limit_no_roll_point(params)
    if junction is not None:
        points[r"$\upsilon = 0$ on the limit"] = (float(junction[0]), float(junction[1]))
    return points


def _label_offsets(params: Parameters) -> dict:
    """Where each seed label goes, in points from the seed, chosen to keep labels apart."""
    k_first = params.gamma_limit < math.atan(_SQRT2)
    return {
        r"$(\arctan k,\,0)$": (-45, 30) if k_first else (-18, 28),
        r"$(\arctan\sqrt{2},\,0)$": (45, 30) if k_first else (-62, 40),
        r"$(\pi/4,\,\pi/4)$": (-82, 10),
        r"$\upsilon = 0$ on the limit": (22, 26),
    }


def _cell_image(params: Parameters, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Category codes at the centres of an ``n x n`` cell grid over ``[0, pi/2]^2``."""
    h = _HALF_PI / n
    centres = (np.arange(n) + 0.5) * h
    G, D = np.meshgrid(centres, centres)
    inside = D <= G
    codes = np.full(G.shape, OUTSIDE, dtype=np.int8)
    codes[inside] = classify_points(G[inside], D[inside], params)
    return codes, inside


def _rgba(codes: np.ndarray) -> np.ndarray:
    from matplotlib.colors import to_rgba

    table = np.array([to_rgba(CATEGORY_COLOURS[name]) for name in CATEGORIES] + [(0, 0, 0, 0)])
    return table[np.where(codes == OUTSIDE, len(CATEGORIES), codes)]


_STYLE_LABELS = {"dr_limit": "T = kN (DR | RS)", "dr_no_roll": r"$\upsilon = 0$ in DR",
                 "rs_no_roll": r"$\upsilon = 0$ in RS"}


def _drawn_entries(boundary_set) -> set:
    """Legend texts of :func:`groove_model.plotting.draw_boundaries` for what it draws."""
    entries = set()
    for name, curve in boundary_set.curves.items():
        physical = np.asarray(curve.physical, dtype=bool)
        if name not in _STYLE_LABELS or not physical.any():
            continue
        entries.add(_STYLE_LABELS[name])
        entries.update(p.kind.replace("_", " ") for p in curve.special_points
                       if physical[p.index])
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
        Cells along each axis of ``[0, pi/2]`` (each cell is classified at its centre).
    boundaries : bool
        Overlay the traced boundaries and their special points.
    degrees : bool
        Axes in degrees instead of radians.
    boundary_set : groove_model.tracer.BoundarySet, optional
        Boundaries already traced for this ``k``; traced here when omitted.
    legend : bool
        Add a legend naming each regime in words, the line styles and the point markers.

    Returns
    -------
    dict
        The artists: ``"image"`` (the shaded regions, an ``AxesImage`` clipped to the triangle),
        ``"segments"`` (the two segments of ``delta = 0``), ``"boundaries"`` (from
        :func:`groove_model.plotting.draw_boundaries`), ``"seeds"`` (markers and labels of the
        seed points), ``"legend"``, and ``"boundary_set"``, the traced boundaries (or None).

    Raises
    ------
    ValueError
        If ``k`` or ``n`` is outside its allowed range.
    """
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch, Polygon

    params = Parameters.coerce(k)
    n = _check_resolution(n)
    scale = 180.0 / math.pi if degrees else 1.0
    unit = "deg" if degrees else "rad"
    top = _HALF_PI * scale
    codes, _ = _cell_image(params, n)
    triangle = Polygon([(0.0, 0.0), (top, 0.0), (top, top)], closed=True,
                       transform=ax.transData, facecolor="none", edgecolor="none")
    image = ax.imshow(_rgba(codes), origin="lower", extent=(0.0, top, 0.0, top),
                      interpolation="nearest", aspect="equal", zorder=0)
    image.set_clip_path(triangle)
    artists = {"image": image, "segments": [], "boundaries": [], "seeds": [],
               "legend": None, "boundary_set": None}

    edge = ax.plot([0.0, top, top, 0.0], [0.0, 0.0, top, 0.0], color="0.35", lw=0.8, zorder=1)
    artists["segments"] += edge
    g_lim = params.gamma_limit * scale
    for name, (a, b) in (("symmetric_no_rotation", (0.0, g_lim)), ("double_sliding", (g_lim, top))):
        artists["segments"] += ax.plot([a, b], [0.0, 0.0], color=CATEGORY_COLOURS[name], lw=4.5,
                                       solid_capstyle="butt", zorder=2)

    boundary_handles = []
    if boundaries:
        from .overlay import draw_boundaries

        if boundary_set is None:
            from ..tracer import trace_boundaries

            boundary_set = trace_boundaries(params)
        if not boundary_set.ok:
            log.warning("k = %g: some boundaries failed and are drawn in part: %s", params.k,
                        "; ".join(boundary_set.failures))
        artists["boundary_set"] = boundary_set
        artists["boundaries"] = draw_boundaries(ax, [boundary_set], degrees=degrees)
        drawn = ax.get_legend()
        if drawn is not None:
            # Keep the entries of what is drawn: the line styles of the curves with a physical
            # part and the markers of their special points (not the per-k colour entry).
            present = _drawn_entries(boundary_set)
            boundary_handles = [(h, t.get_text()) for h, t in zip(drawn.legend_handles,
                                                                  drawn.get_texts())
                                if t.get_text() in present]
            drawn.remove()

    offsets = _label_offsets(params)
    for label, (g, d) in seed_points(params).items():
        xy = (g * scale, d * scale)
        artists["seeds"] += ax.plot(*xy, marker="o", ms=7, mfc="none", mec="black", mew=1.2,
                                    ls="", zorder=4)
        artists["seeds"].append(ax.annotate(
            label, xy, xytext=offsets[label], textcoords="offset points", fontsize=8,
            ha="center", va="bottom", zorder=5,
            bbox=dict(boxstyle="round,pad=0.2", fc="white", ec="0.6", lw=0.5, alpha=0.9),
            arrowprops=dict(arrowstyle="-", color="0.2", lw=0.7, shrinkA=0, shrinkB=4)))

    margin = 0.02 * top
    ax.set_xlim(-margin, top + margin)
    ax.set_ylim(-margin, top + margin)
    ax.set_aspect("equal")
    ax.set_xlabel(rf"$\gamma = (\theta_L + \theta_R)/2$ ({unit})")
    ax.set_ylabel(rf"$\delta = (\theta_L - \theta_R)/2$ ({unit})")

    if legend:
        present = set(np.unique(codes[codes != OUTSIDE]).tolist())
        present |= {_CODE["symmetric_no_rotation"], _CODE["double_sliding"]}
        handles, labels = [], []
        for code, name in enumerate(CATEGORIES):
            if code not in present:
                continue
            if name in ("symmetric_no_rotation", "double_sliding"):
                handles.append(Line2D([], [], color=CATEGORY_COLOURS[name], lw=4.5))
            else:
                handles.append(Patch(facecolor=CATEGORY_COLOURS[name], edgecolor="0.5", lw=0.5))
            labels.append(CATEGORY_LABELS[name])
        for handle, text in boundary_handles:
            if text == r"$\delta = \gamma$":
                continue
            handles.append(handle)
            labels.append(text)
        artists["legend"] = ax.legend(handles, labels, loc="upper left", fontsize=7,
                                      frameon=False, borderaxespad=0.3)
    return artists


def save_regime_map(k, path, n: int = 600, degrees: bool = False, formats=("png", "svg"),
                    boundary_set=None, boundaries: bool = True, dpi: int = 150) -> list:
    """Draw the regime map for ``k`` and write it atomically in each format.

    Parameters
    ----------
    k : float or Parameters
    path : path-like
        Target file; its suffix is replaced by each format's (``map_k10.png`` ->
        ``map_k10.png`` and ``map_k10.svg``). The directory must exist.
    n : int
        Cells along each axis (see :func:`draw_regime_map`).
    degrees : bool
        Axes in degrees.
    formats : sequence of str
        Any of ``"png"``, ``"svg"``, ``"pdf"``.
    boundary_set : groove_model.tracer.BoundarySet, optional
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
    FileNotFoundError
        If the target directory does not exist.

    Notes
    -----
    Each file is written to a temporary name in the target directory and moved into place with
    ``os.replace`` (:func:`groove_model.export.atomic_write`), so no reader sees a partial file.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..io.export import atomic_write

    params = Parameters.coerce(k)
    formats = tuple(formats)
    bad = [f for f in formats if f not in ("png", "svg", "pdf")]
    if bad or not formats:
        raise ValueError(f"format = {bad[0] if bad else formats!r} is not one of png, svg, pdf")
    path = Path(path)
    if not path.parent.is_dir():
        raise FileNotFoundError(f"directory {path.parent} of {path} does not exist")
    fig, ax = plt.subplots(figsize=(7.2, 6.6), layout="constrained")
    try:
        draw_regime_map(ax, params, n=n, degrees=degrees, boundary_set=boundary_set,
                        boundaries=boundaries)
        ax.set_title(f"Regimes of a ball in a groove, friction coefficient k = {params.k:g}",
                     fontsize=10)
        written = []
        for fmt in formats:
            target = path.with_suffix("." + fmt)
            # A fixed hash salt and no date make the SVG the same on every run.
            with matplotlib.rc_context({"svg.hashsalt": "groove"}):
                written.append(atomic_write(target, lambda tmp, f=fmt: fig.savefig(
                    tmp, format=f, dpi=dpi, metadata={"Date": None} if f == "svg" else None)))
        return written
    finally:
        plt.close(fig)
