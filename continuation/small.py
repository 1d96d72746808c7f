"""Norms and checks of tiny vectors without the overhead of general numpy calls.

The engine's systems have a handful of unknowns. On such arrays the cost of a
numpy reduction (``np.abs(v).max()``, ``np.isfinite(a).all()``,
``np.linalg.norm(v)``) is the call overhead of about a microsecond, several
times the arithmetic; these helpers do the same arithmetic on Python floats
(``ndarray.tolist()``), which is 3-5 times faster below about 20 entries.
They are used on the hot path of the corrector and the tracker only; the
LU factorisations stay with LAPACK (``dgetrf``/``dgetrs``), whose direct
calls cost well under a microsecond for a 4 x 4 matrix.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["all_finite", "max_abs", "norm"]


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
    """Euclidean norm of a 1-D array."""
    return math.sqrt(float(v @ v))
