"""Trace every regime boundary for a friction coefficient ``k`` with the continuation engine.

Which curve starts and ends where follows from ``k``: the table of
:mod:`groove_model.tracing.topology`, generated from the atlas of special points
(:mod:`groove_model.tracing.atlas`) with its thresholds ``k_fold = c/sqrt 2``,
``k_branch = c sqrt 2`` and ``k_cross`` (``15.199...`` for ``c = 1``). The tracer uses it to know
what to trace (``dr_no_roll`` only where it has a physical part, ``rs_no_roll`` from the junction
or from the seed) and checks every curve against it:

* ``dr_limit`` and ``rs_limit`` (one curve seen from the two regimes) start at
  ``(arctan(k/c), 0)`` and run towards the origin, which they approach tangentially to
  ``delta = gamma`` with ``beta_L ~ 2 gamma^2 / k``; the origin is a singular corner (a flat
  groove), so they stop at ``gamma = gamma_min``. On the way ``delta`` has one maximum (a fold in
  ``delta``), and for ``k > k_branch`` ``upsilon`` vanishes once: the junction with the
  ``upsilon = 0`` lines, before the maximum of ``delta`` for ``k < k_cross`` and after it above.
* ``dr_no_roll`` leaves the symmetric family ``delta = 0`` at the branch point
  ``(arctan sqrt 2, 0)``; its physical part (``T/N_L <= k``) ends at the junction, so it has
  one only for ``k > k_branch``. It is traced in its deflated form (the no-roll torque divided
  by ``beta_L - beta_R``, :mod:`groove_model.model.boundaries`), whose zero set is this branch alone
  and passes the branch point as a regular point: points next to the branch point are then as
  accurate as anywhere (with the paper's form, which also vanishes on the symmetric family,
  a point at distance ``d`` from the branch point carries errors of order ``eps / d``, so the
  junction of a ``k`` within ``1e-7`` of ``k_branch`` would be off by ``1e-9``).
* ``rs_no_roll`` starts at the junction when ``k > k_branch``, at ``(arctan(k/c), 0)``
  otherwise, and ends at the corner ``(pi/4, pi/4)``; for ``k > k_fold`` it turns once in
  ``gamma`` (for large ``k`` ever closer to the corner, at ``beta_L ~ (2/(3k))^2``).

The curves are traced in the chart ``y = (gamma / g, delta / g, w, upsilon)``, ``beta_L = w^2``,
where every residual is analytic and the corner ``beta_L = 0`` is a regular point located as the
event ``w = 0`` (see :mod:`groove_model.model.boundaries`); ``g = min(1, arctan(k/c))`` for the
limit curves, whose extent in ``gamma`` and ``delta`` is ``arctan(k/c)``, and 1 for the others.
Results are reported in ``x = (gamma, delta, beta_L, upsilon)``. Each curve is cut to its
physical part (its regime valid) at validity events the engine locates exactly;
``keep_unphysical=True`` keeps the rest, flagged ``physical = False``.

Nothing is reported as traced that has not been checked: the engine brackets every zero of an
event and of the tangent's ``gamma`` and ``delta`` components inside each step (pairs of zeros
included) and fails loudly where it cannot locate one; every curve is then compared with the
expected topology for its ``k`` (starts, ends, junctions, folds and their order), and a curve
that differs is a failure with a message saying what differs.
"""

from __future__ import annotations

import logging
import math
from dataclasses import replace
from typing import cast

import numpy as np

from continuation import Curve, Event, Options, SpecialKind
from continuation.numbers import FLOATS, require_flint

from ..model.boundaries import (
    BOUNDARY_NAMES,
    BoundarySystem,
    dr_no_roll_branch_point,
    limit_seed,
)
from ..model.parameters import Compliance, Parameters, check_flag, k_text, traced_parameters
from .assembly import (
    Role,
    Tagged,
    assemble,
    domain_events,
    trace_curve,
    validity_events,
)
from .certification import certify_boundaries
from .curves import BoundaryCurve, BoundarySet, PointKind, TraceError, Where
from .topology import CurveTopology, expected_topology

__all__ = ["DEFAULT_OPTIONS", "GAMMA_MIN", "trace_boundaries"]

log = logging.getLogger(__name__)


