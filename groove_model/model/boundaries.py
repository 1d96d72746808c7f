r"""Residuals, analytic Jacobians, validity functions and seed points of the regime boundaries.

Each boundary is the zero set of three equations in ``x = (gamma, delta, beta_L, upsilon)``
(``docs/model.md``, "The boundaries"). With ``beta_R = pi - 2 gamma - beta_L``,
``s = sin beta``, ``q = sqrt(s)``, ``n = s q`` (scaled normal force), ``A = cos beta_L + upsilon``,
``B = cos beta_R - upsilon``, ``D = cos theta_R - cos theta_L = 2 sin gamma sin delta`` and ``c``
the compliance ratio, the equations are written multiplied out, with no division by
``sin theta_R`` or ``sin beta`` (the paper's Eqs. tran1 and tran2 are these divided through):

=================  ==================================================  ==========================
equation           expression                                          meaning
=================  ==================================================  ==========================
torque (DR)        ``q_L A - q_R B``                                   ``T_L = T_R``
horizontal (DR)    ``n_L sin theta_L - n_R sin theta_R + c q_L A D``   paper Eq. 2
right rolls (RS)   ``c q_R B - k n_L``                                 ``T = k N_L``
horizontal (RS)    ``n_L (sin theta_L + k D) - n_R sin theta_R``       Eq. 2, ``T = k N_L``
limit              ``c A - k s_L``                                     ``T/N_L = k``, ``d_L = 0``
no roll            ``upsilon``                                         ``upsilon = 0``
=================  ==================================================  ==========================

``dr_limit`` = (torque, horizontal DR, limit); ``rs_limit`` = (right rolls, horizontal RS, limit);
``dr_no_roll`` = (torque, horizontal DR, no roll); ``rs_no_roll`` = (right rolls, horizontal RS,
no roll). The Jacobians are derived by hand (product rule on the table above) and checked
against central differences in the tests. ``d q_L / d beta_L = cos beta_L / (2 q_L)`` is
unbounded as ``beta_L -> 0``, where the ``upsilon = 0`` lines end (the corner ``(pi/4, pi/4)``) and
which ``dr_limit`` approaches towards the origin (``beta_L ~ 2 gamma^2 / k``). The chart
``beta_L = w^2`` (``chart="sqrt_beta_L"``) removes that singularity: every residual is analytic
in ``w``, and ``beta_L = 0`` is a regular point where ``w`` changes sign.

Validity functions are ``>= 0`` where the boundary is physical, also multiplied out and divided
by ``sqrt(k^2 + c^2)`` so that they are of order one (and their rounding of order ``eps``) for
every ``k``: ``(k s_L - c A)/r`` (``T/N_L <= k``), ``(k s_R - c B)/r`` (``T/N_R <= k``),
``(c A - k s_L)/r`` (``c d_L / Z >= 0``), ``r = sqrt(k^2 + c^2)``.

In rolling sliding ``T/N_R = mu`` and ``k - mu = 2 k sin(delta) (k sin(gamma) + cos(gamma)) /
(2 k sin(gamma) sin(delta) + sin(theta_L))``, which is ``>= 0`` on the whole domain: the
condition ``T/N_R <= k`` never cuts a rolling-sliding boundary (it only touches zero on
``delta = 0``, where its rounding would fake crossings), so the rolling-sliding boundaries carry
only ``d_L >= 0``. The double-rolling ones carry both wall conditions.
"""

from __future__ import annotations

import enum
import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from .parameters import Parameters

