r"""Trace every regime boundary for a friction coefficient ``k`` with the continuation engine.

Which curve starts and ends where follows from ``k`` (the table in :mod:`groove_model.topology`,
with its thresholds ``k_fold = c/sqrt 2`` and ``k_branch = c sqrt 2`` computed from the
equations):

* ``dr_limit`` and ``rs_limit`` (one curve seen from the two regimes) start at
  ``(arctan(k/c), 0)`` and run towards the origin, which they approach tangentially to
  ``delta = gamma`` with ``beta_L ~ 2 gamma^2 / k``; the origin is a singular corner (a flat
  groove), so they stop at ``gamma = gamma_min``. On the way ``delta`` has one maximum (a fold in
  ``delta``), and for ``k > k_branch`` ``upsilon`` vanishes once: the junction with the
  ``upsilon = 0`` lines.
* ``dr_no_roll`` leaves the symmetric family ``delta = 0`` at the branch point
  ``(arctan sqrt 2, 0)``; its physical part (``T/N_L <= k``) ends at the junction, so it has
  one only for ``k > k_branch``. It is traced in its deflated form (the no-roll torque divided
  by ``beta_L - beta_R``, :mod:`groove_model.boundaries`), whose zero set is this branch alone
  and passes the branch point as a regular point: points next to the branch point are then as
  accurate as anywhere (with the paper's form, which also vanishes on the symmetric family,
  a point at distance ``d`` from the branch point carries errors of order ``eps / d``, so the
  junction of a ``k`` within ``1e-7`` of ``k_branch`` would be off by ``1e-9``).
* ``rs_no_roll`` starts at the junction when ``k > k_branch``, at ``(arctan(k/c), 0)``
  otherwise, and ends at the corner ``(pi/4, pi/4)``; for ``k > k_fold`` it turns once in
  ``gamma`` (for large ``k`` ever closer to the corner, at ``beta_L`` of order ``1/k^2``).

The curves are traced in the chart ``y = (gamma / g, delta / g, w, upsilon)``, ``beta_L = w^2``,
where every residual is analytic and the corner ``beta_L = 0`` is a regular point located as the
event ``w = 0`` (see :mod:`groove_model.boundaries`); ``g = min(1, arctan(k/c))`` for the limit
curves, whose extent in ``gamma`` and ``delta`` is ``arctan(k/c)``, and 1 for the others. Results
are reported in ``x = (gamma, delta, beta_L, upsilon)``. Each curve is cut to its physical part
(its regime valid) at validity events the engine locates exactly; ``keep_unphysical=True``
keeps the rest, flagged ``physical = False``.

Nothing is reported as traced that has not been checked: the engine brackets every zero of an
event and of the tangent's ``gamma`` and ``delta`` components inside each step (pairs of zeros
included) and fails loudly where it cannot locate one; every curve is then compared with the
expected topology for its ``k`` (starts, ends, junctions, folds), and a curve that differs is a
failure with a message saying what differs.
"""

from __future__ import annotations

import enum
import logging
import math
import dataclasses
from dataclasses import dataclass, field

import numpy as np
import pandas as pd
from scipy.linalg.lapack import dgesv

from continuation import Curve, Event, Options, Problem, SpecialKind, trace

from .model.boundaries import (
    BOUNDARY_NAMES,
    BoundarySystem,
    Condition,
    corner_point,
    dr_no_roll_branch_point,
    limit_seed,
)
from .model.parameters import Parameters
from .topology import CurveTopology, expected_topology

__all__ = [
    "CSV_COLUMNS",
    "SPECIAL_POINT_COLUMNS",
    "BoundaryCurve",
    "BoundarySet",
    "BoundarySpecialPoint",
    "PointKind",
    "TraceError",
    "boundary_quantities",
    "trace_boundaries",
]

log = logging.getLogger(__name__)

CSV_COLUMNS = ("boundary", "k", "s", "gamma", "delta", "theta_L", "theta_R", "beta_L", "beta_R",
               "upsilon", "T_over_N_L", "T_over_N_R", "d_L", "physical", "point")
