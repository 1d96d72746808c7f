"""What the audit's checks share: grids, lines and traced boundaries, computed once.

The constants are the resolutions and tolerances the claims' methods name.
"""

from __future__ import annotations

import logging
import math

import numpy as np

from ...model.equilibrium import double_rolling_state, rolling_sliding_state
from ...model.lines import dr_limit_delta, dr_limit_no_roll_point, dr_no_roll_line, rs_no_roll_gamma
from ...model.parameters import Parameters, k_text
from ..regimes import CATEGORIES, classify_grid

__all__ = [
    "CORNER",
    "GRID_N",
    "HALF_PI",
    "IDENTITY_TOL",
    "LINE_N",
    "MAP_N",
    "POINT_TOL",
    "SQRT2",
    "VIOLATION",
    "Context",
    "distance",
    "first_special_point",
    "k_label",
    "rotation_changes",
    "sign_changes",
]

log = logging.getLogger(__name__)

HALF_PI = 0.5 * math.pi
SQRT2 = math.sqrt(2.0)
CORNER = (0.25 * math.pi, 0.25 * math.pi)
#: Residual of an identity evaluated in floating point (relative).
IDENTITY_TOL = 1e-9
#: Distance below which two independently computed points are "the same point".
POINT_TOL = 1e-7
#: Size of a violation that is far beyond round-off.
VIOLATION = 1e-6
#: Steps of the interior grid, of the regime map's grid, and on each line.
GRID_N = 200
MAP_N = 200
LINE_N = 200
#: extra rows of the rs_no_roll line next to pi/4 for k > 100 (its physical part is that short)
TOP_ROWS = 40
#: The double-rolling state does not depend on ``k`` (only its validity does).
_ANY_K = Parameters(1.0)


class Context:
    """Lazily computed grids, lines and traced boundaries shared by the checks.

    Parameters
    ----------
    ks : sequence of float
        The friction coefficients audited.
    use_tracer : bool
        Whether :meth:`traced` runs the tracer (a cross-check; no verdict depends on it).
    """

    def __init__(self, ks, use_tracer: bool):
        self.ks = tuple(ks)
        self.use_tracer = use_tracer
        self._cache: dict = {}
        self.tracer_status: dict = {}

    def cached(self, key, compute):
        """``compute()`` on the first call with ``key``, the stored value after."""
        if key not in self._cache:
            self._cache[key] = compute()
        return self._cache[key]

    def grid(self):
        """Interior grid ``gamma in (0, pi/2)``, ``delta = r gamma``, ``r in (0, 1)``."""
        def compute():
            g = np.linspace(0.0, HALF_PI, GRID_N + 1)[1:-1]
            r = np.linspace(0.0, 1.0, GRID_N + 1)[1:-1]
            G, R = np.meshgrid(g, r)
            return G.ravel(), (R * G).ravel()
        return self.cached("grid", compute)

    def dr_grid(self):
        """Double-rolling state on :meth:`grid` (independent of ``k``)."""
        return self.cached("dr_grid", lambda: double_rolling_state(*self.grid(), _ANY_K))

    def rs_grid(self, k):
        """Rolling-sliding state on :meth:`grid` for friction ``k``."""
        return self.cached(("rs_grid", k),
                           lambda: rolling_sliding_state(*self.grid(), Parameters(k)))

    def regime_grid(self, k):
        """The regime map's classification of a ``MAP_N``-step grid for friction ``k``."""
        return self.cached(("map", k), lambda: classify_grid(k, MAP_N))

    def dr_limit(self, k):
        """``(gamma, delta)`` of the double-rolling limit on columns ``gamma in (0, arctan k)``."""
        def compute():
            g = math.atan(k) * np.linspace(0.0, 1.0, LINE_N + 1)[1:-1]
            return g, dr_limit_delta(k, g)
        return self.cached(("dr_limit", k), compute)

    def dr_no_roll(self):
        """``(gamma, delta, state)`` of the double-rolling ``upsilon = 0`` line on rows.

        Rows ``delta`` in ``[1e-6, pi/4 - 1e-9]``, dense towards both ends (below ~1e-6 the
        line's distance ``O(delta^2)`` from ``gamma = arctan sqrt 2`` is lost in round-off).
        """
        def compute():
            q = 0.25 * math.pi
            d = np.unique(np.concatenate([np.geomspace(1e-6, 1e-2, 41),
                                          q * np.linspace(0.0, 1.0, LINE_N + 1)[1:-1],
                                          q - np.geomspace(1e-9, 1e-2, 41)]))
            g, _ = dr_no_roll_line(d)
            return g, d, double_rolling_state(g, d, _ANY_K)
        return self.cached("dr_no_roll", compute)

    def rs_no_roll(self, k):
        """``(gamma, delta, state)`` on rows ``delta in (0, pi/4)``: evenly spaced, and for
        ``k > 100`` also :data:`TOP_ROWS` rows geometrically closer to ``pi/4`` (1e-2 to 1e-7
        below it), where the line's physical part lies (from the junction, ``~0.5/k``
        below ``pi/4`` in delta, to the corner)."""
        def compute():
            d = 0.25 * math.pi * np.linspace(0.0, 1.0, LINE_N + 1)[1:-1]
            if k > 100.0:
                d = np.union1d(d, 0.25 * math.pi - np.geomspace(1e-2, 1e-7, TOP_ROWS))
            g = rs_no_roll_gamma(k, d)
            return g, d, rolling_sliding_state(g, d, Parameters(k))
        return self.cached(("rs_no_roll", k), compute)

    def junction(self, k):
        """The point of ``dr_limit`` where ``upsilon = 0`` (None for ``k <= sqrt 2``)."""
        return self.cached(("junction", k), lambda: dr_limit_no_roll_point(k))

    def traced(self, k):
        """The tracer's boundaries with their unphysical parts, or None (reason recorded)."""
        def compute():
            label = k_label(k)
            if not self.use_tracer:
                self.tracer_status[label] = "not run (groove audit --trace runs it)"
                return None
            try:
                # Imported here: the tracer brings the continuation engine and pandas, which
                # only this optional cross-check needs.
                from ...tracing import trace_boundaries

                bs = trace_boundaries(k, keep_unphysical=True)
            except (ArithmeticError, RuntimeError, ValueError, np.linalg.LinAlgError) as exc:
                # The cross-check is optional (the verdicts do not use it); its absence is
                # reported in the report's tracer status.
                self.tracer_status[label] = f"unavailable: {type(exc).__name__}: {exc}"
                log.warning("tracer cross-check unavailable for k = %g: %s", k, exc)
                return None
            if not bs.ok:
                # no number of a claim's table comes from a curve that failed (it may stop short)
                self.tracer_status[label] = "failed: " + "; ".join(bs.failures)
                log.warning("tracer cross-check failed for k = %g: %s", k, "; ".join(bs.failures))
                return None
            self.tracer_status[label] = "ok"
            return bs
        return self.cached(("traced", k), compute)


