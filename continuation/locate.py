"""Locating a bracketed special point exactly: Brent's method along the curve.

Each zero bracketed by the step scan (:mod:`continuation.scan`) is located by Brent's method
in the arclength, every trial point predicted on the cubic Hermite arc and corrected onto the
curve (:func:`locate_zero`); branch points are refined on their own
(:func:`refine_branch_point`).
"""

from __future__ import annotations

import logging
import math
from collections.abc import Callable
from typing import cast

import numpy as np

from .corrector import SINGULAR, Correction, correct, tangent_at
from .linalg import all_finite, factor_bordered, lu_determinant, max_abs, norm
from .node import EventNotFinite, LocateError, Node
from .options import Options
from .predictor import hermite
from .problem import Evaluator
from .scan import _TINY, JUMP  # _TINY: how the scans pass a zero at a bracket's start

__all__ = [
    "Located",
    "locate_zero",
    "refine_branch_point",
]

logger = logging.getLogger(__name__)

_EPS = np.finfo(float).eps

#: relative offset of a trial point retried beside an exactly singular one
NUDGE = 1e-9
#: a trial closer than this fraction of the bracket to a zero at its start, where the located
#: function is exactly 0 too, is taken to be at that zero (next to a branch point the tangent
#: component of the branch can round to 0 for about 1e-12 of arclength)
BESIDE = 1e-6

#: a trial's tangent is used when its cosine with the interpolated tangent exceeds this
RELIABLE = math.cos(0.1)


#: a trial whose determinant is below this fraction of the bracket ends' is next to a
#: branch point (where the computed tangent is noise)
NEAR_SINGULAR = 0.1


def _near_branch_point(det: float, det_start: float, det_end: float) -> bool:
    """Whether a trial point with ``det [H'; t^T] = det`` is next to a branch point: the
    determinant changes sign in the bracket, vanishes at one of its ends (a singular start),
    or is much smaller at the trial than at both ends."""
    if det_start == 0.0 or det_end == 0.0 or (det_start > 0.0) != (det_end > 0.0):
        return True
    return abs(det) <= NEAR_SINGULAR * min(abs(det_start), abs(det_end))


class Located:
    """A located zero: its parameter, the point, and the bracket width.

    ``node`` is one of the bracket's ends (an accepted point or a scan node) when
    the zero is there, else ``None`` and ``correction`` is the located point.
    """

    __slots__ = ("accuracy", "correction", "node", "s")

    def __init__(self, s: float, correction: Correction | None, accuracy: float,
                 node: Node | None) -> None:
        self.s = s
        self.correction = correction
        self.accuracy = accuracy
        self.node = node


