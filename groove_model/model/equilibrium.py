r"""Every equilibrium of the ball: the point solver and the regime classification.

The model is Halsey & Ertas, "A Ball in a Groove". Walls at ``theta_L = gamma + delta`` and
``theta_R = gamma - delta``; the ball's centre moves by ``Z`` at angles ``beta_L`` and
``beta_R = pi - 2 gamma - beta_L`` to the walls and rolls by ``upsilon = R phi / Z``. All forces
scale with ``C Z^(3/2)`` (Hertz, paper Eq. hertz), so the solver works with the scaled normal
forces ``n = sin(beta)^(3/2)`` (Eq. norm) and the scaled common tangential force
``t = T / (C Z^(3/2))``; ``c`` is the compliance ratio ``(T/N) / (u_t/u_n)`` (Eq. prop: ``c = 1``).

Every state is written in one unknown, the load-share root

.. math::

    w = \sqrt{\sin\beta_L / \sin\beta_R} \in [0, 1], \qquad \rho = w^2, \qquad
    n_L / n_R = w^3,

with ``w = 1`` the symmetric state and ``w = 0`` the edge ``delta = gamma``. Double rolling
reduces to one equation :math:`P(w) = 0` (a rational function, a quartic over ``1 + w``:
:func:`double_rolling_state`) that is strictly increasing, so it has exactly one root, found
by bracketing (Chandrupatla's method, :func:`~groove_model.model.roots.chandrupatla`), never
by Newton from a guess. Rolling sliding gives ``w^3 = mu/k`` in closed form. Given ``w`` and
``1 - w``, every angle, force ratio, ``upsilon`` and slip is a short algebraic expression in
``sin gamma``, ``cos gamma``, ``w`` and ``1 - w`` (:func:`_kinematics`), each a sum of terms
of one sign or a difference that vanishes only where the physical quantity itself does
(``upsilon`` on the no-roll lines, ``d_L`` at the regime boundary, ``cos beta_R`` at
``beta_R = pi/2``).

No formula subtracts nearly equal angles or cosines, and ratios of small sines are formed
before they can underflow, so the same expressions hold from the corners of the domain
``0 <= delta <= gamma <= pi/2`` down to subnormal ``gamma``, with no series and no case split
near the origin: fields are accurate to a few ulps of their size, and the three differences
above to a few ulps of their terms (checked against a 50-digit reference in the tests).
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from enum import Enum
from typing import Any

import numpy as np

from .parameters import HALF_PI, Parameters, check_domain
from .roots import chandrupatla

__all__ = [
    "Equilibrium",
    "Regime",
    "Rotation",
    "double_rolling_equation",
    "double_rolling_state",
    "regime_validity",
    "rolling_sliding_state",
    "solve_equilibrium",
    "wall_terms",
]

_EPS = np.finfo(float).eps
# Two subnormal spacings: the bracket of a root of any size closes (adjacent floats differ by at
# least one spacing, and the relative tolerance alone is 0 for subnormal roots).
_XATOL = 2.0 * np.finfo(float).smallest_subnormal


class Regime(str, Enum):
    """Contact regime of an equilibrium; values are the names used in files and JSON."""

    DOUBLE_ROLLING = "double_rolling"
    ROLLING_SLIDING = "rolling_sliding"
    DOUBLE_SLIDING = "double_sliding"


class Rotation(str, Enum):
    """Sense of the ball's rolling: ``upsilon < 0`` clockwise (down the steeper, left wall)."""

    CLOCKWISE = "clockwise"
    COUNTERCLOCKWISE = "counterclockwise"
    NONE = "none"


