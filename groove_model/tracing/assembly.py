"""From engine curves to boundaries: the tracer's events, their roles, and the assembly.

The engine reports events by position; each event of the tracer carries a :class:`Role`, so
that what a special point means never depends on its label. :func:`assemble` turns one engine
curve (in the tracer's chart) into a :class:`~groove_model.tracing.curves.BoundaryCurve` in
``x = (gamma, delta, beta_L, upsilon)``: rows moved onto the domain where rounding put them
just outside, folds and physical cut points marked, the part where the boundary's regime is
valid kept, and where it starts and ends recorded.
"""

from __future__ import annotations

import enum
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import cast

import numpy as np

from continuation import Curve, Event, Options, Problem, SpecialKind, trace
from continuation.numbers import FLOATS

from ..model.boundaries import BoundarySystem, Condition, corner_point
from .curves import POINT_ORDER, BoundaryCurve, BoundarySpecialPoint, PointKind, Where

__all__ = ["DOMAIN_TOLERANCE", "Role", "Tagged", "assemble", "domain_events", "into_domain",
           "trace_curve",
           "validity_events"]


#: how close (in gamma and delta) a point must be to (pi/4, pi/4) to be the corner
CORNER_TOLERANCE = 1e-9


#: a validity function (of order one, rounding of order eps) this far below zero is still valid:
#: the rounding of a located cut point, not a violated condition
PHYSICAL_TOLERANCE = 1e-12


#: a point this far outside the domain 0 <= delta <= gamma <= pi/2 (rounding along the edges
#: the curves end on) is moved onto it; farther out it is an error
DOMAIN_TOLERANCE = 1e-11


_FOLD_KINDS = {0: PointKind.FOLD_GAMMA, 1: PointKind.FOLD_DELTA}


class Role(enum.Enum):
    """What an event of the tracer means; the tracer decides by role, never by the event's name."""

    DOMAIN_EDGE = "domain edge"
    GAMMA_MIN = "gamma = gamma_min"
    CORNER = "beta_L = 0"
    VALIDITY = "validity"
    NO_ROLL = "upsilon = 0"


@dataclass(frozen=True)
class Tagged:
    """An engine event with its role and, for a validity event, the condition it checks.

    Event functions take ``(y, numbers)`` (:mod:`continuation.numbers`), so that the same
    formula is traced in floats and certified in balls. ``certified``, if given, is the
    function certified in its place: one with the same zeros and signs along the boundary
    but a simple zero where the traced one touches zero to higher order.
    """

    event: Event
    role: Role
    condition: Condition | None = None
    certified: Callable | None = None


def _edge(name: str, role: Role, function, gradient, certified=None, linear=True) -> Tagged:
    """A terminal event for leaving the domain (its function decreases through zero); most are
    affine in the chart coordinates (``Event.linear``)."""
    return Tagged(Event(name, function, direction=-1, terminal=True, gradient=gradient,
                        linear=linear), role, certified=certified)


