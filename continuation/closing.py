"""Whether a step closes the curve: it passes through the start with the start's tangent."""

from __future__ import annotations

import math

import numpy as np

from .corrector import correct
from .node import Node
from .predictor import arc_length, hermite
from .run import Run

__all__ = ["ARC_CLOSE", "CLOSE_TOLERANCE", "closing_point"]

#: a closing point must lie this close (relative to 1 + max|x0|) to the start
CLOSE_TOLERANCE = 1e-6

#: at a singular start, the step's arc must pass this close to it (relative to the chord)
ARC_CLOSE = 1e-3


def closing_point(run: Run, start: Node, a: Node, b: Node) -> Node | None:
    """The start point, if the step ``a -> b`` passes through it with the same tangent.

    The step must cross the hyperplane through the start normal to its tangent
    in the positive direction; the curve point in that hyperplane, corrected
    from the Hermite arc, must then coincide with the start: within ``CLOSE_TOLERANCE``
    relative to ``1 + max|x0|``, or at a loose ``tol`` within twice the points' accuracy
    ``tol (1 + max|x0|)`` (the corrector's bound on its next correction: the start and the
    closing point are each that close to the curve), where a closed curve was traced round
    again unnoticed.
    """
    t0, x0 = start.tangent, start.x
    g_a = float(t0 @ (a.x - x0))
    g_b = float(t0 @ (b.x - x0))
    if not (g_a < 0.0 <= g_b) or float(t0 @ a.tangent) <= 0.0:
        return None
    chord = b.x - a.x
    tau = g_a / (g_a - g_b)
    if np.linalg.norm(a.x + tau * chord - x0) > np.linalg.norm(chord):
        return None
    h = b.s - a.s
    sigma = tau * h
    for _ in range(5):
        p, dp = hermite(a.x, a.tangent, b.x, b.tangent, h, sigma)
        slope = float(t0 @ dp)
        if slope <= 0:
            break
        sigma = min(h, max(0.0, sigma - float(t0 @ (p - x0)) / slope))
    p, _ = hermite(a.x, a.tangent, b.x, b.tangent, h, sigma)
    scale = CLOSE_TOLERANCE * (1.0 + float(np.max(np.abs(x0))))
    angle = math.acos(max(-1.0, min(1.0, float(t0 @ a.tangent))))
    if start.det == 0.0:
        # a singular start (a branch point): H' vanishes in a direction at x0, so no Newton
        # converges there to show that the curve is back; it is when the step's arc, whose
        # error is far below this bound, passes through the start with the start's tangent
        if float(np.linalg.norm(p - x0)) > max(scale, ARC_CLOSE * float(np.linalg.norm(chord))):
            return None
        return Node(x0.copy(), a.s + arc_length(x0 - a.x, angle), start.tangent, start.det,
                    start.residual, 0, start.events)
    p = p - t0 * float(t0 @ (p - x0))
    options = run.options
    correction = correct(run.evaluator, p, t0, options.newton, need_tangent=False)
    if not correction.ok:
        return None
    distance = float(np.max(np.abs(correction.x - x0)))
    if distance > max(scale, 2.0 * options.tol * (1.0 + float(np.max(np.abs(x0))))):
        return None
    return Node(x0.copy(), a.s + arc_length(x0 - a.x, angle), start.tangent, start.det,
                start.residual, correction.iterations, start.events)
