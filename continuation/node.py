"""A point of a traced curve with the derivatives along the curve that the scans need.

:class:`Node` carries a corrected point, its tangent and ``det [H'; t^T]``, and caches what a
step's scan (:mod:`continuation.scan`) computes there once: event slopes, the Jacobian a small
step along the tangent (:func:`bend`), the curvature ``dt/ds`` (:func:`curvature`) and the slope
of the determinant (:func:`det_slope`). Also the errors of locating special points.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from .errors import CallbackError, CallbackShapeError
from .events import Event
from .linalg import all_finite, factor_bordered, lu_determinant, lu_solve, max_abs
from .problem import Evaluator

__all__ = [
    "CURVATURE_STEP",
    "EventNotFinite",
    "LocateError",
    "Node",
    "StepUnresolved",
    "bend",
    "curvature",
    "det_slope",
    "event_value",
]

#: relative step of the forward difference of the Jacobian along the tangent (:func:`bend`)
CURVATURE_STEP = 1e-7


class LocateError(RuntimeError):
    """A special point was bracketed but could not be located (or a scan not resolved)."""


class StepUnresolved(LocateError):
    """The step does not follow one smooth curve (:meth:`StepScan.check_turn`): too long."""


class EventNotFinite(LocateError):
    """An event function (or its derivative along the curve) is not finite at a point."""


class Node:
    """A point of the curve with its tangent and the values the scan needs.

    Attributes
    ----------
    x, tangent : ndarray, shape (n + 1,)
    s : float
        Arclength parameter of the point (for nodes inside a step, that of the
        step's cubic Hermite arc).
    det : float
        ``det [H'(x); t^T]``.
    residual : float
        ``max |H(x)|``.
    iterations : int
        Newton steps that produced the point.
    events : list of float
        Event values ``g_j(x)``.
    slopes : list of float or None
        ``d g_j / ds`` along the curve, filled when first needed.
    turning : ndarray or None
        The curvature ``dt/ds``, filled when first needed (:func:`curvature`).
    jacobian : ndarray or None
        ``H'(x)``, if the corrector evaluated it there (it saves one in the curvature).
    bend : tuple or None
        ``(H'(x), H'(x + e t), e)``: the Jacobian a small step along the tangent, filled when
        first needed (:func:`bend`).
    det_slope : float or None
        ``d det [H'; t^T] / ds``, filled when first needed (:func:`det_slope`).
    """

    __slots__ = ("bend", "det", "det_slope", "events", "iterations", "jacobian", "residual", "s",
                 "slopes", "tangent", "turning", "x")

    def __init__(self, x, s, tangent, det, residual, iterations, events, jacobian=None):
        self.x = x
        self.s = s
        self.tangent = tangent
        self.det = det
        self.residual = residual
        self.iterations = iterations
        self.events = events
        self.slopes = None
        self.turning = None
        self.jacobian = jacobian
        self.bend = None
        self.det_slope = None


def event_value(event: Event, x: np.ndarray, describe: Callable[[np.ndarray], str]) -> float:
    """``event.function(x)`` as a float; a raised exception becomes a :class:`CallbackError`,
    a value that ``float`` refuses (an array, ``None``, a complex number) a
    :class:`CallbackShapeError`. (numpy's complex scalars ``float`` takes, with numpy's
    ``ComplexWarning``; checking every value for them would cost the hot path.)"""
    try:
        value = event.function(x)
    except Exception as exc:
        raise CallbackError(f"event '{event.name}' raised {type(exc).__name__}: {exc} at "
                            f"x={describe(x)}") from exc
    try:
        return float(value)
    except (TypeError, ValueError):
        pass
    if isinstance(value, np.ndarray) and value.shape != ():
        what = f"an array of shape {value.shape}"
    elif isinstance(value, complex):
        what = f"the complex number {value}"
    else:
        what = "None" if value is None else f"{value!r} (a {type(value).__name__})"
    raise CallbackShapeError(f"event '{event.name}' returned {what} at x={describe(x)}: an "
                             "event must return one real number")


def bend(evaluator: Evaluator, node: Node, length: float) -> tuple[np.ndarray, np.ndarray, float]:
    """``(H'(x), H'(x + e t), e)`` at a node, computed once, with the corrector's ``H'(x)``
    where the node has it: the forward differences along the tangent of :func:`curvature` and
    :func:`det_slope` (relative error about ``1e-7``, ample for the models and signs they serve).

    ``e = CURVATURE_STEP min(1 + max|x|, max(max|x|, 100 length))``: relative to the scale of
    ``x`` (``1 + max|x|``, the tolerances' own), unless the curve's steps (``length``, the
    step's width) show a curve much smaller than that near the origin, where an absolute
    ``1e-7`` would span a good part of it.
    """
    if node.bend is None:
        x, t = node.x, node.tangent
        jacobian = node.jacobian if node.jacobian is not None else evaluator.jacobian(x)
        size = max_abs(x)
        step = CURVATURE_STEP * min(1.0 + size, max(size, 100.0 * length))
        node.bend = (jacobian, evaluator.jacobian(x + step * t), step)
    return node.bend


def curvature(evaluator: Evaluator, node: Node, length: float) -> np.ndarray | None:
    """The curvature vector ``kappa = dt/ds`` at a node; ``None`` where ``[H'; t^T]`` is singular.

    ``[H'; t^T] kappa = [-H''[t, t]; 0]``, from differentiating ``H'(x(s)) t(s) = 0`` and
    ``t^T t = 1``; ``H''[t, t]`` is the forward difference ``(H'(x + e t) - H'(x)) t / e``
    (:func:`bend`: one Jacobian, or two where the corrector left none; ``length``: the step's
    width).
    """
    jacobian, shifted, step = bend(evaluator, node, length)
    t = node.tangent
    second = (shifted - jacobian) @ t / step
    factors = factor_bordered(jacobian, t)
    if factors is None:
        return None
    return lu_solve(factors, np.append(-second, 0.0))


def det_slope(evaluator: Evaluator, node: Node, length: float) -> float:
    """``d det M / ds`` at a node, ``M = [H'; t^T]`` (NaN where ``H'`` is not finite a step on).

    Jacobi's formula gives ``d det M / ds = det M tr(M^-1 dM/ds)`` with
    ``dM/ds = [H''[t, .]; kappa^T]``. The last column of ``M^-1`` is ``t`` itself
    (``H' t = 0``, ``t^T t = 1``) and ``t^T kappa = 0``, so the curvature drops out: the slope
    is that of ``det [H'(x + e t); t^T]`` with the row ``t`` held fixed, here its forward
    difference over :func:`bend`'s step (one Jacobian and one factorisation).
    """
    _, shifted, step = bend(evaluator, node, length)
    if not all_finite(shifted):
        return math.nan
    factors = factor_bordered(shifted, node.tangent)
    shifted_det = 0.0 if factors is None else lu_determinant(*factors)  # None: exactly singular
    return (shifted_det - node.det) / step