def domain_events(system: BoundarySystem, gamma_min: float) -> list[Tagged]:
    """The domain ``0 <= delta <= gamma <= pi/2``, the contact range and the origin, in the chart.

    ``delta = gamma`` is certified through :meth:`BoundarySystem.edge_function`, which has the
    sign of ``gamma - delta`` along the boundary and a simple zero at the corner, where
    ``gamma - delta`` vanishes to third order on ``rs_no_roll``. The ``upsilon = 0`` lines end at
    that corner, and along them ``gamma - delta`` falls below the points' accuracy (about
    ``1e-13``) at ``w ~ 5e-5``, where it would stop them short of it: for them the event is
    that function in floats too (its gradient by central differences); the limit curves, which
    only approach ``delta = gamma`` towards the origin, use ``gamma - delta`` itself.
    """
    g = system.scale
    low = gamma_min / g

    def unit(*entries):
        # one constant array for every point (the engine only reads it)
        gradient = np.array(entries, dtype=float)
        gradient.flags.writeable = False
        return lambda y: gradient

    if system.name.endswith("no_roll"):
        edge_gamma = (system.edge_function, None)
    else:
        edge_gamma = (lambda y, numbers=FLOATS: y[0] - y[1], unit(1, -1, 0, 0))
    linear_gamma = not system.name.endswith("no_roll")
    return [
        _edge("delta = 0", Role.DOMAIN_EDGE, lambda y, numbers=FLOATS: y[1], unit(0, 1, 0, 0)),
        _edge("delta = gamma", Role.DOMAIN_EDGE, *edge_gamma, certified=system.edge_function,
              linear=linear_gamma),
        _edge("gamma = pi/2", Role.DOMAIN_EDGE,
              lambda y, numbers=FLOATS: 0.5 * numbers.pi / g - y[0], unit(-1, 0, 0, 0)),
        _edge("gamma = gamma_min", Role.GAMMA_MIN, lambda y, numbers=FLOATS: y[0] - low,
              unit(1, 0, 0, 0)),
        _edge("beta_L = 0", Role.CORNER, lambda y, numbers=FLOATS: y[2], unit(0, 0, 1, 0)),
        _edge("beta_R = 0", Role.DOMAIN_EDGE,
              lambda y, numbers=FLOATS: numbers.pi - 2.0 * g * y[0] - y[2] * y[2],
              lambda y: np.array([-2.0 * g, 0.0, -2.0 * y[2], 0.0]), linear=False),
    ]


def validity_events(system: BoundarySystem) -> list[Tagged]:
    """An event per validity condition of the boundary's regime (certified in the form of
    :attr:`BoundarySystem.certified_validity`)."""
    return [Tagged(Event(f"validity {condition.value}", f,
                         gradient=system.validity_gradient[condition]), Role.VALIDITY, condition,
                   certified=system.certified_validity[condition])
            for condition, f in system.validity.items()]


def trace_curve(system: BoundarySystem, start, direction, options: Options,
                 tagged: list[Tagged]) -> Curve:
    problem = Problem(system.residual, system.jacobian, names=("gamma", "delta", "w", "upsilon"))
    return trace(problem, start, direction=direction, options=options,
                 events=[t.event for t in tagged])


_CORNER_NOTE = "singular corner (pi/4, pi/4): beta_L = 0, N_L = 0"


def _at_corner(x) -> bool:
    return bool(np.max(np.abs(np.asarray(x)[:2] - corner_point()[:2])) <= CORNER_TOLERANCE)


def _end_role(curve: Curve, tagged: list[Tagged], x_end) -> Role | None:
    """The role of the terminal event that ended the curve (``CORNER`` for any end at it)."""
    if _at_corner(x_end):
        return Role.CORNER
    # an event point's ``event`` is the event's position (an int)
    ends = [p for p in curve.special_points if p.kind is SpecialKind.EVENT
            and p.index == len(curve) - 1 and tagged[cast(int, p.event)].event.terminal]
    return tagged[cast(int, ends[-1].event)].role if ends else None


_END_OF_ROLE = {Role.CORNER: Where.CORNER, Role.GAMMA_MIN: Where.GAMMA_MIN,
                Role.DOMAIN_EDGE: Where.DOMAIN_EDGE}


def _end_note(curve: Curve, tagged: list[Tagged], x_end) -> str:
    role = _end_role(curve, tagged, x_end)
    if role is Role.CORNER:
        return _CORNER_NOTE
    if role is Role.GAMMA_MIN:
        return (f"approaching the singular corner (0, 0) along delta = gamma; "
                f"stopped at gamma = {x_end[0]:.3g}")
    if role is not None:
        ends = [p for p in curve.special_points if p.kind is SpecialKind.EVENT
                and p.index == len(curve) - 1]
        return f"domain edge {ends[-1].name}"
    return curve.status.value


class _Marks:
    """The special points of one curve while it is assembled: rows, kinds, notes, and where
    its physical part ends at a regime limit (row -> the condition that fails beyond)."""

    def __init__(self) -> None:
        self.points: list[tuple[int, PointKind, str]] = []
        self.limits: dict[int, Condition] = {}

    def add(self, index: int, kind: PointKind, note: str) -> None:
        self.points.append((index, kind, note))