@dataclass(frozen=True)
class Equilibrium:
    """The state of the ball at one or many points ``(gamma, delta)``.

    Every field has the shape of the broadcast inputs (plain Python scalars for scalar input).
    Displacements are per unit approach ``Z`` and forces per ``C Z^(3/2)``.

    Attributes
    ----------
    regime, rotation : str
        Values of :class:`Regime` and :class:`Rotation`.
    gamma, delta, theta_L, theta_R, beta_L, beta_R : float
        Angles in radians; ``beta_L + beta_R = pi - 2 gamma``.
    upsilon : float
        Rolling ``R phi / Z``; negative is clockwise.
    d_L, d_R : float
        Slip of each contact down its wall, per ``Z`` (``>= 0``).
    T_over_N_L, T_over_N_R, N_L_over_N_R : float
        Force ratios (``T/N_L = inf`` where ``N_L`` vanishes on the domain edge
        ``delta = gamma``). ``N_L/N_R`` is computed from the kinematics, not from ``n_L, n_R``,
        so it stays exact where both scaled forces vanish (closed groove, its limit value) or
        underflow (near the origin).
    n_L, n_R, t : float
        Scaled forces ``N_L, N_R, T`` divided by ``C Z^(3/2)``; of order ``gamma^(3/2)`` near
        the origin, so subnormal or 0 for ``gamma`` below about ``1e-205`` (their exact values).
    """

    regime: Any
    rotation: Any
    gamma: Any
    delta: Any
    theta_L: Any
    theta_R: Any
    beta_L: Any
    beta_R: Any
    upsilon: Any
    d_L: Any
    d_R: Any
    T_over_N_L: Any
    T_over_N_R: Any
    N_L_over_N_R: Any
    n_L: Any
    n_R: Any
    t: Any

    def to_dict(self) -> dict:
        """The fields as a dict (for JSON); arrays become lists."""
        out = {}
        for f in fields(self):
            value = getattr(self, f.name)
            out[f.name] = value.tolist() if isinstance(value, np.ndarray) else value
        return out


def _ratio(num, den):
    """``num / den`` with ``+inf`` where ``den == 0`` (a vanishing normal force), no warnings."""
    out = np.full(np.broadcast(num, den).shape, np.inf)
    np.divide(num, den, out=out, where=den != 0.0)
    return out


def _quotient(num, den, where):
    """``num / den`` where ``where`` holds, ``0`` elsewhere (no warnings)."""
    out = np.zeros(np.broadcast(num, den).shape)
    np.divide(num, den, out=out, where=where)
    return out


def _flat(gamma, delta):
    """Float copies of the broadcast inputs as 1-d arrays, and the broadcast shape."""
    gamma, delta = np.broadcast_arrays(np.asarray(gamma, float), np.asarray(delta, float))
    return gamma.ravel().copy(), delta.ravel().copy(), gamma.shape


def _shaped(values: dict, shape) -> dict:
    """Each array reshaped to the inputs' broadcast shape (numpy scalars for scalar inputs)."""
    return {name: np.reshape(value, shape)[()] for name, value in values.items()}


def wall_terms(gamma, delta):
    """Trigonometric terms of the groove, each to a few ulps over the whole domain.

    Returns
    -------
    dict of ndarray
        ``sin_g, cos_g, tan_g`` of ``gamma``; ``rho0 = sin theta_R / sin theta_L``,
        ``one_minus_rho0 = 1 - rho0`` and ``E = (cos theta_R - cos theta_L) / sin theta_L``.

    Notes
    -----
    ``1 - rho0 = 2 cos gamma sin delta / sin theta_L`` and
    ``E = 2 sin gamma sin delta / sin theta_L`` (sum-to-product) are formed from the ratio
    ``sin delta / sin theta_L <= 1``, never as differences of cosines or with products of two
    small sines, so they neither cancel near ``delta = 0`` nor underflow near the origin.
    ``sin theta_L = sin gamma cos delta + cos gamma sin delta`` adds two non-negative terms
    (``sin(gamma + delta)`` would cancel near ``theta_L = pi``). The float nearest ``pi/2`` stands
    for ``pi/2`` itself (``cos = 0``), the domain edge that :func:`check_domain` clamps to.
    """
    sin_g, sin_d = np.sin(gamma), np.sin(delta)
    cos_g = np.where(gamma >= HALF_PI, 0.0, np.cos(gamma))
    cos_d = np.where(delta >= HALF_PI, 0.0, np.cos(delta))
    sin_tL = sin_g * cos_d + cos_g * sin_d
    # gamma - delta is exact when delta >= gamma/2 (Sterbenz); at gamma = pi/2 the float
    # gamma - delta would be off by pi/2 - HALF_PI = 6e-17, so use sin(pi/2 - delta) = cos delta.
    sin_tR = np.where(gamma >= HALF_PI, cos_d, np.sin(gamma - delta))
    positive = sin_tL > 0.0  # false only at the origin and at theta_L = pi, theta_R = 0
    share = _quotient(sin_d, sin_tL, positive)
    return dict(sin_g=sin_g, cos_g=cos_g, tan_g=_quotient(sin_g, cos_g, cos_g > 0.0),
                rho0=_quotient(sin_tR, sin_tL, positive), one_minus_rho0=2.0 * cos_g * share,
                E=2.0 * sin_g * share)


