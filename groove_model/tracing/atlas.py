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
from dataclasses import dataclass
from typing import cast

import numpy as np

from continuation import (
    Codim2Curve,
    Codim2Kind,
    Codim2Point,
    Event,
    Options,
    SpecialPoint,
    Status,
    follow_event,
    follow_fold,
)

from ..model.boundaries import Condition
from ..model.parameters import (
    Compliance,
    check_friction,
    check_traced_poisson,
    traced_compliance,
    traced_friction,
)
from .atlas_result import ATLAS_COLUMNS, THRESHOLD_COLUMNS, Atlas, AtlasCurve, Threshold
from .curves import PointKind
from .families import Axis, BoundaryFamily, domain_events, junction_event, special_points

__all__ = ["ATLAS_COLUMNS", "ATLAS_OPTIONS", "DEFAULT_K_RANGE", "DEFAULT_POISSON_RANGE",
           "POISSON_OPTIONS", "THRESHOLD_COLUMNS", "Atlas", "AtlasCurve", "Threshold",
           "atlas_in_k", "trace_atlas", "trace_atlas_in_poisson"]

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
#: not resolved, and the atlas fails instead of reporting it: the fold of rs_no_roll lies
#: ~0.37/k^2 from it (4e-13 at k = 1e6), below the points' accuracy. Its event delta = gamma is
#: computed in a form exact there (families.edge_event: it vanishes only at beta_L = 0, which
#: no fold reaches at a finite k), so this is a safeguard, which none of the atlases checked
#: trips; gamma - delta itself vanished there by rounding (k = 7e5 in nu, say)
CORNER_RESOLUTION = 1e-10


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


def trace_atlas(k_range=DEFAULT_K_RANGE, compliance: Compliance | float | None = None,
                options: Options | None = None) -> Atlas:
    """Follow every special point of the boundaries over ``k`` in ``k_range``.

    Parameters
    ----------
    k_range : (float, float)
        ``k_min < k_max``, both in the traced range ``1e-4 <= k <= 1e6``.
    compliance : Compliance or float, optional
        The compliance (or its ratio ``c``, ``2/3 <= c <= 1``: Mindlin's for Poisson ratios
        ``0 <= nu <= 1/2``); default the paper's ``c = 1``.
    options : continuation.Options, optional
        Engine settings of the curves (default :data:`ATLAS_OPTIONS`).

    Returns
    -------
    Atlas
        Curves in ``p = log k``, thresholds, failures (``atlas.ok``).

    Raises
    ------
    ValueError
        If ``k_min >= k_max``, or the range or the ratio is outside the traced ranges (the
        message names the value and the range).
    TypeError
        If ``k_range`` is not a pair of numbers.
    """
    # (a k that is not positive or not finite is named with the traced range too)
    k_min, k_max = (traced_friction(k) for k in _pair("k_range", k_range, "(k_min, k_max)"))
    compliance = traced_compliance(compliance)
    atlas = atlas_in_k((k_min, k_max), compliance.ratio, options)
    # the Poisson ratio as given, for the tables (the atlas itself keeps the ratio only)
    return dataclasses.replace(atlas, poisson=compliance.poisson)


def _pair(name: str, value, form: str) -> tuple:
    """``value`` as a pair, or ``TypeError`` naming it (a range is two numbers)."""
    if isinstance(value, (str, bytes)):
        raise TypeError(f"{name} must be a pair {form}, got {value!r}")
    try:
        pair = tuple(value)
    except TypeError:
        raise TypeError(f"{name} must be a pair {form}, got {value!r}") from None
    if len(pair) != 2:
        raise TypeError(f"{name} must be a pair {form}, got {len(pair)} values: {value!r}")
    return pair


def atlas_in_k(k_range, ratio: float, options: Options | None = None) -> Atlas:
    """:func:`trace_atlas` without the check of the traced ranges.

    For the tracer's topology table (:func:`~groove_model.tracing.topology.thresholds`), which
    reads the atlas over ``1e-4 c <= k <= 1e6 c`` (the same range of ``k/c`` for every ``c``),
    whose lower end lies below ``1e-4`` for ``c < 1``.
    """
    k_min, k_max = (check_friction(k) for k in _pair("k_range", k_range, "(k_min, k_max)"))
    if not k_min < k_max:
        raise ValueError(f"k_range = {tuple(k_range)!r} must satisfy k_min < k_max")
    return _trace(Axis("k", Compliance(ratio).ratio), math.log(k_min), math.log(k_max),
                  (k_min, k_max), options)