def _engine_marks(curve: Curve, physical: np.ndarray, tagged: list[Tagged],
                  marks: _Marks) -> None:
    """Folds and physical cut points of an engine curve, in its rows."""
    last = len(curve) - 1
    for p in curve.special_points:
        if p.index == 0:
            continue  # a validity function vanishes at a seed on the regime limit: no crossing
        if p.kind is SpecialKind.FOLD and p.coordinate in _FOLD_KINDS:
            if p.index == last or abs(curve.x[p.index][2]) <= CORNER_TOLERANCE:
                # At the end of the curve a stationary coordinate is no turning point; in the
                # w chart gamma and delta are stationary at the corner w = 0.
                continue
            coordinate = "gamma" if p.coordinate == 0 else "delta"
            marks.add(p.index, _FOLD_KINDS[p.coordinate], f"turning point in {coordinate}")
        elif p.kind is SpecialKind.EVENT and tagged[cast(int, p.event)].role is Role.VALIDITY:
            # A cut point: the physical part ends (or begins) here only if the physical flag
            # changes across it; a validity function that crosses zero while another one is
            # still violated (or touches zero) cuts nothing.
            i = p.index
            before = physical[i - 1] if i > 0 else False
            after = physical[i + 1] if i + 1 <= last else False
            # a validity event carries the condition it checks
            condition = cast(Condition, tagged[cast(int, p.event)].condition)
            if before and not after:
                marks.add(i, PointKind.END, f"regime limit: {condition} fails beyond")
                marks.limits[i] = condition
                if condition is Condition.T_OVER_N_L:
                    marks.add(i, PointKind.JUNCTION, "meets dr_limit (T = k N_L)")
            elif after and not before:
                marks.add(i, PointKind.START, f"regime becomes valid: {condition} holds beyond")


def _physical_end(curve: Curve, tagged: list[Tagged], physical: np.ndarray, x: np.ndarray,
                  marks: _Marks) -> Where:
    """Where the first physical part of an engine curve ends."""
    rows = np.flatnonzero(physical)
    if not rows.size or not curve.ok:
        return Where.NOWHERE
    breaks = np.flatnonzero(np.diff(rows) > 1)
    last = int(rows[breaks[0]] if breaks.size else rows[-1])
    if last in marks.limits:
        return Where.JUNCTION if marks.limits[last] is Condition.T_OVER_N_L \
            else Where.REGIME_LIMIT
    if last == len(x) - 1:
        role = _end_role(curve, tagged, x[-1])
        return _END_OF_ROLE.get(role, Where.NOWHERE) if role is not None else Where.NOWHERE
    return Where.REGIME_LIMIT