def _kinematics(w, v, sin_g, cos_g):
    r"""Angles and wall terms of the state with load-share root ``w`` (``v = 1 - w``, accurate).

    Returns
    -------
    dict of ndarray
        ``rho = w^2``, ``beta_L, beta_R``, ``sin_L, sin_R, cos_L, cos_R`` (of ``beta_L``,
        ``beta_R``), ``n_L, n_R``.

    Notes
    -----
    With ``e = (beta_R - beta_L)/2`` the split ``beta_{L,R} = pi/2 - gamma -+ e`` turns
    ``sin beta_L = rho sin beta_R`` into ``(1 - rho) cos gamma cos e = (1 + rho) sin gamma sin e``.
    With ``m = 1 - rho = v (1 + w)`` and ``h = hypot(m cos gamma, (1 + rho) sin gamma)``:

    .. math::

        \sin\beta_R = \frac{2 \sin\gamma\cos\gamma}{h}, \quad
        \sin\beta_L = \rho \sin\beta_R, \quad
        \cos\beta_{L,R} = \frac{(1 + \rho)\sin^2\gamma \pm m \cos^2\gamma}{h},

    and ``beta = atan2(sin beta, cos beta)``. Only ``cos beta_R`` is a difference; it vanishes
    where ``beta_R = pi/2`` and its error is absolute, ``eps`` times the terms. The symmetric state
    (``v = 0``) is set directly, which also covers the origin (``h = 0``).
    """
    rho = w * w
    m = v * (1.0 + w)
    a, b = (1.0 + rho) * sin_g * sin_g, m * cos_g * cos_g
    h = np.hypot(m * cos_g, (1.0 + rho) * sin_g)
    symmetric = v == 0.0  # NaN stays in the general branch and propagates
    h_safe = np.where(symmetric, 1.0, h)
    sin_R = np.where(symmetric, cos_g, (2.0 * sin_g) * (cos_g / h_safe))
    cos_L = np.where(symmetric, sin_g, (a + b) / h_safe)
    cos_R = np.where(symmetric, sin_g, (a - b) / h_safe)
    sin_L = rho * sin_R
    return dict(rho=rho, m=m, h=h, beta_L=np.arctan2(sin_L, cos_L),
                beta_R=np.arctan2(sin_R, cos_R), sin_L=sin_L, sin_R=sin_R, cos_L=cos_L,
                cos_R=cos_R, n_L=sin_L * np.sqrt(sin_L), n_R=sin_R * np.sqrt(sin_R))


def double_rolling_equation(x, upper, rho0, one_minus_rho0, K):
    r"""The double-rolling equation :math:`P(w)`, increasing in ``x`` on ``[0, 1/2]``.

    ``x = w`` where ``upper == 0`` (``P = w^3 + K f(w) - rho0``) and ``x = v = 1 - w`` where
    ``upper == 1`` (``P = (1 - rho0) + K f(w) - v (1 + w + w^2)``, sign flipped so it increases),
    with ``f(w) = w (1 + w^2)/(1 + w)``; the unknown is always the smaller of ``w`` and ``1 - w``.
    """
    up = upper > 0.0
    w = np.where(up, 1.0 - x, x)
    friction = K * (w * (1.0 + w * w) / (1.0 + w))
    return np.where(up, x * (1.0 + w + w * w) - one_minus_rho0 - friction,
                    w * w * w + friction - rho0)


def _double_rolling_root(rho0, one_minus_rho0, K) -> np.ndarray:
    """The root of :func:`double_rolling_equation` on ``[0, 1/2]``: ``w``, or ``-v`` (``v = 1 - w``)
    where it lies in ``v``.

    The half is chosen by the sign of ``P(1/2)`` as evaluated, not by the closed form
    ``rho0 > 1/8 + 5K/12``, which can round the other way: the chosen bracket then had no
    sign change and a root within rounding of ``w = 1/2`` was not found. Where the two forms of
    ``P`` both put the root beyond ``1/2`` by rounding, it is ``1/2``.
    """
    half = np.full(rho0.shape, 0.5)
    upper = (double_rolling_equation(half, np.zeros(rho0.shape), rho0, one_minus_rho0, K)
             < 0.0).astype(float)
    x = chandrupatla(double_rolling_equation, np.zeros(rho0.shape), half,
                     args=(upper, rho0, one_minus_rho0, K), xatol=_XATOL, xrtol=2.0 * _EPS)
    at_half = (upper > 0.0) & (double_rolling_equation(half, upper, rho0, one_minus_rho0, K) < 0.0)
    x[at_half] = 0.5
    return np.where(upper > 0.0, -x, x)