SPECIAL_POINT_COLUMNS = ("boundary", "k", "kind", "gamma", "delta", "beta_L", "upsilon")


class PointKind(str, enum.Enum):
    """Kinds of boundary special points; the values are the names in the CSV files."""

    START = "start"
    END = "end"
    JUNCTION = "junction"
    FOLD_GAMMA = "fold_gamma"
    FOLD_DELTA = "fold_delta"
    BRANCH_POINT = "branch_point"

    def __str__(self) -> str:
        return self.value


#: legacy tuple of the kind names
SPECIAL_KINDS = tuple(kind.value for kind in PointKind)
_PRIORITY = {PointKind.BRANCH_POINT: 0, PointKind.JUNCTION: 1, PointKind.FOLD_GAMMA: 2,
             PointKind.FOLD_DELTA: 3, PointKind.START: 4, PointKind.END: 5}
_FOLD_KINDS = {0: PointKind.FOLD_GAMMA, 1: PointKind.FOLD_DELTA}

#: Engine settings for the boundaries: residuals to 1e-12 (so that rs_limit and dr_limit, two
#: systems for one curve, agree to about 1e-12); CSV rows recomputed from their 17-digit columns
#: satisfy the equations to 1e-10 (rounding of the columns is amplified where |J| ~ 2e4); steps
#: small enough for smooth plots; folds in gamma and in delta located.
DEFAULT_OPTIONS = Options(tol=1e-12, ds=0.02, ds_min=1e-12, ds_max=0.05, max_steps=5000,
                          fold_coordinates=(0, 1), detect_branch_points=False,
                          detect_closed=False)
GAMMA_MIN = 1e-3

#: how close (in gamma and delta) a point must be to (pi/4, pi/4) to be the corner
CORNER_TOLERANCE = 1e-9

#: largest accepted distance between rs_limit and dr_limit, which are one curve
LIMIT_TOLERANCE = 1e-10

#: a validity function (of order one, rounding of order eps) this far below zero is still valid:
#: the rounding of a located cut point, not a violated condition
PHYSICAL_TOLERANCE = 1e-12

#: a point this far outside the domain 0 <= delta <= gamma <= pi/2 (rounding along the edges
#: the curves end on) is moved onto it; farther out it is an error
DOMAIN_TOLERANCE = 1e-11


class Role(enum.Enum):
    """What an event of the tracer means; the tracer decides by role, never by the event's name."""

    DOMAIN_EDGE = "domain edge"
    GAMMA_MIN = "gamma = gamma_min"
    CORNER = "beta_L = 0"
    VALIDITY = "validity"
    NO_ROLL = "upsilon = 0"


@dataclass(frozen=True)
class _Tagged:
    """An engine event with its role and, for a validity event, the condition it checks."""

    event: Event
    role: Role
    condition: Condition | None = None


class Where(str, enum.Enum):
    """Where a boundary's physical part starts or ends."""

    SEED = "seed"
    BRANCH_POINT = "branch_point"
    JUNCTION = "junction"
    GAMMA_MIN = "gamma_min"
    CORNER = "corner"
    REGIME_LIMIT = "regime_limit"
    DOMAIN_EDGE = "domain_edge"
    NOWHERE = "nowhere"

    def __str__(self) -> str:
        return self.value


class TraceError(RuntimeError):
    """A boundary could not be traced; ``boundary_set`` holds everything that was traced."""

    def __init__(self, message: str, boundary_set: BoundarySet) -> None:
        super().__init__(message)
        self.boundary_set = boundary_set


@dataclass(frozen=True)
class BoundarySpecialPoint:
    """A special point of a boundary.

    Attributes
    ----------
    boundary : str
    kind : PointKind
        ``start``, ``end``, ``junction`` (where boundaries meet), ``fold_gamma`` and
        ``fold_delta`` (turning points in gamma and in delta) or ``branch_point``.
    x : ndarray, shape (4,)
        ``(gamma, delta, beta_L, upsilon)``.
    s : float
        Arclength along the boundary in ``x`` (radians).
    index : int
        Row of the point in ``BoundaryCurve.x``.
    note : str
        What the point is, e.g. "singular corner (pi/4, pi/4): beta_L = 0, N_L = 0".
    """

    boundary: str
    kind: PointKind
    x: np.ndarray = field(repr=False)
    s: float
    index: int
    note: str = ""


