"""Simple branch points: location, branch tangents and branch switching."""

from __future__ import annotations

import logging
import math
from collections.abc import Sequence
from dataclasses import replace

import numpy as np

from .bifurcation import branch_tangent_pair
from .corrector import correct
from .events import Event
from .options import Options
from .problem import Evaluator, Problem, as_vector
from .result import Curve, SpecialKind, SpecialPoint, Status
from .run import Run
from .tracker import SINGULAR_RATIO, UNRESOLVED, follow

__all__ = ["branch_tangents", "locate_branch_point", "switch_branch"]

logger = logging.getLogger(__name__)

_EPS = np.finfo(float).eps

#: step off an exactly singular point, relative to 1 + max|x|
STEP_OFF = 1e-3

#: the first point after a branch switch, ``d`` along the new tangent, must be within this
#: fraction of ``theta d`` of the new tangent's line (the old branch is ``~theta d`` away) and
#: its tangent within twice this fraction of ``theta`` of the new tangent (``theta``: the
#: branches' angle); this fraction of ``theta d`` must exceed twice the points' accuracy
ON_NEW_BRANCH = 0.25

#: a given point on the curve whose Jacobian has a smallest-to-largest singular
#: value ratio below this is taken as the branch point itself (rounding level)
EXACT_RATIO = 64 * _EPS