def locate_zero(
    evaluator: Evaluator,
    options: Options,
    function: Callable[..., float],
    start,
    end,
    f_start: float,
    f_end: float,
    need_tangent: bool,
) -> Located:
    """Locate the zero of ``function`` along the curve between two points.

    Parameters
    ----------
    evaluator : Evaluator
        Counting evaluator of the problem.
    options : Options
        ``event_tol`` is the bracket width; ``tol`` the residual tolerance.
    function : callable
        ``function(correction) -> float`` of a corrected trial point.
    start, end : Node
        Curve points bracketing the zero.
    f_start, f_end : float
        The function at ``start`` and ``end``, of opposite signs (or
        ``f_end == 0``); a zero at ``start`` is passed as a tiny value on the
        side the function moves to.
    need_tangent : bool
        Whether ``function`` uses the tangent or determinant.

    Returns
    -------
    Located
        ``node`` is ``start`` or ``end`` when the best point is one of them,
        else ``correction`` is the located point (with its tangent).

    Raises
    ------
    LocateError
        If a trial point cannot be corrected or the function is not finite there.

    Notes
    -----
    Brent's method [1]_ (inverse quadratic interpolation and secant steps
    safeguarded by bisection) on ``f(s)`` keeps a bracket and stops when it is
    at most ``event_tol + 4 eps |s|`` wide. A trial point at ``s`` is the
    cubic Hermite prediction ``p(s)``, corrected by Newton in the hyperplane
    through ``p(s)`` normal to ``p'(s)`` (Allgower & Georg, sec. 9.2).

    References
    ----------
    .. [1] R. P. Brent, *Algorithms for Minimization without Derivatives*,
       Prentice-Hall, 1973, ch. 4.
    """
    if f_end == 0.0:
        return Located(end.s, None, 0.0, end)
    h = end.s - start.s
    trials: dict[float, Correction] = {}
    values: dict[float, float] = {}
    # curve points with exact tangents, (s, x, tangent), sorted by s: the
    # prediction of a trial uses the nearest on either side, so that its error,
    # O(width^4), vanishes as the bracket shrinks and Newton has little to do
    nodes = [(start.s, start.x, start.tangent), (end.s, end.x, end.tangent)]

    def evaluate(s: float) -> float:
        k = next(k for k in range(1, len(nodes)) if nodes[k][0] >= s)
        (s_a, x_a, t_a), (s_b, x_b, t_b) = nodes[k - 1], nodes[k]
        for nudge in (0.0, NUDGE * (s_b - s_a)):
            # a trial exactly at a branch point meets an exactly singular bordered
            # matrix; one a hair beside it (the zero is then refined) does not
            point, derivative = hermite(x_a, t_a, x_b, t_b, s_b - s_a, s + nudge - s_a)
            border = derivative / norm(derivative)
            result = correct(evaluator, point, border, options.locate_newton,
                             max_correction=JUMP * (s_b - s_a), need_tangent=need_tangent,
                             accept_fallback=True)
            if result.ok or result.reason != SINGULAR:
                break
        if not result.ok:
            raise LocateError(f"trial point at s={s!r} not corrected: {result.reason}")
        if norm(result.x - point) > JUMP * (s_b - s_a):
            raise LocateError(f"trial point at s={s!r} moved {norm(result.x - point)!r}"
                              " from its prediction: it may have jumped to another branch")
        if result.tangent is not None and float(result.tangent @ border) < RELIABLE:
            if not _near_branch_point(result.det, start.det, end.det):
                # a regular point whose tangent the Hermite arc misses by that much: the
                # step is too long for its arc (a sharp turn); the tangent of the arc would
                # place a fold where the curve has none
                raise LocateError(
                    f"the tangent at the trial point s={s!r} is "
                    f"{math.acos(max(-1.0, min(1.0, float(result.tangent @ border)))):.3g} rad "
                    "from the Hermite arc's: the step is too long to locate in")
            # next to a branch point the computed null vector is noise; the
            # interpolated tangent is the branch's tangent
            result.tangent = border
        elif result.tangent is not None:
            nodes.insert(k, (s, result.x, result.tangent))
        trials[s] = result
        value = float(function(result))
        if not math.isfinite(value):
            raise EventNotFinite(f"the located function is {value!r} at s={s!r}, "
                                 f"x={evaluator.problem.describe(result.x)}")
        values[s] = value
        return value

    beside = _beside_start(evaluate, start.s, f_start, max(options.event_tol, BESIDE * h))
    s, _, width = _brent(beside, start.s, f_start, end.s, f_end, options.event_tol)
    if s == start.s:
        return Located(s, None, width, start)
    if s == end.s:
        return Located(s, None, width, end)
    result = trials[s]
    if result.tangent is None:
        _, derivative = hermite(start.x, start.tangent, end.x, end.tangent, h, s - start.s)
        result.tangent, result.det = tangent_at(evaluator, result.x, derivative)
        if result.tangent is None:
            raise LocateError(f"no tangent at the located point s={s!r}")
    # the bracket is narrow, but is the function small there? Next to a singular point the
    # corrected trials may jump, and the bracket closes on the jump, not on a zero: the
    # distance the value leaves, at the step's mean slope, is then the accuracy
    slope = (abs(f_start) + abs(f_end)) / abs(h)
    miss = abs(values[s]) / slope if slope > 0.0 else math.inf
    return Located(s, result, max(width, miss), None)


def _beside_start(evaluate: Callable[[float], float], start: float, f_start: float,
                  reach: float) -> Callable[[float], float]:
    """``evaluate``, but ``f_start`` for an exact 0 within ``reach`` of a zero at ``start``.

    A zero at the bracket's start is passed as a tiny value (it belongs to the interval
    before, or is the curve's own start, e.g. a branch point whose branch tangent has
    ``t_i = 0``): a trial a hair beside it can round to exactly 0 too, which is that same zero,
    not the crossing inside the bracket (Brent would stop there, and miss a fold 0.01 on).
    """
    if abs(f_start) != _TINY:
        return evaluate

    def beside(s: float) -> float:
        value = evaluate(s)
        return f_start if value == 0.0 and s - start <= reach else value

    return beside


def _brent(f, a: float, fa: float, b: float, fb: float, xtol: float,
           max_iterations: int = 100) -> tuple[float, float, float]:
    """Brent's root finder on a bracket; returns ``(root, f(root), bracket width)``.

    Raises
    ------
    LocateError
        If the bracket is not below ``xtol`` after ``max_iterations``.
    """
    c, fc = a, fa
    d = e = b - a
    for _ in range(max_iterations):
        if (fb > 0) == (fc > 0) and fb != 0:
            c, fc = a, fa
            d = e = b - a
        if abs(fc) < abs(fb):
            a, fa = b, fb
            b, fb = c, fc
            c, fc = a, fa
        tol1 = 2.0 * _EPS * abs(b) + 0.5 * xtol
        m = 0.5 * (c - b)
        if fb == 0.0:
            return b, fb, 0.0
        if abs(m) <= tol1:
            return b, fb, abs(c - b)
        if abs(e) >= tol1 and abs(fa) > abs(fb):
            s = fb / fa
            if a == c:
                p = 2.0 * m * s
                q = 1.0 - s
            else:
                q = fa / fc
                r = fb / fc
                p = s * (2.0 * m * q * (q - r) - (b - a) * (r - 1.0))
                q = (q - 1.0) * (r - 1.0) * (s - 1.0)
            if p > 0:
                q = -q
            else:
                p = -p
            if 2.0 * p < min(3.0 * m * q - abs(tol1 * q), abs(e * q)):
                e = d
                d = p / q
            else:
                d = e = m
        else:
            d = e = m
        a, fa = b, fb
        b = b + d if abs(d) > tol1 else b + math.copysign(tol1, m)
        fb = f(b)
    raise LocateError(f"Brent's method did not narrow the bracket to {xtol:g} in "
                      f"{max_iterations} iterations (width {abs(c - b):.3g})")


