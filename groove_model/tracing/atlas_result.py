"""The results of the atlas: its curves of special points, its thresholds, and their tables.

:func:`~groove_model.tracing.atlas.trace_atlas` computes an :class:`Atlas`; this module holds
the objects it returns (kept apart from how they are computed, as the engine keeps its results
in ``continuation.result``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..model.parameters import number_text
from .curves import PointKind
from .families import Axis, BoundaryFamily

__all__ = ["ATLAS_COLUMNS", "THRESHOLD_COLUMNS", "Atlas", "AtlasCurve", "Threshold"]

ATLAS_COLUMNS = ("curve", "k", "nu", "compliance", "gamma", "delta", "beta_L", "upsilon",
                 "physical", "threshold")

THRESHOLD_COLUMNS = ("threshold", "axis", "value", "fixed", "gamma", "delta", "beta_L",
                     "upsilon", "curve", "what", "equations", "residual", "also")

if TYPE_CHECKING:  # the tables are made with pandas only on request
    import pandas as pd


@dataclass(frozen=True)
class Threshold:
    """A value of ``k`` (or ``nu``) where the picture changes: a codimension-2 point.

    Attributes
    ----------
    name : str
        ``k_fold``, ``k_branch``, ``k_cross`` (``nu_...`` on the ``nu`` axis), or
        ``"<curve>: <event>"`` for one the atlas did not know of.
    value : float
        ``k`` or ``nu``.
    x : ndarray, shape (4,)
        ``(gamma, delta, beta_L, upsilon)`` there.
    curve : str
        The atlas curve it lies on.
    what : str
        What happens, in words.
    equations : tuple of str
        Its defining equations: the curve's four and the event's (five in ``x`` and ``p``).
    residual : float
        ``max |F|`` of the defining equations at the polished point (chart units).
    accuracy : float
        Width in arclength of the final root bracket of its location.
    also : tuple of str
        Other events of the same curve that vanish at the same point.
    """

    name: str
    value: float
    x: np.ndarray = field(repr=False)
    curve: str
    what: str
    equations: tuple[str, ...] = field(repr=False)
    residual: float
    accuracy: float
    also: tuple[str, ...] = ()


@dataclass(frozen=True, eq=False)
class AtlasCurve:
    """One special point followed along the axis.

    Attributes
    ----------
    name : str
        ``junction`` or ``<boundary>_fold_<gamma|delta>``.
    boundary : str
        The boundary the point is a special point of (``dr_limit`` for the junction).
    kind : PointKind
        ``JUNCTION``, ``FOLD_GAMMA`` or ``FOLD_DELTA``.
    axis : Axis
    p : ndarray, shape (m,)
        The parameter (``log k`` or ``nu``) of each row, rows in order along the curve.
    x : ndarray, shape (m, 4)
        ``(gamma, delta, beta_L, upsilon)``.
    physical : ndarray of bool, shape (m,)
        Whether the point lies on the physical part of its boundary.
    traces : tuple of Codim2Curve
        The engine's curves (in the chart of ``family``), for dense output.
    p_range : (float, float)
        The range of ``p`` of the atlas the curve belongs to: :meth:`at` answers inside it.
    """

    name: str
    boundary: str
    kind: PointKind
    axis: Axis
    p: np.ndarray = field(repr=False)
    x: np.ndarray = field(repr=False)
    physical: np.ndarray = field(repr=False)
    traces: tuple = field(repr=False)
    family: BoundaryFamily = field(repr=False)
    p_range: tuple[float, float] = (-math.inf, math.inf)

    @property
    def values(self) -> np.ndarray:
        """``k`` or ``nu`` of each row."""
        return self.axis.value(self.p)

    def dense(self, per_step: int = 8) -> tuple[np.ndarray, np.ndarray]:
        """``(values, x)`` on the Hermite arcs between the rows, for drawing (not corrected
        onto the curve; :meth:`at` is exact)."""
        parts = [trace.dense(per_step) for trace in self.traces]
        z = np.concatenate(parts) if parts else np.zeros((0, 5))
        return self.axis.value(z[:, -1]), self.family.to_x(z) if len(z) else np.zeros((0, 4))

    def at(self, value: float) -> list[np.ndarray]:
        """The point(s) ``x`` of the curve at ``k`` (or ``nu``) ``= value``, corrected onto it.

        Empty where the curve does not exist.

        Raises
        ------
        ValueError
            If ``value`` is outside the atlas's range (where the atlas cannot say whether
            the curve exists) or not a finite number.
        """
        p = self._p(value)
        found: list[np.ndarray] = []
        for trace in self.traces:
            for z in trace.at(p):
                x = self.family.to_x(z)[0]
                if not any(np.max(np.abs(x - other)) <= 1e-12 for other in found):
                    found.append(x)
        return found

    def _p(self, value: float) -> float:
        """``p`` of ``value``, checked against the atlas's range."""
        name = self.axis.name
        if isinstance(value, bool) or not isinstance(value, (int, float, np.integer,
                                                             np.floating)):
            raise TypeError(f"{name} must be a real number, got {value!r}")
        lo, hi = (self.axis.value(end) for end in self.p_range)
        allowed = f"{float(lo):.15g} <= {name} <= {float(hi):.15g}, the range of the atlas"
        if not math.isfinite(value) or (name == "k" and value <= 0.0):
            raise ValueError(f"{name} = {number_text(value)} is outside the allowed range: "
                             f"{allowed}")
        p = self.axis.to_p(value)
        slack = 1e-12 * (1.0 + abs(p))
        if not self.p_range[0] - slack <= p <= self.p_range[1] + slack:
            raise ValueError(f"{name} = {number_text(value)} is outside the allowed range: "
                             f"{allowed} (trace an atlas over a range that holds it)")
        return p

    def physical_at(self, value: float) -> list[np.ndarray]:
        """:meth:`at`, only the points on the physical part of the boundary."""
        p = self._p(value)
        return [x for x in self.at(value)
                if self.family.physical(np.append(self.family.from_x(x, p), p))]