def branch_tangents(problem: Problem, x_bp: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Return the unit tangents of the two branches through a simple branch point.

    Parameters
    ----------
    problem : Problem
        The problem.
    x_bp : array_like, shape (n + 1,)
        A located simple branch point (``rank H'(x_bp) = n - 1``).

    Returns
    -------
    t1, t2 : ndarray, shape (n + 1,)
        Unit tangents of the two branches (each up to sign).

    Raises
    ------
    ValueError
        If the Jacobian at ``x_bp`` is not rank deficient, or the algebraic
        bifurcation equation has no two distinct real roots (not a simple
        branch point).

    Notes
    -----
    At a simple branch point the null space of ``H'`` is spanned by the
    orthonormal ``v1, v2`` and the left null space by ``psi``. Branch tangents
    ``t = alpha v1 + beta v2`` solve the algebraic bifurcation equation
    (Allgower & Georg, sec. 8.1; Keller 1977)

    .. math::

        \\psi^T H''(x)[t, t] = a \\alpha^2 + 2 b \\alpha\\beta + c \\beta^2 = 0,
        \\qquad b^2 - a c > 0,

    with ``a = psi^T H''[v1, v1]``, ``b = psi^T H''[v1, v2]``,
    ``c = psi^T H''[v2, v2]``. The second derivatives are central differences
    of the Jacobian, ``H''[v, w] ~ (H'(x + h v) - H'(x - h v)) w / (2h)``
    (four Jacobian evaluations). In the eigenbasis of the symmetric
    ``Q = [[a, b], [b, c]]`` with eigenvalues ``l1 < 0 < l2`` the roots are
    ``(sqrt(l2), +-sqrt(-l1))``.
    """
    return branch_tangent_pair(Evaluator(problem), as_vector("x_bp", x_bp))


def locate_branch_point(
    problem: Problem,
    x_approx: np.ndarray,
    options: Options | None = None,
    radius: float | None = None,
) -> SpecialPoint:
    """Locate a simple branch point near an approximate point.

    Parameters
    ----------
    problem : Problem
        The problem.
    x_approx : array_like, shape (n + 1,)
        Approximate branch point.
    options : Options, optional
        Tolerances (``tol``, ``event_tol``, ``ds``).
    radius : float, optional
        Pseudo-arclength searched on each side; default
        ``max(2 ds, 4 |x_c - x_approx|)`` with ``x_c`` the projection of
        ``x_approx`` onto the curve.

    Returns
    -------
    SpecialPoint
        Kind ``'branch_point'``; ``tangent`` is the tangent of the branch on
        which it was located, ``accuracy`` the final bracket width.

    Raises
    ------
    ValueError
        If ``x_approx`` cannot be projected onto ``H = 0`` or no branch point
        lies within ``radius``.

    Notes
    -----
    ``x_approx`` is projected onto ``H = 0`` by Gauss-Newton steps of minimal
    norm, ``dx = -H'(x)^+ H(x)``. From there the branch is traced a short way
    in both directions and the sign change of ``det [H'; t^T]`` is located
    like any special point (Allgower & Georg, sec. 8.1 and 9.2). If the
    projection is (numerically) the singular point itself, the search starts
    from a point projected after a step of ``1e-3 (1 + max|x|)`` along the null
    space.
    """
    options = Options() if options is None else options
    return _locate_branch_point(Evaluator(problem), problem, as_vector("x_approx", x_approx),
                                options, radius)


def _locate_branch_point(evaluator, problem, x_approx, options, radius):
    x = _project(evaluator, x_approx, options)
    J = evaluator.jacobian(x)
    _, singular_values, right = np.linalg.svd(J, full_matrices=True)
    if singular_values[0] == 0 or singular_values[-1] <= SINGULAR_RATIO * singular_values[0]:
        step = STEP_OFF * (1.0 + float(np.max(np.abs(x))))
        x = _project(evaluator, x + step * right[-1], options)
        radius = 4.0 * step if radius is None else radius
    elif radius is None:
        radius = max(2.0 * options.ds, 4.0 * float(np.linalg.norm(x - x_approx)))
    if not (radius > 0 and math.isfinite(radius)):
        raise ValueError(f"radius must be a finite number > 0, got {radius!r}")
    ds = min(options.ds, radius / 8.0)
    local = replace(options, ds=ds, ds_min=min(options.ds_min, ds),
                    ds_max=max(ds, min(options.ds_max, radius / 4.0)), max_arclength=radius,
                    fold_coordinates=(), detect_branch_points=True, detect_closed=False,
                    raise_on_failure=False)
    candidates = []
    for direction in (1, -1):
        curve = follow(problem, x, direction, local, evaluator=evaluator)
        candidates.extend(curve.special("branch_point"))
    if not candidates:
        raise ValueError(
            f"no branch point found within arclength {radius:.3g} of x_approx="
            f"{problem.describe(x_approx)}: det[H'; t^T] keeps its sign there; pass a closer "
            "approximation or a larger radius")
    best = min(candidates, key=lambda p: float(np.linalg.norm(p.x - x_approx)))
    return replace(best, index=0, s=0.0)


def _exact_branch_point(evaluator: Evaluator, x: np.ndarray, options: Options) -> float | None:
    """Whether ``x`` is a branch point to rounding: its accuracy estimate, else ``None``.

    ``x`` qualifies if ``max |H(x)| <= tol`` and the singular values of ``H'(x)`` have
    ``sigma_min <= EXACT_RATIO sigma_max``. Near a simple branch point ``sigma_min``
    grows linearly with the distance to it, so ``(sigma_min / sigma_max) (1 + max|x|)``
    estimates that distance (the reported accuracy).
    """
    H = evaluator.residual(x)
    if not (np.isfinite(H).all() and float(np.max(np.abs(H))) <= options.tol):
        return None
    J = evaluator.jacobian(x)
    if not np.isfinite(J).all():
        return None
    singular_values = np.linalg.svd(J, compute_uv=False)
    # H' = 0 (e.g. a pitchfork in one equation) is as singular as it gets
    ratio = float(singular_values[-1] / singular_values[0]) if singular_values[0] > 0 else 0.0
    if ratio > EXACT_RATIO:
        return None
    return ratio * (1.0 + float(np.max(np.abs(x))))


def _project(evaluator: Evaluator, x: np.ndarray, options: Options) -> np.ndarray:
    """Gauss-Newton projection of ``x`` onto ``H = 0`` with minimal-norm steps."""
    x = x.copy()
    for _ in range(4 * options.max_newton):
        H = evaluator.residual(x)
        if not np.isfinite(H).all():
            break
        if float(np.max(np.abs(H))) <= options.tol:
            return x
        J = evaluator.jacobian(x)
        if not np.isfinite(J).all():
            break
        x = x + np.linalg.lstsq(J, -H, rcond=None)[0]
    raise ValueError(f"could not project x={evaluator.problem.describe(x)} onto H = 0 "
                     "(Gauss-Newton did not converge); give a point closer to the curve")


def switch_branch(
    problem: Problem,
    x_bp: SpecialPoint | np.ndarray,
    direction: int | np.ndarray | None = None,
    options: Options | None = None,
    events: Sequence[Event] = (),
    tangent_hint: np.ndarray | None = None,
) -> Curve:
    """Follow the other branch through a simple branch point.

    Parameters
    ----------
    problem : Problem
        The problem.
    x_bp : SpecialPoint or array_like of shape (n + 1,)
        A branch point from ``Curve.special('branch_point')`` (its tangent is
        the current branch), or an approximate (or exact) branch point, which
        is located first with :func:`locate_branch_point`. An array that is
        already a branch point to rounding (``max |H| <= tol`` and
        ``sigma_min(H') <= 64 eps sigma_max(H')``) is used as it is when the
        branch is chosen by a ``direction`` array or ``tangent_hint``.
    direction : {None, 1, -1} or array_like of shape (n + 1,), optional
        Orientation of the new branch: ``None``/``+1`` along its tangent
        normalised so that its largest-magnitude component is positive, ``-1``
        the opposite way; an array: positive dot product with it. For an
        array ``x_bp`` without ``tangent_hint``, an array direction also
        chooses the branch: the one most nearly parallel to it. Otherwise the
        new branch is the one other than the current branch (the
        SpecialPoint's tangent, ``tangent_hint``, or the branch along which an
        array ``x_bp`` was located).
    options : Options, optional
        Options of the new trace.
    events : sequence of Event, optional
        Events of the new trace.
    tangent_hint : array_like of shape (n + 1,), optional
        Tangent of the current branch (overrides the one from ``x_bp``), e.g.
        ``curve.tangents[i]`` at the point of the traced curve nearest ``x_bp``.

    Returns
    -------
    Curve
        Starts at the branch point (its first special point, kind
        ``'branch_point'``); counters include the location and the tangents.

    Raises
    ------
    ValueError
        If the point is not a simple branch point, or the current branch is
        unknown and ``direction`` is not an array.

    Notes
    -----
    The two branch tangents come from the algebraic bifurcation equation
    (:func:`branch_tangents`); the new branch is the one less parallel to the
    current branch tangent. The trace starts at the branch point without a
    correction (the bordered matrix is singular there); the first corrector
    works in the hyperplane normal to the new tangent at distance ``h <= ds``, where it may
    converge back to the old branch when the new one bends towards it. The first step is
    therefore checked to land on the new branch (near the new tangent's line and with a
    tangent near it, against the branches' angle: :func:`_on_new_branch`) and halved until it
    does; where no step down to ``ds_min`` (or to where the points' accuracy cannot tell the
    branches apart) does, the curve is the branch point alone with status ``STEP_TOO_SMALL``
    and a message (raised with ``options.raise_on_failure``), never the old branch. The
    trace's ``options.ds`` is then that first step.
    """
    options = Options() if options is None else options
    evaluator = Evaluator(problem)
    reference = None
    if direction is not None and not isinstance(direction, (int, np.integer)):
        reference = as_vector("direction", direction)
    elif direction not in (None, 1, -1):
        raise ValueError(f"direction must be None, 1, -1 or an array, got {direction!r}")
    hint = None if tangent_hint is None else as_vector("tangent_hint", tangent_hint)
    if isinstance(x_bp, SpecialPoint):
        x, accuracy, found = x_bp.x.copy(), x_bp.accuracy, x_bp.tangent
    else:
        x, accuracy, found = _branch_point(evaluator, problem, as_vector("x_bp", x_bp), options,
                                           reference is not None or hint is not None)
    if reference is not None and reference.shape != x.shape:
        raise ValueError(f"direction must be None, 1, -1 or an array of shape {x.shape}, got "
                         f"{direction!r}")
    # the branch a search happened to run along is a guess of the current one; a direction
    # array or tangent_hint is the caller's explicit choice and wins
    if hint is None and not (reference is not None and not isinstance(x_bp, SpecialPoint)):
        hint = found
    first, second = branch_tangent_pair(evaluator, x)
    new = _new_branch_tangent(first, second, hint, reference, direction)
    logger.info("switching branch at x=%s along tangent %s", problem.describe(x), new)
    theta = math.acos(min(1.0, abs(float(first @ second))))
    noise = options.tol * (1.0 + float(np.max(np.abs(x)))) + (accuracy or 0.0)
    # a step below 2 noise / (ON_NEW_BRANCH theta) cannot tell the branches apart: a shorter
    # ds than that starts at twice it (a 1e-3-rad crossing at tol 1e-6 and ds 1e-3 failed,
    # where ds 1e-2 switches), within ds_max
    shortest = 4.0 * noise / (ON_NEW_BRANCH * theta) if theta > 0.0 else 0.0
    h = min(max(options.ds, shortest), options.ds_max, options.max_arclength)
    while True:
        h, why = _first_step(evaluator, x, new, theta, noise, options, h)
        if why:
            return _switch_failed(problem, evaluator, x, new, accuracy, options, events, why)
        curve = follow(problem, x, None, replace(options, ds=max(h, options.ds_min)), events,
                       new, evaluator=evaluator, at_branch_point=True,
                       start_mark=(SpecialKind.BRANCH_POINT, "branch point", accuracy))
        if _took_first_step(curve, x, new, h, noise):
            return curve
        h *= 0.5  # the trace rejected the step checked here (by its own tests): a shorter one


def _first_step(evaluator, x, new, theta, noise, options, h):
    """``(h, "")``: the longest step ``<= h`` (halving) whose first point lands on the new
    branch, or ``(h, reason)`` when none does down to the smallest step that can tell.

    The trace's first step from a branch point is the Euler prediction ``x + h t_new``
    corrected in the hyperplane normal to ``t_new``, where the corrector converges as readily
    to the old branch (about ``theta h`` away, ``theta`` the branches' angle) when the new one
    bends towards it. On the new branch the corrected point is ``O(h^2 kappa)`` from the
    prediction and its tangent ``O(h kappa)`` from ``t_new``; both are small against ``theta h``
    and ``theta`` once ``h`` is short against ``theta / kappa`` (:func:`_on_new_branch`).
    The step is the trace's own (:func:`continuation.tracker.follow`), with its tests of the
    angle and of the corrected point's distance to the curve, so the trace repeats it.
    """
    reason, tried = "", h
    while h >= options.ds_min and ON_NEW_BRANCH * theta * h > 2.0 * noise:
        c = correct(evaluator, x + h * new, new, options.newton,
                    max_correction=options.max_correction)
        if not c.ok:
            reason = c.reason
        elif float(c.tangent @ new) < math.cos(options.max_angle):
            reason = "angle between tangents > max_angle"
        elif c.remaining > UNRESOLVED * h:
            reason = "the corrected point does not meet the tolerances"
        else:
            reason = _on_new_branch(x, new, theta, c.x, c.tangent)
            if not reason:
                return h, ""
        logger.debug("first step %.3g off the branch point rejected: %s", h, reason)
        tried, h = h, 0.5 * h
    return h, (f"no first step from the branch point reaches the new branch: at the step "
               f"{tried:.3g} (ds_min={options.ds_min:.3g}, and the branches, {theta:.3g} rad "
               f"apart, must be told apart beyond the points' accuracy {noise:.3g}) the last "
               f"rejection was: {reason or 'none'}; the new branch bends back onto the old one "
               "faster than the steps resolve, or this is no simple branch point")


def _on_new_branch(x, new, theta, x1, t1) -> str:
    """Why the point ``x1`` with tangent ``t1`` is not on the branch leaving ``x`` along
    ``new`` at the angle ``theta`` to the other ("" if it is): at ``d = (x1 - x) . new`` it must
    lie within ``ON_NEW_BRANCH theta d`` of the line ``x + d new`` (the old branch is about
    ``theta d`` from it) and ``t1`` within ``2 ON_NEW_BRANCH theta`` of ``new`` (on the new
    branch of curvature ``kappa`` they are ``d^2 kappa / 2`` and ``d kappa``: the same bound on
    ``d kappa``)
    (Allgower & Georg, sec. 8.1: the branches leave a simple branch point along the roots of
    the bifurcation equation)."""
    d = float((x1 - x) @ new)
    off = float(np.linalg.norm(x1 - x - d * new))
    angle = math.acos(max(-1.0, min(1.0, float(t1 @ new))))
    if not d > 0.0 or off > ON_NEW_BRANCH * theta * d:
        return (f"the corrected point is {off:.3g} off the new branch's tangent line at "
                f"{d:.3g} along it, more than {ON_NEW_BRANCH:g} of the branches' angle "
                f"{theta:.3g} times that: it may be on the old branch")
    if angle > 2.0 * ON_NEW_BRANCH * theta:
        return (f"the tangent there is {angle:.3g} rad off the new branch's, more than "
                f"{2.0 * ON_NEW_BRANCH:g} of the branches' angle {theta:.3g}: it may be on the old "
                "branch")
    return ""


def _took_first_step(curve: Curve, x, new, h: float, noise: float) -> bool:
    """Whether the trace's first step from the branch point was the one checked, ``h`` along
    ``new`` (its end is in the hyperplane there): one of its points is there, or it failed (a
    loud failure stays one), or it ended before (a terminal event on that step's arc)."""
    along = (curve.x[1:] - x) @ new
    if not along.size or curve.status.failed or float(along.max()) < h - 2.0 * noise:
        return True
    return bool(np.any(np.abs(along - h) <= 2.0 * noise))


def _switch_failed(problem, evaluator, x, new, accuracy, options, events, why) -> Curve:
    """The curve of a branch switch that found no first step: the branch point, and a failure
    status (raised as :class:`ContinuationError` with ``options.raise_on_failure``)."""
    run = Run(problem, options, tuple(events), evaluator)
    residual = float(np.max(np.abs(evaluator.residual(x))))
    index = run.append(x, 0.0, new, residual, 0)
    run.mark(SpecialKind.BRANCH_POINT, "branch point", index, accuracy or 0.0)
    return run.curve(Status.STEP_TOO_SMALL, f"{Status.STEP_TOO_SMALL.value}: {why}", x.size)


def _branch_point(evaluator: Evaluator, problem: Problem, x_given: np.ndarray,
                  options: Options, chosen: bool):
    """``(x, accuracy, tangent of the branch it was found on or None)`` for an array.

    With the branch ``chosen`` by the caller an exact branch point (e.g. an analytic one) is
    used as given; otherwise it is located along the curve through ``x_given``.
    """
    exact = _exact_branch_point(evaluator, x_given, options) if chosen else None
    if exact is not None:
        return x_given.copy(), exact, None
    located = _locate_branch_point(evaluator, problem, x_given, options, None)
    return located.x, located.accuracy, located.tangent


def _new_branch_tangent(first: np.ndarray, second: np.ndarray, hint, reference, direction):
    """The oriented tangent of the new branch among the two branch tangents.

    With the current branch's tangent ``hint`` the new one is the less parallel to it;
    otherwise the one more parallel to the ``reference`` direction. Oriented along
    ``reference``, else with its largest component positive (times ``direction``).
    """
    if hint is not None:
        new = first if abs(float(first @ hint)) < abs(float(second @ hint)) else second
    elif reference is not None:
        new = first if abs(float(first @ reference)) > abs(float(second @ reference)) \
            else second
    else:
        raise ValueError("cannot tell the new branch from the current one: pass a SpecialPoint "
                         "from a traced curve, tangent_hint= or a direction array")
    if reference is not None:
        dot = float(new @ reference)
        if dot == 0:
            raise ValueError("direction is orthogonal to the new branch's tangent")
        return new if dot > 0 else -new
    largest = int(np.argmax(np.abs(new)))
    return new * (math.copysign(1.0, new[largest]) * (1 if direction is None else direction))
