"""The algebraic bifurcation equation at a simple branch point: the tangents of its branches.

Used by :mod:`continuation.branching` (switching branches) and by the step scan, which checks
that a step past a branch point stayed on the branch it came along.
"""

from __future__ import annotations

import math

import numpy as np

from .problem import Evaluator

__all__ = ["BRANCH_POINT_RATIO", "branch_tangent_pair"]

_EPS = np.finfo(float).eps

#: largest smallest-singular-value ratio accepted at a branch point
BRANCH_POINT_RATIO = 1e-6

#: a ratio of the bifurcation form's eigenvalues below which their signs are checked against
#: the error of the differences (a second set with twice the step, and Richardson's
#: extrapolation of the two): a double root (a cusp, a touching of branches) has eigenvalues of
#: either sign at the level of that error
_IN_DOUBT = 1e-4


def branch_tangent_pair(evaluator: Evaluator, x: np.ndarray,
                        length: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The unit tangents (each up to sign) of the two branches through the branch point ``x``:
    the roots of the algebraic bifurcation equation (:func:`continuation.branch_tangents` has
    the equations); :class:`ValueError` if ``x`` is not a simple branch point.

    ``length``: a length scale of the curve (a step's width), where known: the differences'
    step ``eps^(1/3) max(1, max|x|)`` then shrinks to ``eps^(1/3) max(max|x|, 100 length)``
    for a curve much smaller than 1 near the origin.
    """
    J = evaluator.jacobian(x)
    n = J.shape[0]
    if J.shape != (n, x.size) or not np.isfinite(J).all():
        raise ValueError(f"jacobian(x_bp) must be finite of shape ({x.size - 1}, {x.size})")
    left, singular_values, right = np.linalg.svd(J, full_matrices=True)
    v1, v2 = right[n - 1], right[n]
    psi = left[:, n - 1]
    size = float(np.max(np.abs(x)))
    scale = max(1.0, size) if length is None else min(max(1.0, size), max(size, 100.0 * length))
    h = _EPS ** (1.0 / 3.0) * scale
    quadratic = _bifurcation_form(evaluator, x, psi, v1, v2, h)
    a, b, c = quadratic[0, 0], quadratic[0, 1], quadratic[1, 1]
    scale = singular_values[0] if n > 1 else float(np.max(np.abs(quadratic)))
    if not singular_values[n - 1] <= BRANCH_POINT_RATIO * scale:
        raise ValueError(
            f"x_bp is not a branch point: the Jacobian's smallest singular value "
            f"{singular_values[n - 1]:.3g} is not below {BRANCH_POINT_RATIO:g} x {scale:.3g}; "
            "locate it first with locate_branch_point or take it from Curve.special"
            "('branch_point')")
    eigenvalues, rotation = np.linalg.eigh(quadratic)
    noise = 0.0
    if min(-eigenvalues[0], eigenvalues[1]) < _IN_DOUBT * max(-eigenvalues[0], eigenvalues[1]):
        # two nearly equal roots: a real pair, or a double root split by the differences'
        # error? With twice the step the truncation error is 4 times as large: Richardson's
        # (4 Q(h) - Q(2h)) / 3 cancels it, and |Q(h) - Q(2h)| / 3 estimates what is left
        wide = _bifurcation_form(evaluator, x, psi, v1, v2, 2.0 * h)
        noise = float(np.max(np.abs(quadratic - wide))) / 3.0
        quadratic = (4.0 * quadratic - wide) / 3.0
        a, b, c = quadratic[0, 0], quadratic[0, 1], quadratic[1, 1]
        eigenvalues, rotation = np.linalg.eigh(quadratic)
    if not (eigenvalues[0] < -noise and eigenvalues[1] > noise):
        raise ValueError(
            "x_bp is not a simple branch point (or cannot be told from a double root): the "
            "algebraic bifurcation equation "
            f"a*alpha^2 + 2*b*alpha*beta + c*beta^2 = 0 has a={a:.3g}, b={b:.3g}, c={c:.3g}, "
            f"discriminant b^2 - a*c = {b * b - a * c:.3g} (must be > 0"
            + (f", with eigenvalues of [[a, b], [b, c]] beyond the differences' error "
               f"{noise:.3g})" if noise else ")"))
    tangents = []
    for sign in (1.0, -1.0):
        z = rotation @ np.array([math.sqrt(eigenvalues[1]), sign * math.sqrt(-eigenvalues[0])])
        t = z[0] * v1 + z[1] * v2
        tangents.append(t / np.linalg.norm(t))
    return tangents[0], tangents[1]


def _bifurcation_form(evaluator: Evaluator, x: np.ndarray, psi: np.ndarray, v1: np.ndarray,
                      v2: np.ndarray, h: float) -> np.ndarray:
    """``[[a, b], [b, c]]`` of the bifurcation equation from central differences of step ``h``
    of the Jacobian (error ``O(h^2) + O(eps |J| / h)``)."""
    d1 = (evaluator.jacobian(x + h * v1) - evaluator.jacobian(x - h * v1)) / (2.0 * h)
    d2 = (evaluator.jacobian(x + h * v2) - evaluator.jacobian(x - h * v2)) / (2.0 * h)
    b = 0.5 * float(psi @ d1 @ v2 + psi @ d2 @ v1)
    return np.array([[float(psi @ d1 @ v1), b], [b, float(psi @ d2 @ v2)]])
