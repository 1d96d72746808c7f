r"""The boundary lines by bracketed root finding with the point solver, one row or column at a time.

Where the tracer (:func:`groove_model.tracing.trace_boundaries`) follows each boundary as one
curve, these functions find its points on given rows ``delta`` or columns ``gamma`` from the
regime states of :mod:`groove_model.model.equilibrium`, each root bracketed by a sign change
that the paper's equations guarantee. They are independent of the tracer, which is why the
audit of the paper's claims and the regime map use them as a cross-check.

The names follow the boundaries (see ``docs/glossary.md``): ``dr_limit`` (double rolling
reaches ``T/N_L = k``), ``rs_limit`` (the rolling-sliding slip ``d_L`` vanishes; the same
curve), ``dr_no_roll`` and ``rs_no_roll`` (``upsilon = 0`` in each regime).

``dr_limit_delta``, ``rs_limit_delta``, ``rs_no_roll_gamma`` and ``dr_no_roll_line`` solve the
paper's model (compliance ratio ``c = 1``); :func:`dr_limit_no_roll_point` takes any
:class:`~groove_model.model.parameters.Parameters`.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Callable

import numpy as np
from scipy import optimize
from scipy.optimize import elementwise

from .boundaries import BoundarySystem
from .equilibrium import double_rolling_state, rolling_sliding_state
from .parameters import Parameters

__all__ = [
    "ROOT_TOLERANCES",
    "bracketed_root",
    "dr_limit_delta",
    "dr_limit_no_roll_point",
    "dr_margins",
    "dr_no_roll_line",
    "rs_limit_delta",
    "rs_no_roll_gamma",
]

log = logging.getLogger(__name__)

#: Tolerances of :func:`bracketed_root`: the root to 4 ulp, no absolute tolerance.
ROOT_TOLERANCES = dict(xatol=0.0, xrtol=4.0 * np.finfo(float).eps, fatol=0.0, frtol=0.0)
_HALF_PI = 0.5 * math.pi
_SQRT2 = math.sqrt(2.0)
#: The double-rolling state does not depend on ``k`` (only its validity does).
_ANY_K = Parameters(1.0)


def bracketed_root(f: Callable, lo, hi, args=()) -> np.ndarray:
    """Vectorised bracketed root of ``f(x, *args)`` between ``lo`` and ``hi``.

    Parameters
    ----------
    f : callable
        ``f(x, *args)``, elementwise over arrays.
    lo, hi : array_like
        Brackets, broadcastable; ``f`` must change sign between them.
    args : tuple
        Extra arguments of ``f``, broadcastable with ``lo`` and ``hi``.

    Returns
    -------
    ndarray
        The roots, to :data:`ROOT_TOLERANCES`.

    Raises
    ------
    ArithmeticError
        If a bracket does not enclose a sign change.

    Notes
    -----
    Chandrupatla's method (``scipy.optimize.elementwise.find_root``).
    """
    res = elementwise.find_root(f, (np.asarray(lo, float), np.asarray(hi, float)), args=args,
                                tolerances=ROOT_TOLERANCES)
    if not np.all(res.success):
        bad = np.flatnonzero(~np.atleast_1d(res.success))
        raise ArithmeticError(f"root finding failed for {bad.size} brackets "
                              f"(status {np.atleast_1d(res.status)[bad[0]]})")
    return res.x


def dr_margins(gamma, delta, k: float):
    """How far the double-rolling state is from ``T/N = k`` on each wall; ``>= 0`` where valid.

    Parameters
    ----------
    gamma, delta : array_like
        Points of the domain, radians, broadcastable.
    k : float
        Friction coefficient, > 0.

    Returns
    -------
    margin_L, margin_R : ndarray
        ``k sin beta_L - A`` and ``k sin beta_R - B``, proportional to ``k - T/N`` on each wall.

    Notes
    -----
    ``A = cos beta_L + upsilon = q_R S / (q_L + q_R)`` and ``B = cos beta_R - upsilon = q_L S /
    (q_L + q_R)`` with ``q = sqrt(sin beta)`` and ``S = cos beta_L + cos beta_R = 2 sin gamma
    cos((beta_L - beta_R)/2)``: the torque balance with ``upsilon`` eliminated (paper Eqs. rollt
    and prop, ``c = 1``), which keeps full relative accuracy where both are small, near the
    origin.
    """
    dr = double_rolling_state(gamma, delta, _ANY_K)
    q_L, q_R = np.sqrt(np.sin(dr["beta_L"])), np.sqrt(np.sin(dr["beta_R"]))
    S = 2.0 * np.sin(gamma) * np.cos(0.5 * (dr["beta_L"] - dr["beta_R"]))
    A, B = q_R * S / (q_L + q_R), q_L * S / (q_L + q_R)
    return k * np.sin(dr["beta_L"]) - A, k * np.sin(dr["beta_R"]) - B


def dr_limit_delta(k: float, gamma) -> np.ndarray:
    """``delta`` of the double-rolling limit ``T/N_L = k`` on each column ``gamma``.

    Parameters
    ----------
    k : float
        Friction coefficient, > 0.
    gamma : array_like
        Columns, radians, ``0 < gamma < arctan k``.

    Returns
    -------
    ndarray
        ``delta`` of ``dr_limit`` on each column.

    Notes
    -----
    The margin ``k sin beta_L - (cos beta_L + upsilon)`` (:func:`dr_margins`) is
    ``k cos gamma - sin gamma > 0`` on ``delta = 0`` and ``-2 sin^2 gamma < 0`` on
    ``delta = gamma``; the root between is bracketed.
    """
    gamma = np.asarray(gamma, dtype=float)
    return bracketed_root(lambda d, g: dr_margins(g, d, k)[0], np.zeros_like(gamma), gamma,
                          args=(gamma,))


def rs_limit_delta(k: float, gamma) -> np.ndarray:
    """``delta`` where the rolling-sliding slip ``d_L`` vanishes on each column ``gamma``.

    The same curve as :func:`dr_limit_delta` (same arguments and result), found from the
    other side: ``d_L/Z = 2 (sin gamma - k cos gamma) < 0`` on ``delta = 0`` and
    ``2 sin^2 gamma > 0`` on ``delta = gamma`` (paper, "Rolling-sliding solutions"), and the
    root between is bracketed.
    """
    gamma = np.asarray(gamma, dtype=float)
    params = Parameters(k)
    return bracketed_root(lambda d, g: rolling_sliding_state(g, d, params)["d_L"],
                          np.zeros_like(gamma), gamma, args=(gamma,))


def rs_no_roll_gamma(k: float, delta) -> np.ndarray:
    """``gamma`` of the rolling-sliding ``upsilon = 0`` line on each row ``delta``.

    Parameters
    ----------
    k : float
        Friction coefficient, > 0.
    delta : array_like
        Rows, radians, ``0 < delta < pi/4``.

    Returns
    -------
    ndarray
        ``gamma`` of ``rs_no_roll`` (its physical part and the rest) on each row.

    Notes
    -----
    ``upsilon = -cos 2 delta < 0`` on ``gamma = delta`` and ``upsilon = 1`` on ``gamma = pi/2``;
    the root between is bracketed.
    """
    delta = np.asarray(delta, dtype=float)
    params = Parameters(k)
    return bracketed_root(lambda g, d: rolling_sliding_state(g, d, params)["upsilon"],
                          delta, np.full_like(delta, _HALF_PI), args=(delta,))


def _dr_upsilon(gamma, delta):
    """Double-rolling ``upsilon(gamma, delta)`` for root finding in ``gamma``."""
    return double_rolling_state(gamma, delta, _ANY_K)["upsilon"]


def dr_no_roll_line(delta):
    r"""The double-rolling ``upsilon = 0`` line on rows ``delta`` in ``(0, pi/4)``.

    Parameters
    ----------
    delta : array_like
        Rows, radians, ``0 < delta < pi/4``.

    Returns
    -------
    gamma, beta_L : ndarray
        The line's ``gamma`` on each row and its ``beta_L`` (the double-rolling state does not
        depend on ``k``).

    Notes
    -----
    The line leaves the symmetric family at the branch point ``(arctan sqrt 2, 0)`` as
    ``gamma ~ arctan sqrt 2 - O(delta^2)`` and ends at ``(pi/4, pi/4)``, so it is a graph over
    ``delta`` but not over ``gamma`` near the branch point. On each row ``upsilon < 0`` at
    ``gamma = pi/4`` and ``upsilon > 0`` at ``gamma = arctan sqrt 2 + 0.05`` (where it is
    ``O(delta)``, well above round-off; at ``arctan sqrt 2`` itself it is only ``O(delta^3)``),
    so the root is bracketed (Chandrupatla, scipy ``elementwise.find_root``).
    """
    delta = np.asarray(delta, dtype=float)
    res = elementwise.find_root(_dr_upsilon, (np.full_like(delta, 0.25 * math.pi),
                                              np.full_like(delta, math.atan(_SQRT2) + 0.05)),
                                args=(delta,), tolerances=ROOT_TOLERANCES)
    gamma = np.where(res.success, res.x, np.nan)
    return gamma, double_rolling_state(gamma, delta, _ANY_K)["beta_L"]


def dr_limit_no_roll_point(k):
    r"""The point of ``dr_limit`` where ``upsilon = 0``, or ``None`` when ``k <= sqrt 2``.

    Parameters
    ----------
    k : float or Parameters
        Friction coefficient, finite and > 0.

    Returns
    -------
    ndarray, shape (4,), or None
        ``x = (gamma, delta, beta_L, upsilon)`` with ``upsilon = 0`` to round-off.

    Notes
    -----
    With ``upsilon = 0`` the double-rolling ratios are ``T/N_L = c cot beta_L``,
    ``T/N_R = c cot beta_R`` (paper Eq. rollt with Eq. prop), so the point is where the
    ``upsilon = 0`` line of double rolling (:func:`dr_no_roll_line`) reaches
    ``c cot beta_L = k``. Along the line ``beta_L`` falls from ``arctan(1/sqrt 2)`` at the branch
    point to 0 at ``(pi/4, pi/4)``; it is sampled on rows ``delta`` (densely towards both ends),
    the crossing is bracketed, and the point is polished by Newton's method on the four
    equations ``dr_limit`` and ``upsilon = 0`` with the analytic Jacobian of
    :mod:`groove_model.model.boundaries`; Brent's method on the line is the fallback.
    """
    params = Parameters.coerce(k)
    if params.k / params.c <= _SQRT2:
        return None
    target = math.atan2(params.c, params.k)  # beta_L with c cot beta_L = k
    quarter = 0.25 * math.pi
    # Below delta ~ 1e-7 the line's gamma = arctan sqrt 2 - O(delta^2) is lost in round-off.
    deltas = np.unique(np.concatenate([np.geomspace(1e-7, 1e-2, 26),
                                       np.linspace(0.0, quarter, 65)[1:-1],
                                       quarter - np.geomspace(1e-10, 1e-2, 33)]))
    gammas, beta_L = dr_no_roll_line(deltas)
    below = beta_L < target
    if not below.any():
        log.warning("k = %g: the upsilon = 0 point of dr_limit is within 1e-10 of the corner "
                    "(pi/4, pi/4) and was not located", params.k)
        return None
    if below.all():
        # Within 1e-7 of the branch point (k just above sqrt 2): beta_L ~ beta* - delta there.
        beta_star = math.atan(1.0 / _SQRT2)
        x = _polish_no_roll_point(params, np.array([math.atan(_SQRT2), beta_star - target,
                                                    target, 0.0]), 0.0, 1e-6)
        if x is None:
            log.warning("k = %g: the upsilon = 0 point of dr_limit is too close to the branch "
                        "point (arctan sqrt 2, 0) to be located", params.k)
        return x
    i = int(np.argmax(below))  # first row past the crossing: bracket rows (i - 1, i)
    w = (target - beta_L[i - 1]) / (beta_L[i] - beta_L[i - 1])
    x0 = np.array([gammas[i - 1] + w * (gammas[i] - gammas[i - 1]),
                   deltas[i - 1] + w * (deltas[i] - deltas[i - 1]), target, 0.0])
    x = _polish_no_roll_point(params, x0, deltas[i - 1], deltas[i])
    if x is not None:
        return x

    def excess(delta):
        return float(dr_no_roll_line(np.array([delta]))[1][0]) - target

    delta = optimize.brentq(excess, deltas[i - 1], deltas[i], xtol=1e-16,
                            rtol=4.0 * np.finfo(float).eps)
    gamma, beta = dr_no_roll_line(np.array([delta]))
    return np.array([float(gamma[0]), delta, float(beta[0]), 0.0])


def _polish_no_roll_point(params: Parameters, x0: np.ndarray, lo: float, hi: float):
    """Newton (MINPACK ``hybr``) on ``dr_limit`` and ``upsilon = 0`` from ``x0``; None unless
    it converges to a point with ``lo <= delta <= hi``."""
    system = BoundarySystem("dr_limit", params)

    def equations(x):
        H, J = system.residual_and_jacobian(x)
        return np.append(H, x[3]), np.vstack([J, [0.0, 0.0, 0.0, 1.0]])

    sol = optimize.root(equations, x0, jac=True, method="hybr", options=dict(xtol=1e-15))
    good = (sol.success and lo <= sol.x[1] <= hi
            and np.max(np.abs(equations(sol.x)[0])) <= 1e-13 * (1.0 + params.k))
    return sol.x if good else None