@dataclass(frozen=True)
class BoundaryCurve:
    """One traced boundary in ``x = (gamma, delta, beta_L, upsilon)``.

    Attributes
    ----------
    name : str
    k : float
    x : ndarray, shape (m, 4)
    s : ndarray, shape (m,)
        Arclength in ``x`` from the first traced point.
    physical : ndarray of bool, shape (m,)
        Whether the boundary's regime is valid at each point.
    special_points : tuple of BoundarySpecialPoint
    status : str
        The engine's status message of the run behind the curve, or what failed.
    ok : bool
        False if the engine failed or the curve differs from the expected topology; the
        points traced are kept.
    residual : float
        Largest ``|H_i| / scale_i`` over the points, in the ``x`` form of the paper's equations
        (:meth:`groove_model.boundaries.BoundarySystem.scaled_residual`: each equation relative
        to the size of its terms, which grow with ``k``).
    start, end : Where
        Where the physical part starts and ends (``NOWHERE`` if it has none or the engine
        failed before its end).
    """

    name: str
    k: float
    x: np.ndarray = field(repr=False)
    s: np.ndarray = field(repr=False)
    physical: np.ndarray = field(repr=False)
    special_points: tuple = ()
    status: str = ""
    ok: bool = True
    residual: float = 0.0
    engine: tuple = field(default=(), repr=False, compare=False)
    start: Where = Where.NOWHERE
    end: Where = Where.NOWHERE

    def failed(self, message: str) -> BoundaryCurve:
        """This curve marked as failed, with ``message`` as its status."""
        return dataclasses.replace(self, status=message, ok=False)

    def special(self, kind: PointKind | str) -> tuple:
        """The special points of one kind."""
        kind = PointKind(kind)
        return tuple(p for p in self.special_points if p.kind is kind)

    def to_frame(self, params: Parameters | None = None) -> pd.DataFrame:
        """The CSV table of this boundary (columns :data:`CSV_COLUMNS`)."""
        params = params or Parameters(self.k)
        q = boundary_quantities(self.name, self.x, params)
        point = np.full(len(self.x), "", dtype=object)
        for p in sorted(self.special_points, key=lambda p: -_PRIORITY[p.kind]):
            point[p.index] = p.kind.value
        return pd.DataFrame({"boundary": self.name, "k": self.k, "s": self.s,
                             **q, "physical": self.physical, "point": point},
                            columns=list(CSV_COLUMNS))


@dataclass(frozen=True)
class BoundarySet:
    """Every boundary traced for one ``k``.

    Attributes
    ----------
    k : float
    curves : dict of str to BoundaryCurve
        By name, in the order of ``BOUNDARY_NAMES``; a boundary with no physical part is
        absent unless the unphysical parts were kept.
    limit_distance : float
        Largest distance in ``x`` from a point of ``rs_limit`` to the curve ``dr_limit``
        (they are the same curve, paper "Rolling-sliding solutions").
    notes : tuple of str
        What was found, e.g. that ``dr_no_roll`` has no physical part for ``k < sqrt 2``.
    params : Parameters
        The parameters of the trace.
    """

    k: float
    curves: dict = field(repr=False)
    limit_distance: float = math.nan
    notes: tuple = ()
    params: Parameters | None = field(default=None, repr=False, compare=False)

    @property
    def ok(self) -> bool:
        return all(c.ok for c in self.curves.values())

    @property
    def failures(self) -> tuple:
        return tuple(f"{c.name}: {c.status}" for c in self.curves.values() if not c.ok)

    def to_frame(self) -> pd.DataFrame:
        """All boundaries as one table (columns :data:`CSV_COLUMNS`)."""
        params = self.params or Parameters(self.k)
        frames = [c.to_frame(params) for c in self.curves.values()]
        return pd.concat(frames, ignore_index=True) if frames else pd.DataFrame(
            columns=list(CSV_COLUMNS))

    def special_points_frame(self) -> pd.DataFrame:
        """All special points (columns :data:`SPECIAL_POINT_COLUMNS`, plus ``note``)."""
        rows = [dict(boundary=p.boundary, k=self.k, kind=p.kind.value, gamma=p.x[0],
                     delta=p.x[1], beta_L=p.x[2], upsilon=p.x[3], note=p.note)
                for c in self.curves.values() for p in c.special_points]
        return pd.DataFrame(rows, columns=[*SPECIAL_POINT_COLUMNS, "note"])