#: Engine settings for the boundaries: residuals to 1e-12 (so that rs_limit and dr_limit, two
#: systems for one curve, agree to about 1e-12); CSV rows recomputed from their 17-digit columns
#: satisfy the equations to 1e-10 (rounding of the columns is amplified where |J| ~ 2e4); steps
#: small enough for smooth plots; folds in gamma and in delta located.
DEFAULT_OPTIONS = Options(tol=1e-12, ds=0.02, ds_min=1e-12, ds_max=0.05, max_steps=5000,
                          fold_coordinates=(0, 1), detect_branch_points=False,
                          detect_closed=False)


GAMMA_MIN = 1e-3


#: largest accepted distance between rs_limit and dr_limit, which are one curve
LIMIT_TOLERANCE = 1e-10


def _limit_distance(rs: BoundaryCurve, params: Parameters) -> float:
    """Largest distance from a point of ``rs_limit`` to the curve ``dr_limit`` (its equations,
    not its traced points).

    Each point is projected onto ``dr_limit`` by Gauss-Newton with the minimum-norm step
    ``dx = -J^T (J J^T)^{-1} H`` in the smooth chart, every point at once. The first step is
    the distance to first order, with an error of order ``|dx|^2`` (times the curvature of
    ``H = 0``): once it is below ``1e-8`` that error is below rounding and the point's
    iteration stops. NaN (no distance claimed) if a ``J J^T`` is singular or a point does
    not converge in 20 steps.
    """
    system = BoundarySystem("dr_limit", params, "sqrt_beta_L")
    y = system.from_x(rs.x).reshape(-1, 4)
    active = np.arange(len(y))
    # a point that is not finite makes the distance NaN (checked below), without warnings
    with np.errstate(invalid="ignore", over="ignore", divide="ignore"):
        for _ in range(20):
            if not active.size:
                break
            H, J = system.residuals_and_jacobians(y[active])
            Jt = J.transpose(0, 2, 1)
            try:
                multipliers = np.linalg.solve(J @ Jt, H[:, :, None])
            except np.linalg.LinAlgError:
                return math.nan  # rank-deficient: no distance is claimed
            if not np.all(np.isfinite(multipliers)):
                return math.nan
            step = (Jt @ multipliers)[:, :, 0]
            y[active] -= step
            done = _norms(step) <= 1e-8 * (1.0 + np.max(np.abs(y[active]), axis=1))
            active = active[~done]
        if active.size:
            return math.nan  # not converged: no distance is claimed
        return float(np.max(_norms(system.to_x(y) - rs.x), initial=0.0))


def _norms(v: np.ndarray) -> np.ndarray:
    """The 2-norms of the rows of ``v``: ``sqrt(v_i . v_i)`` as row-by-row dot products (the
    rounding of ``v @ v`` for each row, which a sum of squares does not always repeat)."""
    return np.sqrt((v[:, None, :] @ v[:, :, None])[:, 0, 0])


def _topology_problems(curve: BoundaryCurve, expected: CurveTopology) -> list[str]:
    """How a traced curve's physical part differs from its expected topology (empty if not)."""
    rows = np.flatnonzero(curve.physical)
    if expected.present is False:
        return [f"has a physical part of {len(rows)} points, expected none"] if len(rows) > 1 \
            else []
    if expected.present is None and len(rows) <= 1:
        # next to a threshold where the boundary is absent on one side: this is that side (a
        # curve kept with --keep-unphysical, with no physical part, starts "nowhere")
        return []
    problems = []
    if expected.start is not None and curve.start.value != expected.start:
        problems.append(f"starts at {curve.start}, expected {expected.start}")
    if expected.end is not None and curve.end.value != expected.end:
        where = ""
        if len(rows):
            last = curve.x[rows[-1]]
            where = f" (gamma, delta) = ({last[0]:.9g}, {last[1]:.9g})"
        if curve.end is Where.NOWHERE and curve.engine:
            # no end of any kind: the continuation stopped short, and its message says why
            problems.append(f"stops at no end{where} (the continuation: "
                            f"{curve.engine[0].message}), expected {expected.end}")
        else:
            problems.append(f"ends at {curve.end}{where}, expected {expected.end}")
    first, last = (int(rows[0]), int(rows[-1])) if len(rows) else (0, -1)
    inner_points = [p for p in curve.special_points
                    if first < p.index < last and curve.physical[p.index]
                    and p.kind in (PointKind.JUNCTION, PointKind.FOLD_GAMMA,
                                   PointKind.FOLD_DELTA)]
    for kind, count in ((PointKind.JUNCTION, expected.junctions),
                        (PointKind.FOLD_GAMMA, expected.folds_gamma),
                        (PointKind.FOLD_DELTA, expected.folds_delta)):
        inner = [p for p in inner_points if p.kind is kind]
        if count is not None and len(inner) != count:
            problems.append(f"has {len(inner)} {kind.value} point(s) inside, expected {count}")
    sequence = tuple(p.kind.value for p in sorted(inner_points, key=lambda p: p.index))
    if not problems and expected.sequence is not None and sequence != expected.sequence:
        problems.append(f"has its inner points in the order {', '.join(sequence)}, expected "
                        f"{', '.join(expected.sequence)}")
    return problems