def double_rolling_state(gamma, delta, params: Parameters) -> dict:
    r"""The double-rolling solution (``d_L = d_R = 0``) wherever it is defined.

    Parameters
    ----------
    gamma, delta : ndarray
        Points of the domain ``0 <= delta <= gamma <= pi/2`` (radians, not checked here), any
        broadcastable shapes. NaN, or a point outside the domain (no bracket), gives NaN.
    params : Parameters

    Returns
    -------
    dict of ndarray
        ``beta_L, beta_R, upsilon, n_L, n_R, t, T_over_N_L, T_over_N_R, N_L_over_N_R``. On the
        edge ``gamma = pi/2`` (closed groove) no double-rolling state exists and every entry is
        NaN there; on ``delta = gamma < pi/2`` the limit ``beta_L = 0`` (``T/N_L = inf``) is
        returned; at the origin the symmetric limit (``beta = pi/2``).

    Notes
    -----
    Torque balance (paper Eq. 3, ``T_L = T_R``) with proportional loading (Eqs. rollt, prop):

    .. math::

        t = c q_L (\cos\beta_L + \upsilon) = c q_R (\cos\beta_R - \upsilon), \quad
        q = \sqrt{\sin\beta},

    is linear in ``upsilon``; eliminating it,
    ``upsilon = (cos beta_R - w cos beta_L)/(1 + w)`` and
    ``t = c q_R w (cos beta_L + cos beta_R)/(1 + w)``. Because ``beta_L + beta_R = pi - 2 gamma``,

    .. math::

        \cos\beta_L + \cos\beta_R = \tan\gamma\,(\sin\beta_L + \sin\beta_R)
        \quad (\text{both} = 2 \{\sin,\cos\}\gamma \, \sin(\beta_L + \gamma)),

    so the horizontal balance (Eq. 2) ``n_L sin theta_L - n_R sin theta_R + t (cos theta_R -
    cos theta_L) = 0``, divided by ``n_R sin theta_L``, depends on ``w`` alone:

    .. math::

        P(w) = w^3 + K \frac{w (1 + w^2)}{1 + w} - \rho_0 = 0, \qquad
        \rho_0 = \frac{\sin\theta_R}{\sin\theta_L}, \quad
        K = c \tan\gamma \, \frac{2 \sin\gamma \sin\delta}{\sin\theta_L}.

    ``P`` is strictly increasing on ``[0, 1]`` (``d/dw [w (1 + w^2)/(1 + w)] = (1 + 3 w^2 +
    2 w^3)/(1 + w)^2 > 0``, ``K >= 0``), ``P(0) = -rho0 <= 0`` and ``P(1) = 1 + K - rho0 >= 0``:
    the root exists and is unique. (The paper's Eqs. tran1 and tran2 are the same two balances
    divided by ``n_L sin theta_R`` and by ``q_R (cos beta_R - upsilon)``, which vanish on the
    domain's edges.) Times ``1 + w``, ``P`` is the quartic
    ``w^4 + (1 + K) w^3 + (K - rho0) w - rho0``. Since ``P(1/2) >= 0`` iff
    ``rho0 <= 1/8 + 5K/12`` (decided by the sign of ``P(1/2)`` as evaluated, which the closed
    form can contradict by rounding), the root is bracketed either in ``w`` on ``[0, 1/2]`` or in
    ``v = 1 - w`` on ``[0, 1/2]``, where ``P = (1 - rho0) + K f(w) - v (1 + w + w^2)`` (minus
    sign aside) is again a sum of terms of one sign; the unknown is always the small one of
    ``w, 1 - w``, so its relative accuracy carries over to ``beta_L`` (small near
    ``delta = gamma``) and to ``beta_R - beta_L`` and ``upsilon`` (small near ``delta = 0``). Then

    .. math::

        \frac{T}{N_L} = \frac{c \tan\gamma (1 + \rho)}{\rho (1 + w)}, \quad
        \frac{T}{N_R} = w^3 \frac{T}{N_L}, \quad
        \upsilon = \frac{(1 - w) [(1 + \rho) \sin^2\gamma - (1 + w)^2 \cos^2\gamma]}{h (1 + w)}

    (``h`` of :func:`_kinematics`). The bracket of ``upsilon`` changes sign on
    ``tan^2 gamma = (1 + w)^2/(1 + w^2)``: at ``arctan sqrt 2`` on ``delta = 0`` (``w = 1``) and
    at ``pi/4`` on ``delta = gamma`` (``w = 0``), the paper's ends of the no-roll line.
    """
    gamma, delta, shape = _flat(gamma, delta)
    walls = wall_terms(gamma, delta)
    sin_g, cos_g, rho0 = walls["sin_g"], walls["cos_g"], walls["rho0"]
    K = params.c * walls["E"] * walls["tan_g"]
    # w = 1 on delta = 0 and w = 0 on delta = gamma are exact; NaN marks no state.
    w = np.where(delta == 0.0, 1.0, np.where(rho0 == 0.0, 0.0, np.nan))
    exists = cos_g > 0.0
    w[~exists] = np.nan
    inner = np.isnan(w) & exists & (delta > 0.0)
    v = 1.0 - w
    if np.any(inner):
        x = _double_rolling_root(rho0[inner], walls["one_minus_rho0"][inner], K[inner])
        upper = (x < 0.0).astype(float)  # the root was found in v = 1 - w
        x = np.abs(x)
        w[inner] = np.where(upper > 0.0, 1.0 - x, x)
        v[inner] = np.where(upper > 0.0, x, 1.0 - x)
    kin = _kinematics(w, v, sin_g, cos_g)
    rho = kin["rho"]
    no_roll = (1.0 + rho) * sin_g * sin_g - (1.0 + w) ** 2 * cos_g * cos_g
    upsilon = v * _quotient(no_roll, kin["h"] * (1.0 + w), v > 0.0)  # NaN where w is
    # tan gamma multiplies last: for subnormal gamma it is exact and the product rounds once.
    T_over_N_L = params.c * _ratio(1.0 + rho, rho * (1.0 + w)) * walls["tan_g"]
    T_over_N_R = params.c * ((1.0 + rho) * w / (1.0 + w)) * walls["tan_g"]
    return _shaped(dict(
        beta_L=kin["beta_L"], beta_R=kin["beta_R"], upsilon=upsilon, n_L=kin["n_L"],
        n_R=kin["n_R"], t=T_over_N_R * kin["n_R"], T_over_N_L=T_over_N_L, T_over_N_R=T_over_N_R,
        N_L_over_N_R=w * w * w,
    ), shape)


