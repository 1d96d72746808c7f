"""Newton corrector on the Keller pseudo-arclength (bordered) system, and the tangent at a point."""

from __future__ import annotations

import math

import numpy as np

from .linalg import all_finite, factor_bordered, lu_determinant, lu_solve, max_abs, norm
from .options import Newton
from .problem import Evaluator

__all__ = ["Correction", "correct", "tangent_at"]

#: reasons a correction fails, used in log and status messages
NON_FINITE = "non-finite residual or Jacobian"
SINGULAR = "singular bordered Jacobian"
DIVERGING = "Newton corrections not contracting"
NO_CONVERGENCE = "no convergence within max_newton iterations"
TOO_FAR = "Newton correction longer than max_correction"

#: a chord step (old factors, no new Jacobian) is taken while it shrinks the
#: correction at least this much; otherwise the Jacobian is re-evaluated
CHORD_RATE = 0.1


class Correction:
    """Outcome of one corrector call (internal, plain slots object for speed).

    Attributes
    ----------
    ok : bool
        Whether Newton converged.
    reason : str
        Why it failed (empty when ``ok``).
    x : ndarray, shape (n + 1,)
        Last iterate (the converged point when ``ok``).
    tangent : ndarray or None
        Unit tangent at ``x`` oriented with the border row (``None`` when not
        requested and Newton converged without a Jacobian at ``x``).
    det : float
        ``det [H'(x); t^T]`` for the oriented tangent (0 when unknown).
    residual : float
        ``max |H(x)|``.
    iterations : int
        Newton steps taken from the prediction.
    first_correction : float
        2-norm of the first Newton correction (distance predictor-curve).
    contraction : float
        ``|dx_1| / |dx_0|``, the contraction rate of the first two corrections.
    border_det : float
        ``det [H'(x); b^T]`` for the border row ``b`` (0 when unknown); same
        sign as ``det``, and well defined even where the tangent is not (at a
        branch point it vanishes).
    jacobian : ndarray or None
        ``H'(x)`` where the tangent was computed from it (else ``None``).
    remaining : float
        2-norm of the Newton correction at the accepted ``x``, computed and not applied:
        the estimate of its distance to the curve (0 when unknown).
    """

    __slots__ = (
        "border_det",
        "contraction",
        "det",
        "first_correction",
        "iterations",
        "jacobian",
        "ok",
        "reason",
        "remaining",
        "residual",
        "tangent",
        "x",
    )

    def __init__(self, ok, reason, x, tangent, det, residual, iterations,
                 first_correction, contraction, border_det=0.0):
        self.ok = ok
        self.border_det = border_det
        self.reason = reason
        self.x = x
        self.tangent = tangent
        self.det = det
        self.residual = residual
        self.iterations = iterations
        self.first_correction = first_correction
        self.contraction = contraction
        self.jacobian = None
        self.remaining = 0.0