def _check(curves: dict, params: Parameters, expected: dict) -> dict:
    """Compare each curve with the expected topology; a differing curve becomes a failure."""
    checked = {}
    for name, curve in curves.items():
        problems = _topology_problems(curve, expected[name]) if curve.ok else []
        if problems:
            curve = curve.failed(f"the traced curve differs from the expected topology for "
                                 f"k = {k_text(params.k)}: it " + "; it ".join(problems))
        checked[name] = curve
    return checked


#: largest distance between the junction located on dr_limit and the one on dr_no_roll
JUNCTION_TOLERANCE = 1e-5


def _limit_junction(system: BoundarySystem, limit: Curve, tagged: list[Tagged],
                    junction, expected: int | None) -> tuple[tuple, str]:
    """The junction mark of the limit curve, at the junction found on ``dr_no_roll``.

    ``upsilon = 0`` on the limit curve is located as an event, but next to ``k_branch`` it is
    nearly tangent to the curve (``upsilon`` has a double zero at the seed when
    ``k = k_branch``), so that point is only accurate to ``event_tol / |k - k_branch|``; the
    same junction is where ``dr_no_roll`` reaches ``T/N_L = k``, which it crosses transversally
    for every ``k``. The event's point is replaced by that one; the two must agree to
    :data:`JUNCTION_TOLERANCE`. Within rounding of ``k_branch`` the junction may lie within
    :data:`SEED_JUNCTION` of the seed, where ``upsilon = 0`` already: no crossing is located, and
    the seed is marked as the junction too, so that the three curves that meet there agree.
    A crossing without a junction on ``dr_no_roll`` (where one is not ``expected``: ``0``; ``None``
    near a threshold, where either is accepted), or a junction on ``dr_no_roll`` with no crossing
    away from the seed, is a problem. Returns the marks for :func:`assemble` and the problem.
    """
    crossings = [p for p in limit.special_points if p.kind is SpecialKind.EVENT
                 and tagged[cast(int, p.event)].role is Role.NO_ROLL and p.index > 0]
    note = "meets dr_no_roll and rs_no_roll (upsilon = 0)"
    if junction is None:
        if crossings and expected is not None:
            where = _x_text(system.to_x(limit.x[crossings[0].index]))
            return (), (f"upsilon = 0 on dr_limit at {where}, but dr_no_roll has no junction: the "
                        "junction is not consistent")
        return (), ""
    if not crossings:
        seed = system.to_x(limit.x[0])
        distance = float(np.max(np.abs(seed - junction)))
        if distance <= SEED_JUNCTION:
            return ((0, f"{note}, within {distance:.2g} of the seed", seed),), ""
        return (), (f"dr_no_roll ends at a junction {_x_text(junction)}, {distance:.3g} from the "
                    "seed, but upsilon = 0 is not crossed on dr_limit: the junction is not "
                    "consistent")
    index = crossings[0].index
    distance = float(np.max(np.abs(system.to_x(limit.x[index]) - junction)))
    problem = "" if distance <= JUNCTION_TOLERANCE else (
        f"upsilon = 0 on dr_limit at {_x_text(system.to_x(limit.x[index]))} is {distance:.3g} "
        f"from the end of dr_no_roll at {_x_text(junction)}, where T/N_L = k: the junction is not "
        "consistent")
    return ((index, note, junction),), problem


def _x_text(x) -> str:
    """A point ``x = (gamma, delta, beta_L, upsilon)`` for messages."""
    return "(gamma, delta, beta_L, upsilon) = (" + ", ".join(f"{float(v):.10g}" for v in x) + ")"


