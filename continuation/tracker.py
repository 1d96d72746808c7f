"""The predictor-corrector driver: :func:`trace`.

One step is one readable sequence: predict, correct, accept or reject,
close, locate special points, check termination, adapt the step.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Iterable, Sequence
from typing import cast

import numpy as np

from .closing import closing_point
from .corrector import NON_FINITE, SINGULAR, Correction, correct
from .errors import CallbackError, CallbackShapeError
from .events import Event
from .node import EventNotFinite, LocateError, Node, StepUnresolved
from .options import Options
from .predictor import arc_length, extrapolate, hermite
from .problem import Evaluator, Problem, as_vector, probe_jacobian
from .result import Curve, SpecialKind, SpecialPoint, Status
from .run import Run
from .special import (
    add_step,
    drop_unresolved_folds,
    fold_inconsistency,
    jacobian_at_special_points,
    scan_step,
)

__all__ = ["follow", "trace"]

logger = logging.getLogger(__name__)

#: relative size of the smallest singular value below which a Jacobian is singular
SINGULAR_RATIO = 1e-8

#: accepted points interpolated by the predictor (3: quintic Hermite)
PREDICTOR_NODES = 3


#: a corrected point whose next Newton correction (its distance to the curve) exceeds this
#: fraction of the step is not a point of the curve at that step's resolution: the step is
#: rejected (the tolerances, relative to ``1 + max|x|``, are too loose for the curve's scale)
UNRESOLVED = 0.1
_UNRESOLVED_REASON = "the corrected point meets the tolerances"

#: a run that reaches max_steps with its step below this fraction of its longest says so
CREEPING = 1e-6
#: a run whose last step fails within this many of its length of a step that met non-finite
#: values ends NON_FINITE (the steps shrank towards the edge of the residual's domain)
EDGE = 1e3


def trace(
    problem: Problem,
    x0: np.ndarray,
    direction: int | np.ndarray | None = None,
    options: Options | None = None,
    events: Sequence[Event] = (),
    tangent: np.ndarray | None = None,
) -> Curve:
    """Follow the curve ``H(x) = 0`` from ``x0`` by pseudo-arclength continuation.

    Parameters
    ----------
    problem : Problem
        Residual ``H: R^(n+1) -> R^n`` and (optionally) its Jacobian.
    x0 : array_like, shape (n + 1,)
        Start point; it is first corrected onto the curve by Newton in the
        hyperplane through ``x0`` normal to the initial tangent.
    direction : {None, 1, -1} or array_like of shape (n + 1,), optional
        ``None`` or ``+1``: along the tangent induced by the Jacobian,
        ``det [H'(x0); t^T] > 0`` (or along ``tangent`` if given); ``-1``: the
        opposite way; an array: the initial tangent has a positive dot product
        with it.
    options : Options, optional
        Tolerances, step sizes and switches (default ``Options()``).
    events : sequence of Event, optional
        Scalar functions whose zeros are located (and may stop the curve). Each is
        also sampled inside every step and the step split where it changes faster than
        the step (:class:`Event`, Notes), but sampling can miss what falls between its
        samples: an event that changes on a scale much shorter than ``options.ds_max``
        (oscillating, a narrow dip) needs a smaller ``ds_max`` to be sure of its zeros.
    tangent : array_like of shape (n + 1,), optional
        Initial tangent, required at a singular start (e.g. a branch point);
        it is normalised.

    Returns
    -------
    Curve
        Points, arclength, tangents, special points, status and counters. A
        failure (``curve.status.failed``) returns the partial curve, or raises
        :class:`ContinuationError` carrying it if
        ``options.raise_on_failure``.

    Raises
    ------
    ValueError
        If an argument has the wrong shape or value.
    CallbackShapeError
        (a ``ValueError``) If the residual, the Jacobian or an event returns an array of
        the wrong shape or complex values, at the start or later; always, whatever
        ``raise_on_failure``, with the points traced before in ``error.curve``.
    CallbackError
        If the residual, the Jacobian or an event raises; always, with the points traced
        before in ``error.curve`` and the original exception as ``__cause__``.
    ContinuationError
        On any other failure when ``options.raise_on_failure`` is set (otherwise the
        failure is the returned curve's ``status`` and ``message``).

    Notes
    -----
    Predictor: the Euler step ``x + h t`` on the first step, afterwards the
    Hermite interpolant of the last two or three accepted points (positions
    and tangents) extrapolated by ``h`` (:func:`_extrapolate`): a cubic with
    error ``O(h^4)`` on the second step, then a quintic with error ``O(h^6)``
    (variable-order predictors: Lundberg & Poore 1991; Allgower & Georg,
    sec. 6.1 and 7.1). A higher-order prediction lands so close to the curve
    that one Newton step usually reaches the tolerance. Corrector: Newton on
    Keller's bordered system with the hyperplane through the prediction
    normal to the predicted tangent (:func:`continuation.corrector.correct`),
    with chord steps while they contract fast.

    Step control (Allgower & Georg, sec. 6.1; Den Heijer & Rheinboldt 1981):
    with the contraction rate ``kappa`` of the first two Newton corrections,
    the first correction ``delta`` and the angle ``alpha`` between consecutive
    tangents, compared with half their limits ``kappa~, delta~, alpha~`` in ``options``,
    the next step is ``h_new = h / clip(f, 1/2, 2)`` with

        f = max((kappa / kappa~)^(1/p), (delta / delta~)^(1/p), alpha / alpha~),

    where ``p`` is the order of the predictor error (2 Euler, 3 to 6 extrapolated).
    A step exceeding a limit, or whose corrector fails, is rejected and halved; so is a
    step whose corrected point meets the tolerances while its next Newton correction (the
    estimate of its distance to the curve) exceeds ``UNRESOLVED = 0.1`` of the step size,
    since the tolerances (``tol`` on the residual, ``tol (1 + max|x|)`` on the corrections)
    then do not resolve the curve on the step's scale (a curve much smaller than its
    distance from the origin, or whose residual is below ``tol`` on a whole neighbourhood):
    where halving does not help, the run ends with ``STEP_TOO_SMALL`` at ``ds_min`` and the
    rejection's reason, instead of tracing points off the curve. A step that does not
    increase the arclength (it moved no coordinate, or less than the rounding of ``s``)
    ends the run with ``STEP_TOO_SMALL`` at once.

    The arclength of a step is its chord corrected by the angle ``alpha``
    between the end tangents, ``|x_b - x_a| (alpha/2) / sin(alpha/2)``; the
    predictor's step ``h`` is the pseudo-arclength (Keller's hyperplane
    distance), which differs from it by ``O(h^3)``.

    Special points in each accepted step ``(x_a, x_b]``: event zeros, folds
    (sign changes of ``t_i``) and simple branch points (sign changes of
    ``det [H'; t^T]``, Allgower & Georg, sec. 8.1) are located by
    :func:`continuation.events.locate_zero` and inserted into the curve. The zeros of
    terminal events are located first, the simplest-looking first: once the curve's end in a
    step is known, a bracket beyond it is dropped and one that contains it is cut at it if
    the event has changed sign there (dropped otherwise), so that a multiple zero at the
    same end (e.g. a curve ending where it also touches a box edge) costs no bisections.

    Branch points are scanned inside each step like folds: a step whose determinant is not
    clear of zero (judged from its values at the step's ends and the point before, at no
    cost) is modelled with the determinant's exact slopes, so two branch points inside one
    step are both found, and a step whose arc bends otherwise than the curvature at its ends
    (it landed on the crossing branch near a branch point, or outran a sharp turn) is
    rejected and retaken shorter (:meth:`continuation.scan.StepScan.check_turn`); so is a step
    past a branch point whose end is not on the branch it came along (corrected from the
    branch point along that branch's tangent, from the bifurcation equation). A step that
    lands on the crossing branch keeps the determinant's sign; its end tangent is off the one
    the step before predicts by about the crossing angle, so a step whose end tangent differs
    from that prediction by more than ``SURPRISE max_angle`` (the first step: whose arc bends
    off the curvature at its ends by as much) is not clear either and gets the same checks
    (:meth:`continuation.scan.StepScan.det_clear`).

    Known limits: a pair of branch points much closer together than a step, whose
    determinant dips and returns between the step's ends with little trace at them (a steep,
    narrow branch crossing a straight one), is missed like an event's narrow dip; two branch
    points closer together than a step, on branches that cross at a small angle (they nearly
    touch between the two), can be passed by a step that lands on the other branch between
    them, and only one or neither is reported. Lower ``ds_max`` below such a pair's spacing.
    Two branch points closer than about ``sqrt(tol)`` are located only to about ``tol`` over
    their distance.

    Folds in a coordinate the points do not resolve (constant along the curve, its tangent
    component rounding noise) are dropped at the end of the run: pairs closer in ``x_i`` than
    ``100 tol (1 + max|x|)`` with ``|t_i| <= 1e-6`` around them
    (:func:`continuation.special.drop_unresolved_folds`).
    """
    return follow(problem, x0, direction, options, events, tangent)


def follow(problem: Problem, x0, direction=None, options: Options | None = None,
           events: Sequence[Event] = (), tangent=None, *, evaluator: Evaluator | None = None,
           start_mark: tuple = (SpecialKind.START, "start", 0.0),
           at_branch_point: bool = False, closes_at: tuple | None = None) -> Curve:
    """:func:`trace` with the hooks branch switching and the pieces of a curve need.

    Parameters
    ----------
    problem, x0, direction, options, events, tangent
        As for :func:`trace`.
    evaluator : Evaluator, optional
        A counting evaluator shared with earlier work (its counts go into the curve).
    start_mark : tuple
        ``(kind, name, accuracy)`` of the start's special point, e.g. a branch point.
    at_branch_point : bool
        ``x0`` is a located branch point and ``tangent`` the new branch's: the start is not
        corrected (the bordered matrix is singular there).
    closes_at : (ndarray, ndarray), optional
        ``(x, t)``: the curve closes where it passes through the point ``x`` (on the curve)
        with the tangent ``t``, instead of through its own start (a curve traced in pieces,
        :mod:`continuation.codim2`, closes on the first piece's start).
    """
    if not isinstance(problem, Problem):
        raise TypeError(f"problem must be a Problem, got {type(problem).__name__}")
    options = Options() if options is None else options
    if not isinstance(options, Options):
        raise TypeError(f"options must be an Options, got {type(options).__name__}")
    if isinstance(events, Event) or not isinstance(events, Iterable):
        raise TypeError(f"events must be a sequence of Event instances (e.g. [event]), got "
                        f"{type(events).__name__}")
    events = tuple(events)
    for event in events:
        if not isinstance(event, Event):
            raise TypeError(f"events must be Event instances, got {type(event).__name__}")
    x0 = as_vector("x0", x0)
    n1 = x0.size
    if n1 < 2:
        raise ValueError(f"x0 must have n + 1 >= 2 coordinates, got {n1}")
    if problem.names is not None and len(problem.names) != n1:
        raise ValueError(f"Problem.names has {len(problem.names)} names, x0 has {n1} coordinates")
    for i in options.fold_coordinates:
        if i >= n1:
            raise ValueError(f"Options.fold_coordinates entries must be < {n1}, got {i}")
    evaluator = Evaluator(problem) if evaluator is None else evaluator
    evaluator.expect(n1)
    run = Run(problem, options, events, evaluator)
    try:
        try:
            start, status, message = _start(run, x0, direction, tangent, at_branch_point)
        except EventNotFinite as error:
            return run.curve(Status.EVENT_NOT_FINITE, f"at the start: {error}", n1)
        if start is None:
            return run.curve(status, message, n1)
        index = run.append(start.x, 0.0, start.tangent, start.residual, start.iterations)
        run.mark(start_mark[0], start_mark[1], index, start_mark[2] or 0.0)
        stepper = _Stepper(run, start)
        if closes_at is not None and options.detect_closed:
            stepper.start = _closing_target(run, *closes_at)
        while not stepper.check_terminated():
            stepper.step()
        return run.curve(cast(Status, stepper.status), stepper.message, n1)
    except (CallbackError, CallbackShapeError) as error:
        # the user's function failed: the exception carries what was traced before
        error.curve = run.curve(Status.CALLBACK_FAILED, str(error), n1, raise_failure=False)
        raise


class _Stepper:
    """The state of a run between steps: the point, the predictor's nodes, the step size."""

    def __init__(self, run: Run, start: Node) -> None:
        self.run = run
        self.start = start
        self.point = start
        # the accepted points the predictor interpolates, oldest first
        self.nodes: list[Node] = []
        self.ds = run.options.ds
        self.steps = 0
        self.status: Status | None = None
        self.message = ""
        # (s, h) of the last step rejected for non-finite values: the steps that shrink
        # towards the edge of the residual's domain end in other rejections
        self.non_finite: tuple[float, float] | None = None
        self.longest = 0.0

    def check_terminated(self) -> bool:
        """Whether the run has ended; the last checks, of the folds, once it has."""
        if self.status is None and self.steps >= self.run.options.max_steps:
            self.status = Status.MAX_STEPS
            self.message = f"{Status.MAX_STEPS.value} ({self.steps})"
            if self.ds < CREEPING * self.longest:
                self.message += (
                    f"; the step size had fallen to {self.ds:.3g} (the longest step was "
                    f"{self.longest:.3g}): the curve may be singular or turn "
                    "sharply there, or the Jacobian may be wrong (continuation.check_jacobian); "
                    "the rejections are logged at DEBUG level by 'continuation.tracker'")
        if self.status is None:
            return False
        drop_unresolved_folds(self.run)
        if not self.status.failed:  # (a Jacobian is checked where the steps collapsed too)
            creeping = self.status is Status.MAX_STEPS and self.ds < CREEPING * self.longest
            inconsistency = fold_inconsistency(self.run)
            mismatch = "" if inconsistency else jacobian_at_special_points(self.run, creeping)
            if inconsistency or mismatch:
                self.status = Status.INCONSISTENT if inconsistency else Status.JACOBIAN_MISMATCH
                self.message = inconsistency or mismatch
        return True

    def step(self) -> None:
        """One step: predict, correct, accept (locating its special points) or reject, adapt."""
        run, options, point = self.run, self.run.options, self.point
        h = min(self.ds, options.max_arclength - point.s)
        if self.nodes:
            x_pred, border, order = extrapolate((*self.nodes, point), h)
        else:
            x_pred, border, order = point.x + h * point.tangent, point.tangent, 2
        correction = correct(run.evaluator, x_pred, border, options.newton,
                             max_correction=options.max_correction)
        alpha = 0.0
        if correction.ok:
            alpha = math.acos(max(-1.0, min(1.0, float(correction.tangent @ point.tangent))))
            if alpha > options.max_angle:
                correction.ok = False
                correction.reason = f"angle between tangents {alpha:.3g} > max_angle"
            elif correction.remaining > UNRESOLVED * self.ds:
                # against the step size, not h: a last step cut short by max_arclength is
                # as resolved as the steps before it
                correction.ok = False
                correction.reason = (
                    f"{_UNRESOLVED_REASON} but Newton would still move it "
                    f"by {correction.remaining:.3g}, more than {UNRESOLVED:g} of the step "
                    f"{self.ds:.3g}: the tolerances do not resolve the curve on this step's "
                    f"scale (tol={options.tol:.3g} on the residual, on the corrections relative "
                    "to 1 + max|x|)")
        if not correction.ok:
            self._reject(h, correction.reason, Status.STEP_TOO_SMALL)
            return
        truncated = h >= options.max_arclength - point.s
        try:
            new, closing = self._accepted_point(correction, alpha, truncated)
            truncated = truncated or new.s >= options.max_arclength
            if not new.s > point.s:
                self.status, self.message = _unresolved_step(run, point, self.steps, h)
                return
            found = scan_step(run, point, new, self.nodes[-1] if self.nodes else None)
        except EventNotFinite as error:
            self.status, self.message = Status.EVENT_NOT_FINITE, (
                f"{error}; the event's zeros cannot be found beyond s={point.s:.12g}: make the "
                "event finite along the curve or stop the curve before")
            return
        except StepUnresolved as error:
            # a step that jumped to another branch, or bends faster than it resolves
            self._reject(h, str(error), Status.STEP_TOO_SMALL)
            return
        except LocateError as error:
            # a step whose special points cannot be located is too long for its Hermite
            # arc: reject it like any other, and fail only at the smallest step
            self._reject(h, str(error), Status.NOT_LOCATED)
            return
        self.steps += 1
        self.longest = max(self.longest, h)
        self._end(add_step(run, point, new, found), closing, truncated, new)
        self.ds = max(options.ds_min,
                      min(options.ds_max, h * _step_multiplier(correction, alpha, order, options)))
        # a singular start (det 0) carries a given tangent, not a computed null vector,
        # whose error the extrapolation would amplify: it is no Hermite node
        self.nodes = [*self.nodes[-(PREDICTOR_NODES - 2):], point] if point.det != 0.0 else []
        self.point = new

    def _accepted_point(self, correction: Correction, alpha: float, truncated: bool):
        """The new curve point, moved to ``max_arclength`` or onto the start if it closes."""
        run, point = self.run, self.point
        new = run.node(correction.x, point.s + arc_length(correction.x - point.x, alpha),
                       correction.tangent, correction.det, correction.residual,
                       correction.iterations, correction.jacobian)
        if (truncated or new.s > run.options.max_arclength) \
                and new.s != run.options.max_arclength:
            # (a step's arclength exceeds its pseudo-arclength h by O(h^3): one that was not
            # cut may still pass max_arclength, and is brought back to it)
            new = _point_at_arclength(run, point, new, run.options.max_arclength)
        closing = None
        if run.options.detect_closed:
            closing = closing_point(run, self.start, point, new)
        return (new if closing is None else closing), closing

    def _reject(self, h: float, reason: str, failure: Status) -> None:
        """Halve the step; at the smallest step the run fails with ``failure``."""
        self.run.rejected += 1
        logger.debug("step %d rejected at s=%.6g with ds=%.3g: %s", self.steps + 1,
                     self.point.s, h, reason)
        self.ds = 0.5 * h
        if reason == NON_FINITE:
            self.non_finite = (self.point.s, h)
        if self.ds < self.run.options.ds_min:
            if failure is Status.NOT_LOCATED:
                self.status, self.message = failure, (
                    f"{failure.value}: {reason}; even with the step size {h:.3g} "
                    f"(ds_min={self.run.options.ds_min:.3g}); the curve ends before it")
            else:
                # near the edge: a step that met it from here was nearly as short as this one
                edge = self.non_finite is not None \
                    and self.point.s - self.non_finite[0] <= self.non_finite[1] <= EDGE * h
                self.status, self.message = _step_failure(self.run, self.point, self.steps,
                                                          reason, self.ds, edge)

    def _end(self, terminal: SpecialPoint | None, closing, truncated: bool, new: Node) -> None:
        """The status if the accepted step ended the run."""
        run = self.run
        if terminal is not None:
            self.status, self.message = Status.TERMINAL_EVENT, (
                f"terminal event '{terminal.name}' at s={terminal.s:.12g}, "
                f"x={run.problem.describe(terminal.x)}")
        elif closing is not None:
            run.mark(SpecialKind.CLOSED, "closed", len(run.s) - 1, 0.0)
            self.status, self.message = Status.CLOSED, (
                f"{Status.CLOSED.value} after {self.steps} steps, length s={new.s:.12g}")
        elif truncated:
            self.status = Status.MAX_ARCLENGTH
            self.message = f"{Status.MAX_ARCLENGTH.value} s={new.s:.12g}"


def _start(run: Run, x0: np.ndarray, direction, tangent, at_branch_point=False):
    """Correct ``x0`` onto the curve and orient its tangent; ``(point, status, message)``."""
    problem, options, evaluator = run.problem, run.options, run.evaluator
    n1 = x0.size
    H = evaluator.residual(x0)
    if H.shape != (n1 - 1,):
        raise ValueError(f"residual(x0) has shape {H.shape}, expected ({n1 - 1},) for x0 of "
                         f"shape ({n1},)")
    where = f"x0={problem.describe(x0)}"
    if not np.isfinite(H).all():
        return None, Status.NON_FINITE, f"the residual is not finite at the start {where}"
    J = evaluator.jacobian(x0)
    if J.shape != (n1 - 1, n1):
        raise ValueError(f"jacobian(x0) has shape {J.shape}, expected ({n1 - 1}, {n1})")
    if not np.isfinite(J).all():
        return None, Status.NON_FINITE, f"the Jacobian is not finite at the start {where}"
    if options.check_jacobian and problem.jacobian is not None:
        mismatch = probe_jacobian(evaluator, x0, J)
        if mismatch is not None:
            return None, Status.JACOBIAN_MISMATCH, (
                f"{Status.JACOBIAN_MISMATCH.value} at the start {where}: {mismatch}. Check "
                "the Jacobian with continuation.check_jacobian(problem, None, x0); if the "
                "residual is not smooth there, pass Options(check_jacobian=False)")
    reference, sign = _orientation(direction, n1)
    if tangent is None:
        singular_values, basis = _svd(J)
        if singular_values[0] == 0 or singular_values[-1] <= SINGULAR_RATIO * singular_values[0]:
            ratio = abs(singular_values[-1]) / singular_values[0] if singular_values[0] else 0.0
            return None, Status.SINGULAR_START, (
                f"the Jacobian has rank < n at the start {where} (smallest/largest singular "
                f"value {ratio:.2e}): the start is a branch point or another singular point; "
                "use switch_branch(problem, x0, ...) or pass an explicit tangent=")
        guess = basis[-1]
    else:
        guess = as_vector("tangent", tangent)
        norm = float(np.linalg.norm(guess))
        if guess.size != n1 or not norm > 0:
            raise ValueError(f"tangent must be a nonzero finite array of shape ({n1},), "
                             f"got {tangent!r}")
        guess = guess / norm

    if at_branch_point and tangent is not None and float(np.max(np.abs(H))) <= options.tol:
        # the bordered matrix is singular at a branch point: keep the located point
        correction = Correction(False, SINGULAR, x0, None, 0.0, float(np.max(np.abs(H))), 0,
                                0.0, 0.0)
    else:
        correction = correct(evaluator, x0, guess, options.newton,
                             residual=H, jacobian=J)
    if correction.ok:
        x, t, det = correction.x, correction.tangent, correction.det
        if reference is None and tangent is None and det < 0:
            sign = -sign
    elif (tangent is not None and correction.reason == SINGULAR
          and float(np.max(np.abs(H))) <= options.tol):
        # a singular start on the curve with a given tangent (a branch point)
        x, t, det = x0, guess, 0.0
        correction.residual = float(np.max(np.abs(H)))
        correction.iterations = 0
    elif correction.reason == NON_FINITE:
        return None, Status.NON_FINITE, (
            f"the residual or Jacobian became non-finite while correcting the start {where}; "
            "give a start closer to the curve, inside the residual's domain")
    else:
        return None, Status.START_NOT_CONVERGED, (
            f"Newton did not converge from the start {where}, |H(x0)|="
            f"{float(np.max(np.abs(H))):.3g}: {correction.reason} after "
            f"{correction.iterations} iterations (last |H|={correction.residual:.3g}, "
            f"last x={problem.describe(correction.x)}); give a start closer to the curve, "
            "or raise Options.max_newton / loosen Options.tol")
    if reference is not None:
        dot = float(t @ reference)
        if dot == 0:
            raise ValueError("direction is orthogonal to the tangent at the start; "
                             "it cannot choose an orientation")
        sign = 1 if dot > 0 else -1
    point = run.node(x, 0.0, sign * t, sign * det, correction.residual, correction.iterations,
                     correction.jacobian if correction.ok else None)
    return point, None, ""


def _closing_target(run: Run, x, tangent) -> Node:
    """The node a run closes on, at the curve point ``x`` with the tangent ``tangent``: its
    determinant and event values are this run's (the problem may differ from the one that
    found ``x``, by its borders, and define the same curve), its arclength 0."""
    x = as_vector("closes_at x", x)
    t = as_vector("closes_at tangent", tangent)
    t = t / float(np.linalg.norm(t))
    J = run.evaluator.jacobian(x)
    det = float(np.linalg.det(np.vstack([J, t])))
    residual = float(np.max(np.abs(run.evaluator.residual(x))))
    return run.node(x.copy(), 0.0, t, det, residual, 0, J)


def _orientation(direction, n1: int) -> tuple[np.ndarray | None, int]:
    """``(reference array or None, sign)`` from the ``direction`` argument of :func:`trace`.

    Raises
    ------
    ValueError
        If ``direction`` is not ``None``, 1, -1 or a nonzero array of shape ``(n1,)``.
    """
    if direction is not None and not isinstance(direction, (int, np.integer)):
        reference = as_vector("direction", direction)
        if reference.size != n1 or not np.any(reference):
            raise ValueError(f"direction must be None, 1, -1 or a nonzero array of shape "
                             f"({n1},), got {direction!r}")
        return reference, 1
    if direction not in (None, 1, -1):
        raise ValueError(f"direction must be None, 1, -1 or an array of shape ({n1},), "
                         f"got {direction!r}")
    return None, 1 if direction is None else int(direction)


def _svd(J: np.ndarray):
    """Singular values of ``J`` and the full right singular basis (rows)."""
    _, singular_values, basis = np.linalg.svd(J, full_matrices=True)
    return singular_values, basis


def _step_multiplier(correction, alpha: float, order: int, options: Options) -> float:
    """Step-size factor ``1 / clip(f, 1/2, 2)`` from Allgower & Georg's sec. 6.1 estimates."""
    f = max(
        (correction.contraction / (0.5 * options.newton_contraction)) ** (1.0 / order),
        (correction.first_correction / (0.5 * options.max_correction)) ** (1.0 / order),
        alpha / (0.5 * options.max_angle),
    )
    return 2.0 if f <= 0.5 else max(0.5, 1.0 / f)


def _step_failure(run: Run, point: Node, steps: int, reason: str, ds: float,
                  edge: bool = False):
    """Status and message when the step falls below ``ds_min``; ``edge``: a step from
    within its length of ``point`` met non-finite values (the steps shrank towards the edge
    of the residual's domain, and the last ones may have failed otherwise)."""
    where = (f"after step {steps} at s={point.s:.12g}, x={run.problem.describe(point.x)} "
             f"(step size {ds:.3g} < ds_min={run.options.ds_min:.3g})")
    if reason == NON_FINITE or edge:
        last = "" if reason == NON_FINITE else f" (the last, shortest steps failed: {reason})"
        return Status.NON_FINITE, (
            f"the residual or Jacobian is not finite ahead of the curve {where}: the curve "
            "leaves the residual's domain; stop it before with box_events or an Event, or "
            f"extend the residual{last}")
    if reason.startswith(_UNRESOLVED_REASON):
        advice = ("Either the curve is smaller than the tolerances resolve near this point "
                  "(tighten Options.tol, or shift and scale the problem so that the curve's "
                  "size and coordinates are of order one), or the steps had shrunk for another "
                  "reason (the earlier rejections, logged at DEBUG level by "
                  "'continuation.tracker', say which)")
    else:
        advice = ("The curve may end, turn sharply or be singular here: check the residual "
                  "and Jacobian near this point, loosen Options.tol, or lower Options.ds_min")
    return Status.STEP_TOO_SMALL, (
        f"{Status.STEP_TOO_SMALL.value} {where}; last rejection: {reason}. {advice}")


def _unresolved_step(run: Run, point: Node, steps: int, h: float):
    """Status and message when a step of ``h`` did not increase the arclength ``s``.

    It moved no coordinate, or less than the rounding of ``s``: a smaller step could not
    advance the curve either, so the run ends at once instead of halving down to ``ds_min``.
    """
    return Status.STEP_TOO_SMALL, (
        f"no step can advance the curve: the step {h:.3g} after step {steps} at "
        f"s={point.s:.12g}, x={run.problem.describe(point.x)} moved no coordinate or less "
        f"than the rounding of s (the rounding of x is up to "
        f"{np.spacing(np.abs(point.x)).max():.3g}), so the curve cannot be followed further "
        "in floating point (the steps get this small where the corrector cannot meet "
        "Options.tol, as where the residual's rounding exceeds it, or when Options.ds is set "
        "this small): loosen Options.tol to above the residual's rounding, or shift and scale "
        "the problem so that its coordinates near the curve are of order one")


def _point_at_arclength(run: Run, a: Node, b: Node, s: float) -> Node:
    """The curve point at arclength ``s`` near the step ``a -> b`` (else ``b``).

    The step was sized in pseudo-arclength, whose sum differs from the
    arclength by ``O(h^3)``; the Hermite arc of the step, extended slightly if
    needed, is corrected at ``s`` so that the curve ends exactly there.
    """
    options = run.options
    p, dp = hermite(a.x, a.tangent, b.x, b.tangent, b.s - a.s, s - a.s)
    correction = correct(run.evaluator, p, dp / np.linalg.norm(dp), options.newton)
    if not correction.ok:
        logger.debug("could not move the last point to s=%.12g: %s", s, correction.reason)
        return b
    return run.node(correction.x, s, correction.tangent, correction.det, correction.residual,
                    correction.iterations, correction.jacobian)
