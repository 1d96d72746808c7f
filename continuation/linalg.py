"""Small dense linear algebra of the engine: tiny-vector norms and the bordered system.

Norms and checks of tiny vectors without the overhead of general numpy calls:

The engine's systems have a handful of unknowns. On such arrays the cost of a
numpy reduction (``np.abs(v).max()``, ``np.isfinite(a).all()``,
``np.linalg.norm(v)``) is the call overhead of about a microsecond, several
times the arithmetic; these helpers do the same arithmetic on Python floats
(``ndarray.tolist()``), which is 3-5 times faster below about 20 entries.
They are used on the hot path of the corrector and the tracker.

The bordered matrix ``[H'(x); b^T]`` of Keller's pseudo-arclength system is
factored by LAPACK (``dgetrf``/``dgetrs`` called directly, well under a
microsecond for a 4 x 4 matrix); its determinant's sign orients tangents and
detects branch points.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.linalg.lapack import dgetrf, dgetrs

__all__ = [
    "all_finite",
    "factor_bordered",
    "lu_determinant",
    "lu_solve",
    "max_abs",
    "norm",
]


def max_abs(v: np.ndarray) -> float:
    """``max |v_i|`` (0 for an empty array); NaN if any entry is NaN."""
    largest = 0.0
    for value in v.tolist():
        value = abs(value)
        if not value <= largest:
            if value != value:
                return math.nan
            largest = value
    return largest


def all_finite(a: np.ndarray) -> bool:
    """Whether every entry of ``a`` (any shape) is finite.

    The sum of the entries is finite exactly when they all are, except when
    finite entries near the largest double overflow it; such values are
    treated as not finite, which for a residual or Jacobian is the safe side.
    """
    total = sum(a.ravel().tolist())
    return total - total == 0.0


def norm(v: np.ndarray) -> float:
    """Euclidean norm of a 1-D array, without overflow for entries up to the largest float."""
    return math.hypot(*v.tolist())


def factor_bordered(jacobian: np.ndarray, border: np.ndarray):
    """LU factors of the bordered matrix ``[J; border^T]`` (LAPACK ``dgetrf``).

    Returns ``(lu, piv)`` for :func:`lu_solve` and :func:`lu_determinant`, or ``None``
    if the matrix is exactly singular.
    """
    n = jacobian.shape[0]
    bordered = np.empty((n + 1, n + 1))
    bordered[:n] = jacobian
    bordered[n] = border
    lu, piv, info = dgetrf(bordered, overwrite_a=1)
    if info != 0:
        return None
    return lu, piv


def lu_determinant(lu: np.ndarray, piv: np.ndarray) -> float:
    """Determinant from an LU factorisation ``P A = L U`` (LAPACK pivots, 0-based)."""
    det = 1.0
    swaps = 0
    # on Python floats and ints: indexing numpy scalars one by one costs more than the product
    for i, (diagonal, pivot) in enumerate(zip(lu.diagonal().tolist(), piv.tolist(), strict=True)):
        det *= diagonal
        swaps += pivot != i
    return float(-det if swaps % 2 else det)


def lu_solve(factors, rhs: np.ndarray) -> np.ndarray:
    """Solve with the factors of :func:`factor_bordered` (one right-hand side).

    One right-hand side per LAPACK call: with two, OpenBLAS's threaded
    triangular solve costs milliseconds on a 4 x 4 system whenever a core is busy.
    """
    return dgetrs(factors[0], factors[1], rhs)[0]
