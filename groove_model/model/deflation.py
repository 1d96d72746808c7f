r"""Deflated no-roll torque of ``dr_no_roll``: a divided difference written once for any numbers.

With ``upsilon = 0`` the double-rolling torque is ``f(beta_L) - f(beta_R)``,
``f(beta) = sqrt(sin beta) cos beta``; it vanishes on the whole symmetric family
``beta_L = beta_R`` as well as on ``dr_no_roll``. Its divided difference

.. math:: g = \frac{f(\beta_L) - f(\beta_R)}{\beta_L - \beta_R}
            = \int_0^1 f'(\beta_R + t(\beta_L - \beta_R))\,dt

vanishes on ``dr_no_roll`` alone, which crosses the family where ``f' = 0`` (the branch point):
with ``g`` in place of the torque the branch point is a regular point (deflation, Allgower &
Georg sec. 8.3). ``g`` is the quotient where ``|beta_L - beta_R| >= 0.05`` and a 6-point
Gauss-Legendre quadrature of ``f'`` closer to the family, where the quotient would cancel; in
ball arithmetic, where the quotient would amplify the balls' width instead, the quadrature
is used up to ``|beta_L - beta_R| < 0.6``, with the fewest points (4 to 12, on one or two
panels) whose remainder is estimated below ``1e-13`` and the box's own width. All are exact
formulas for the same ``g`` where they are used (the quadrature's remainder, below rounding
in floats, is carried in balls).

The float quadrature is exact to rounding where both angles exceed about 0.3, which holds all
along ``dr_no_roll`` (``beta_L + beta_R = pi - 2 gamma >= pi - 2 arctan sqrt 2 = 1.23``); closer
to ``beta = 0`` its error grows (about 1e-10 at ``beta ~ 0.05``), where the ball version's
remainder says so.

Every function takes a numbers namespace ``m`` (:mod:`continuation.numbers`). In ball
arithmetic the quadrature carries its remainder (Gauss-Legendre with ``n`` points, Davis &
Rabinowitz, *Methods of Numerical Integration*, 2nd ed., eq. 2.7.12)

.. math:: \int_0^1 F - Q_n(F) = \frac{(n!)^4}{(2n+1)\,((2n)!)^3} F^{(2n)}(\xi),

with ``F^(2n)`` bounded by Cauchy's estimate: ``f`` is analytic on the strip
``0 < Re z < pi`` (there ``Re sin z > 0``) with ``|f(z)| <= cosh(Im z)^(3/2)``, so
``|f^(j)(z)| <= j! cosh(|Im z| + rho)^(3/2) / rho^j`` for a disc of radius ``rho`` inside the strip.
"""

from __future__ import annotations

import math
from fractions import Fraction

from continuation.numbers import balls

__all__ = ["deflated_torque", "f1", "f2"]

#: below this |beta_L - beta_R| the divided difference is a quadrature of f' (in floats)
DIVIDED_SWITCH = 0.05

#: the same in ball arithmetic, where the quotient would amplify the width of wide balls by
#: 1/d^2 (its derivatives) and the quadrature does not
BALL_SWITCH = 0.6

#: Gauss-Legendre nodes in floats (error O(d^12), below rounding where it is used)
FLOAT_NODES = 6

#: the ball quadratures, ``(nodes, panels)`` in order of cost: the first whose remainder is
#: estimated below :data:`BALL_TOLERANCE` is taken (the last, the most accurate, where none
#: is: below about 1e-13 along the boundaries, where both angles exceed about 0.6)
BALL_RULES = ((4, 1), (6, 1), (8, 1), (10, 1), (12, 1), (8, 2), (10, 2), (12, 2))

#: the remainder the ball quadrature is chosen for
BALL_TOLERANCE = 1e-13


def _gauss_constant(n: int) -> float:
    """``(n!)^4 / ((2n + 1) ((2n)!)^3)``: Gauss-Legendre error constant on [0, 1], rounded up."""
    exact = Fraction(math.factorial(n) ** 4, (2 * n + 1) * math.factorial(2 * n) ** 3)
    value = float(exact)
    return value if Fraction(value) >= exact else math.nextafter(value, math.inf)