def first_special_point(bs, name, kind):
    """``(gamma, delta)`` of the first special point ``kind`` of curve ``name``, or None."""
    if bs is None or name not in bs.curves:
        return None
    points = bs.curves[name].special(kind)
    return (float(points[0].x[0]), float(points[0].x[1])) if points else None


def distance(a, b) -> float:
    """Euclidean distance of two ``(gamma, delta)`` points; NaN if either is None."""
    if a is None or b is None:
        return math.nan
    return float(math.hypot(a[0] - b[0], a[1] - b[1]))


def k_label(k: float) -> str:
    """The key of one ``k`` in the numbers of a claim (``k`` in full, so keys never collide)."""
    return f"k = {k_text(k)}"


def rotation_changes(rg, regime: str):
    """Changes of the rotation sense among the nodes of one regime on each row ``delta > 0``.

    Parameters
    ----------
    rg : RegimeGrid
    regime : str
        ``"double_rolling"`` or ``"rolling_sliding"``.

    Returns
    -------
    changes : ndarray of int
        Number of changes on each row, left to right.
    bad_order : int
        Rows with more than one change, or one that is not clockwise -> counter-clockwise.
    """
    cw = CATEGORIES.index(f"{regime}_clockwise")
    ccw = CATEGORIES.index(f"{regime}_counterclockwise")
    bad_order, changes = 0, []
    for row in rg.category[1:]:
        seq = row[(row == cw) | (row == ccw)]
        n = int(np.count_nonzero(np.diff(seq)))
        changes.append(n)
        if n > 1 or (n == 1 and seq[0] != cw):
            bad_order += 1
    return np.array(changes), bad_order


def sign_changes(values: np.ndarray, axis: int = -1) -> np.ndarray:
    """Number of changes between strictly negative and strictly positive values along ``axis``.

    A zero carries the sign before it, so ``-, 0, +`` is one change and ``-, 0, -`` none.
    """
    s = np.sign(np.moveaxis(np.asarray(values), axis, -1))
    idx = np.where(s != 0, np.arange(s.shape[-1]), 0)
    np.maximum.accumulate(idx, axis=-1, out=idx)
    filled = np.take_along_axis(s, idx, axis=-1)
    return np.count_nonzero(filled[..., 1:] * filled[..., :-1] < 0, axis=-1)
