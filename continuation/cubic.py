"""Cubic models of a scalar function on an interval, and where they may hide zeros.

A function ``f`` along a piece of curve ``u in [0, 1]`` is modelled by the cubic with its
values and slopes at the ends (:func:`cubic`, power coefficients); :func:`split_point` says
where the model allows zeros the end values do not show, :func:`samples_disagree` whether
two values of ``f`` inside the interval show the model cannot be trusted with its zeros.
Used by :class:`continuation.scan.StepScan`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

__all__ = [
    "APPROACH",
    "CLEAR",
    "MODEL_TOL",
    "NEAR_ZERO",
    "SAMPLES",
    "SPLIT_MARGIN",
    "ZERO_COUNT_GRID",
    "bounded_away",
    "critical_points",
    "cubic",
    "cubic_derivative",
    "cubic_value",
    "error_term",
    "same_sign",
    "samples_disagree",
    "sign_changes",
    "split_point",
    ]

#: a model extremum this close to zero, relative to the end values, is checked by a node
APPROACH = 0.5

#: a function is clear of zero on a step when its cubic model provably stays above this
#: fraction of its smaller end value (a margin above ``APPROACH``, so rounding cannot matter)
CLEAR = APPROACH + 0.1 * (1.0 - APPROACH)

#: a split point is kept this far (as a fraction) from the ends of its interval
SPLIT_MARGIN = 0.01

#: where inside each interval an event is compared with its model (fractions of the width)
SAMPLES = (1.0 / 3.0, 2.0 / 3.0)

#: points of the grid on which the zeros of an event's model and of the model with its
#: error term are counted (:func:`samples_disagree`)
ZERO_COUNT_GRID = 64

#: an event's sample further than this fraction of the model's largest value from the
#: model marks the model as inaccurate (:func:`samples_disagree`)
MODEL_TOL = 0.1

#: ... and matters where the model comes closer to zero than this many times the error term
NEAR_ZERO = 4.0


def same_sign(f_a: float, f_b: float) -> bool:
    """Whether two end values are both positive or both negative (neither zero)."""
    return (f_a > 0.0 and f_b > 0.0) or (f_a < 0.0 and f_b < 0.0)


def bounded_away(f_a: float, f_b: float, m_a: float, m_b: float, width: float) -> bool:
    """Whether the cubic Hermite model with end values ``f_a, f_b`` of one sign and end slopes
    ``m_a, m_b`` (per unit arclength, over ``width``) provably stays above :data:`CLEAR` times
    the smaller end value.

    The model is ``P = f_a h00 + f_b h01 + m_a h10 + m_b h11`` with ``h00 + h01 = 1``,
    ``h00, h01 >= 0`` and ``|h10|, |h11| <= 4/27`` on ``[0, 1]``, so for end values of one sign
    ``|P| >= min(|f_a|, |f_b|) - (4/27) width (|m_a| + |m_b|)``.
    """
    return (4.0 / 27.0) * width * (abs(m_a) + abs(m_b)) <= (1.0 - CLEAR) * min(abs(f_a), abs(f_b))


def cubic(f0: float, m0: float, f1: float, m1: float) -> tuple[float, float, float, float]:
    """Power coefficients on ``u in [0, 1]`` of the cubic with ``P(0), P'(0), P(1), P'(1)``."""
    return (f0, m0, 3.0 * (f1 - f0) - 2.0 * m0 - m1, 2.0 * (f0 - f1) + m0 + m1)


def cubic_value(c, u):
    """``P(u)`` of the power coefficients ``c``, for a float or an array of ``u``."""
    return c[0] + u * (c[1] + u * (c[2] + u * c[3]))


def cubic_derivative(c, u: float) -> float:
    return c[1] + u * (2.0 * c[2] + 3.0 * u * c[3])


def critical_points(c) -> list[float]:
    """Zeros of ``P'(u) = c1 + 2 c2 u + 3 c3 u^2`` in ``(0, 1)``, in order."""
    qa, qb, qc = 3.0 * c[3], 2.0 * c[2], c[1]
    scale = abs(qb) + abs(qc)
    if abs(qa) <= 1e-14 * scale or qa == 0.0:
        roots = [-qc / qb] if qb != 0.0 else []
    else:
        disc = qb * qb - 4.0 * qa * qc
        if disc < 0.0:
            return []
        q = -0.5 * (qb + math.copysign(math.sqrt(disc), qb))
        roots = [q / qa] + ([qc / q] if q != 0.0 else [])
    return sorted(u for u in roots if 0.0 < u < 1.0)