def into_domain(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Points moved onto ``0 <= delta <= gamma <= pi/2`` where rounding put them just outside.

    The limit curves start on ``delta = 0`` and end along ``delta = gamma``, the ``upsilon = 0``
    lines end at the corner on ``delta = gamma``: points on these edges are computed to the
    Newton tolerance and may fall outside by that much. Returns the points and a flag per
    point that was farther out than :data:`DOMAIN_TOLERANCE` (left as it is).
    """
    x = x.copy()
    gamma, delta = x[:, 0], x[:, 1]
    excess = np.maximum.reduce([-delta, delta - gamma, gamma - 0.5 * math.pi]) \
        if len(x) else np.zeros(0)
    outside = excess > DOMAIN_TOLERANCE
    near = (excess > 0.0) & ~outside
    gamma[near] = np.minimum(gamma[near], 0.5 * math.pi)
    delta[near] = np.clip(delta[near], 0.0, gamma[near])
    return x, outside


def _largest_scaled_residual(system: BoundarySystem, x: np.ndarray) -> float:
    """``max`` over the rows of :meth:`BoundarySystem.scaled_residual`, every row at once
    (the same numbers, row by row)."""
    if not len(x):
        return 0.0
    return float(np.max(np.abs(system.residuals(x)) / system.row_scales))


def assemble(name: str, system: BoundarySystem, curve: Curve, tagged: list[Tagged],
              keep_unphysical: bool, start: Where, start_note: str,
              junctions=()) -> BoundaryCurve:
    """Turn one engine curve into a BoundaryCurve in x, cut to its physical part.

    ``junctions``: ``(row, note, x)`` marks a junction at a row and puts it at ``x``.
    """
    x, outside = into_domain(system.to_x(curve.x))
    physical = system.physical(curve.x, tol=PHYSICAL_TOLERANCE)
    marks = _Marks()
    marks.add(0, PointKind.START, start_note)
    if start is Where.BRANCH_POINT:
        marks.add(0, PointKind.BRANCH_POINT, start_note)
    elif start is Where.JUNCTION:
        marks.add(0, PointKind.JUNCTION, start_note)
    _engine_marks(curve, physical, tagged, marks)
    for index, note, exact in junctions:
        marks.add(index, PointKind.JUNCTION, note)
        x[index] = exact  # the junction as found where it is well conditioned
    end = _physical_end(curve, tagged, physical, x, marks)
    if curve.ok and len(x):
        marks.add(len(x) - 1, PointKind.END, _end_note(curve, tagged, x[-1]))
        if _at_corner(x[-1]):
            x[-1] = corner_point()  # exactly the corner, where every residual vanishes
    # the arclength of the rows as written, after the junction and the corner were put in
    # place (before, a junction moved by 6.7e-10 from a row 1.8e-11 away had s 97% short)
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(x, axis=0), axis=1))])

    keep = np.ones(len(x), bool) if keep_unphysical else physical
    index_map = np.cumsum(keep) - 1
    points = [BoundarySpecialPoint(name, kind, x[i].copy(), float(s[i]), int(index_map[i]), note)
              for i, kind, note in marks.points if keep[i]]
    if np.any(keep):
        # Every kept part starts and ends at a located point: mark the first and last.
        first, last = np.flatnonzero(keep)[[0, -1]]
        kinds = {(p.index, p.kind) for p in points}
        if (int(index_map[first]), PointKind.START) not in kinds:
            points.append(BoundarySpecialPoint(name, PointKind.START, x[first].copy(),
                                               float(s[first]), int(index_map[first]),
                                               "regime becomes valid"))
        if curve.ok and (int(index_map[last]), PointKind.END) not in kinds:
            note = next((p.note for p in points if p.index == index_map[last]), "regime limit")
            points.append(BoundarySpecialPoint(name, PointKind.END, x[last].copy(),
                                               float(s[last]), int(index_map[last]), note))
    points.sort(key=lambda p: (p.index, POINT_ORDER[p.kind]))
    # Check the reported points in the x form of the paper's equations (the form written to CSV),
    # each equation divided by the largest size of its terms (row_scales).
    in_x = BoundarySystem(name, system.params)
    residual = _largest_scaled_residual(in_x, x[keep])
    status = curve.status.value if curve.ok else curve.message
    ok = curve.ok
    if ok and np.any(outside[keep]):
        i = int(np.flatnonzero(outside & keep)[0])
        ok, status = False, (f"row {i} ({float(x[i][0])!r}, {float(x[i][1])!r}) is outside the "
                             f"domain 0 <= delta <= gamma <= pi/2 by more than "
                             f"{DOMAIN_TOLERANCE:g}")
    physical_start = start if physical.size and physical[0] else Where.NOWHERE
    if physical.size and not physical[0] and np.any(physical):
        physical_start = Where.REGIME_LIMIT
    return BoundaryCurve(name=name, k=system.params.k, x=x[keep], s=s[keep],
                         physical=physical[keep], special_points=tuple(points),
                         status=status, ok=ok, residual=residual, engine=(curve,),
                         start=physical_start, end=end if np.any(physical) else Where.NOWHERE,
                         engine_rows=np.flatnonzero(keep), params=system.params)

