r"""Every equilibrium of the ball: the point solver and the regime classification.

The model is Halsey & Ertas, "A Ball in a Groove" (``shared/paper``; conventions in
``shared/MODEL.md``). All forces scale with ``C Z^(3/2)`` (Hertz, ``C = sqrt(R)/G``), so the
solver works with the scaled normal forces ``n = sin(beta)^(3/2)`` and the scaled common
tangential force ``t = T / (C Z^(3/2))``.

Double rolling (paper Eqs. 1-3 with Eqs. norm, rollt, prop, ``c`` the compliance ratio):

.. math::

    t = c\sqrt{\sin\beta_L}(\cos\beta_L + \upsilon) = c\sqrt{\sin\beta_R}(\cos\beta_R - \upsilon)
    \quad\text{(torque, } T_L = T_R)

    n_L \sin\theta_L - n_R \sin\theta_R + t(\cos\theta_R - \cos\theta_L) = 0
    \quad\text{(horizontal balance, Eq. 2)}

``upsilon`` enters linearly; eliminating it gives
``t = c q_L q_R (cos beta_L + cos beta_R) / (q_L + q_R)`` with ``q = sqrt(sin beta)``, and the
horizontal balance times ``q_L + q_R`` becomes one scalar equation in
``a = beta_L / (pi - 2 gamma)`` on ``[0, 1]``, negative at ``a = 0`` and positive at ``a = 1``
whenever ``0 < delta < gamma < pi/2``. It is bracketed and solved by Chandrupatla's method
(scipy.optimize.elementwise.find_root), never by Newton from a guess. Its root is unique: a
sign-change count on a fine grid over the domain (see tests) finds exactly one.

Rolling-sliding (left wall slides, paper's "Rolling-sliding solutions"): ``T = k N_L`` and
the horizontal balance give ``T/N_R = mu = sin theta_R / (cos theta_R - cos theta_L + sin
theta_L / k)``, then ``(sin beta_L / sin beta_R)^(3/2) = mu / k`` is solved in closed form,
``tan beta_L = rho sin 2gamma / (1 - rho cos 2gamma)`` with ``rho = (mu/k)^(2/3)``; the rolling
right wall gives ``upsilon = cos beta_R - mu sin beta_R / c`` and the slip of the left contact
is ``d_L / Z = cos beta_L + upsilon - (k/c) sin beta_L``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from enum import Enum

import numpy as np
from scipy.optimize import elementwise

from .parameters import Parameters, check_domain

__all__ = [
    "Equilibrium",
    "Regime",
    "Rotation",
    "double_rolling_state",
    "regime_validity",
    "rolling_sliding_state",
    "solve_equilibrium",
]

_EPS = np.finfo(float).eps


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
        Force ratios (``inf`` where a normal force vanishes on the domain edge ``delta = gamma``).
    n_L, n_R, t : float
        Scaled forces ``N_L, N_R, T`` divided by ``C Z^(3/2)``.
    """

    regime: object
    rotation: object
    gamma: object
    delta: object
    theta_L: object
    theta_R: object
    beta_L: object
    beta_R: object
    upsilon: object
    d_L: object
    d_R: object
    T_over_N_L: object
    T_over_N_R: object
    N_L_over_N_R: object
    n_L: object
    n_R: object
    t: object

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


def _double_rolling_residual(a, omega, sin_tL, sin_tR, D, c):
    """Horizontal balance times ``q_L + q_R`` with ``upsilon`` eliminated; increasing through 0."""
    s_L, s_R = np.sin(a * omega), np.sin((1.0 - a) * omega)
    c_L, c_R = np.cos(a * omega), np.cos((1.0 - a) * omega)
    q_L, q_R = np.sqrt(s_L), np.sqrt(s_R)
    return (q_L + q_R) * (s_L * q_L * sin_tL - s_R * q_R * sin_tR) + c * q_L * q_R * (c_L + c_R) * D