def rolling_sliding_state(gamma, delta, params: Parameters) -> dict:
    r"""The rolling-sliding solution (left wall slides, ``T = k N_L``; right wall rolls).

    Parameters
    ----------
    gamma, delta : ndarray
        Points of the domain (radians, not checked here), any broadcastable shapes.
    params : Parameters

    Returns
    -------
    dict of ndarray
        ``beta_L, beta_R, upsilon, d_L, mu, n_L, n_R, t, N_L_over_N_R``; NaN only at the
        origin, where ``mu`` is ``0/0``. At ``gamma = pi/2`` (closed groove) the limit
        ``beta_L = beta_R = 0``, ``upsilon = 1``, ``d_L = 2``.

    Notes
    -----
    Paper, "Rolling-sliding solutions": ``T = k N_L`` in the horizontal balance (Eq. 2) gives

    .. math::

        \frac{T}{N_R} = \mu = \frac{\sin\theta_R}{\cos\theta_R - \cos\theta_L
        + \sin\theta_L / k}, \qquad w^3 = \frac{N_L}{N_R} = \frac{\mu}{k}
        = \frac{\rho_0}{1 + k E},

    with ``1 - w^3 = (1 - rho0 + kE)/(1 + kE)`` and ``v = 1 - w = (1 - w^3)/(1 + w + w^2)``
    formed without cancellation. The rolling right wall (``mu = c (cos beta_R - upsilon)/
    sin beta_R``) and the sliding left wall (``k = c (cos beta_L + upsilon - d_L)/sin beta_L``,
    Eq. tang with Amontons) give

    .. math::

        \upsilon = \cos\beta_R - \frac{\mu}{c}\sin\beta_R, \qquad
        \frac{d_L}{Z} = \frac{2\sin\gamma}{h}\Big[(1 + \rho)\sin\gamma
        - \frac{k}{c}\rho(1 + w)\cos\gamma\Big],

    the second from ``cos beta_L + cos beta_R = 2 (1 + rho) sin^2 gamma / h`` (see
    :func:`_kinematics`); its bracket changes sign exactly where the double-rolling
    ``T/N_L = k``.
    """
    gamma, delta, shape = _flat(gamma, delta)
    k, c = params.k, params.c
    walls = wall_terms(gamma, delta)
    sin_g, cos_g = walls["sin_g"], walls["cos_g"]
    # k E overflows only for k near the float maximum; its limit is mu/k = 0, 1 - mu/k = 1.
    with np.errstate(over="ignore", invalid="ignore"):
        kE = k * walls["E"]
        share = walls["rho0"] / (1.0 + kE)  # mu / k = N_L / N_R
        rest = np.where(kE == np.inf, 1.0, (walls["one_minus_rho0"] + kE) / (1.0 + kE))
    w = np.cbrt(share)
    v = rest / (1.0 + w + w * w)
    origin = gamma == 0.0
    share[origin] = w[origin] = v[origin] = np.nan
    kin = _kinematics(w, v, sin_g, cos_g)
    rho = kin["rho"]
    mu = k * share
    upsilon = kin["cos_R"] - (mu / c) * kin["sin_R"]
    # The bracket is formed before the factor 2 sin(gamma)/h ~ gamma: d_L ~ gamma^2 may
    # underflow near the origin, but never with the wrong sign.
    slip = (1.0 + rho) * sin_g - (k / c) * rho * (1.0 + w) * cos_g
    d_L = _quotient(2.0 * sin_g, kin["h"], kin["h"] > 0.0) * slip  # NaN at the origin
    return _shaped(dict(
        beta_L=kin["beta_L"], beta_R=kin["beta_R"], upsilon=upsilon, mu=mu, d_L=d_L,
        n_L=kin["n_L"], n_R=kin["n_R"], t=k * kin["n_L"], N_L_over_N_R=share,
    ), shape)