def sign_changes(values: Sequence[float]) -> int:
    signs = [v > 0.0 for v in values if v != 0.0]
    return sum(1 for p, q in zip(signs, signs[1:], strict=False) if p != q)


def samples_disagree(c, deltas: tuple[float, float], f_lo: float, f_hi: float) -> bool:
    """Whether an event's values inside an interval show that its cubic model ``P`` there
    cannot be trusted with the event's zeros.

    ``deltas`` are the event's values at ``u = 1/3`` and ``u = 2/3`` (:data:`SAMPLES`) less
    the model's. The error of a cubic Hermite interpolant is ``f^(4)(xi) u^2 (1 - u)^2 / 24``
    (times the width to the fourth), so ``Q = P + u^2 (1 - u)^2 (alpha + beta u)``, which
    also matches the two values, is the model with its error term added. The model is not
    trusted where ``P`` and ``Q`` have different numbers of zeros in ``(0, 1)`` (counted on a
    grid of :data:`ZERO_COUNT_GRID` points, with the zero-adjusted end values ``f_lo``,
    ``f_hi``), or where a delta exceeds :data:`MODEL_TOL` times the model's largest value
    while the model comes within :data:`NEAR_ZERO` times ``max |Q - P|`` of zero (an event
    that changes faster than the interval, seen at two points: elsewhere it may be further
    off still). A model that keeps its sign further than that from zero is trusted.
    """
    alpha, beta = error_term(deltas)
    if (alpha == 0.0 and beta == 0.0) or not (math.isfinite(alpha) and math.isfinite(beta)):
        return False
    critical = [cubic_value(c, u) for u in critical_points(c)]
    values = [f_lo, *critical, f_hi]
    one_sign = all((v > 0.0) == (f_lo > 0.0) for v in values)
    nearest = min(map(abs, values)) if one_sign else 0.0
    if nearest > NEAR_ZERO * (abs(alpha) + abs(beta)) / 16.0:
        return False
    if max(map(abs, deltas)) > MODEL_TOL * max(map(abs, values)):
        return True
    u = np.linspace(0.0, 1.0, ZERO_COUNT_GRID + 1)[1:-1]
    p = cubic_value(c, u)
    q = p + (u * (1.0 - u)) ** 2 * (alpha + beta * u)
    return sign_changes([f_lo, *p.tolist(), f_hi]) != sign_changes([f_lo, *q.tolist(), f_hi])


def error_term(deltas: tuple[float, float]) -> tuple[float, float]:
    """``(alpha, beta)`` of ``E(u) = u^2 (1 - u)^2 (alpha + beta u)`` with ``E(1/3)``,
    ``E(2/3)`` equal to ``deltas`` (``u^2 (1 - u)^2 = 4/81`` at both), ``|E| <= (|alpha| +
    |beta|)/16`` on ``[0, 1]``."""
    d1, d2 = deltas
    return 20.25 * (2.0 * d1 - d2), 60.75 * (d2 - d1)


def split_point(c, f_lo: float, f_hi: float) -> float | None:
    """Where to look inside an interval whose model may hide zeros, else ``None``.

    The model ``P`` (with ``P(0) = f_lo``, ``P(1) = f_hi``, both nonzero) may hide
    zeros that the ends do not show when it changes sign more often than the ends
    do, or when it has an interior extremum that comes within ``APPROACH`` of zero
    relative to the smaller end value (the function turns towards zero and back).
    The split point is that extremum.
    """
    critical = critical_points(c)
    if not critical:
        return None
    values = [cubic_value(c, u) for u in critical]
    ends = 1 if (f_lo > 0.0) != (f_hi > 0.0) else 0
    nearest = min(range(len(critical)), key=lambda i: abs(values[i]))
    if sign_changes([f_lo, *values, f_hi]) > ends \
            or abs(values[nearest]) < APPROACH * min(abs(f_lo), abs(f_hi)):
        return min(1.0 - SPLIT_MARGIN, max(SPLIT_MARGIN, critical[nearest]))
    return None