def trace_atlas_in_poisson(k: float, nu_range=DEFAULT_POISSON_RANGE,
                           options: Options | None = None) -> Atlas:
    """Follow every special point over the Poisson ratio ``nu`` at a fixed ``k``.

    The compliance ratio is Mindlin's ``c(nu) = 2 (1 - nu)/(2 - nu)``
    (:meth:`~groove_model.model.parameters.Compliance.from_poisson`).

    At large ``k`` the fold in ``gamma`` of ``rs_no_roll`` lies within about ``1e-12`` of the
    singular corner ``(pi/4, pi/4)`` (``beta_L = (2c/(3k))^2``, ``gamma - delta ~
    8 c^3/(27 k^2)``), closer than its points resolve ``gamma - delta``; its event
    ``delta = gamma`` is computed in a form exact there
    (:func:`~groove_model.tracing.families.edge_event`), which vanishes only at the corner
    itself, so the fold's curve runs over the whole range for every ``k`` of the traced range.

    Raises
    ------
    ValueError
        If ``k`` or the range is invalid: ``1e-4 <= k <= 1e6`` and
        ``0 <= nu_min < nu_max <= 1/2`` (the traced ranges).
    """
    k = traced_friction(k)
    nu_min, nu_max = (check_traced_poisson(nu)
                      for nu in _pair("nu_range", nu_range, "(nu_min, nu_max)"))
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
                elif trace.status in (Status.MAX_STEPS, Status.MAX_ARCLENGTH):
                    # the options' limit, not an end of the curve: the rest of the range, and
                    # the thresholds on it, would be missing from an atlas reported ok
                    failures.append(f"{start.name}: stopped before the curve's end at "
                                    f"{axis.name} = {float(axis.value(trace.p[-1])):.12g}: "
                                    f"{trace.message}; raise Options.max_steps or "
                                    "max_arclength")
    # a fixed order: the junction, then the folds by boundary and coordinate
    order = sorted(starts.items(), key=lambda item: (
        item[1].kind is not PointKind.JUNCTION, _BOUNDARIES.index(item[1].boundary),
        item[1].coordinate or 0, item[0]))
    curves = {name: _curve(start, [t for s, t in followed if s is start], (p_lo, p_hi))
              for name, start in order}
    thresholds = [t for start, trace in followed
                  for t in _thresholds(start, trace, len(_events(start)))]
    thresholds.sort(key=lambda t: t.value)
    unresolved = [t for t in thresholds if _corner_distance(t.x) <= CORNER_RESOLUTION]
    for t in unresolved:
        failures.append(f"{t.name} at {axis.name} = {t.value:.12g} is {_corner_distance(t.x):.1e} "
                        "from the singular corner (pi/4, pi/4), closer than events are resolved "
                        f"there ({CORNER_RESOLUTION:g}): no threshold can be trusted")
    thresholds = [t for t in thresholds if _corner_distance(t.x) > CORNER_RESOLUTION]
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


def _curve(start: _Start, traces: list[Codim2Curve], p_range) -> AtlasCurve:
    """The rows of one curve, in increasing ``p`` from its lower end; a ``p`` beyond an end of
    ``p_range`` by rounding (``nu = -2e-13``) is put on that end."""
    rows: list[np.ndarray] = []
    # increasing p: a start inside the range is followed both ways (down, then up from it)
    for trace in traces:
        z = trace.z[::-1] if len(trace) > 1 and trace.z[-1, -1] < trace.z[0, -1] else trace.z
        if rows and len(z) and len(rows[-1]) and z[0, -1] == rows[-1][-1, -1]:
            z = z[1:]  # the shared start
        rows.append(z)
    z = np.concatenate(rows) if rows else np.zeros((0, 5))
    for end, beyond in ((p_range[0], z[:, -1] < p_range[0]), (p_range[1], z[:, -1] > p_range[1])):
        rounding = beyond & (np.abs(z[:, -1] - end) <= 1e-9 * (1.0 + abs(end)))
        z[rounding, -1] = end
    family = start.family
    return AtlasCurve(start.name, start.boundary, start.kind, family.axis, z[:, -1].copy(),
                      family.to_x(z) if len(z) else np.zeros((0, 4)),
                      np.array([family.physical(row) for row in z], dtype=bool),
                      tuple(traces), family, (float(p_range[0]), float(p_range[1])))


def _coincide(a: Codim2Point, b: Codim2Point) -> bool:
    """Whether two codimension-2 points are one (:data:`COINCIDENT` in ``p``, :data:`SAME_POINT`
    in the chart)."""
    return abs(a.p - b.p) <= COINCIDENT * (1.0 + abs(b.p)) and bool(
        np.max(np.abs(a.z[:-1] - b.z[:-1])) <= SAME_POINT)


def _thresholds(start: _Start, trace: Codim2Curve, n_events: int) -> list[Threshold]:
    """The codimension-2 points of one followed curve, coincident ones merged; the ends of
    the range, and any point that coincides with one, dropped (a threshold at an end is
    located there by chance, and by whichever of its functions vanishes first: it is not
    listed, rather than listed under another function's name)."""
    axis, family = start.family.axis, start.family
    ends = [p for p in trace.points
            if p.kind is Codim2Kind.EVENT and p.event is not None and p.event >= n_events]
    points = [p for p in trace.points if not any(p is end for end in ends)]
    # a terminal event first: it is the threshold, a monitor vanishing with it is "also"
    points.sort(key=lambda p: (not p.terminal, p.index))
    merged: list[list[Codim2Point]] = []
    for point in points:
        for group in merged:
            if _coincide(point, group[0]):
                group.append(point)
                break
        else:
            merged.append([point])
    return [_threshold(start, group, axis, family) for group in merged
            if not any(_coincide(point, end) for point in group for end in ends)]


def _threshold(start: _Start, group: list, axis: Axis, family: BoundaryFamily) -> Threshold:
    lead = group[0]
    event = lead.name if lead.kind is Codim2Kind.EVENT else lead.kind.value
    known = _KNOWN.get((start.name, event))
    if known is None:
        short = f"{start.name}: {event}"
        what = {Codim2Kind.CUSP: f"two folds ({start.name}) meet and vanish (a cusp)",
                Codim2Kind.SINGULAR: f"the boundary of {start.name} is itself singular there "
                                     "(its Jacobian loses rank)",
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