__all__ = [
    "BOUNDARY_NAMES",
    "BoundarySystem",
    "Condition",
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


class Condition(str, enum.Enum):
    """A condition of a regime's validity; the values are the names used in notes and files."""

    T_OVER_N_L = "T_over_N_L <= k"
    T_OVER_N_R = "T_over_N_R <= k"
    SLIP_LEFT = "d_L >= 0"

    def __str__(self) -> str:
        return self.value


def _left_contact(var: float, chart: str):
    """``beta_L``, ``q_L = sqrt(sin beta_L)`` and their derivatives with respect to the chart
    variable.

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


#: nodes and weights of 6-point Gauss-Legendre quadrature on [0, 1]
_GAUSS = tuple(zip((0.5 * (1.0 + t) for t in np.polynomial.legendre.leggauss(6)[0]),
                   (0.5 * w for w in np.polynomial.legendre.leggauss(6)[1]), strict=True))

#: below this |beta_L - beta_R| the divided difference is a quadrature of f'
_DIVIDED_SWITCH = 0.05


def _f1(beta: float) -> float:
    """``f'(beta)`` for ``f = sqrt(sin beta) cos beta``: ``cos^2/(2 sqrt sin) - sin^(3/2)``."""
    s, c = math.sin(beta), math.cos(beta)
    q = math.sqrt(s)
    return c * c / (2.0 * q) - s * q


def _f2(beta: float) -> float:
    """``f''(beta) = -(5/2) cos(beta) q - cos(beta)^3 / (4 q^3)``, ``q = sqrt(sin beta)``."""
    s, c = math.sin(beta), math.cos(beta)
    q = math.sqrt(s)
    return -2.5 * c * q - c * c * c / (4.0 * q * s)


def _deflated_torque(gamma, beta_L, q_L, b1, dq_L, jacobian):
    """The no-roll torque divided by ``beta_L - beta_R``, and its row (dr_no_roll, deflated).

    With ``upsilon = 0`` the torque is ``f(beta_L) - f(beta_R)``, ``f = sqrt(sin beta) cos
    beta``, which vanishes on the whole symmetric family ``beta_L = beta_R`` as well as on
    ``dr_no_roll``. Its divided difference

    .. math:: g = \\frac{f(\\beta_L) - f(\\beta_R)}{\\beta_L - \\beta_R}
                = \\int_0^1 f'(\\beta_R + t(\\beta_L - \\beta_R))\\,dt

    vanishes on ``dr_no_roll`` alone, which crosses the family where ``f' = 0`` (the branch
    point): with ``g`` in place of the torque the branch point is a regular point (deflation,
    Allgower & Georg sec. 8.3). ``g`` is the quotient where ``|beta_L - beta_R| >= 0.05`` and a
    6-point Gauss-Legendre quadrature of ``f'`` (error ``O(d^12)``) closer to the family, where
    the quotient would cancel.
    """
    beta_R = _PI - 2.0 * gamma - beta_L
    d = beta_L - beta_R
    if abs(d) >= _DIVIDED_SWITCH:
        s_R, c_R = math.sin(beta_R), math.cos(beta_R)
        q_R = math.sqrt(s_R) if s_R >= 0.0 else math.nan
        g = (q_L * math.cos(beta_L) - q_R * c_R) / d
        if not jacobian:
            return g, None
        dF_L = dq_L * math.cos(beta_L) - q_L * math.sin(beta_L) * b1  # d f(beta_L) / d var
        g_R = (g - _f1(beta_R)) / d                                   # d g / d beta_R
        g_var = (dF_L - g * b1) / d - g_R * b1
    else:
        g = sum(w * _f1(beta_R + t * d) for t, w in _GAUSS)
        if not jacobian:
            return g, None
        second = [(t, w, _f2(beta_R + t * d)) for t, w in _GAUSS]
        g_L = sum(w * t * f2 for t, w, f2 in second)
        g_R = sum(w * (1.0 - t) * f2 for t, w, f2 in second)
        g_var = (g_L - g_R) * b1
    return g, (-2.0 * g_R, 0.0, g_var, 0.0)


def _rows(x, k, c, system, chart="beta_L", jacobian=True, unit=0.0):
    """Residual (3,) and Jacobian (3, 4) of one boundary system at ``x``; see module table.

    The third coordinate of ``x`` is ``beta_L`` or ``w = sqrt(beta_L)`` (``chart``); its column
    is assembled from ``d beta_L`` (``b1``) and ``d q_L`` (``dq_L``) by the product rule. With
    ``jacobian=False`` only the residual is computed (the rows are ``None``). ``unit > 0``
    selects the conditioned form (:func:`_limit_rows` for the limit curve, the deflated torque
    :func:`_deflated_torque` for ``dr_no_roll``).
    """
    if unit > 0.0 and system.endswith("limit"):
        return _limit_rows(x, k, c, chart, jacobian, unit)
    if unit > 0.0 and system == "dr_no_roll":
        values, rows = _rows(x, k, c, system, chart, jacobian)
        beta_L, q_L, b1, dq_L = _left_contact(float(x[2]), chart)
        values[0], row = _deflated_torque(float(x[0]), beta_L, q_L, b1, dq_L, jacobian)
        if jacobian:
            rows[0] = row
        return values, rows
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


def _limit_rows(x, k, c, chart, jacobian, unit):
    """The limit curve (``dr_limit`` = ``rs_limit``) in a form conditioned for every ``k``.

    On the limit ``c A = k s_L``; the double-rolling horizontal balance then equals the
    rolling-sliding one, and the torque (or right-rolling) equation, combined with the limit,
    loses ``upsilon``:

    .. math::

        \\text{torque} - \\frac{q_L + q_R}{c}\\,\\text{limit}
        = -\\frac{1}{c}\\left[2 c\\, q_R \\sin\\gamma \\sin(\\beta_L + \\gamma)
          - k s_L (q_L + q_R)\\right] = -\\frac{C}{c},

    using ``cos beta_L + cos beta_R = 2 sin(gamma) sin(beta_L + gamma)``. The rows are
    ``(c A - k s_L, h / unit, C / unit)`` with ``h`` the rolling-sliding horizontal balance:
    the same zero set as ``dr_limit`` and as ``rs_limit``, but where ``gamma`` and ``k`` are
    small (``unit ~ arctan(k/c)``) the torque and limit rows of the paper's form are parallel
    up to terms of order ``gamma``, and ``h`` is of order ``gamma``; here every row is of order
    one with independent gradients, and ``C`` has no cancellation.
    """
    gamma, delta, upsilon = float(x[0]), float(x[1]), float(x[3])
    beta_L, q_L, b1, dq_L = _left_contact(float(x[2]), chart)
    beta_R = _PI - 2.0 * gamma - beta_L
    s_L, c_L, s_R, c_R = math.sin(beta_L), math.cos(beta_L), math.sin(beta_R), math.cos(beta_R)
    q_R = math.sqrt(s_R) if s_R >= 0.0 else math.nan
    n_L, n_R = s_L * q_L, s_R * q_R
    theta_L, theta_R = gamma + delta, gamma - delta
    sin_tL, sin_tR = math.sin(theta_L), math.sin(theta_R)
    sin_g, sin_d = math.sin(gamma), math.sin(delta)
    D = 2.0 * sin_g * sin_d
    sin_bg, cos_bg = math.sin(beta_L + gamma), math.cos(beta_L + gamma)
    values = [c * (c_L + upsilon) - k * s_L,
              (n_L * (sin_tL + k * D) - n_R * sin_tR) / unit,
              (2.0 * c * q_R * sin_g * sin_bg - k * s_L * (q_L + q_R)) / unit]
    if not jacobian:
        return values, None
    cos_tL, cos_tR = math.cos(theta_L), math.cos(theta_R)
    cos_g, cos_d = math.cos(gamma), math.cos(delta)
    D_g, D_d = 2.0 * cos_g * sin_d, 2.0 * sin_g * cos_d
    qR_beta = -c_R / (2.0 * q_R) if q_R != 0.0 else -math.inf  # d q_R / d beta_L
    nR_beta = -1.5 * q_R * c_R                                  # d n_R / d beta_L
    ds_L = c_L * b1
    dn_L = ds_L * q_L + s_L * dq_L
    dq_R, dn_R = qR_beta * b1, nR_beta * b1
    qR_gamma = 2.0 * qR_beta                                    # beta_R = pi - 2 gamma - beta_L
    rows = [(0.0, 0.0, -c * s_L * b1 - k * ds_L, c),
            ((n_L * (cos_tL + k * D_g) - 2.0 * nR_beta * sin_tR - n_R * cos_tR) / unit,
             (n_L * (cos_tL + k * D_d) + n_R * cos_tR) / unit,
             (dn_L * (sin_tL + k * D) - dn_R * sin_tR) / unit, 0.0),
            ((2.0 * c * (qR_gamma * sin_g * sin_bg + q_R * cos_g * sin_bg + q_R * sin_g * cos_bg)
              - k * s_L * qR_gamma) / unit,
             0.0,
             (2.0 * c * sin_g * (dq_R * sin_bg + q_R * cos_bg * b1)
              - k * (ds_L * (q_L + q_R) + s_L * (dq_L + dq_R))) / unit,
             0.0)]
    return values, rows


@dataclass(frozen=True)
class BoundarySystem:
    """One regime boundary as ``H(x) = 0``, ``H: R^4 -> R^3``,
    ``x = (gamma, delta, beta_L, upsilon)``.

    Attributes
    ----------
    name : str
        One of ``BOUNDARY_NAMES``.
    params : Parameters
    chart : str
        ``"beta_L"`` (default): ``x = (gamma, delta, beta_L, upsilon)``. ``"sqrt_beta_L"``:
        ``y = (gamma / scale, delta / scale, w, upsilon)`` with ``beta_L = w^2``, the smooth form
        the tracer uses (see :func:`_left_contact`); :meth:`to_x` and :meth:`from_x` convert.
    scale : float
        Unit of ``gamma`` and ``delta`` in the chart (``"sqrt_beta_L"`` only, default 1): the
        limit boundaries of a small ``k`` live in ``gamma <= arctan(k/c)``, and in units of that
        size every coordinate of the curve is of order one, as the step control assumes.
    conditioned : bool
        The form the tracer uses, with the same zero set as the paper's rows but well
        conditioned for every ``k``: for ``dr_limit`` and ``rs_limit`` the conditioned form of
        the one limit curve (:func:`_limit_rows`, rows divided by ``scale``); for
        ``dr_no_roll`` the deflated torque (:func:`_deflated_torque`), which makes its branch
        point a regular point. Not for ``rs_no_roll``.
    regime : str
        The regime whose equations it uses (``double_rolling`` or ``rolling_sliding``).
    validity : dict of Condition to callable
        ``condition -> f(x)`` at chart coordinates, ``f >= 0`` where the boundary is physical
        (its regime valid).
    """

    name: str
    params: Parameters
    chart: str = "beta_L"
    scale: float = 1.0
    conditioned: bool = False
    regime: str = field(init=False)
    validity: dict = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if self.name not in BOUNDARY_NAMES:
            raise ValueError(f"boundary = {self.name!r} is not one of {', '.join(BOUNDARY_NAMES)}")
        if self.chart not in CHARTS:
            raise ValueError(f"chart = {self.chart!r} is not one of {', '.join(CHARTS)}")
        if not (math.isfinite(self.scale) and self.scale > 0.0) or (
                self.chart == "beta_L" and self.scale != 1.0):
            raise ValueError(f"scale = {self.scale!r} must be finite and > 0 (and 1 in the "
                             "beta_L chart)")
        if self.conditioned and self.name == "rs_no_roll":
            raise ValueError("conditioned=True is for dr_limit, rs_limit and dr_no_roll, not "
                             "rs_no_roll")
        k, c = self.params.k, self.params.c
        r = math.hypot(k, c)
        scale = self.scale
        beta = (lambda y: y[2]) if self.chart == "beta_L" else (lambda y: y[2] * y[2])

        def tn_left(y):
            return (k * math.sin(beta(y)) - c * (math.cos(beta(y)) + y[3])) / r

        def tn_right(y):
            beta_R = _PI - 2.0 * scale * y[0] - beta(y)
            return (k * math.sin(beta_R) - c * (math.cos(beta_R) - y[3])) / r

        def slip_left(y):
            return (c * (math.cos(beta(y)) + y[3]) - k * math.sin(beta(y))) / r

        checks: dict[Condition, Callable] = {
            "dr_limit": {Condition.T_OVER_N_R: tn_right},
            "rs_limit": {},
            "dr_no_roll": {Condition.T_OVER_N_L: tn_left, Condition.T_OVER_N_R: tn_right},
            "rs_no_roll": {Condition.SLIP_LEFT: slip_left},
        }[self.name]
        object.__setattr__(self, "regime", REGIME_OF[self.name])
        object.__setattr__(self, "validity", checks)

    def _unscaled(self, y):
        if self.scale == 1.0:
            return y
        return (y[0] * self.scale, y[1] * self.scale, y[2], y[3])

    @property
    def _unit(self) -> float:
        return self.scale if self.conditioned else 0.0

    def residual(self, x) -> np.ndarray:
        """``H(x)``, shape (3,), at chart coordinates ``x``."""
        values, _ = _rows(self._unscaled(x), self.params.k, self.params.c, self.name,
                          self.chart, jacobian=False, unit=self._unit)
        return np.array(values)

    def jacobian(self, x) -> np.ndarray:
        """``dH/dx``, shape (3, 4), analytic, with respect to the chart coordinates."""
        _, rows = _rows(self._unscaled(x), self.params.k, self.params.c, self.name, self.chart,
                        unit=self._unit)
        J = np.array(rows)
        if self.scale != 1.0:
            J[:, :2] *= self.scale
        return J

    def residual_and_jacobian(self, x):
        """Both at once (one evaluation of the shared trigonometry)."""
        values, rows = _rows(self._unscaled(x), self.params.k, self.params.c, self.name,
                             self.chart, unit=self._unit)
        J = np.array(rows)
        if self.scale != 1.0:
            J[:, :2] *= self.scale
        return np.array(values), J

    def to_x(self, y) -> np.ndarray:
        """Chart coordinates (any shape ``(..., 4)``) to ``x = (gamma, delta, beta_L, upsilon)``."""
        x = np.array(y, dtype=float)
        if self.chart == "sqrt_beta_L":
            x[..., :2] *= self.scale
            x[..., 2] = x[..., 2] ** 2
        return x

    def from_x(self, x) -> np.ndarray:
        """``x = (gamma, delta, beta_L, upsilon)`` (``beta_L >= 0``) to chart coordinates."""
        y = np.array(x, dtype=float)
        if self.chart == "sqrt_beta_L":
            y[..., :2] /= self.scale
            y[..., 2] = np.sqrt(y[..., 2])
        return y

    @property
    def row_scales(self) -> np.ndarray:
        """The size of the terms of each equation (paper's form), shape (3,).

        ``|H_i(x)| / scale_i`` is the residual relative to the equation's terms, whose rounding
        is of order ``eps`` for every ``k`` and ``c``: 1 for the torque and ``upsilon = 0``,
        ``max(1, c)`` for the double-rolling horizontal balance, ``sqrt(k^2 + c^2)`` for the
        limit and the rolling right wall, ``1 + k`` for the rolling-sliding horizontal balance.
        """
        k, c = self.params.k, self.params.c
        r = math.hypot(k, c)
        first, second = (1.0, max(1.0, c)) if self.name.startswith("dr") else (r, 1.0 + k)
        return np.array([first, second, r if self.name.endswith("limit") else 1.0])

    def scaled_residual(self, x) -> float:
        """``max_i |H_i(x)| / scale_i`` (see :attr:`row_scales`), in the paper's form."""
        paper = self if not self.conditioned else BoundarySystem(self.name, self.params,
                                                                   self.chart, self.scale)
        return float(np.max(np.abs(paper.residual(x)) / self.row_scales))

    def is_physical(self, x, tol: float = 0.0) -> bool:
        """Whether every validity function is ``>= -tol`` at ``x``."""
        return all(f(x) >= -tol for f in self.validity.values())


def boundary_system(name: str, k_or_params, chart: str = "beta_L",
                    scale: float = 1.0) -> BoundarySystem:
    """The boundary system ``name`` for friction ``k`` (or a :class:`Parameters`)."""
    params = Parameters.coerce(k_or_params)
    return BoundarySystem(name, params, chart, scale)


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
    """``(arctan sqrt 2, 0, arctan(1/sqrt 2), 0)``: where ``dr_no_roll`` leaves the symmetric
    family.

    Notes
    -----
    On the symmetric family ``beta_L = beta_R = beta`` the torque equation with ``upsilon = 0``
    is ``f(beta_L) = f(beta_R)``, ``f(beta) = sqrt(sin beta) cos beta``. Perturbing
    antisymmetrically, ``beta_{L,R} = beta +- e``, its linear part is ``2 f'(beta) e``, so a second
    branch can leave only where ``f'(beta) = cos^2 beta / (2 sqrt(sin beta)) - sin^(3/2) beta = 0``,
    that is ``tan beta = 1/sqrt 2``, ``gamma = pi/2 - beta = arctan sqrt 2``, for any ``k`` and
    ``c``.
    """
    return _symmetric_point(math.atan(math.sqrt(2.0)))


def corner_point() -> np.ndarray:
    """``(pi/4, pi/4, 0, 0)``: the singular end of both ``upsilon = 0`` lines.

    There ``theta_R = 0``, ``beta_L = 0`` (``N_L = 0``) and ``beta_R = pi/2``; every boundary
    residual vanishes, but ``d q_L / d beta_L`` is unbounded.
    """
    return np.array([0.25 * _PI, 0.25 * _PI, 0.0, 0.0])
