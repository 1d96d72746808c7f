r"""Trace every regime boundary for a friction coefficient ``k`` with the continuation engine.

Which curve starts and ends where follows from ``k`` (``shared/MODEL.md``, "Seed points"):

* ``dr_limit`` and ``rs_limit`` (one curve seen from the two regimes) start at
  ``(arctan k, 0)`` and run towards the origin, which they approach tangentially to
  ``delta = gamma`` with ``beta_L ~ 2 gamma^2 / k``; the origin is a singular corner
  (a flat groove), so they stop at ``gamma = gamma_min``.
* ``dr_no_roll`` leaves the symmetric family ``delta = 0`` at the branch point
  ``(arctan sqrt 2, 0)`` by branch switching and ends at the corner ``(pi/4, pi/4)``.
* ``rs_no_roll`` starts where ``upsilon = 0`` on ``dr_limit``: an event located on
  ``dr_limit`` when ``k > sqrt 2``, the seed ``(arctan k, 0)`` itself otherwise; it ends
  at ``(pi/4, pi/4)``.

The curves are traced in the chart ``y = (gamma, delta, w, upsilon)``, ``beta_L = w^2``,
where every residual is analytic and the corner ``beta_L = 0`` is a regular point located as
the event ``w = 0`` (see :mod:`groove_model.boundaries`); results are reported in
``x = (gamma, delta, beta_L, upsilon)``. Each curve is cut to its physical part (its regime
valid) at validity events the engine locates exactly; ``keep_unphysical=True`` keeps the rest,
flagged ``physical = False``.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd
from scipy.linalg.lapack import dgesv

from continuation import Curve, Event, Options, Problem, switch_branch, trace
from continuation.small import all_finite, max_abs, norm

from .model.boundaries import (
    BOUNDARY_NAMES,
    BoundarySystem,
    corner_point,
    dr_no_roll_branch_point,
    limit_seed,
)
from .model.parameters import Parameters

__all__ = [
    "BoundaryCurve",
    "BoundarySet",
    "BoundarySpecialPoint",
    "CSV_COLUMNS",
    "SPECIAL_POINT_COLUMNS",
    "TraceError",
    "boundary_quantities",
    "trace_boundaries",
]

log = logging.getLogger(__name__)

CSV_COLUMNS = ("boundary", "k", "s", "gamma", "delta", "theta_L", "theta_R", "beta_L", "beta_R",
               "upsilon", "T_over_N_L", "T_over_N_R", "d_L", "physical", "point")
SPECIAL_POINT_COLUMNS = ("boundary", "k", "kind", "gamma", "delta", "beta_L", "upsilon")
SPECIAL_KINDS = ("start", "end", "junction", "fold_gamma", "branch_point")
_PRIORITY = {"branch_point": 0, "junction": 1, "fold_gamma": 2, "start": 3, "end": 4}

#: Engine settings for the boundaries: residuals to 1e-12 (so that rs_limit and dr_limit, two
#: systems for one curve, agree to about 1e-12); CSV rows recomputed from their 17-digit columns
#: satisfy the equations to 1e-10 (rounding of the columns is amplified where |J| ~ 2e4); steps
#: small enough for smooth plots.
DEFAULT_OPTIONS = Options(tol=1e-12, ds=0.02, ds_min=1e-12, ds_max=0.05, max_steps=5000,
                          fold_coordinates=(0,), detect_branch_points=False, detect_closed=False)
GAMMA_MIN = 1e-3


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
    kind : str
        ``start``, ``end``, ``junction`` (where boundaries meet), ``fold_gamma`` (turning point
        in gamma) or ``branch_point``.
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
    kind: str
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
        The engine's status message of the run(s) behind the curve.
    ok : bool
        False if the engine failed; the points traced before the failure are kept.
    residual : float
        Largest ``|H|`` over the points, in the ``x`` form of the equations.
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

    def special(self, kind: str) -> tuple:
        """The special points of one kind."""
        return tuple(p for p in self.special_points if p.kind == kind)

    def to_frame(self, params: Parameters | None = None) -> pd.DataFrame:
        """The CSV table of this boundary (columns :data:`CSV_COLUMNS`)."""
        params = params or Parameters(self.k)
        q = boundary_quantities(self.name, self.x, params)
        point = np.full(len(self.x), "", dtype=object)
        for p in sorted(self.special_points, key=lambda p: -_PRIORITY[p.kind]):
            point[p.index] = p.kind
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
    """

    k: float
    curves: dict = field(repr=False)
    limit_distance: float = math.nan
    notes: tuple = ()

    @property
    def ok(self) -> bool:
        return all(c.ok for c in self.curves.values())

    @property
    def failures(self) -> tuple:
        return tuple(f"{c.name}: {c.status}" for c in self.curves.values() if not c.ok)

    def to_frame(self) -> pd.DataFrame:
        """All boundaries as one table (columns :data:`CSV_COLUMNS`)."""
        params = Parameters(self.k)
        frames = [c.to_frame(params) for c in self.curves.values()]
        return pd.concat(frames, ignore_index=True) if frames else pd.DataFrame(
            columns=list(CSV_COLUMNS))

    def special_points_frame(self) -> pd.DataFrame:
        """All special points (columns :data:`SPECIAL_POINT_COLUMNS`, plus ``note``)."""
        rows = [dict(boundary=p.boundary, k=self.k, kind=p.kind, gamma=p.x[0], delta=p.x[1],
                     beta_L=p.x[2], upsilon=p.x[3], note=p.note)
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


def _domain_events(gamma_min: float) -> list:
    """Terminal events: the domain ``0 <= delta <= gamma <= pi/2``, the contact range, the origin."""
    return [
        Event("delta = 0", lambda y: y[1], direction=-1, terminal=True),
        Event("delta = gamma", lambda y: y[0] - y[1], direction=-1, terminal=True),
        Event("gamma = pi/2", lambda y: 0.5 * math.pi - y[0], direction=-1, terminal=True),
        Event("gamma = gamma_min", lambda y: y[0] - gamma_min, direction=-1, terminal=True),
        Event("beta_L = 0", lambda y: y[2], direction=-1, terminal=True),
        Event("beta_R = 0", lambda y: math.pi - 2.0 * y[0] - y[2] * y[2], direction=-1,
              terminal=True),
    ]


def _validity_events(system: BoundarySystem) -> list:
    return [Event(f"validity {name}", f) for name, f in system.validity.items()]


def _problem(system: BoundarySystem) -> Problem:
    return Problem(system.residual, system.jacobian, names=("gamma", "delta", "w", "upsilon"))


_CORNER_NOTE = "singular corner (pi/4, pi/4): beta_L = 0, N_L = 0"


def _at_corner(x) -> bool:
    return bool(np.max(np.abs(np.asarray(x)[:2] - corner_point()[:2])) <= 1e-9)


def _end_note(curve: Curve, x_end) -> str:
    if _at_corner(x_end):
        return _CORNER_NOTE
    events = [p for p in curve.special_points if p.kind == "event"]
    last = events[-1] if events else None
    if last is not None and last.name == "gamma = gamma_min":
        return (f"approaching the singular corner (0, 0) along delta = gamma; "
                f"stopped at gamma = {curve.x[-1][0]:.3g}")
    if last is not None:
        return f"domain edge {last.name}"
    return curve.status.value


def _assemble(name: str, system: BoundarySystem, curve: Curve, keep_unphysical: bool,
              start_kind: str, start_note: str, junctions=()) -> BoundaryCurve:
    """Turn one engine curve into a BoundaryCurve in x, cut to its physical part."""
    x = system.to_x(curve.x)
    diffs = np.linalg.norm(np.diff(x, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(diffs)])
    physical = np.array([system.is_physical(y, tol=1e-9) for y in curve.x])
    specials = [(0, "start", start_note)]
    if start_kind != "start":
        specials.append((0, start_kind, start_note))
    for p in curve.special_points:
        if p.index == 0:
            continue  # a validity function vanishes at a seed on the regime limit: no crossing
        if p.kind == "fold" and p.coordinate == 0:
            if _at_corner(x[p.index]):
                # In the w chart gamma is stationary at the corner: an end, not a turning point.
                # (At the branch point, where gamma is stationary by the symmetry
                # delta -> -delta, the engine reports no fold: it is the curve's start.)
                continue
            specials.append((p.index, "fold_gamma", "turning point in gamma"))
        elif p.kind == "event" and p.name.startswith("validity"):
            # A cut point: the physical part ends (or begins) here only if the physical flag
            # changes across it; a validity function that crosses zero while another one is
            # still violated (or touches zero) cuts nothing.
            i = p.index
            before = physical[i - 1] if i > 0 else False
            after = physical[i + 1] if i + 1 < len(x) else False
            cut = p.name.removeprefix("validity ")
            if before and not after:
                specials.append((i, "end", f"regime limit: {cut} fails beyond"))
                if cut == "T_over_N_L <= k":
                    specials.append((i, "junction", "meets dr_limit (T = k N_L)"))
            elif after and not before:
                specials.append((i, "start", f"regime becomes valid: {cut} holds beyond"))
    for index, note in junctions:
        specials.append((index, "junction", note))
    if curve.ok:
        specials.append((len(x) - 1, "end", _end_note(curve, x[-1])))

    keep = np.ones(len(x), bool) if keep_unphysical else physical
    index_map = np.cumsum(keep) - 1
    points = []
    for index, kind, note in specials:
        if not keep[index]:
            continue
        points.append(BoundarySpecialPoint(name, kind, x[index].copy(), float(s[index]),
                                           int(index_map[index]), note))
    if np.any(keep):
        # Every kept part starts and ends at a located point: mark the first and last.
        first, last = np.flatnonzero(keep)[[0, -1]]
        kinds = {(p.index, p.kind) for p in points}
        if (int(index_map[first]), "start") not in kinds:
            points.append(BoundarySpecialPoint(name, "start", x[first].copy(), float(s[first]),
                                               int(index_map[first]), "regime becomes valid"))
        if curve.ok and (int(index_map[last]), "end") not in kinds:
            note = next((p.note for p in points if p.index == index_map[last]), "regime limit")
            points.append(BoundarySpecialPoint(name, "end", x[last].copy(), float(s[last]),
                                               int(index_map[last]), note))
    points.sort(key=lambda p: (p.index, _PRIORITY[p.kind]))
    # Certify the reported points in the x form of the equations (the form written to CSV).
    in_x = BoundarySystem(name, system.params)
    residual = max((float(np.max(np.abs(in_x.residual(xi)))) for xi in x[keep]), default=0.0)
    return BoundaryCurve(name=name, k=system.params.k, x=x[keep], s=s[keep],
                         physical=physical[keep], special_points=tuple(points),
                         status=curve.status.value if curve.ok else
                         f"{curve.status.value}: {curve.message}",
                         ok=curve.ok, residual=residual, engine=(curve,))


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
            if info != 0 or not all_finite(multipliers):
                return math.nan  # rank-deficient: no distance is claimed
            step = J.T @ multipliers
            y = y - step
            if norm(step) <= 1e-8 * (1.0 + max_abs(y)):
                break
        else:
            return math.nan  # not converged: no distance is claimed
        worst = max(worst, norm(system.to_x(y) - x))
    return worst


def _direction_of_increase(f, y: np.ndarray, h: float = 1e-7) -> np.ndarray:
    return np.array([(f(y + h * e) - f(y - h * e)) / (2.0 * h) for e in np.eye(len(y))])


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
        with residuals <= 1e-12.
    gamma_min : float, optional
        Where ``dr_limit`` and ``rs_limit`` stop on their way to the singular origin; default
        ``min(1e-3, arctan(k) / 100)``.
    raise_on_failure : bool
        Raise :class:`TraceError` (carrying everything traced) if any boundary failed.

    Returns
    -------
    BoundarySet
    """
    params = Parameters.coerce(k)
    options = options or DEFAULT_OPTIONS
    if gamma_min is None:
        gamma_min = min(GAMMA_MIN, 0.01 * params.gamma_limit)
    if not (0.0 < gamma_min < params.gamma_limit):
        raise ValueError(f"gamma_min = {gamma_min!r} is outside the allowed range "
                         f"0 < gamma_min < arctan(k) = {params.gamma_limit!r}")
    domain = _domain_events(gamma_min)
    curves, notes = {}, []

    # dr_limit and rs_limit from (arctan k, 0) into delta > 0; upsilon = 0 is located on dr_limit.
    seed = limit_seed(params)
    systems = {name: BoundarySystem(name, params, "sqrt_beta_L") for name in BOUNDARY_NAMES}
    no_roll_event = Event("upsilon = 0", lambda y: y[3])
    up = np.array([0.0, 1.0, 0.0, 0.0])
    engine = {}
    for name in ("dr_limit", "rs_limit"):
        system = systems[name]
        extra = [no_roll_event] if name == "dr_limit" else []
        engine[name] = trace(_problem(system), system.from_x(seed), direction=up, options=options,
                             events=[*domain, *_validity_events(system), *extra])
    # The upsilon = 0 point of dr_limit away from its seed (k > sqrt 2): a junction.
    crossings = [p for p in engine["dr_limit"].special_points
                 if p.kind == "event" and p.name == "upsilon = 0" and p.s > 1e-9]
    junction = crossings[0] if crossings else None
    junction_note = "meets dr_no_roll and rs_no_roll (upsilon = 0)"
    for name in ("dr_limit", "rs_limit"):
        marks = ()
        if junction is not None and name == "dr_limit":
            marks = ((junction.index, junction_note),)
        curves[name] = _assemble(name, systems[name], engine[name], keep_unphysical, "start",
                                 "seed (arctan k, 0): T/N = tan gamma = k on delta = 0", marks)

    # dr_no_roll by branch switching off the symmetric family at (arctan sqrt 2, 0).
    system = systems["dr_no_roll"]
    engine["dr_no_roll"] = switch_branch(
        _problem(system), system.from_x(dr_no_roll_branch_point()), direction=up,
        options=options, events=[*domain, *_validity_events(system)])
    curve = _assemble("dr_no_roll", system, engine["dr_no_roll"], keep_unphysical,
                      "branch_point", "branch point (arctan sqrt 2, 0) off the symmetric family; "
                      "gamma is stationary there (symmetry delta -> -delta)")
    if len(curve.x) >= 2 or not curve.ok:
        curves["dr_no_roll"] = curve
    elif len(curve.x) == 1:
        notes.append(f"dr_no_roll reduces to its branch point (arctan sqrt 2, 0) for "
                     f"k = {params.k:.17g}: T/N = sqrt 2 = k there and > k beyond")
    else:
        notes.append(f"dr_no_roll has no physical part for k = {params.k:g}: "
                     "T/N_L > k all along it")

    # rs_no_roll from the junction (k > sqrt 2) or from the seed, into the rolling-sliding side.
    system = systems["rs_no_roll"]
    if junction is not None:
        # From dr_limit (d_L = 0) into the rolling-sliding side, where d_L grows.
        start = junction.x
        start_note = "junction with dr_limit where upsilon = 0"
        direction = _direction_of_increase(system.validity["d_L >= 0"], start)
    else:
        start = system.from_x(seed)
        start_note = "seed (arctan k, 0)"
        direction = up
    engine["rs_no_roll"] = trace(_problem(system), start, direction=direction, options=options,
                                 events=[*domain, *_validity_events(system)])
    curves["rs_no_roll"] = _assemble("rs_no_roll", system, engine["rs_no_roll"], keep_unphysical,
                                     "junction" if junction is not None else "start", start_note)

    distance = (_limit_distance(curves["dr_limit"], curves["rs_limit"], params)
                if curves["dr_limit"].ok and curves["rs_limit"].ok else math.nan)
    order = {name: i for i, name in enumerate(BOUNDARY_NAMES)}
    result = BoundarySet(k=params.k, curves=dict(sorted(curves.items(), key=lambda kv: order[kv[0]])),
                         limit_distance=distance, notes=tuple(notes))
    if raise_on_failure and not result.ok:
        raise TraceError(f"k = {params.k:g}: " + "; ".join(result.failures), result)
    return result
