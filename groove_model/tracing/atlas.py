r"""The atlas: every special point of the boundaries followed as a curve in ``k`` (or in ``nu``).

For one ``k`` the tracer gives the boundaries and their special points; here the special points
themselves are followed, as ``k`` runs over ten decades, by two-parameter continuation
(:mod:`continuation.codim2`) in ``p = log k`` at a fixed compliance (:func:`trace_atlas`), or in
the Poisson ratio ``nu`` at a fixed ``k`` (:func:`trace_atlas_in_poisson`):

=========================  ========================================================  ==========
curve                      defining equations (in ``x = (gamma, delta, w, upsilon)``  exists for
                           with ``beta_L = w^2``, and ``p``)                          (``c = 1``)
=========================  ========================================================  ==========
``junction``               ``dr_no_roll`` (deflated) and ``T/N_L = k``: the point     ``k > k_branch``
                           of ``dr_limit`` where ``upsilon = 0``
``rs_no_roll_fold_gamma``  ``rs_no_roll`` and its fold test in ``gamma``              ``k > k_fold``
``dr_limit_fold_delta``    the limit curve and its fold test in ``delta`` (the       every ``k``
                           maximum of ``delta`` along ``dr_limit``)
=========================  ========================================================  ==========

and any other fold (in ``gamma`` or ``delta``) of ``dr_limit``, ``rs_no_roll`` or the physical
part of ``dr_no_roll`` that exists at an end of the range. Where the picture of one ``k``
changes (a special point is born, dies, or crosses another), the curves have codimension-2
points: the *thresholds*, located as events of the two-parameter curves to ``1e-12`` and
polished by Newton on their square defining systems (the curve's four equations and the
event's), each reported with its equations (:class:`Threshold`):

* a special point is born or dies where its curve reaches the axis ``delta = 0`` (a terminal
  event): ``k_fold`` (the fold of ``rs_no_roll`` enters through the seed), ``k_branch`` (the
  junction is born at the branch point);
* one crosses another where a monitor event vanishes on its curve: ``upsilon = 0`` on the fold
  in ``delta`` of ``dr_limit`` is ``k_cross``, where the junction passes the maximum of
  ``delta``; a validity function vanishing on a fold curve is a fold leaving the physical part;
* two folds meet at a cusp, two junctions at a tangency (turning points of the curves in
  ``p``); none occurs for the paper's compliance.

Where a curve is found: each boundary is traced (as the tracer does) at both ends of the range
and, in ``k``, at ``k = 10 c`` inside it (where every special point of the paper's topology
exists and is well conditioned; at an end one can sit within rounding of a boundary's end and
go unseen); its folds and junction are the starting points, and each is followed towards the
other end or until it dies (both ways from the inner seed); a point already on a followed curve
is not followed again. A special point that is born and dies strictly inside the range, away
from ``k = 10 c``, would be missed: :mod:`~.topology` is checked against a bisection on the
per-``k`` topology in the tests, and the tracer checks every curve against it.
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, cast

import numpy as np

from continuation import (
    Codim2Curve,
    Codim2Kind,
    Codim2Point,
    Event,
    Options,
    SpecialPoint,
    follow_event,
    follow_fold,
)

from ..model.boundaries import Condition
from ..model.parameters import Compliance, check_friction
from .curves import PointKind
from .families import Axis, BoundaryFamily, domain_events, junction_event, special_points

__all__ = ["ATLAS_COLUMNS", "ATLAS_OPTIONS", "DEFAULT_K_RANGE", "DEFAULT_POISSON_RANGE",
           "POISSON_OPTIONS", "THRESHOLD_COLUMNS", "Atlas", "AtlasCurve", "Threshold",
           "trace_atlas", "trace_atlas_in_poisson"]

DEFAULT_K_RANGE = (1e-4, 1e6)
DEFAULT_POISSON_RANGE = (0.0, 0.5)

#: engine settings of the curves of special points: residuals to 1e-12, thresholds located to
#: 1e-12 in arclength; steps up to one unit of log k (a factor e), which the curves, smooth
#: in log k, allow; every point is on the curve whatever the step
ATLAS_OPTIONS = Options(tol=1e-12, ds=0.05, ds_min=1e-12, ds_max=1.0, max_steps=5000,
                        event_tol=1e-12, detect_closed=False)

#: the same in nu, whose range [0, 1/2] is short: steps of at most 0.02
POISSON_OPTIONS = dataclasses.replace(ATLAS_OPTIONS, ds=0.01, ds_max=0.02)

#: a point already on a followed curve (in the chart, and in p) is not followed again
SAME_POINT = 1e-7

#: codimension-2 points this close in p (relative to 1 + |p|) and in the chart are one threshold
COINCIDENT = 1e-9

#: a threshold this close to the singular corner (pi/4, pi/4) (max-norm in gamma and delta) is
#: not resolved: the fold of rs_no_roll lies ~0.37/k^2 from it (4e-13 at k = 1e6), below the
#: tracer's tolerance, and its events there (delta = gamma) are rounding; the atlas fails
CORNER_RESOLUTION = 1e-10

ATLAS_COLUMNS = ("curve", "k", "nu", "compliance", "gamma", "delta", "beta_L", "upsilon",
                 "physical", "threshold")

THRESHOLD_COLUMNS = ("threshold", "axis", "value", "fixed", "gamma", "delta", "beta_L",
                     "upsilon", "curve", "what", "equations", "residual", "also")

if TYPE_CHECKING:  # the tables are made with pandas only on request
    import pandas as pd

_FOLD_NAMES = {0: "gamma", 1: "delta"}
_BOUNDARIES = ("dr_limit", "rs_no_roll", "dr_no_roll")

#: what each curve's equations are, in words (n = sin(beta)^(3/2), q = sqrt(sin beta),
#: D = 2 sin(gamma) sin(delta), beta_R = pi - 2 gamma - beta_L, theta = gamma +- delta)
_EQUATIONS = {
    "dr_limit": ("limit: c (cos beta_L + upsilon) - k sin beta_L = 0 (T/N_L = k, d_L = 0)",
                 "horizontal balance: n_L (sin theta_L + k D) - n_R sin theta_R = 0",
                 "torque with the limit: 2 c q_R sin(gamma) sin(beta_L + gamma) - k sin(beta_L) "
                 "(q_L + q_R) = 0"),
    "rs_no_roll": ("right wall rolls: c q_R (cos beta_R - upsilon) - k n_L = 0",
                   "horizontal balance: n_L (sin theta_L + k D) - n_R sin theta_R = 0",
                   "upsilon = 0"),
    "dr_no_roll": ("torque / (beta_L - beta_R): (q_L cos beta_L - q_R cos beta_R) / (beta_L - "
                   "beta_R) = 0", "horizontal balance: n_L sin theta_L - n_R sin theta_R + c q_L "
                   "(cos beta_L + upsilon) D = 0", "upsilon = 0"),
}

#: known thresholds: (curve, event) -> (short name, what happens)
_KNOWN = {
    ("junction", "delta = 0"): (
        "branch", "the junction (upsilon = 0 on dr_limit, the end of dr_no_roll and start of "
                  "rs_no_roll) is born at the branch point (arctan sqrt 2, 0), which the seed "
                  "(arctan(k/c), 0) meets there"),
    ("rs_no_roll_fold_gamma", "delta = 0"): (
        "fold", "the fold in gamma of rs_no_roll enters through its start, the seed "
                "(arctan(k/c), 0)"),
    ("dr_limit_fold_delta", "upsilon = 0"): (
        "cross", "the junction passes the maximum of delta along dr_limit: below, the junction "
                 "comes first from the seed; above, the maximum does"),
}


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
        """
        p = self.axis.to_p(value)
        found: list[np.ndarray] = []
        for trace in self.traces:
            for z in trace.at(p):
                x = self.family.to_x(z)[0]
                if not any(np.max(np.abs(x - other)) <= 1e-12 for other in found):
                    found.append(x)
        return found

    def physical_at(self, value: float) -> list[np.ndarray]:
        """:meth:`at`, only the points on the physical part of the boundary."""
        p = self.axis.to_p(value)
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
    """

    axis: Axis
    range: tuple[float, float]
    curves: dict = field(repr=False)
    thresholds: tuple[Threshold, ...]
    failures: tuple[str, ...] = ()
    seconds: float = 0.0

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
        nu = _poisson(self.axis)
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


def trace_atlas(k_range=DEFAULT_K_RANGE, compliance: Compliance | float | None = None,
                options: Options | None = None) -> Atlas:
    """Follow every special point of the boundaries over ``k`` in ``k_range``.

    Parameters
    ----------
    k_range : (float, float)
        ``k_min < k_max``, both finite and > 0.
    compliance : Compliance or float, optional
        The compliance (or its ratio ``c``); default the paper's ``c = 1``.
    options : continuation.Options, optional
        Engine settings of the curves (default :data:`ATLAS_OPTIONS`).

    Returns
    -------
    Atlas
        Curves in ``p = log k``, thresholds, failures (``atlas.ok``).

    Raises
    ------
    ValueError
        If the range is not ``0 < k_min < k_max < inf``.
    """
    k_min, k_max = (check_friction(k) for k in k_range)
    if not k_min < k_max:
        raise ValueError(f"k_range = {tuple(k_range)!r} must satisfy k_min < k_max")
    if compliance is None:
        compliance = Compliance()
    ratio = compliance.ratio if isinstance(compliance, Compliance) else Compliance(
        compliance).ratio
    return _trace(Axis("k", ratio), math.log(k_min), math.log(k_max), (k_min, k_max), options)


def trace_atlas_in_poisson(k: float, nu_range=DEFAULT_POISSON_RANGE,
                           options: Options | None = None) -> Atlas:
    """Follow every special point over the Poisson ratio ``nu`` at a fixed ``k``.

    The compliance ratio is Mindlin's ``c(nu) = 2 (1 - nu)/(2 - nu)``
    (:meth:`~groove_model.model.parameters.Compliance.from_poisson`).

    Raises
    ------
    ValueError
        If ``k`` or the range is invalid (``-1 < nu_min < nu_max <= 1/2``).
    """
    k = check_friction(k)
    # from_poisson records the checked Poisson ratio (never None)
    nu_min, nu_max = (cast(float, Compliance.from_poisson(nu).poisson) for nu in nu_range)
    if not nu_min < nu_max:
        raise ValueError(f"nu_range = {tuple(nu_range)!r} must satisfy nu_min < nu_max")
    return _trace(Axis("nu", k), nu_min, nu_max, (nu_min, nu_max), options or POISSON_OPTIONS)


@dataclass
class _Start:
    name: str
    boundary: str
    kind: PointKind
    family: BoundaryFamily
    point: SpecialPoint
    p: float
    coordinate: int | None


def _starts(families: dict, p: float) -> list[_Start]:
    """The special points at ``p``: each boundary traced there, its folds and the junction."""
    starts = []
    for boundary in _BOUNDARIES:
        family = families[boundary]
        junction, folds = special_points(family, p)
        if junction is not None:
            starts.append(_Start("junction", "dr_limit", PointKind.JUNCTION, family, junction, p,
                                 None))
        if boundary == "dr_no_roll":  # its physical part only: branch point to junction
            folds = [f for f in folds if family.physical(np.append(f.x, p))]
        for coordinate, name in _FOLD_NAMES.items():
            points = [f for f in folds if f.coordinate == coordinate]
            kind = PointKind.FOLD_GAMMA if coordinate == 0 else PointKind.FOLD_DELTA
            for j, point in enumerate(points):
                label = f"{boundary}_fold_{name}" + (f"_{j + 1}" if j else "")
                starts.append(_Start(label, boundary, kind, family, point, p, coordinate))
    return starts


def _events(start: _Start) -> list[Event]:
    """Terminal domain events and the monitors of one curve (see the module docstring)."""
    family = start.family
    skip = (Condition.T_OVER_N_L,) if start.kind is PointKind.JUNCTION else ()
    events = [*domain_events(family), *family.validity_events(skip)]
    if start.boundary == "dr_limit" and start.kind is not PointKind.JUNCTION:
        events.append(Event("upsilon = 0", lambda z: z[3]))
    return events


def _covered(start: _Start, followed: list) -> bool:
    """Whether a followed curve of the same kind passes through ``start``: one of its points,
    or its point(s) at ``start.p`` corrected onto it, within ``SAME_POINT``."""
    z = np.append(start.point.x, start.p)
    tolerance = SAME_POINT * (1.0 + np.abs(z).max())
    for other, trace in followed:
        if (other.boundary, other.kind) != (start.boundary, start.kind):
            continue
        if np.any(np.max(np.abs(trace.z - z), axis=1) <= tolerance):
            return True
        try:
            points = trace.at(start.p)
        except ValueError:  # p stationary on the curve there (a cusp or tangency)
            points = []
        if any(np.max(np.abs(q - z)) <= tolerance for q in points):
            return True
    return False


def _follow(start: _Start, direction: int, p_range, options) -> Codim2Curve:
    events = _events(start)
    family = start.family.family
    if start.kind is PointKind.JUNCTION:
        return follow_event(family, junction_event(start.family.axis), start.point, p=start.p,
                            direction=direction, options=options, events=events,
                            parameter_range=p_range)
    return follow_fold(family, start.point, p=start.p, coordinate=start.coordinate,
                       direction=direction, options=options, events=events,
                       parameter_range=p_range)


def _trace(axis: Axis, p_lo: float, p_hi: float, value_range, options) -> Atlas:
    began = time.perf_counter()
    options = options or ATLAS_OPTIONS
    families = {boundary: BoundaryFamily(boundary, axis) for boundary in _BOUNDARIES}
    followed: list[tuple[_Start, Codim2Curve]] = []
    starts: dict[str, _Start] = {}
    failures = []
    seeds: list[tuple[float, tuple[int, ...]]] = [(p_hi, (-1,)), (p_lo, (1,))]
    inner = _inner_seed(axis, p_lo, p_hi)
    if inner is not None:
        seeds.append((inner, (-1, 1)))
    for p, directions in seeds:
        for start in _starts(families, p):
            if _covered(start, followed):
                continue
            if start.name in starts:  # a second curve of the same kind: _2, _3, ...
                start.name = next(f"{start.name}_{n}" for n in range(2, len(starts) + 3)
                                  if f"{start.name}_{n}" not in starts)
            starts[start.name] = start
            for direction in directions:
                trace = _follow(start, direction, (p_lo, p_hi), options)
                followed.append((start, trace))
                if not trace.ok:
                    failures.append(f"{start.name}: {trace.message}")
    # a fixed order: the junction, then the folds by boundary and coordinate
    order = sorted(starts.items(), key=lambda item: (
        item[1].kind is not PointKind.JUNCTION, _BOUNDARIES.index(item[1].boundary),
        item[1].coordinate or 0, item[0]))
    curves = {name: _curve(start, [t for s, t in followed if s is start])
              for name, start in order}
    thresholds = [t for start, trace in followed
                  for t in _thresholds(start, trace, len(_events(start)))]
    thresholds.sort(key=lambda t: t.value)
    unresolved = [t for t in thresholds if _corner_distance(t.x) <= CORNER_RESOLUTION]
    for t in unresolved:
        failures.append(f"{t.name} at {axis.name} = {t.value:.12g} is {_corner_distance(t.x):.1e} "
                        "from the singular corner (pi/4, pi/4), closer than events are resolved "
                        f"there ({CORNER_RESOLUTION:g}): no threshold can be trusted")
    thresholds = [t for t in thresholds if t not in unresolved]
    return Atlas(axis=axis, range=(float(value_range[0]), float(value_range[1])), curves=curves,
                 thresholds=tuple(thresholds), failures=tuple(failures),
                 seconds=time.perf_counter() - began)


def _corner_distance(x: np.ndarray) -> float:
    """Max-norm distance of ``(gamma, delta)`` from the corner ``(pi/4, pi/4)``."""
    return float(max(abs(x[0] - 0.25 * math.pi), abs(x[1] - 0.25 * math.pi)))


def _inner_seed(axis: Axis, p_lo: float, p_hi: float) -> float | None:
    """A third place to look for special points, inside the range, or ``None``.

    In ``k``: ``k = 10 c``, where every special point of the paper's topology exists (above
    ``k_branch = c sqrt 2``) and is well conditioned. At the ends of a wide range one can sit
    within rounding of a boundary's end and go unseen (the fold in ``gamma`` of ``rs_no_roll``
    is ``~1/k^2`` from the corner: at ``k = 8.6e5`` the tracer does not resolve it), and the
    curve through it would be missed. A point found here is followed both ways.
    """
    if axis.name != "k":
        return None
    p = math.log(10.0 * axis.fixed)
    return p if p_lo < p < p_hi else None


def _curve(start: _Start, traces: list[Codim2Curve]) -> AtlasCurve:
    """The rows of one curve, in increasing ``p`` from its lower end."""
    rows: list[np.ndarray] = []
    # increasing p: a start inside the range is followed both ways (down, then up from it)
    for trace in traces:
        z = trace.z[::-1] if len(trace) > 1 and trace.z[-1, -1] < trace.z[0, -1] else trace.z
        if rows and len(z) and len(rows[-1]) and z[0, -1] == rows[-1][-1, -1]:
            z = z[1:]  # the shared start
        rows.append(z)
    z = np.concatenate(rows) if rows else np.zeros((0, 5))
    family = start.family
    return AtlasCurve(start.name, start.boundary, start.kind, family.axis, z[:, -1].copy(),
                      family.to_x(z) if len(z) else np.zeros((0, 4)),
                      np.array([family.physical(row) for row in z], dtype=bool),
                      tuple(traces), family)


def _thresholds(start: _Start, trace: Codim2Curve, n_events: int) -> list[Threshold]:
    """The codimension-2 points of one followed curve, coincident ones merged, range ends
    dropped."""
    axis, family = start.family.axis, start.family
    points = [p for p in trace.points
              if not (p.kind is Codim2Kind.EVENT and p.event is not None
                      and p.event >= n_events)]
    # a terminal event first: it is the threshold, a monitor vanishing with it is "also"
    points.sort(key=lambda p: (not p.terminal, p.index))
    merged: list[list[Codim2Point]] = []
    for point in points:
        for group in merged:
            lead = group[0]
            if abs(point.p - lead.p) <= COINCIDENT * (1.0 + abs(lead.p)) and np.max(
                    np.abs(point.z[:-1] - lead.z[:-1])) <= SAME_POINT:
                group.append(point)
                break
        else:
            merged.append([point])
    return [_threshold(start, group, axis, family) for group in merged]


def _threshold(start: _Start, group: list, axis: Axis, family: BoundaryFamily) -> Threshold:
    lead = group[0]
    event = lead.name if lead.kind is Codim2Kind.EVENT else lead.kind.value
    known = _KNOWN.get((start.name, event))
    if known is None:
        short = f"{start.name}: {event}"
        what = {Codim2Kind.CUSP: f"two folds ({start.name}) meet and vanish (a cusp)",
                Codim2Kind.TANGENCY: "two junctions meet and vanish (a tangency)",
                Codim2Kind.BRANCH_POINT: f"{start.name} crosses another curve of special "
                                         "points"}.get(lead.kind, f"{start.name} meets {event}")
        name = short
    else:
        short, what = known
        name = f"{axis.name}_{short}"
    base = _EQUATIONS[start.boundary if start.kind is not PointKind.JUNCTION else "dr_no_roll"]
    if start.kind is PointKind.JUNCTION:
        extra = ("T/N_L = k: c (cos beta_L + upsilon) - k sin beta_L = 0",)
    else:
        other = "(delta, w, upsilon)" if start.coordinate == 0 else "(gamma, w, upsilon)"
        # a fold's start has its coordinate (the junction's alone has None)
        extra = (f"fold in {_FOLD_NAMES[cast(int, start.coordinate)]}: the Jacobian in {other} is "
                 "singular (minimally augmented test g = 0)",)
    equations = (*base, *extra, lead.equations[-1])
    return Threshold(name=name, value=float(axis.value(lead.p)), x=family.to_x(lead.z)[0],
                     curve=start.name, what=what, equations=equations, residual=lead.residual,
                     accuracy=lead.accuracy,
                     also=tuple(p.name for p in group[1:] if p.name != lead.name))