def regime_validity(gamma, delta, k):
    """Where each regime's own conditions hold, evaluated independently of the other.

    Returns
    -------
    dr_valid, rs_valid : ndarray of bool
        ``T/N <= k`` on both walls for double rolling; ``d_L >= 0`` and ``mu <= k`` for
        rolling sliding. On ``delta = 0`` beyond ``arctan(k/c)`` the rolling-sliding state is
        the double-sliding one (both walls at ``T = kN``).
    """
    params = Parameters.coerce(k)
    gamma, delta = check_domain(gamma, delta)
    dr = double_rolling_state(gamma, delta, params)
    rs = rolling_sliding_state(gamma, delta, params)
    with np.errstate(invalid="ignore"):
        dr_valid = (dr["T_over_N_L"] <= params.k) & (dr["T_over_N_R"] <= params.k)
        # Near the origin d_L ~ gamma^2 underflows; a negative slip then rounds to -0.0,
        # which compares >= 0, so its sign bit decides.
        rs_valid = (rs["d_L"] >= 0.0) & ~np.signbit(rs["d_L"]) & (rs["mu"] <= params.k)
    return dr_valid, rs_valid


def solve_equilibrium(gamma, delta, k) -> Equilibrium:
    """The equilibrium the paper predicts at ``(gamma, delta)`` for friction ``k``.

    Double rolling where it is valid (``T/N <= k`` on both walls), double sliding on
    ``delta = 0`` for ``gamma > arctan(k/c)`` (the symmetric state, ``upsilon = 0``,
    ``d_L = d_R = sin gamma - (k/c) cos gamma``), rolling sliding elsewhere.

    Parameters
    ----------
    gamma, delta : float or array_like
        Half-sum and half-difference of the wall angles, radians, ``0 <= delta <= gamma <= pi/2``.
    k : float or Parameters
        Friction coefficient, finite and > 0, or a full parameter object
        (``solve_equilibrium(0.6, 0.2, k=1.0)``).

    Returns
    -------
    Equilibrium
        Fields of the broadcast shape (scalars for scalar input).

    Raises
    ------
    ValueError, TypeError
        For ``k`` or angles outside their ranges (the message names the quantity and range).
    RuntimeError
        If the bracketed double-rolling solve fails at a point of the open groove (a bug, never
        expected: the bracket is proven valid there).
    """
    params = Parameters.coerce(k)
    scalar = np.ndim(gamma) == 0 and np.ndim(delta) == 0
    gamma, delta = check_domain(gamma, delta)
    gamma, delta = np.atleast_1d(gamma), np.atleast_1d(delta)
    k, c = params.k, params.c
    dr = double_rolling_state(gamma, delta, params)
    # The bracket is valid everywhere in the open groove (see double_rolling_state), so a NaN
    # there is a bug; refuse to return a regime decided on it.
    failed = np.isnan(dr["beta_L"]) & (gamma < HALF_PI)
    if np.any(failed):
        i = np.flatnonzero(failed)[0]
        raise RuntimeError(f"double-rolling root not found at gamma = {float(gamma[i])!r} rad, "
                           f"delta = {float(delta[i])!r} rad, although it is bracketed there")
    # gamma = pi/2 (the float) is the closed groove, T/N = c tan gamma = inf > k for every k,
    # also where arctan(k/c) rounds to pi/2 (k/c >= 1e16)
    sliding_both = (delta == 0.0) & ((gamma > params.gamma_limit) | (gamma >= HALF_PI))
    with np.errstate(invalid="ignore"):
        use_dr = (dr["T_over_N_L"] <= k) & (dr["T_over_N_R"] <= k) & ~sliding_both
    # On delta = 0, T/N = c tan gamma <= k exactly when gamma <= arctan(k/c); deciding by the
    # angle avoids tan(pi/4) rounding above 1 at the seed itself.
    on_axis = delta == 0.0
    use_dr[on_axis] = ~sliding_both[on_axis]
    use_rs = ~use_dr & ~sliding_both

    out = {name: np.zeros(gamma.shape) for name in (
        "beta_L", "beta_R", "upsilon", "d_L", "d_R", "T_over_N_L", "T_over_N_R",
        "N_L_over_N_R", "n_L", "n_R", "t")}
    regime = np.full(gamma.shape, Regime.DOUBLE_ROLLING.value, dtype=object)

    for name in ("beta_L", "beta_R", "upsilon", "n_L", "n_R", "t", "T_over_N_L", "T_over_N_R",
                 "N_L_over_N_R"):
        out[name][use_dr] = dr[name][use_dr]

    if np.any(use_rs):
        rs = rolling_sliding_state(gamma[use_rs], delta[use_rs], params)
        for name in ("beta_L", "beta_R", "upsilon", "d_L", "n_L", "n_R", "t", "N_L_over_N_R"):
            out[name][use_rs] = rs[name]
        out["T_over_N_L"][use_rs] = k
        out["T_over_N_R"][use_rs] = rs["mu"]
        regime[use_rs] = Regime.ROLLING_SLIDING.value

    if np.any(sliding_both):
        g = gamma[sliding_both]
        walls = wall_terms(g, np.zeros_like(g))
        sin_g, cos_g = walls["sin_g"], walls["cos_g"]
        beta = np.arctan2(cos_g, sin_g)  # pi/2 - gamma, exactly 0 at gamma = pi/2
        n = cos_g * np.sqrt(cos_g)
        slip = sin_g - (k / c) * cos_g
        for name, value in (("beta_L", beta), ("beta_R", beta), ("upsilon", 0.0), ("d_L", slip),
                            ("d_R", slip), ("T_over_N_L", k), ("T_over_N_R", k),
                            ("N_L_over_N_R", 1.0), ("n_L", n), ("n_R", n), ("t", k * n)):
            out[name][sliding_both] = value
        regime[sliding_both] = Regime.DOUBLE_SLIDING.value

    rotation = np.where(out["upsilon"] < 0.0, Rotation.CLOCKWISE.value,
                        np.where(out["upsilon"] > 0.0, Rotation.COUNTERCLOCKWISE.value,
                                 Rotation.NONE.value)).astype(object)
    theta_L, theta_R = gamma + delta, gamma - delta
    values = dict(out, regime=regime, rotation=rotation, gamma=gamma, delta=delta,
                  theta_L=theta_L, theta_R=theta_R)
    if scalar:
        values = {key: (v[0].item() if hasattr(v[0], "item") else v[0])
                  for key, v in values.items()}
    return Equilibrium(**values)