def refine_branch_point(
    evaluator: Evaluator,
    options: Options,
    located: Located,
    start,
    end,
) -> Located:
    """Refine a branch point located by :func:`locate_zero` beyond ``sqrt(eps)``.

    Parameters
    ----------
    evaluator : Evaluator
        Counting evaluator of the problem.
    options : Options
        Tolerances.
    located : Located
        The zero of ``det [H'; b^T]`` found with corrected trial points.
    start, end : object with ``x``, ``s``, ``tangent``
        The accepted points of the step.

    Returns
    -------
    Located
        The refined branch point, or ``located`` if the refinement does not
        bracket the zero.

    Notes
    -----
    Next to a branch point the bordered matrix has a smallest singular value
    ``sigma ~ |s - s*|``, so corrected trial points carry rounding errors
    ``eps / sigma`` and the located point is only accurate to about
    ``sqrt(eps)``. The branch itself is smooth through the branch point, so two
    nodes ``d = 3e-4 (1 + max|x|)`` on either side (where ``eps / sigma`` is
    negligible) are corrected, and the zero of
    ``det [H'(p(s)); p'(s)^T]`` is found by Brent's method on their cubic
    Hermite arc ``p`` without further correction: ``p`` is accurate to
    ``O(d^4)`` and the determinant is smooth, so both the arclength and the
    point are accurate to about ``event_tol`` (``d`` balances the Hermite
    error ``d^4`` against the rounding ``eps / d`` at the nodes). A final
    Gauss-Newton step of minimal norm, blind to the near null space, removes
    the residual left by the arc.
    """
    s_star = located.s
    # within the bracket, which holds this zero alone (a second branch point close by, as
    # where two meet, would otherwise be inside the nodes and cancel this one's sign change)
    distance = min(3e-4 * (1.0 + max_abs(cast(Correction, located.correction).x)),
                   0.5 * (s_star - start.s), 0.5 * (end.s - s_star))
    nodes = []
    for s in (s_star - distance, s_star + distance):
        h = end.s - start.s
        point, derivative = hermite(start.x, start.tangent, end.x, end.tangent, h, s - start.s)
        border = derivative / norm(derivative)
        node = correct(evaluator, point, border, options.locate_newton,
                       max_correction=JUMP * distance, accept_fallback=True)
        if not node.ok:
            return located
        nodes.append((s, node.x, node.tangent))
    (s_a, x_a, t_a), (s_b, x_b, t_b) = nodes
    width = s_b - s_a

    def on_arc(s: float):
        point, derivative = hermite(x_a, t_a, x_b, t_b, width, s - s_a)
        return point, derivative / norm(derivative)

    def determinant(s: float) -> float:
        point, border = on_arc(s)
        jacobian = evaluator.jacobian(point)
        factors = factor_bordered(jacobian, border) if all_finite(jacobian) else None
        if factors is None:
            return 0.0
        return lu_determinant(*factors)

    f_a, f_b = determinant(s_a), determinant(s_b)
    if not f_a * f_b < 0:
        return located
    s, _, accuracy = _brent(determinant, s_a, f_a, s_b, f_b, options.event_tol)
    point, border = on_arc(s)
    residual = evaluator.residual(point)
    rnorm = max_abs(residual)
    for _ in range(3):
        if rnorm <= 1e-3 * options.tol:
            break
        # Gauss-Newton steps of minimal norm that ignore the (near) null space
        # of the rank-deficient H': they remove the O(d^4) residual of the arc
        # without sliding along either branch
        jacobian = evaluator.jacobian(point)
        step = np.linalg.lstsq(jacobian, -residual, rcond=1e-8)[0]
        trial = point + step
        trial_residual = evaluator.residual(trial)
        trial_norm = max_abs(trial_residual)
        if not trial_norm < rnorm:
            break
        point, residual, rnorm = trial, trial_residual, trial_norm
    if not rnorm <= options.tol:
        return located
    refined = Correction(True, "", point, border, 0.0, rnorm, 0, 0.0, 0.0)
    return Located(s, refined, accuracy, None)