def boundary_quantities(name: str, x, params: Parameters) -> dict:
    """Angles, force ratios and slip along a boundary from its points ``x`` (m, 4).

    Double-rolling boundaries: ``T/N_L = c (cos beta_L + upsilon) / sin beta_L``,
    ``T/N_R = c (cos beta_R - upsilon) / sin beta_R``, ``d_L = 0``. Rolling-sliding ones:
    ``T/N_L = k``, ``T/N_R = mu`` from the rolling right wall, ``d_L / Z = cos beta_L + upsilon -
    (k/c) sin beta_L``. ``T/N_L`` is ``inf`` where ``beta_L = 0`` (``N_L = 0``).
    """
    x = np.atleast_2d(np.asarray(x, dtype=float))
    gamma, delta, beta_L, upsilon = x.T
    beta_R = math.pi - 2.0 * gamma - beta_L
    k, c = params.k, params.c
    s_L, s_R = np.sin(beta_L), np.sin(beta_R)
    A, B = np.cos(beta_L) + upsilon, np.cos(beta_R) - upsilon
    T_over_N_R = np.full_like(gamma, np.inf)
    np.divide(c * B, s_R, out=T_over_N_R, where=s_R != 0.0)
    if name.startswith("dr"):
        T_over_N_L = np.full_like(gamma, np.inf)
        np.divide(c * A, s_L, out=T_over_N_L, where=s_L != 0.0)
        d_L = np.zeros_like(gamma)
    else:
        T_over_N_L = np.full_like(gamma, k)
        d_L = A - (k / c) * s_L
    return dict(gamma=gamma, delta=delta, theta_L=gamma + delta, theta_R=gamma - delta,
                beta_L=beta_L, beta_R=beta_R, upsilon=upsilon, T_over_N_L=T_over_N_L,
                T_over_N_R=T_over_N_R, d_L=d_L)


# --- events ---------------------------------------------------------------------------------

def _edge(name: str, role: Role, function, gradient) -> _Tagged:
    """A terminal event for leaving the domain (its function decreases through zero)."""
    return _Tagged(Event(name, function, direction=-1, terminal=True, gradient=gradient), role)


def _domain_events(system: BoundarySystem, gamma_min: float) -> list[_Tagged]:
    """The domain ``0 <= delta <= gamma <= pi/2``, the contact range and the origin, in the chart."""
    g = system.scale
    half_pi = 0.5 * math.pi

    def unit(*entries):
        return lambda y: np.array(entries, dtype=float)

    return [
        _edge("delta = 0", Role.DOMAIN_EDGE, lambda y: y[1], unit(0, 1, 0, 0)),
        _edge("delta = gamma", Role.DOMAIN_EDGE, lambda y: y[0] - y[1], unit(1, -1, 0, 0)),
        _edge("gamma = pi/2", Role.DOMAIN_EDGE, lambda y: half_pi / g - y[0], unit(-1, 0, 0, 0)),
        _edge("gamma = gamma_min", Role.GAMMA_MIN, lambda y: y[0] - gamma_min / g,
              unit(1, 0, 0, 0)),
        _edge("beta_L = 0", Role.CORNER, lambda y: y[2], unit(0, 0, 1, 0)),
        _edge("beta_R = 0", Role.DOMAIN_EDGE, lambda y: math.pi - 2.0 * g * y[0] - y[2] * y[2],
              lambda y: np.array([-2.0 * g, 0.0, -2.0 * y[2], 0.0])),
    ]