#: largest distance of a junction from the seed at which no crossing of upsilon = 0 is located
#: on the limit curve (upsilon vanishes at the seed): about that far within rounding of k_branch
SEED_JUNCTION = 1e-9


#: the direction every boundary starts in: into delta > 0
_UP = np.array([0.0, 1.0, 0.0, 0.0])

#: the gradient of the event upsilon = 0 (read-only, shared by every point)
_UPSILON = np.array([0.0, 0.0, 0.0, 1.0])
_UPSILON.flags.writeable = False


class _Job:
    """The settings of one call of :func:`trace_boundaries`, and its three traces."""

    def __init__(self, params: Parameters, options: Options, gamma_min: float,
                 keep_unphysical: bool) -> None:
        self.params = params
        self.options = options
        self.gamma_min = gamma_min
        self.keep_unphysical = keep_unphysical
        self.seed = limit_seed(params)
        #: boundary name -> (system, tagged events) of its engine curve, for certification
        self.traced: dict = {}

    def _events(self, system: BoundarySystem) -> list[Tagged]:
        return [*domain_events(system, self.gamma_min), *validity_events(system)]

    def dr_no_roll(self, expected: bool | None) -> tuple[dict, list, np.ndarray | None]:
        """``dr_no_roll`` from the branch point ``(arctan sqrt 2, 0)``, and the junction.

        In its deflated form the branch point is a regular point of ``dr_no_roll`` alone. Its
        physical part ends where ``T/N_L`` reaches ``k``, the junction, which it crosses
        transversally for every ``k``. Returns the curve (if it has a physical part, or if it
        has none where it is ``expected``: then it is a failure), notes and the junction
        (``None`` for ``k <= k_branch``).
        """
        params = self.params
        system = BoundarySystem("dr_no_roll", params, "sqrt_beta_L", conditioned=True)
        tagged = self._events(system)
        self.traced["dr_no_roll"] = (system, tagged)
        engine = trace_curve(system, system.from_x(dr_no_roll_branch_point()), _UP,
                             self.options, tagged)
        curve = assemble("dr_no_roll", system, engine, tagged, self.keep_unphysical,
                         Where.BRANCH_POINT, "branch point (arctan sqrt 2, 0) off the "
                         "symmetric family; gamma is stationary there (symmetry delta -> -delta)")
        junction = None
        if curve.ok and curve.end is Where.JUNCTION:
            junction = curve.x[np.flatnonzero(curve.physical)[-1]].copy()
        if len(curve.x) >= 2 or not curve.ok:
            return {"dr_no_roll": curve}, [], junction
        if expected:
            return {"dr_no_roll": curve.failed(
                f"dr_no_roll is expected for k = {params.k!r} (k > c sqrt 2) but its physical "
                f"part is {len(curve.x)} point(s): T/N_L > k where it should be below")}, [], None
        if len(curve.x) == 1:
            return {}, [f"dr_no_roll reduces to its branch point (arctan sqrt 2, 0) for "
                        f"k = {params.k!r}: T/N = c sqrt 2 = k there and > k beyond"], junction
        return {}, [f"dr_no_roll has no physical part for k = {k_text(params.k)}: "
                    "T/N_L > k all along it"], junction

    def limit(self, junction, expected: int | None) -> dict:
        """``dr_limit`` and ``rs_limit`` from ``(arctan(k/c), 0)`` into ``delta > 0``; the
        junctions ``expected`` on ``dr_limit`` (:func:`_limit_junction`).

        One trace in the conditioned form of the limit curve, reported as ``dr_limit`` (with
        the junction where ``upsilon = 0``) and as ``rs_limit``; each is then checked against
        its own equations in the paper's form.
        """
        params, scale = self.params, min(1.0, self.params.gamma_limit)
        system = BoundarySystem("dr_limit", params, "sqrt_beta_L", scale, conditioned=True)
        tagged = [*self._events(system),
                  Tagged(Event("upsilon = 0", lambda y, numbers=FLOATS: y[3],
                               gradient=lambda y: _UPSILON, linear=True),
                         Role.NO_ROLL)]
        self.traced["dr_limit"] = self.traced["rs_limit"] = (system, tagged)
        engine = trace_curve(system, system.from_x(self.seed), _UP, self.options, tagged)
        note = "seed (arctan(k/c), 0): T/N = c tan gamma = k on delta = 0"
        marks, problem = _limit_junction(system, engine, tagged, junction, expected)
        dr = assemble("dr_limit", system, engine, tagged, self.keep_unphysical, Where.SEED,
                      note, marks)
        rs_system = BoundarySystem("rs_limit", params, "sqrt_beta_L", scale, conditioned=True)
        rs = assemble("rs_limit", rs_system, engine, tagged, self.keep_unphysical, Where.SEED,
                      note)
        return {"dr_limit": dr.failed(problem) if problem else dr, "rs_limit": rs}

    def rs_no_roll(self, junction) -> BoundaryCurve:
        """``rs_no_roll`` from the junction (``k > k_branch``) or the seed to the corner.

        From the seed through the junction (``d_L < 0`` between them) to the corner, ``delta``
        increases: the direction is taken from ``delta``, not from ``d_L``, which barely
        changes at the junction of a ``k`` near ``k_branch``.
        """
        system = BoundarySystem("rs_no_roll", self.params, "sqrt_beta_L")
        tagged = self._events(system)
        self.traced["rs_no_roll"] = (system, tagged)
        if junction is not None:
            start, where, note = (system.from_x(junction), Where.JUNCTION,
                                  "junction with dr_limit where upsilon = 0")
        else:
            start, where, note = system.from_x(self.seed), Where.SEED, "seed (arctan(k/c), 0)"
        engine = trace_curve(system, start, _UP, self.options, tagged)
        return assemble("rs_no_roll", system, engine, tagged, self.keep_unphysical, where, note)