def double_rolling_state(gamma, delta, params: Parameters) -> dict:
    """The double-rolling solution (``d_L = d_R = 0``) wherever it is defined.

    Parameters
    ----------
    gamma, delta : ndarray
        Points of the domain (already checked), any broadcastable shapes.
    params : Parameters

    Returns
    -------
    dict of ndarray
        ``beta_L, beta_R, upsilon, n_L, n_R, t, T_over_N_L, T_over_N_R``. On the edge
        ``gamma = pi/2`` (closed groove) no double-rolling state exists and every entry is NaN
        there; on ``delta = gamma < pi/2`` the limit ``beta_L = 0`` (``T/N_L = inf``) is returned.
    """
    gamma, delta = np.broadcast_arrays(np.asarray(gamma, float), np.asarray(delta, float))
    omega = math.pi - 2.0 * gamma
    a = np.full(gamma.shape, np.nan)
    a[(delta == 0.0) & (omega > 0.0)] = 0.5  # symmetric solution, exact
    a[(delta >= gamma) & (omega > 0.0) & (delta > 0.0)] = 0.0  # theta_R = 0: N_L -> 0
    inner = np.isnan(a) & (omega > 0.0)
    if np.any(inner):
        g, d, w = gamma[inner], delta[inner], omega[inner]
        args = (w, np.sin(g + d), np.sin(g - d), 2.0 * np.sin(g) * np.sin(d), params.c)
        res = elementwise.find_root(
            _double_rolling_residual,
            (np.zeros_like(g), np.ones_like(g)),
            args=args,
            tolerances=dict(xatol=1e-300, xrtol=2.0 * _EPS, fatol=0.0, frtol=0.0),
        )
        a[inner] = res.x
    beta_L, beta_R = a * omega, (1.0 - a) * omega
    s_L, s_R, c_L, c_R = np.sin(beta_L), np.sin(beta_R), np.cos(beta_L), np.cos(beta_R)
    q_L, q_R = np.sqrt(s_L), np.sqrt(s_R)
    upsilon = (q_R * c_R - q_L * c_L) / (q_L + q_R)
    t = params.c * q_L * (c_L + upsilon)
    n_L, n_R = s_L * q_L, s_R * q_R
    return dict(
        beta_L=beta_L, beta_R=beta_R, upsilon=upsilon, n_L=n_L, n_R=n_R, t=t,
        T_over_N_L=_ratio(t, n_L), T_over_N_R=_ratio(t, n_R),
    )


def rolling_sliding_state(gamma, delta, params: Parameters) -> dict:
    """The rolling-sliding solution (left wall slides, ``T = k N_L``; right wall rolls).

    Returns
    -------
    dict of ndarray
        ``beta_L, beta_R, upsilon, d_L, mu, n_L, n_R, t``; NaN only at the origin, where
        ``mu`` is ``0/0``.
    """
    gamma, delta = np.broadcast_arrays(np.asarray(gamma, float), np.asarray(delta, float))
    k, c = params.k, params.c
    sin_tL, sin_tR = np.sin(gamma + delta), np.sin(gamma - delta)
    den = 2.0 * np.sin(gamma) * np.sin(delta) + sin_tL / k
    mu = np.full(gamma.shape, np.nan)
    np.divide(sin_tR, den, out=mu, where=den > 0.0)
    rho = np.cbrt(mu / k) ** 2
    beta_L = np.arctan2(rho * np.sin(2.0 * gamma), 1.0 - rho * np.cos(2.0 * gamma))
    beta_R = np.maximum(math.pi - 2.0 * gamma - beta_L, 0.0)
    s_L, s_R, c_L, c_R = np.sin(beta_L), np.sin(beta_R), np.cos(beta_L), np.cos(beta_R)
    upsilon = c_R - mu * s_R / c
    n_L, n_R = s_L * np.sqrt(s_L), s_R * np.sqrt(s_R)
    return dict(
        beta_L=beta_L, beta_R=beta_R, upsilon=upsilon, mu=mu,
        d_L=c_L + upsilon - (k / c) * s_L, n_L=n_L, n_R=n_R, t=k * n_L,
    )