def _validity_events(system: BoundarySystem) -> list[_Tagged]:
    return [_Tagged(Event(f"validity {condition.value}", f), Role.VALIDITY, condition)
            for condition, f in system.validity.items()]


def _trace_curve(system: BoundarySystem, start, direction, options: Options,
                 tagged: list[_Tagged]) -> Curve:
    problem = Problem(system.residual, system.jacobian, names=("gamma", "delta", "w", "upsilon"))
    return trace(problem, start, direction=direction, options=options,
                 events=[t.event for t in tagged])


# --- assembling engine curves into boundaries ----------------------------------------------

_CORNER_NOTE = "singular corner (pi/4, pi/4): beta_L = 0, N_L = 0"


def _at_corner(x) -> bool:
    return bool(np.max(np.abs(np.asarray(x)[:2] - corner_point()[:2])) <= CORNER_TOLERANCE)


def _end_role(curve: Curve, tagged: list[_Tagged], x_end) -> Role | None:
    """The role of the terminal event that ended the curve (``CORNER`` for any end at it)."""
    if _at_corner(x_end):
        return Role.CORNER
    ends = [p for p in curve.special_points if p.kind is SpecialKind.EVENT
            and p.index == len(curve) - 1 and tagged[p.event].event.terminal]
    return tagged[ends[-1].event].role if ends else None


_END_OF_ROLE = {Role.CORNER: Where.CORNER, Role.GAMMA_MIN: Where.GAMMA_MIN,
                Role.DOMAIN_EDGE: Where.DOMAIN_EDGE}


def _end_note(curve: Curve, tagged: list[_Tagged], x_end) -> str:
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