def _tracer_options(options: Options | None, raise_on_failure: bool) -> tuple[Options, bool]:
    """``options`` with the tracer's own switches (those of :data:`DEFAULT_OPTIONS`), and
    whether to raise (``options.raise_on_failure`` asks it too; the engine never raises here)."""
    if options is None:
        return DEFAULT_OPTIONS, raise_on_failure
    if not isinstance(options, Options):
        raise TypeError(f"options must be a continuation.Options, got {type(options).__name__}")
    kept = replace(options, fold_coordinates=DEFAULT_OPTIONS.fold_coordinates,
                   detect_branch_points=DEFAULT_OPTIONS.detect_branch_points,
                   detect_closed=DEFAULT_OPTIONS.detect_closed, raise_on_failure=False)
    return kept, raise_on_failure or options.raise_on_failure


def trace_boundaries(k, *, compliance: Compliance | float | None = None,
                     keep_unphysical: bool = False, options: Options | None = None,
                     gamma_min: float | None = None, raise_on_failure: bool = False,
                     certify: bool = False) -> BoundarySet:
    """Trace ``dr_limit``, ``rs_limit``, ``dr_no_roll`` and ``rs_no_roll`` for friction ``k``.

    Parameters
    ----------
    k : float or Parameters
        Friction coefficient, ``1e-4 <= k <= 1e6``, with a compliance ratio ``2/3 <= c <= 1``
        (Mindlin's for Poisson ratios ``0 <= nu <= 1/2``): the ranges the tracer is verified
        for (:data:`~groove_model.model.parameters.TRACED_K_RANGE`).
    compliance : Compliance or float, optional
        With a float ``k``: the contact's compliance, or its ratio ``c`` (default the paper's
        law, ``c = 1``); ``Compliance.from_poisson(nu)`` for a Poisson ratio. A
        :class:`Parameters` ``k`` carries its own.
    keep_unphysical : bool
        Keep the parts of each traced curve where its regime is not valid (flagged
        ``physical = False``). Above ``k_branch``, ``rs_no_roll`` is traced from the junction,
        where its physical part starts, so its unphysical part between the seed and the
        junction is not traced (a note says so).
    options : continuation.Options, optional
        Engine settings; the default (:data:`DEFAULT_OPTIONS`) resolves the curves for plotting
        with residuals <= 1e-12 (e.g. ``dataclasses.replace(DEFAULT_OPTIONS, ds_max=0.01)``
        for finer steps). Three switches are the tracer's and are kept whatever ``options``
        says, since the topology check depends on them: folds are located in gamma and in
        delta (``fold_coordinates=(0, 1)``), and the engine neither detects branch points (the
        tracer locates the junction itself) nor closes curves. ``options.raise_on_failure``
        acts as ``raise_on_failure``.
    gamma_min : float, optional
        Where ``dr_limit`` and ``rs_limit`` stop on their way to the singular origin; default
        ``min(1e-3, arctan(k/c) / 100)``, the value the tracer is verified with. Another value
        may stop the limit curves before their expected special points or closer to the
        origin than they are resolved: such runs fail (``ok`` False), they do not mislead.
    raise_on_failure : bool
        Raise :class:`TraceError` (carrying everything traced) if any boundary failed.
    certify : bool
        Prove each boundary in ball arithmetic (:mod:`groove_model.tracing.certification`,
        ``docs/certification.md``): ``BoundaryCurve.certificate`` says proven, or not proven
        and why. Needs python-flint (``pip install 'groove-continuation[certify]'``).

    Returns
    -------
    BoundarySet
        ``ok`` only if every boundary was traced to its expected end with its expected
        junctions and folds, in their expected order
        (:func:`groove_model.tracing.topology.expected_topology`). A boundary that is not
        proven is still ``ok``; its certificate says what failed.

    Raises
    ------
    ValueError
        If ``k`` or the compliance ratio is outside the traced ranges (the message names it).
    TypeError
        If a flag (``keep_unphysical``, ``raise_on_failure``, ``certify``) is not a bool.
    ImportError
        With ``certify=True`` if python-flint is not installed (before anything is traced).

    Notes
    -----
    The expected topology comes from the atlas of special points; its thresholds are computed
    on the first call for a compliance ratio (about half a second) and kept for later calls.
    """
    params = traced_parameters(k, compliance)
    keep_unphysical = check_flag("keep_unphysical", keep_unphysical)
    raise_on_failure = check_flag("raise_on_failure", raise_on_failure)
    certify = check_flag("certify", certify)
    if certify:
        require_flint()
    options, raise_on_failure = _tracer_options(options, raise_on_failure)
    if gamma_min is None:
        gamma_min = min(GAMMA_MIN, 0.01 * params.gamma_limit)
    if isinstance(gamma_min, bool) or not isinstance(gamma_min, (int, float, np.floating)):
        raise TypeError(f"gamma_min must be a real number, got {gamma_min!r}")
    if not (0.0 < gamma_min < params.gamma_limit):
        raise ValueError(f"gamma_min = {gamma_min!r} is outside the allowed range "
                         f"0 < gamma_min < arctan(k/c) = {params.gamma_limit!r}")
    job = _Job(params, options, gamma_min, keep_unphysical)
    expected = expected_topology(params)
    curves: dict[str, BoundaryCurve]
    if expected["dr_no_roll"].present is False and not keep_unphysical:
        # below k_branch the atlas has no junction: dr_no_roll has no physical part
        curves, notes, junction = {}, [f"dr_no_roll has no physical part for k = "
                                       f"{k_text(params.k)}: T/N_L > k all along it"], None
    else:
        curves, notes, junction = job.dr_no_roll(expected["dr_no_roll"].present)
    curves.update(job.limit(junction, expected["dr_limit"].junctions))
    from_seed = expected["rs_no_roll"].start == Where.SEED.value
    curves["rs_no_roll"] = job.rs_no_roll(None if from_seed else junction)
    if keep_unphysical and not from_seed:
        notes.append("rs_no_roll is traced from the junction, where its physical part starts: "
                     "its unphysical part from the seed (arctan(k/c), 0) to the junction "
                     "(d_L < 0) is not traced, even with keep_unphysical")

    curves = _check(curves, params, expected)
    distance = _limit_distance(curves["rs_limit"], params) if curves["rs_limit"].ok else math.nan
    if curves["rs_limit"].ok and not distance <= LIMIT_TOLERANCE:
        curves["rs_limit"] = curves["rs_limit"].failed(
            f"rs_limit is {distance:.3g} from dr_limit, more than {LIMIT_TOLERANCE:g}: the two "
            "systems of the one limit curve disagree" if math.isfinite(distance) else
            "rs_limit could not be compared with dr_limit: projecting its points onto the "
            "equations of dr_limit did not converge")
    if certify:
        curves = certify_boundaries(curves, job.traced, gamma_min)
    order = {name: i for i, name in enumerate(BOUNDARY_NAMES)}
    result = BoundarySet(k=params.k,
                         curves=dict(sorted(curves.items(), key=lambda kv: order[kv[0]])),
                         limit_distance=distance, notes=tuple(notes), params=params)
    if raise_on_failure and not result.ok:
        raise TraceError(f"k = {params.k!r}: " + "; ".join(result.failures), result)
    return result

