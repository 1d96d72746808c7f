"""Bracketed roots of many scalar equations at once, with numpy alone.

The point solver needs one root per point of a bracketing interval. scipy has it
(``scipy.optimize.elementwise.find_root``), but importing ``scipy.optimize`` takes longer than
everything else ``groove solve`` does, so this module implements the same algorithm,
Chandrupatla's, with the same tolerances and termination rules.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

__all__ = ["chandrupatla"]

#: More iterations than bisection needs to close any bracket of doubles (about 2100).
_MAX_ITERATIONS = 2100


def chandrupatla(f: Callable, lo, hi, args: tuple = (), xatol: float = 0.0,
                 xrtol: float = 4.0 * np.finfo(float).eps) -> np.ndarray:
    r"""Roots of ``f(x, *args) = 0``, one in each bracket ``[lo, hi]``.

    Parameters
    ----------
    f : callable
        ``f(x, *args)`` elementwise: 1-d arrays in, one value per element out.
    lo, hi : array_like, shape (m,)
        The brackets; ``f(lo)`` and ``f(hi)`` must differ in sign (or one be zero).
    args : tuple of ndarray, each of shape (m,)
        Extra arguments of ``f``, one value per bracket.
    xatol, xrtol : float
        The bracket ``[x1, x2]`` is closed when ``|x2 - x1| < |x| xrtol + xatol``, with ``x`` the
        end with the smaller ``|f|``; give ``xatol > 0`` for roots that may be 0.

    Returns
    -------
    ndarray, shape (m,)
        The end of the final bracket with the smaller ``|f|`` (an exact zero as soon as one is
        hit); NaN where the bracket does not change sign, ``f`` is NaN at both ends, or the
        iterations run out.

    Notes
    -----
    Chandrupatla (1997), "A new hybrid quadratic/bisection algorithm for finding the zero of a
    nonlinear function without using derivatives", Adv. Eng. Softw. 28, 145-149: inverse
    quadratic interpolation through the last three points when it is safe (the criterion
    :math:`1 - \sqrt{1 - \xi} < \phi < \sqrt{\xi}`), bisection otherwise, and each new point
    kept at least half the tolerance inside the bracket. Termination as in scipy's
    ``elementwise.find_root`` with ``fatol = frtol = 0``.
    """
    x1, x2 = (np.array(end, dtype=float).ravel() for end in np.broadcast_arrays(lo, hi))
    args = tuple(np.asarray(a, dtype=float).ravel() for a in args)
    f1, f2 = f(x1, *args), f(x2, *args)
    root = np.full(x1.shape, np.nan)
    active = np.arange(x1.size)
    t = np.full(x1.shape, 0.5)
    x3 = f3 = None
    for _ in range(_MAX_ITERATIONS + 1):
        stop, xmin, tol, converged = _terminated(x1, f1, x2, f2, xatol, xrtol)
        root[active[converged]] = xmin[converged]
        keep = ~stop
        active, x1, f1, x2, f2, t, tol = (a[keep] for a in (active, x1, f1, x2, f2, t, tol))
        args = tuple(a[keep] for a in args)
        if not active.size:
            break
        if x3 is not None and f3 is not None:
            t = _step_fraction(x1, f1, x2, f2, x3[keep], f3[keep], tol)
        x = x1 + t * (x2 - x1)
        fx = f(x, *args)
        same = np.sign(fx) == np.sign(f1)
        x3, f3 = np.where(same, x1, x2), np.where(same, f1, f2)
        x2, f2 = np.where(same, x2, x1), np.where(same, f2, f1)
        x1, f1 = x, fx
    return root


def _terminated(x1, f1, x2, f2, xatol: float, xrtol: float):
    """Which brackets stop, the better end of each, its tolerance, and which stop converged."""
    smaller = np.abs(f1) < np.abs(f2)
    xmin, fmin = np.where(smaller, x1, x2), np.where(smaller, f1, f2)
    zero = fmin == 0.0
    lost = (np.sign(f1) == np.sign(f2)) & ~zero
    broken = (~(np.isfinite(x1) & np.isfinite(x2)) | (np.isnan(f1) & np.isnan(f2))) & ~zero
    tol = np.abs(xmin) * xrtol + xatol
    closed = np.abs(x2 - x1) < tol
    converged = zero | (closed & ~lost & ~broken)
    return zero | lost | broken | closed, xmin, tol, converged


def _step_fraction(x1, f1, x2, f2, x3, f3, tol):
    """Where the next point goes, as a fraction of ``[x1, x2]`` (Chandrupatla's Eq. 1)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        xi = (x1 - x2) / (x3 - x2)
        phi = (f1 - f2) / (f3 - f2)
        alpha = (x3 - x1) / (x2 - x1)
        quadratic = ((1.0 - np.sqrt(1.0 - xi)) < phi) & (phi < np.sqrt(xi))
        t = np.where(quadratic,
                     f1 / (f1 - f2) * f3 / (f3 - f2) - alpha * f1 / (f3 - f1) * f2 / (f2 - f3),
                     0.5)
        limit = 0.5 * tol / np.abs(x2 - x1)
    return np.clip(t, limit, 1.0 - limit)