def _engine_marks(curve: Curve, physical: np.ndarray, tagged: list[_Tagged],
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
        elif p.kind is SpecialKind.EVENT and tagged[p.event].role is Role.VALIDITY:
            # A cut point: the physical part ends (or begins) here only if the physical flag
            # changes across it; a validity function that crosses zero while another one is
            # still violated (or touches zero) cuts nothing.
            i = p.index
            before = physical[i - 1] if i > 0 else False
            after = physical[i + 1] if i + 1 <= last else False
            condition = tagged[p.event].condition
            if before and not after:
                marks.add(i, PointKind.END, f"regime limit: {condition} fails beyond")
                marks.limits[i] = condition
                if condition is Condition.T_OVER_N_L:
                    marks.add(i, PointKind.JUNCTION, "meets dr_limit (T = k N_L)")
            elif after and not before:
                marks.add(i, PointKind.START, f"regime becomes valid: {condition} holds beyond")


def _physical_end(curve: Curve, tagged: list[_Tagged], physical: np.ndarray, x: np.ndarray,
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
        return _END_OF_ROLE.get(_end_role(curve, tagged, x[-1]), Where.NOWHERE)
    return Where.REGIME_LIMIT


def _into_domain(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
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


def _assemble(name: str, system: BoundarySystem, curve: Curve, tagged: list[_Tagged],
              keep_unphysical: bool, start: Where, start_note: str,
              junctions=()) -> BoundaryCurve:
    """Turn one engine curve into a BoundaryCurve in x, cut to its physical part.

    ``junctions``: ``(row, note, x)`` marks a junction at a row and puts it at ``x``.
    """
    x, outside = _into_domain(system.to_x(curve.x))
    diffs = np.linalg.norm(np.diff(x, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(diffs)])
    physical = np.array([system.is_physical(y, tol=PHYSICAL_TOLERANCE) for y in curve.x],
                        dtype=bool)
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
    points.sort(key=lambda p: (p.index, _PRIORITY[p.kind]))
    # Check the reported points in the x form of the paper's equations (the form written to CSV),
    # each equation relative to the size of its terms.
    in_x = BoundarySystem(name, system.params)
    residual = max((in_x.scaled_residual(xi) for xi in x[keep]), default=0.0)
    status = curve.status.value if curve.ok else curve.message
    ok = curve.ok
    if ok and np.any(outside[keep]):
        i = int(np.flatnonzero(outside & keep)[0])
        ok, status = False, (f"row {i} ({x[i][0]!r}, {x[i][1]!r}) is outside the domain "
                             f"0 <= delta <= gamma <= pi/2 by more than {DOMAIN_TOLERANCE:g}")
    physical_start = start if physical.size and physical[0] else Where.NOWHERE
    if physical.size and not physical[0] and np.any(physical):
        physical_start = Where.REGIME_LIMIT
    return BoundaryCurve(name=name, k=system.params.k, x=x[keep], s=s[keep],
                         physical=physical[keep], special_points=tuple(points),
                         status=status, ok=ok, residual=residual, engine=(curve,),
                         start=physical_start, end=end if np.any(physical) else Where.NOWHERE)


# --- checks -----------------------------------------------------------------------------------

def _limit_distance(dr: BoundaryCurve, rs: BoundaryCurve, params: Parameters) -> float:
    """Largest distance from a point of ``rs_limit`` to the curve ``dr_limit``.

    Each point is projected onto ``dr_limit`` by Gauss-Newton with the minimum-norm step
    ``dx = -J^T (J J^T)^{-1} H`` in the smooth chart. The first step is the distance to first
    order, with an error of order ``|dx|^2`` (times the curvature of ``H = 0``): once it is
    below ``1e-8`` that error is below rounding and the iteration stops.
    """
    system = BoundarySystem("dr_limit", params, "sqrt_beta_L")
    worst = 0.0
    for x in rs.x:
        y = system.from_x(x)
        for _ in range(20):
            H, J = system.residual_and_jacobian(y)
            _, _, multipliers, info = dgesv(J @ J.T, H)
            if info != 0 or not np.all(np.isfinite(multipliers)):
                return math.nan  # rank-deficient: no distance is claimed
            step = J.T @ multipliers
            y = y - step
            if float(np.linalg.norm(step)) <= 1e-8 * (1.0 + float(np.max(np.abs(y)))):
                break
        else:
            return math.nan  # not converged: no distance is claimed
        worst = max(worst, float(np.linalg.norm(system.to_x(y) - x)))
    return worst


def _topology_problems(curve: BoundaryCurve, expected: CurveTopology) -> list[str]:
    """How a traced curve's physical part differs from its expected topology (empty if not)."""
    rows = np.flatnonzero(curve.physical)
    if expected.present is False:
        return [f"has a physical part of {len(rows)} points, expected none"] if len(rows) > 1 \
            else []
    problems = []
    if expected.start is not None and curve.start.value != expected.start:
        problems.append(f"starts at {curve.start}, expected {expected.start}")
    if expected.end is not None and curve.end.value != expected.end:
        where = ""
        if len(rows):
            last = curve.x[rows[-1]]
            where = f" (gamma, delta) = ({last[0]:.9g}, {last[1]:.9g})"
        problems.append(f"ends at {curve.end}{where}, expected {expected.end}")
    first, last = (int(rows[0]), int(rows[-1])) if len(rows) else (0, -1)
    for kind, count in ((PointKind.JUNCTION, expected.junctions),
                        (PointKind.FOLD_GAMMA, expected.folds_gamma),
                        (PointKind.FOLD_DELTA, expected.folds_delta)):
        inner = [p for p in curve.special(kind)
                 if first < p.index < last and curve.physical[p.index]]
        if count is not None and len(inner) != count:
            problems.append(f"has {len(inner)} {kind.value} point(s) inside, expected {count}")
    return problems


def _check(curves: dict, params: Parameters, notes: list) -> dict:
    """Compare each curve with the expected topology; a differing curve becomes a failure."""
    expected = expected_topology(params)
    checked = {}
    for name, curve in curves.items():
        problems = _topology_problems(curve, expected[name]) if curve.ok else []
        if problems:
            curve = curve.failed(f"the traced curve differs from the expected topology for "
                                 f"k = {params.k!r}: it " + "; it ".join(problems))
        checked[name] = curve
    if expected["dr_no_roll"].present and "dr_no_roll" not in checked:
        notes.append(f"dr_no_roll is expected for k = {params.k!r} but was not traced")
    return checked


# --- the tracer -------------------------------------------------------------------------------

#: largest distance between the junction located on dr_limit and the one on dr_no_roll
JUNCTION_TOLERANCE = 1e-5


def _limit_junction(system: BoundarySystem, limit: Curve, tagged: list[_Tagged],
                    junction) -> tuple[tuple, str]:
    """The junction mark of the limit curve, at the junction found on ``dr_no_roll``.

    ``upsilon = 0`` on the limit curve is located as an event, but next to ``k_branch`` it is
    nearly tangent to the curve (``upsilon`` has a double zero at the seed when
    ``k = k_branch``), so that point is only accurate to ``event_tol / |k - k_branch|``; the
    same junction is where ``dr_no_roll`` reaches ``T/N_L = k``, which it crosses transversally
    for every ``k``. The event's point is replaced by that one; the two must agree to
    :data:`JUNCTION_TOLERANCE`. Returns the marks for :func:`_assemble` and a problem, if any.
    """
    crossings = [p for p in limit.special_points if p.kind is SpecialKind.EVENT
                 and tagged[p.event].role is Role.NO_ROLL and p.index > 0]
    if not crossings or junction is None:
        return (), ""
    index = crossings[0].index
    distance = float(np.max(np.abs(system.to_x(limit.x[index]) - junction)))
    problem = "" if distance <= JUNCTION_TOLERANCE else (
        f"upsilon = 0 on dr_limit at {tuple(system.to_x(limit.x[index]))} is {distance:.3g} from "
        f"the end of dr_no_roll at {tuple(junction)}, where T/N_L = k: the junction is not "
        "consistent")
    return ((index, "meets dr_no_roll and rs_no_roll (upsilon = 0)", junction),), problem


def trace_boundaries(k, *, keep_unphysical: bool = False, options: Options | None = None,
                     gamma_min: float | None = None,
                     raise_on_failure: bool = False) -> BoundarySet:
    """Trace ``dr_limit``, ``rs_limit``, ``dr_no_roll`` and ``rs_no_roll`` for friction ``k``.

    Parameters
    ----------
    k : float or Parameters
        Friction coefficient, finite and > 0.
    keep_unphysical : bool
        Keep the parts of each boundary where its regime is not valid (flagged).
    options : continuation.Options, optional
        Engine settings; the default (:data:`DEFAULT_OPTIONS`) resolves the curves for plotting
        with residuals <= 1e-12. Folds are located in the coordinates ``options.fold_coordinates``
        (0 = gamma, 1 = delta); the topology check expects both.
    gamma_min : float, optional
        Where ``dr_limit`` and ``rs_limit`` stop on their way to the singular origin; default
        ``min(1e-3, arctan(k/c) / 100)``.
    raise_on_failure : bool
        Raise :class:`TraceError` (carrying everything traced) if any boundary failed.

    Returns
    -------
    BoundarySet
        ``ok`` only if every boundary was traced to its expected end with its expected
        junctions and folds (:func:`groove_model.topology.expected_topology`).
    """
    params = Parameters.coerce(k)
    options = options or DEFAULT_OPTIONS
    if gamma_min is None:
        gamma_min = min(GAMMA_MIN, 0.01 * params.gamma_limit)
    if not (0.0 < gamma_min < params.gamma_limit):
        raise ValueError(f"gamma_min = {gamma_min!r} is outside the allowed range "
                         f"0 < gamma_min < arctan(k/c) = {params.gamma_limit!r}")
    curves, notes = {}, []
    up = np.array([0.0, 1.0, 0.0, 0.0])
    seed = limit_seed(params)
    limit_scale = min(1.0, params.gamma_limit)

    # dr_no_roll from the branch point (arctan sqrt 2, 0) where it leaves the symmetric family:
    # in its deflated form the branch point is a regular point of dr_no_roll alone. Its physical
    # part ends where T/N_L reaches k, the junction, which it crosses transversally for every k.
    system = BoundarySystem("dr_no_roll", params, "sqrt_beta_L", conditioned=True)
    tagged = [*_domain_events(system, gamma_min), *_validity_events(system)]
    drn = _trace_curve(system, system.from_x(dr_no_roll_branch_point()), up, options, tagged)
    curve = _assemble("dr_no_roll", system, drn, tagged, keep_unphysical,
                      Where.BRANCH_POINT, "branch point (arctan sqrt 2, 0) off the symmetric "
                      "family; gamma is stationary there (symmetry delta -> -delta)")
    junction = None
    if curve.ok and curve.end is Where.JUNCTION:
        junction = curve.x[np.flatnonzero(curve.physical)[-1]].copy()
    if len(curve.x) >= 2 or not curve.ok:
        curves["dr_no_roll"] = curve
    elif len(curve.x) == 1:
        notes.append(f"dr_no_roll reduces to its branch point (arctan sqrt 2, 0) for "
                     f"k = {params.k!r}: T/N = c sqrt 2 = k there and > k beyond")
    else:
        notes.append(f"dr_no_roll has no physical part for k = {params.k:g}: "
                     "T/N_L > k all along it")

    # The limit curve from (arctan k, 0) into delta > 0, traced once in its conditioned form and
    # reported as dr_limit (with the junction where upsilon = 0) and as rs_limit; each is then
    # checked against its own equations in the paper's form.
    system = BoundarySystem("dr_limit", params, "sqrt_beta_L", limit_scale, conditioned=True)
    tagged = [*_domain_events(system, gamma_min), *_validity_events(system),
              _Tagged(Event("upsilon = 0", lambda y: y[3],
                            gradient=lambda y: np.array([0.0, 0.0, 0.0, 1.0])), Role.NO_ROLL)]
    limit = _trace_curve(system, system.from_x(seed), up, options, tagged)
    seed_note = "seed (arctan(k/c), 0): T/N = c tan gamma = k on delta = 0"
    marks, problem = _limit_junction(system, limit, tagged, junction)
    curves["dr_limit"] = _assemble("dr_limit", system, limit, tagged, keep_unphysical,
                                   Where.SEED, seed_note, marks)
    if problem:
        curves["dr_limit"] = curves["dr_limit"].failed(problem)
    rs_system = BoundarySystem("rs_limit", params, "sqrt_beta_L", limit_scale, conditioned=True)
    curves["rs_limit"] = _assemble("rs_limit", rs_system, limit, tagged, keep_unphysical,
                                   Where.SEED, seed_note)

    # rs_no_roll from the junction (k > sqrt 2) or from the seed, into the rolling-sliding side:
    # from the seed through the junction (d_L < 0 between them) to the corner, delta increases.
    system = BoundarySystem("rs_no_roll", params, "sqrt_beta_L")
    tagged = [*_domain_events(system, gamma_min), *_validity_events(system)]
    if junction is not None:
        start, start_kind = system.from_x(junction), Where.JUNCTION
        start_note = "junction with dr_limit where upsilon = 0"
    else:
        start, start_kind, start_note = system.from_x(seed), Where.SEED, "seed (arctan(k/c), 0)"
    rsn = _trace_curve(system, start, up, options, tagged)
    curves["rs_no_roll"] = _assemble("rs_no_roll", system, rsn, tagged, keep_unphysical,
                                     start_kind, start_note)

    curves = _check(curves, params, notes)
    distance = (_limit_distance(curves["dr_limit"], curves["rs_limit"], params)
                if curves["dr_limit"].ok and curves["rs_limit"].ok else math.nan)
    if curves["rs_limit"].ok and not distance <= LIMIT_TOLERANCE:
        curves["rs_limit"] = curves["rs_limit"].failed(
            f"rs_limit is {distance!r} from dr_limit, more than {LIMIT_TOLERANCE:g}: the two "
            "systems of the one limit curve disagree")
    order = {name: i for i, name in enumerate(BOUNDARY_NAMES)}
    result = BoundarySet(k=params.k,
                         curves=dict(sorted(curves.items(), key=lambda kv: order[kv[0]])),
                         limit_distance=distance, notes=tuple(notes), params=params)
    if raise_on_failure and not result.ok:
        raise TraceError(f"k = {params.k!r}: " + "; ".join(result.failures), result)
    return result