def correct(
    evaluator: Evaluator,
    x_pred: np.ndarray,
    border: np.ndarray,
    newton: Newton,
    *,
    max_correction: float = math.inf,
    target: float | None = None,
    need_tangent: bool = True,
    residual: np.ndarray | None = None,
    jacobian: np.ndarray | None = None,
    accept_fallback: bool = False,
) -> Correction:
    """Correct a predicted point onto the curve by Newton's method.

    Parameters
    ----------
    evaluator : Evaluator
        Counting evaluator of the problem.
    x_pred : ndarray, shape (n + 1,)
        Predicted point, the first iterate.
    border : ndarray, shape (n + 1,)
        Border row ``b``; the corrected point satisfies ``b^T x = target``.
    newton : Newton
        Tolerances ``tol`` (of ``max |H|``) and ``xtol`` (of ``max |dx| / (1 + max |x|)``),
        the most iterations, and the largest accepted ratio of consecutive corrections
        while ``|dx|`` is above its tolerance.
    max_correction : float, optional
        Largest accepted 2-norm of a correction; a longer one is not applied
        (the iterate is returned if its residual is within ``tol``, else the
        correction fails), so that Newton cannot slide along a nearly singular
        direction to another branch.
    target : float or None, optional
        Right-hand side of the border equation; ``None`` means ``b^T x_pred``
        (the hyperplane through the prediction).
    need_tangent : bool, optional
        Whether the tangent at the converged point is needed. If not, a
        converged iterate is accepted on its residual and the simplified
        Newton correction with the previous factorisation, saving a Jacobian.
    residual, jacobian : ndarray or None, optional
        ``H(x_pred)`` and ``H'(x_pred)`` if already evaluated.
    accept_fallback : bool, optional
        If a later step fails (diverges, meets a singular matrix or a
        non-finite value), return the last iterate with ``max |H| <= tol``
        even though its Newton correction was above ``xtol``. Only the
        locators ask for it, on points they check themselves: next to a branch
        point the bordered matrix is nearly singular and the corrections stall
        at the rounding level ``eps / sigma_min`` above ``xtol``, or blow up
        from a point that already solves the equations. Never for curve points:
        where ``H'`` is small (a cusp), ``|H| <= tol`` holds far from the curve
        and only a small correction shows that a point is on it.

    Returns
    -------
    Correction

    Notes
    -----

    Each step solves Keller's bordered system [1]_

    .. math::

        \\begin{pmatrix} H'(x_k) \\\\ b^T \\end{pmatrix} \\Delta x_k
        = -\\begin{pmatrix} H(x_k) \\\\ b^T x_k - \\text{target} \\end{pmatrix},

    and, with the same LU factors, :math:`[H'; b^T] v = e_{n+1}`, whose
    normalisation is the tangent ``t = v / |v|`` oriented so that
    ``b^T t > 0`` (Allgower & Georg, sec. 2.1 and 3.4). The determinant
    ``det [H'; t^T] = |v| det [H'; b^T]`` follows without extra work; its sign
    changes at simple branch points, not at folds (Allgower & Georg,
    Theorem 8.1.14). After a full step, the next one is a chord step with the
    same factors (no new Jacobian) as long as it shrinks the correction at
    least ``CHORD_RATE``-fold (Deuflhard, *Newton Methods for Nonlinear
    Problems*, 2004, sec. 2.1: simplified Newton); otherwise the Jacobian is
    re-evaluated. When the tangent is needed, a point is accepted only after a
    full step at it (a fresh Jacobian), so the returned tangent and
    determinant belong to the returned point. The iterate is accepted when its
    residual and the next correction are below tolerance; the correction is
    not applied, so the returned point's residual is the one checked.

    References
    ----------
    .. [1] H. B. Keller, "Numerical solution of bifurcation and nonlinear
       eigenvalue problems", in *Applications of Bifurcation Theory*,
       Academic Press, 1977, pp. 359-384.
    """
    # kept whole: the hot path of every step, its iteration state held in locals for speed
    n1 = x_pred.size
    if target is None:
        target = float(border @ x_pred)
    tol, xtol, max_newton = newton.tol, newton.xtol, newton.max_iterations
    x = x_pred
    H = evaluator.residual(x) if residual is None else residual
    if not all_finite(H):
        return Correction(False, NON_FINITE, x, None, 0.0, math.inf, 0, 0.0, 0.0)
    J: np.ndarray | None = evaluator.jacobian(x) if jacobian is None else jacobian
    rhs = np.empty(n1)
    first = 0.0
    contraction = 0.0
    previous = math.inf
    factors = None
    # the last iterate with max|H| <= tol: the answer if a later step fails
    fallback: Correction | None = None

    def failure(reason, rnorm, k, rate=None):
        if fallback is not None and accept_fallback:
            return fallback
        return Correction(False, reason, x, None, 0.0, rnorm, k, first,
                          contraction if rate is None else rate)

    for k in range(max_newton + 1):
        rnorm = max_abs(H)
        if not rnorm < math.inf:
            return failure(NON_FINITE, math.inf, k)
        scale = xtol * (1.0 + max_abs(x))
        if J is None:
            # Chord step with the factors of an earlier iterate (Deuflhard's
            # simplified Newton correction): it is taken while it contracts at
            # least CHORD_RATE-fold, and it also estimates the distance to the curve
            dx = _solve(factors, rhs, H, border, target, x)
            dnorm = max_abs(dx)
            converged = rnorm <= tol and dnorm <= scale
            if converged and not need_tangent:
                contraction = contraction or dnorm / max(first, 1e-300)
                return Correction(True, "", x, None, 0.0, rnorm, k, first, contraction)
            if not converged and dnorm <= CHORD_RATE * previous and k < max_newton:
                if k == 1:
                    contraction = dnorm / max(previous, 1e-300)
                if norm(dx) > max_correction:
                    return failure(TOO_FAR, rnorm, k)
                previous = dnorm
                x = x + dx
                H = evaluator.residual(x)
                continue
            J = evaluator.jacobian(x)
        if not all_finite(J):
            return failure(NON_FINITE, rnorm, k)
        factors = factor_bordered(J, border)
        if factors is None:
            return failure(SINGULAR, rnorm, k)
        dx = _solve(factors, rhs, H, border, target, x)
        dnorm = max_abs(dx)
        if not dnorm < math.inf:
            return failure(SINGULAR, rnorm, k)
        small = dnorm <= scale
        length = norm(dx)
        if k == 0:
            first = length
        elif k == 1:
            contraction = dnorm / max(previous, 1e-300)
        if rnorm <= tol and (small or accept_fallback):
            # (the tangent of an iterate that is not accepted is only needed as a fallback; one
            # that would be singular there no longer ends the correction early)
            within = _with_tangent(factors, x, rnorm, k, first, contraction)
            if within is None:
                return failure(SINGULAR, rnorm, k)
            within.jacobian = J
            within.remaining = length
            if small:
                return within
            fallback = within
        if length > max_correction:
            return failure(TOO_FAR, rnorm, k)
        if k > 0 and not small and dnorm > newton.max_contraction * previous:
            return failure(DIVERGING, rnorm, k, dnorm / max(previous, 1e-300))
        if k == max_newton:
            break
        previous = dnorm
        x = x + dx
        H = evaluator.residual(x)
        J = None
    return failure(NO_CONVERGENCE, rnorm, max_newton)


