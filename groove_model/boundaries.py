r"""Residuals, analytic Jacobians, validity functions and seed points of the regime boundaries.

Each boundary is the zero set of three equations in ``x = (gamma, delta, beta_L, upsilon)``.
With ``beta_R = pi - 2 gamma - beta_L``,
``s = sin beta``, ``q = sqrt(s)``, ``n = s q`` (scaled normal force), ``A = cos beta_L + upsilon``,
``B = cos beta_R - upsilon``, ``D = cos theta_R - cos theta_L = 2 sin gamma sin delta`` and ``c``
the compliance ratio, the equations are written multiplied out, with no division by
``sin theta_R`` or ``sin beta`` (the paper's Eqs. tran1 and tran2 are these divided through):

=================  ===========================================================  ============
equation           expression                                                   meaning
=================  ===========================================================  ============
torque (DR)        ``q_L A - q_R B``                                            ``T_L = T_R``
horizontal (DR)    ``n_L sin theta_L - n_R sin theta_R + c q_L A D``            paper Eq. 2
right rolls (RS)   ``c q_R B - k n_L``                                          ``T = k N_L``
horizontal (RS)    ``n_L (sin theta_L + k D) - n_R sin theta_R``                Eq. 2, ``T = k N_L``
limit              ``c A - k s_L``                                              ``T/N_L = k``, ``d_L = 0``
no roll            ``upsilon``                                                  ``upsilon = 0``
=================  ===========================================================  ============

``dr_limit`` = (torque, horizontal DR, limit); ``rs_limit`` = (right rolls, horizontal RS, limit);
``dr_no_roll`` = (torque, horizontal DR, no roll); ``rs_no_roll`` = (right rolls, horizontal RS,
no roll). The Jacobians are derived by hand (product rule on the table above) and checked
against central differences in the tests. ``d q_L / d beta_L = cos beta_L / (2 q_L)`` is
unbounded as ``beta_L -> 0``, where the ``upsilon = 0`` lines end (the corner ``(pi/4, pi/4)``) and
which ``dr_limit`` approaches towards the origin (``beta_L ~ 2 gamma^2 / k``). The chart
``beta_L = w^2`` (``chart="sqrt_beta_L"``) removes that singularity: every residual is analytic
in ``w``, and ``beta_L = 0`` is a regular point where ``w`` changes sign.

Validity functions are ``>= 0`` where the boundary is physical, also multiplied out:
``k s_L - c A`` (``T/N_L <= k``), ``k s_R - c B`` (``T/N_R <= k``, which is ``mu <= k`` in RS),
``c A - k s_L`` (``c d_L / Z >= 0``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from .parameters import Parameters

__all__ = [
    "BOUNDARY_NAMES",
    "BoundarySystem",
    "boundary_system",
    "corner_point",
    "dr_no_roll_branch_point",
    "limit_seed",
]

BOUNDARY_NAMES = ("dr_limit", "rs_limit", "dr_no_roll", "rs_no_roll")
CHARTS = ("beta_L", "sqrt_beta_L")
REGIME_OF = {"dr_limit": "double_rolling", "rs_limit": "rolling_sliding",
             "dr_no_roll": "double_rolling", "rs_no_roll": "rolling_sliding"}
_PI = math.pi


def _left_contact(var: float, chart: str):
    """``beta_L``, ``q_L = sqrt(sin beta_L)`` and their derivatives with respect to the chart variable.

    In the ``"beta_L"`` chart the variable is ``beta_L`` itself and ``d q_L / d beta_L =
    cos beta_L / (2 q_L)`` is unbounded as ``beta_L -> 0``. In the ``"sqrt_beta_L"`` chart the
    variable is ``w`` with ``beta_L = w^2``, and ``q_L = w sqrt(sin(w^2) / w^2)`` is analytic
    (odd in ``w``), so the ends ``beta_L = 0`` become regular points where ``w`` crosses 0.
    """
    if chart == "beta_L":
        beta_L = var
        s_L = math.sin(beta_L)
        # Outside 0 <= beta_L <= pi the state is not a contact: NaN, which the engine rejects.
        q_L = math.sqrt(s_L) if s_L >= 0.0 else math.nan
        dq_L = math.cos(beta_L) / (2.0 * q_L) if q_L != 0.0 else math.inf
        return beta_L, q_L, 1.0, dq_L
    w2 = var * var
    # sin(w^2) / w^2 = 1 - w^4/6 + ..., evaluated without cancellation near w = 0.
    ratio = math.sin(w2) / w2 if w2 > 1e-4 else 1.0 - w2 * w2 / 6.0
    r = math.sqrt(ratio) if ratio >= 0.0 else math.nan
    return w2, var * r, 2.0 * var, math.cos(w2) / r


def _rows(x, k, c, system, chart="beta_L", jacobian=True):
    """Residual (3,) and Jacobian (3, 4) of one boundary system at ``x``; see module table.

    The third coordinate of ``x`` is ``beta_L`` or ``w = sqrt(beta_L)`` (``chart``); its column
    is assembled from ``d beta_L`` (``b1``) and ``d q_L`` (``dq_L``) by the product rule. With
    ``jacobian=False`` only the residual is computed (the rows are ``None``).
    """
    gamma, delta, upsilon = float(x[0]), float(x[1]), float(x[3])
    beta_L, q_L, b1, dq_L = _left_contact(float(x[2]), chart)
    beta_R = _PI - 2.0 * gamma - beta_L
    s_L, c_L, s_R, c_R = math.sin(beta_L), math.cos(beta_L), math.sin(beta_R), math.cos(beta_R)
    q_R = math.sqrt(s_R) if s_R >= 0.0 else math.nan
    n_L, n_R = s_L * q_L, s_R * q_R
    A, B = c_L + upsilon, c_R - upsilon
    theta_L, theta_R = gamma + delta, gamma - delta
    sin_tL, sin_tR = math.sin(theta_L), math.sin(theta_R)
    sin_g, sin_d = math.sin(gamma), math.sin(delta)
    D = 2.0 * sin_g * sin_d
    dr = system.startswith("dr")
    if dr:
        values = [q_L * A - q_R * B, n_L * sin_tL - n_R * sin_tR + c * q_L * A * D]
    else:
        values = [c * q_R * B - k * n_L, n_L * (sin_tL + k * D) - n_R * sin_tR]
    limit = system.endswith("limit")
    values.append(c * A - k * s_L if limit else upsilon)
    if not jacobian:
        return values, None

    cos_tL, cos_tR = math.cos(theta_L), math.cos(theta_R)
    cos_g, cos_d = math.cos(gamma), math.cos(delta)
    D_g, D_d = 2.0 * cos_g * sin_d, 2.0 * sin_g * cos_d
    # beta_R = pi - 2 gamma - beta_L: d/d gamma = -2, d/d(chart variable) = -b1.
    qR_beta = -c_R / (2.0 * q_R) if q_R != 0.0 else -math.inf  # d q_R / d beta_L
    nR_beta = -1.5 * q_R * c_R                                  # d n_R / d beta_L
    # Derivatives with respect to the chart variable.
    dA, dB, ds_L = -s_L * b1, s_R * b1, c_L * b1
    dn_L = ds_L * q_L + s_L * dq_L
    dq_R, dn_R = qR_beta * b1, nR_beta * b1
    if dr:
        rows = [(-(2.0 * qR_beta * B + 2.0 * q_R * s_R), 0.0,
                 dq_L * A + q_L * dA - dq_R * B - q_R * dB, q_L + q_R),
                (n_L * cos_tL - 2.0 * nR_beta * sin_tR - n_R * cos_tR + c * q_L * A * D_g,
                 n_L * cos_tL + n_R * cos_tR + c * q_L * A * D_d,
                 dn_L * sin_tL - dn_R * sin_tR + c * D * (dq_L * A + q_L * dA),
                 c * q_L * D)]
    else:
        rows = [(c * (2.0 * qR_beta * B + 2.0 * q_R * s_R), 0.0,
                 c * (dq_R * B + q_R * dB) - k * dn_L, -c * q_R),
                (n_L * (cos_tL + k * D_g) - 2.0 * nR_beta * sin_tR - n_R * cos_tR,
                 n_L * (cos_tL + k * D_d) + n_R * cos_tR,
                 dn_L * (sin_tL + k * D) - dn_R * sin_tR, 0.0)]
    rows.append((0.0, 0.0, c * dA - k * ds_L, c) if limit else (0.0, 0.0, 0.0, 1.0))
    return values, rows


@dataclass(frozen=True)
class BoundarySystem:
    """One regime boundary as ``H(x) = 0``, ``H: R^4 -> R^3``, ``x = (gamma, delta, beta_L, upsilon)``.

    Attributes
    ----------
    name : str
        One of ``BOUNDARY_NAMES``.
    params : Parameters
    chart : str
        ``"beta_L"`` (default): ``x = (gamma, delta, beta_L, upsilon)``. ``"sqrt_beta_L"``:
        ``y = (gamma, delta, w, upsilon)`` with ``beta_L = w^2``, the smooth form the tracer
        uses (see :func:`_left_contact`); :meth:`to_x` and :meth:`from_x` convert.
    regime : str
        The regime whose equations it uses (``double_rolling`` or ``rolling_sliding``).
    validity : dict of str to callable
        ``name -> f(x)``, ``f >= 0`` where the boundary is physical (its regime valid).
    """

    name: str
    params: Parameters
    chart: str = "beta_L"
    regime: str = field(init=False)
    validity: dict = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if self.name not in BOUNDARY_NAMES:
            raise ValueError(f"boundary = {self.name!r} is not one of {', '.join(BOUNDARY_NAMES)}")
        if self.chart not in CHARTS:
            raise ValueError(f"chart = {self.chart!r} is not one of {', '.join(CHARTS)}")
        k, c = self.params.k, self.params.c
        beta = (lambda y: y[2]) if self.chart == "beta_L" else (lambda y: y[2] * y[2])

        def tn_left(x):
            return k * math.sin(beta(x)) - c * (math.cos(beta(x)) + x[3])

        def tn_right(x):
            beta_R = _PI - 2.0 * x[0] - beta(x)
            return k * math.sin(beta_R) - c * (math.cos(beta_R) - x[3])

        def slip_left(x):
            return c * (math.cos(beta(x)) + x[3]) - k * math.sin(beta(x))

        checks: dict[str, Callable] = {
            "dr_limit": {"T_over_N_R <= k": tn_right},
            "rs_limit": {"T_over_N_R <= k": tn_right},
            "dr_no_roll": {"T_over_N_L <= k": tn_left, "T_over_N_R <= k": tn_right},
            "rs_no_roll": {"d_L >= 0": slip_left, "T_over_N_R <= k": tn_right},
        }[self.name]
        object.__setattr__(self, "regime", REGIME_OF[self.name])
        object.__setattr__(self, "validity", checks)

    def residual(self, x) -> np.ndarray:
        """``H(x)``, shape (3,)."""
        values, _ = _rows(x, self.params.k, self.params.c, self.name, self.chart,
                          jacobian=False)
        return np.array(values)

    def jacobian(self, x) -> np.ndarray:
        """``dH/dx``, shape (3, 4), analytic."""
        _, rows = _rows(x, self.params.k, self.params.c, self.name, self.chart)
        return np.array(rows)

    def residual_and_jacobian(self, x):
        """Both at once (one evaluation of the shared trigonometry)."""
        values, rows = _rows(x, self.params.k, self.params.c, self.name, self.chart)
        return np.array(values), np.array(rows)

    def to_x(self, y) -> np.ndarray:
        """Chart coordinates (any shape ``(..., 4)``) to ``x = (gamma, delta, beta_L, upsilon)``."""
        x = np.array(y, dtype=float)
        if self.chart == "sqrt_beta_L":
            x[..., 2] = x[..., 2] ** 2
        return x

    def from_x(self, x) -> np.ndarray:
        """``x = (gamma, delta, beta_L, upsilon)`` (``beta_L >= 0``) to chart coordinates."""
        y = np.array(x, dtype=float)
        if self.chart == "sqrt_beta_L":
            y[..., 2] = np.sqrt(y[..., 2])
        return y

    def is_physical(self, x, tol: float = 0.0) -> bool:
        """Whether every validity function is ``>= -tol`` at ``x``."""
        return all(f(x) >= -tol for f in self.validity.values())


def boundary_system(name: str, k_or_params, chart: str = "beta_L") -> BoundarySystem:
    """The boundary system ``name`` for friction ``k`` (or a :class:`Parameters`)."""
    params = Parameters.coerce(k_or_params)
    return BoundarySystem(name, params, chart)


def _symmetric_point(gamma: float) -> np.ndarray:
    return np.array([gamma, 0.0, 0.5 * _PI - gamma, 0.0])


def limit_seed(params: Parameters) -> np.ndarray:
    """``(arctan(k/c), 0, pi/2 - arctan(k/c), 0)``: start of ``dr_limit`` and ``rs_limit``.

    On ``delta = 0`` the symmetric state has ``T/N = c tan gamma`` (paper, below Eq. tran2),
    which reaches ``k`` at ``gamma = arctan(k/c)`` (``arctan k`` for the paper's ``c = 1``).
    It is also where the rolling-sliding ``upsilon = upsilon(beta_R)`` vanishes on
    ``delta = 0``, the start of ``rs_no_roll`` when ``k < sqrt 2``.
    """
    return _symmetric_point(params.gamma_limit)


def dr_no_roll_branch_point() -> np.ndarray:
    """``(arctan sqrt 2, 0, arctan(1/sqrt 2), 0)``: where ``dr_no_roll`` leaves the symmetric family.

    Notes
    -----
    On the symmetric family ``beta_L = beta_R = beta`` the torque equation with ``upsilon = 0``
    is ``f(beta_L) = f(beta_R)``, ``f(beta) = sqrt(sin beta) cos beta``. Perturbing
    antisymmetrically, ``beta_{L,R} = beta +- e``, its linear part is ``2 f'(beta) e``, so a second
    branch can leave only where ``f'(beta) = cos^2 beta / (2 sqrt(sin beta)) - sin^(3/2) beta = 0``,
    that is ``tan beta = 1/sqrt 2``, ``gamma = pi/2 - beta = arctan sqrt 2``, for any ``k`` and ``c``.
    """
    return _symmetric_point(math.atan(math.sqrt(2.0)))


def corner_point() -> np.ndarray:
    """``(pi/4, pi/4, 0, 0)``: the singular end of both ``upsilon = 0`` lines.

    There ``theta_R = 0``, ``beta_L = 0`` (``N_L = 0``) and ``beta_R = pi/2``; every boundary
    residual vanishes, but ``d q_L / d beta_L`` is unbounded.
    """
    return np.array([0.25 * _PI, 0.25 * _PI, 0.0, 0.0])