def f1(beta, m):
    """``f'(beta)`` for ``f = sqrt(sin beta) cos beta``: ``cos^2/(2 sqrt sin) - sin^(3/2)``."""
    s, c = m.sin(beta), m.cos(beta)
    q = m.sqrt(s)
    return c * c / (2.0 * q) - s * q


def f2(beta, m):
    """``f''(beta) = -(5/2) cos(beta) q - cos(beta)^3 / (4 q^3)``, ``q = sqrt(sin beta)``."""
    s, c = m.sin(beta), m.cos(beta)
    q = m.sqrt(s)
    return -2.5 * c * q - c * c * c / (4.0 * q * s)


def _derivative_bound(order: int, real: tuple, imag: float) -> float:
    """Bound of ``|f^(order)|`` on points with real parts in ``real`` and ``|Im| <= imag``.

    Cauchy's estimate on the disc of radius ``rho = 0.9 margin`` (``margin`` the distance of
    ``real`` to ``{0, pi}``), evaluated in ball arithmetic and rounded up.
    """
    margin = min(real[0], math.pi - real[1])
    if not margin > 0.0:
        return math.inf
    arb = balls().arb
    rho = arb(0.9 * margin)
    c = (arb(imag) + rho).cosh()
    bound = arb(math.factorial(order)) * c * c.sqrt() / rho ** order
    return math.nextafter(float(bound.upper()), math.inf) if bound.is_finite() else math.inf


def _times_power(c: float, size: float, p: int) -> float:
    """``c size^p`` (``c, size >= 0``), never rounded down to 0 where it is positive: where
    ``size^p`` underflows, from logarithms (rounded up), at least the smallest float."""
    value = c * size ** p
    if value > 1e-290 or c == 0.0 or size == 0.0 or not math.isfinite(value):
        return value
    return max(math.exp(math.log(c) + p * math.log(size)) * (1.0 + 1e-10), 5e-324)


def _remainder_bound(weighted: bool, panels: int, n: int):
    """``bound(intervals, widen)`` of the ball quadrature's remainder for ``g`` (or the ``t``-
    and ``(1 - t)``-weighted integrals of ``f''`` in its Jacobian row): ``n`` nodes on each of
    ``P`` panels.

    ``intervals`` are ``(lo, hi)`` of ``beta_R`` and ``d``; over the complex polydisc of radius
    ``widen`` around them the quadrature nodes ``beta_R + t d`` have real parts within
    ``2 widen`` of the real hull and imaginary parts up to ``2 widen``. On a panel of length
    ``1/P``, ``F(t) = f'(beta_R + t d)`` has ``2n``-th derivative ``(d/P)^(2n) f^(2n+1)`` in
    the panel's own variable; weighted by ``t`` or ``1 - t`` it is at most
    ``(d/P)^(2n) |f^(2n+2)| + (2n/P) (d/P)^(2n-1) |f^(2n+1)|``. The panels' errors add up to
    ``P (1/P)`` times that, times the constant.
    """
    n2, gauss = 2 * n, _gauss_constant(n)

    def bound(intervals, widen: float) -> float:
        (r_lo, r_hi), (d_lo, d_hi) = intervals
        real = (min(r_lo, r_lo + d_lo) - 2.0 * widen, max(r_hi, r_hi + d_hi) + 2.0 * widen)
        size = (max(abs(d_lo), abs(d_hi)) + widen) / panels
        first = _derivative_bound(n2 + 1, real, 2.0 * widen)
        if weighted:
            second = _derivative_bound(n2 + 2, real, 2.0 * widen)
            value = gauss * (_times_power(second, size, n2)
                             + _times_power(n2 / panels * first, size, n2 - 1))
        else:
            value = gauss * _times_power(first, size, n2)
        return value * (1.0 + 1e-12)  # a few float roundings of positive terms

    return bound


#: the remainder bounds of g and of its Jacobian row, for each ball rule
_BOUNDS = {rule: (_remainder_bound(False, rule[1], rule[0]),
                  _remainder_bound(True, rule[1], rule[0])) for rule in BALL_RULES}