def _solve(factors, rhs: np.ndarray, H: np.ndarray, border: np.ndarray, target: float,
           x: np.ndarray) -> np.ndarray:
    """The Newton correction ``dx`` of the bordered system at ``x``."""
    n = rhs.size - 1
    np.negative(H, out=rhs[:n])
    rhs[n] = target - float(border @ x)
    return lu_solve(factors, rhs)


def _with_tangent(factors, x, rnorm, k, first, contraction) -> Correction | None:
    """A converged correction with the tangent and determinant from the bordered factors;
    ``None`` if the tangent is not finite (a numerically singular bordered matrix)."""
    unit = np.zeros(x.size)
    unit[-1] = 1.0
    v = lu_solve(factors, unit)
    vnorm = norm(v)
    if not 0.0 < vnorm < math.inf:
        return None
    border_det = lu_determinant(*factors)
    return Correction(True, "", x, v / vnorm, vnorm * border_det, rnorm, k, first, contraction,
                      border_det)


def tangent_at(evaluator: Evaluator, x: np.ndarray, border: np.ndarray):
    """Return the unit tangent at ``x`` oriented with ``border``, and its determinant.

    Parameters
    ----------
    evaluator : Evaluator
        Counting evaluator (one Jacobian evaluation).
    x : ndarray, shape (n + 1,)
        A point on the curve.
    border : ndarray, shape (n + 1,)
        Orientation reference, ``border^T t > 0``.

    Returns
    -------
    tangent : ndarray, shape (n + 1,) or None
        ``None`` if ``[H'(x); border^T]`` is singular.
    det : float
        ``det [H'(x); t^T]``.
    """
    J = evaluator.jacobian(x)
    if not all_finite(J):
        return None, 0.0
    factors = factor_bordered(J, border)
    if factors is None:
        return None, 0.0
    rhs = np.zeros(x.size)
    rhs[-1] = 1.0
    v = lu_solve(factors, rhs)
    vnorm = norm(v)
    if not 0 < vnorm < math.inf:
        return None, 0.0
    return v / vnorm, vnorm * lu_determinant(*factors)