@dataclass(frozen=True, eq=False)
class Atlas:
    """The special points of the boundaries over a range of ``k`` (or ``nu``).

    Attributes
    ----------
    axis : Axis
    range : (float, float)
        The range of ``k`` (or ``nu``).
    curves : dict of str to AtlasCurve
    thresholds : tuple of Threshold
        In increasing order of their value.
    failures : tuple of str
        Curves that could not be followed to the end of the range or their death.
    seconds : float
        Wall time of the computation.
    poisson : float or None
        The Poisson ratio the fixed compliance ratio was computed from, as given
        (``Compliance.poisson``); ``None``: the ratio was given, and the tables write the
        Poisson ratio that Mindlin's law inverts it to.
    """

    axis: Axis
    range: tuple[float, float]
    curves: dict = field(repr=False)
    thresholds: tuple[Threshold, ...]
    failures: tuple[str, ...] = ()
    seconds: float = 0.0
    poisson: float | None = None

    @property
    def ok(self) -> bool:
        return not self.failures

    def threshold(self, name: str) -> Threshold:
        """The threshold called ``name``.

        Raises
        ------
        KeyError
            If the atlas has none of that name (e.g. outside its range).
        """
        for threshold in self.thresholds:
            if threshold.name == name:
                return threshold
        raise KeyError(f"no threshold {name!r} in the atlas; it has "
                       f"{', '.join(t.name for t in self.thresholds) or 'none'}")

    def curve_table(self, name: str) -> list[tuple]:
        """The rows of one curve, in the order of :data:`ATLAS_COLUMNS`."""
        curve = self.curves[name]
        marks = [""] * len(curve.p)
        for threshold in self.thresholds:
            if threshold.curve == name:
                marks[int(np.argmin(np.abs(curve.p - self.axis.to_p(threshold.value))))] = \
                    threshold.name
        nu = self.poisson if self.poisson is not None else _poisson(self.axis)
        rows = []
        for i, p in enumerate(curve.p):
            k, c = self.axis.friction_and_ratio(p)
            rows.append((name, k, float(p) if self.axis.name == "nu" else nu, c,
                         *(float(v) for v in curve.x[i]), bool(curve.physical[i]), marks[i]))
        return rows

    def thresholds_table(self) -> list[tuple]:
        """The thresholds, in the order of :data:`THRESHOLD_COLUMNS`."""
        return [(t.name, self.axis.name, t.value, self.axis.fixed, *(float(v) for v in t.x),
                 t.curve, t.what, "; ".join(t.equations), t.residual, "; ".join(t.also))
                for t in self.thresholds]

    def curve_frame(self, name: str) -> pd.DataFrame:
        """:meth:`curve_table` as a DataFrame."""
        import pandas as pd  # only the tables need it: `groove atlas` writes without it

        return pd.DataFrame(self.curve_table(name), columns=list(ATLAS_COLUMNS))

    def thresholds_frame(self) -> pd.DataFrame:
        """:meth:`thresholds_table` as a DataFrame."""
        import pandas as pd  # only the tables need it: `groove atlas` writes without it

        return pd.DataFrame(self.thresholds_table(), columns=list(THRESHOLD_COLUMNS))


def _poisson(axis: Axis) -> float:
    """The Poisson ratio of a fixed compliance ratio (NaN if none gives it)."""
    c = axis.fixed
    # c = 2 (1 - nu)/(2 - nu)  <=>  nu = 2 (1 - c)/(2 - c)
    nu = 2.0 * (1.0 - c) / (2.0 - c) if c != 2.0 else math.nan
    return nu if -1.0 < nu <= 0.5 else math.nan