#: ``log(constant (2n + 1)!)`` of each rule's remainder, for :func:`_ball_rule`'s estimates
_LOG_FACTORS = {n: math.log(_gauss_constant(n)) + math.lgamma(2 * n + 2)
                for n in {n for n, _ in BALL_RULES}}


def _ball_rule(beta_R, d, m) -> tuple[int, int]:
    """The cheapest of :data:`BALL_RULES` whose remainder for ``g`` is estimated below
    :data:`BALL_TOLERANCE` and below the width (or rounding) of the balls ``beta_R`` and ``d``
    (so a thin box, at 53 bits or at more, is not widened by it), in floats, by the logarithm
    of the bound of :func:`_remainder_bound` at ``widen = 0``: an estimate only chooses the
    rule; its remainder is then bounded rigorously, whichever it is."""
    r_lo, r_hi = m.bounds(beta_R)
    d_lo, d_hi = m.bounds(d)
    margin = min(r_lo, r_lo + d_lo, math.pi - max(r_hi, r_hi + d_hi))
    size = max(abs(d_lo), abs(d_hi))
    if not margin > 0.0 or not size > 0.0:
        return BALL_RULES[-1] if not size == 0.0 else BALL_RULES[0]
    tolerance = min(BALL_TOLERANCE, max(m.resolution(beta_R), m.resolution(d)))
    rho = 0.9 * margin
    log_room = math.log(tolerance) - 1.5 * math.log(math.cosh(rho))
    for n, panels in BALL_RULES:
        if (_LOG_FACTORS[n] + 2 * n * math.log(size / panels)
                - (2 * n + 1) * math.log(rho)) < log_room:
            return n, panels
    return BALL_RULES[-1]


def deflated_torque(gamma, beta_L, q_L, b1, dq_L, jacobian, m):
    """The no-roll torque divided by ``beta_L - beta_R``, and its row (``dr_no_roll``, deflated).

    ``b1 = d beta_L / d var`` and ``dq_L = d q_L / d var`` for the chart variable ``var``.
    Returns ``(g, row)``; ``row`` is ``None`` if ``jacobian`` is false.
    """
    beta_R = m.pi - 2.0 * gamma - beta_L
    d = beta_L - beta_R
    if abs(d) >= (BALL_SWITCH if m.rigorous else DIVIDED_SWITCH):
        s_R, c_R = m.sin(beta_R), m.cos(beta_R)
        q_R = m.sqrt(s_R)
        c_L = m.cos(beta_L)
        g = (q_L * c_L - q_R * c_R) / d
        if not jacobian:
            return g, None
        dF_L = dq_L * c_L - q_L * m.sin(beta_L) * b1  # d f(beta_L) / d var
        g_R = (g - f1(beta_R, m)) / d                  # d g / d beta_R
        g_var = (dF_L - g * b1) / d - g_R * b1
    else:
        rule = _ball_rule(beta_R, d, m) if m.rigorous else (FLOAT_NODES, 1)
        nodes = m.gauss_legendre(*rule)
        g = sum(w * m.local(f1, beta_R + t * d) for t, w in nodes)  # (f1's derivative: f2)
        if m.rigorous:
            g = g + m.analytic_error(_BOUNDS[rule][0], (beta_R, d))
        if not jacobian:
            return g, None
        second = [(t, w, f2(beta_R + t * d, m)) for t, w in nodes]
        # g_L - g_R as one sum: its terms cancel, which separate ball sums would not see
        g_LR = sum(w * (2.0 * t - 1.0) * f2_t for t, w, f2_t in second)
        g_R = sum(w * (1.0 - t) * f2_t for t, w, f2_t in second)
        if m.rigorous:
            g_LR = g_LR + 2.0 * m.analytic_error(_BOUNDS[rule][1], (beta_R, d))
            g_R = g_R + m.analytic_error(_BOUNDS[rule][1], (beta_R, d))
        g_var = g_LR * b1
    return g, (-2.0 * g_R, 0.0, g_var, 0.0)