def regime_validity(gamma, delta, k_or_params):
    """Where each regime's own conditions hold, evaluated independently of the other.

    Returns
    -------
    dr_valid, rs_valid : ndarray of bool
        ``T/N <= k`` on both walls for double rolling; ``d_L >= 0`` and ``mu <= k`` for
        rolling sliding. On ``delta = 0`` beyond ``arctan(k/c)`` the rolling-sliding state is
        the double-sliding one (both walls at ``T = kN``).
    """
    params = Parameters.coerce(k_or_params)
    gamma, delta = check_domain(gamma, delta)
    dr = double_rolling_state(gamma, delta, params)
    rs = rolling_sliding_state(gamma, delta, params)
    with np.errstate(invalid="ignore"):
        dr_valid = (dr["T_over_N_L"] <= params.k) & (dr["T_over_N_R"] <= params.k)
        rs_valid = (rs["d_L"] >= 0.0) & (rs["mu"] <= params.k)
    return dr_valid, rs_valid


def solve_equilibrium(gamma, delta, k_or_params) -> Equilibrium:
    """The equilibrium the paper predicts at ``(gamma, delta)`` for friction ``k``.

    Double rolling where it is valid (``T/N <= k`` on both walls), double sliding on
    ``delta = 0`` for ``gamma > arctan(k/c)`` (the symmetric state, ``upsilon = 0``,
    ``d_L = d_R = sin gamma - (k/c) cos gamma``), rolling sliding elsewhere.

    Parameters
    ----------
    gamma, delta : float or array_like
        Half-sum and half-difference of the wall angles, radians, ``0 <= delta <= gamma <= pi/2``.
    k_or_params : float or Parameters
        Friction coefficient, finite and > 0, or a full parameter object.

    Returns
    -------
    Equilibrium
        Fields of the broadcast shape (scalars for scalar input).

    Raises
    ------
    ValueError, TypeError
        For ``k`` or angles outside their ranges (the message names the quantity and range).
    """
    params = Parameters.coerce(k_or_params)
    scalar = np.ndim(gamma) == 0 and np.ndim(delta) == 0
    gamma, delta = check_domain(gamma, delta)
    gamma, delta = np.atleast_1d(gamma), np.atleast_1d(delta)
    k, c = params.k, params.c
    dr = double_rolling_state(gamma, delta, params)
    sliding_both = (delta == 0.0) & (gamma > params.gamma_limit)
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

    for name in ("beta_L", "beta_R", "upsilon", "n_L", "n_R", "t", "T_over_N_L", "T_over_N_R"):
        out[name][use_dr] = dr[name][use_dr]

    if np.any(use_rs):
        rs = rolling_sliding_state(gamma[use_rs], delta[use_rs], params)
        for name in ("beta_L", "beta_R", "upsilon", "d_L", "n_L", "n_R", "t"):
            out[name][use_rs] = rs[name]
        out["T_over_N_L"][use_rs] = k
        out["T_over_N_R"][use_rs] = rs["mu"]
        regime[use_rs] = Regime.ROLLING_SLIDING.value

    if np.any(sliding_both):
        g = gamma[sliding_both]
        beta = 0.5 * math.pi - g
        n = np.cos(g) ** 1.5
        slip = np.sin(g) - (k / c) * np.cos(g)
        for name, value in (("beta_L", beta), ("beta_R", beta), ("upsilon", 0.0), ("d_L", slip),
                            ("d_R", slip), ("T_over_N_L", k), ("T_over_N_R", k),
                            ("n_L", n), ("n_R", n), ("t", k * n)):
            out[name][sliding_both] = value
        regime[sliding_both] = Regime.DOUBLE_SLIDING.value

    out["N_L_over_N_R"] = _ratio(out["n_L"], out["n_R"])
    rotation = np.where(out["upsilon"] < 0.0, Rotation.CLOCKWISE.value,
                        np.where(out["upsilon"] > 0.0, Rotation.COUNTERCLOCKWISE.value,
                                 Rotation.NONE.value)).astype(object)
    theta_L, theta_R = gamma + delta, gamma - delta
    values = dict(out, regime=regime, rotation=rotation, gamma=gamma, delta=delta,
                  theta_L=theta_L, theta_R=theta_R)
    if scalar:
        values = {key: (v[0].item() if hasattr(v[0], "item") else v[0]) for key, v in values.items()}
    return Equilibrium(**values)
