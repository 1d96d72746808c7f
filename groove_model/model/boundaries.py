r"""Residuals, analytic Jacobians, validity functions and seed points of the regime boundaries.

Each boundary is the zero set of three equations in ``x = (gamma, delta, beta_L, upsilon)``
(``docs/model.md``, "The boundaries"). With ``beta_R = pi - 2 gamma - beta_L``,
``s = sin beta``, ``q = sqrt(s)``, ``n = s q`` (scaled normal force), ``A = cos beta_L + upsilon``,
``B = cos beta_R - upsilon``, ``D = cos theta_R - cos theta_L = 2 sin gamma sin delta`` and ``c``
the compliance ratio, the equations are written multiplied out, with no division by
``sin theta_R`` or ``sin beta`` (the paper's Eqs. tran1 and tran2 are these divided through):

=================  =================================================  ==========================
equation           expression                                         meaning
=================  =================================================  ==========================
torque (DR)        ``q_L A - q_R B``                                  ``T_L = T_R``
horizontal (DR)    ``n_L sin theta_L - n_R sin theta_R + c q_L A D``  paper Eq. 2
right rolls (RS)   ``c q_R B - k n_L``                                ``T = k N_L``
horizontal (RS)    ``n_L (sin theta_L + k D) - n_R sin theta_R``      Eq. 2, ``T = k N_L``
limit              ``c A - k s_L``                                    ``T/N_L = k``, ``d_L = 0``
no roll            ``upsilon``                                        ``upsilon = 0``
=================  =================================================  ==========================

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

from continuation.numbers import ARRAYS, FLOATS, quotient

from .deflation import deflated_torque
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


def _split(ys) -> list:
    """The four columns of the points ``ys`` (``(n, 4)``, or one point ``(4,)``)."""
    ys = np.asarray(ys, dtype=float).reshape(-1, 4)
    return [ys[:, i] for i in range(4)]


def _quiet() -> np.errstate:
    """Over arrays, as over floats, an infinite or undefined intermediate gives NaN or inf
    silently (``inf * 0`` at the contact's ends); where ``math`` would raise (``sin(inf)``),
    NaN."""
    return np.errstate(invalid="ignore", over="ignore", divide="ignore")


class Condition(str, enum.Enum):
    """A condition of a regime's validity; the values are the names used in notes and files."""

    T_OVER_N_L = "T_over_N_L <= k"
    T_OVER_N_R = "T_over_N_R <= k"
    SLIP_LEFT = "d_L >= 0"

    def __str__(self) -> str:
        return self.value


def _left_contact(var, chart: str, m):
    """``beta_L``, ``q_L = sqrt(sin beta_L)`` and their derivatives w.r.t. the chart variable.

    In the ``"beta_L"`` chart the variable is ``beta_L`` itself and ``d q_L / d beta_L =
    cos beta_L / (2 q_L)`` is unbounded as ``beta_L -> 0``. In the ``"sqrt_beta_L"`` chart the
    variable is ``w`` with ``beta_L = w^2``, and ``q_L = w sqrt(sin(w^2) / w^2)`` is analytic
    (odd in ``w``), so the ends ``beta_L = 0`` become regular points where ``w`` crosses 0.
    Outside ``0 <= beta_L <= pi`` the state is not a contact: ``m.sqrt`` gives NaN (a
    non-finite ball), which the engine rejects.
    """
    if chart == "beta_L":
        q_L = m.sqrt(m.sin(var))
        dq_L = quotient(m.cos(var), 2.0 * q_L, math.inf)
        return var, q_L, 1.0, dq_L
    w2 = var * var
    r = m.sqrt(m.sinc(w2))
    return w2, var * r, 2.0 * var, m.cos(w2) / r


def _rows(x, k, c, system, chart, m, jacobian=True, unit=0.0):
    """Residual (3,) and Jacobian (3, 4) of one boundary system at ``x``; see module table.

    ``x`` is a sequence of four numbers of the namespace ``m`` (:mod:`continuation.numbers`);
    the third is ``beta_L`` or ``w = sqrt(beta_L)`` (``chart``); its column is assembled from
    ``d beta_L`` (``b1``) and ``d q_L`` (``dq_L``) by the product rule. With ``jacobian=False``
    only the residual is computed (the rows are ``None``). ``unit > 0`` selects the
    conditioned form (:func:`_limit_rows` for the limit curve, the deflated torque
    :func:`~groove_model.model.deflation.deflated_torque` for ``dr_no_roll``).
    """
    if unit > 0.0 and system.endswith("limit"):
        return _limit_rows(x, k, c, chart, m, jacobian, unit)
    if unit > 0.0 and system == "dr_no_roll":
        values, rows = _rows(x, k, c, system, chart, m, jacobian)
        beta_L, q_L, b1, dq_L = _left_contact(x[2], chart, m)
        values[0], row = deflated_torque(x[0], beta_L, q_L, b1, dq_L, jacobian, m)
        if jacobian:
            rows[0] = row
        return values, rows
    gamma, delta, upsilon = x[0], x[1], x[3]
    beta_L, q_L, b1, dq_L = _left_contact(x[2], chart, m)
    beta_R = m.pi - 2.0 * gamma - beta_L
    s_L, c_L, s_R, c_R = m.sin(beta_L), m.cos(beta_L), m.sin(beta_R), m.cos(beta_R)
    q_R = m.sqrt(s_R)
    n_L, n_R = s_L * q_L, s_R * q_R
    A, B = c_L + upsilon, c_R - upsilon
    theta_L, theta_R = gamma + delta, gamma - delta
    sin_tL, sin_tR = m.sin(theta_L), m.sin(theta_R)
    sin_g, sin_d = m.sin(gamma), m.sin(delta)
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

    cos_tL, cos_tR = m.cos(theta_L), m.cos(theta_R)
    cos_g, cos_d = m.cos(gamma), m.cos(delta)
    D_g, D_d = 2.0 * cos_g * sin_d, 2.0 * sin_g * cos_d
    # beta_R = pi - 2 gamma - beta_L: d/d gamma = -2, d/d(chart variable) = -b1.
    qR_beta = quotient(-c_R, 2.0 * q_R, -math.inf)             # d q_R / d beta_L
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


def _limit_rows(x, k, c, chart, m, jacobian, unit):
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
    gamma, delta, upsilon = x[0], x[1], x[3]
    beta_L, q_L, b1, dq_L = _left_contact(x[2], chart, m)
    beta_R = m.pi - 2.0 * gamma - beta_L
    s_L, c_L, s_R, c_R = m.sin(beta_L), m.cos(beta_L), m.sin(beta_R), m.cos(beta_R)
    q_R = m.sqrt(s_R)
    n_L, n_R = s_L * q_L, s_R * q_R
    theta_L, theta_R = gamma + delta, gamma - delta
    sin_tL, sin_tR = m.sin(theta_L), m.sin(theta_R)
    sin_g, sin_d = m.sin(gamma), m.sin(delta)
    D = 2.0 * sin_g * sin_d
    sin_bg, cos_bg = m.sin(beta_L + gamma), m.cos(beta_L + gamma)
    values = [c * (c_L + upsilon) - k * s_L,
              (n_L * (sin_tL + k * D) - n_R * sin_tR) / unit,
              (2.0 * c * q_R * sin_g * sin_bg - k * s_L * (q_L + q_R)) / unit]
    if not jacobian:
        return values, None
    cos_tL, cos_tR = m.cos(theta_L), m.cos(theta_R)
    cos_g, cos_d = m.cos(gamma), m.cos(delta)
    D_g, D_d = 2.0 * cos_g * sin_d, 2.0 * sin_g * cos_d
    qR_beta = quotient(-c_R, 2.0 * q_R, -math.inf)             # d q_R / d beta_L
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
    """One regime boundary ``H(x) = 0``, ``H: R^4 -> R^3``, ``x = (gamma, delta, beta_L, upsilon)``.

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
    validity_gradient : dict of Condition to callable
        ``condition -> grad f(x)`` (floats, shape (4,)), derived by hand and checked against
        central differences in the tests.
    certified_validity : dict of Condition to callable
        The same conditions in the form certification uses: the validity function itself,
        except ``T/N_R <= k`` on ``dr_limit``, which on the limit curve has the sign of
        ``k cos(gamma) - c sin(gamma)``: with ``c upsilon = k s_L - c cos beta_L`` there,
        ``k s_R - c (cos beta_R - upsilon) = k (s_L + s_R) - c (cos beta_L + cos beta_R)
        = 2 cos((beta_L - beta_R)/2) (k cos gamma - c sin gamma)`` (``beta_L + beta_R =
        pi - 2 gamma``), so ``T/N_R <= k`` exactly where ``gamma <= arctan(k/c)``; for small
        ``k`` the validity function is of order ``k^2`` along the curve and its enclosures
        would not separate it from zero.
    """

    name: str
    params: Parameters
    chart: str = "beta_L"
    scale: float = 1.0
    conditioned: bool = False
    regime: str = field(init=False)
    validity: dict = field(init=False, repr=False, compare=False)
    validity_gradient: dict = field(init=False, repr=False, compare=False)
    certified_validity: dict = field(init=False, repr=False, compare=False)
    _kept: tuple | None = field(init=False, repr=False, compare=False, default=None)

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
        sqrt_chart = self.chart == "sqrt_beta_L"

        def tn_left(y, numbers=FLOATS):
            beta_L = y[2] * y[2] if sqrt_chart else y[2]
            return (k * numbers.sin(beta_L) - c * (numbers.cos(beta_L) + y[3])) / r

        def tn_right(y, numbers=FLOATS):
            beta_R = numbers.pi - 2.0 * scale * y[0] - (y[2] * y[2] if sqrt_chart else y[2])
            return (k * numbers.sin(beta_R) - c * (numbers.cos(beta_R) - y[3])) / r

        def slip_left(y, numbers=FLOATS):
            beta_L = y[2] * y[2] if sqrt_chart else y[2]
            return (c * (numbers.cos(beta_L) + y[3]) - k * numbers.sin(beta_L)) / r

        def tn_left_gradient(y):
            w = y[2]
            beta_L, d_beta = (w * w, 2.0 * w) if sqrt_chart else (w, 1.0)
            slope = (k * math.cos(beta_L) + c * math.sin(beta_L)) / r
            return np.array([0.0, 0.0, slope * d_beta, -c / r])

        def tn_right_gradient(y):
            w = y[2]
            beta_L, d_beta = (w * w, 2.0 * w) if sqrt_chart else (w, 1.0)
            beta_R = math.pi - 2.0 * scale * y[0] - beta_L
            slope = (k * math.cos(beta_R) + c * math.sin(beta_R)) / r
            return np.array([-2.0 * scale * slope, 0.0, -slope * d_beta, c / r])

        def slip_left_gradient(y):
            return -tn_left_gradient(y)

        def limit_margin(y, numbers=FLOATS):
            gamma = scale * y[0]
            return (k * numbers.cos(gamma) - c * numbers.sin(gamma)) / r

        checks: dict[Condition, Callable] = {
            "dr_limit": {Condition.T_OVER_N_R: tn_right},
            "rs_limit": {},
            "dr_no_roll": {Condition.T_OVER_N_L: tn_left, Condition.T_OVER_N_R: tn_right},
            "rs_no_roll": {Condition.SLIP_LEFT: slip_left},
        }[self.name]
        gradients = {Condition.T_OVER_N_L: tn_left_gradient,
                     Condition.T_OVER_N_R: tn_right_gradient,
                     Condition.SLIP_LEFT: slip_left_gradient}
        certified = dict(checks)
        if self.name == "dr_limit":
            certified[Condition.T_OVER_N_R] = limit_margin
        object.__setattr__(self, "regime", REGIME_OF[self.name])
        object.__setattr__(self, "validity", checks)
        object.__setattr__(self, "validity_gradient", {condition: gradients[condition]
                                                        for condition in checks})
        object.__setattr__(self, "certified_validity", certified)

    def _unscaled(self, y) -> list:
        """Chart coordinates as Python numbers, ``gamma`` and ``delta`` in radians."""
        y = y.tolist() if isinstance(y, np.ndarray) else list(y)
        if self.scale != 1.0:
            y[0] = y[0] * self.scale
            y[1] = y[1] * self.scale
        return y

    @property
    def _unit(self) -> float:
        return self.scale if self.conditioned else 0.0

    def _evaluate(self, y, numbers, jacobian: bool):
        x = self._unscaled(y)
        if numbers is not FLOATS:
            x = [numbers.number(v) for v in x]
        return _rows(x, self.params.k, self.params.c, self.name, self.chart, numbers,
                     jacobian=jacobian, unit=self._unit)

    def residual(self, x, numbers=None):
        """``H(x)`` at chart coordinates ``x``: shape (3,) floats, or a list in ``numbers``.

        ``numbers`` is a namespace of :mod:`continuation.numbers` (``None``: floats, returned as
        an array); the same formulas are evaluated in any of them.
        """
        if numbers is None:
            return np.array(self._float_residual(x))
        return [numbers.number(v) for v in self._evaluate(x, numbers, False)[0]]

    def _float_residual(self, y) -> list:
        """``H(y)`` in floats; the Jacobian's rows, which share its trigonometry (both cost 60 %
        of the two apart), are kept for a :meth:`jacobian` at the same bits of ``y``: 94 % of
        the engine's Jacobians are at its last residual's point (a Newton iterate's).
        The residual alone where only the rows' formulas fail (a quotient by ``q_R = 0``)."""
        x, p = self._unscaled(y), self.params
        try:
            values, rows = _rows(x, p.k, p.c, self.name, self.chart, FLOATS, True, self._unit)
        except (ArithmeticError, ValueError):
            values, rows = _rows(x, p.k, p.c, self.name, self.chart, FLOATS, False, self._unit)
        if rows is not None and isinstance(y, np.ndarray):
            object.__setattr__(self, "_kept", ((y.dtype, y.tobytes()), rows))
        return values

    def jacobian(self, x, numbers=None):
        """``dH/dx`` with respect to the chart coordinates, analytic: shape (3, 4) floats, or
        three rows of four numbers of ``numbers`` (see :meth:`residual`)."""
        if numbers is None:
            kept = self._kept
            if kept is not None and isinstance(x, np.ndarray) and kept[0] == (x.dtype, x.tobytes()):
                return self._float_jacobian(kept[1])
            return self._float_jacobian(self._evaluate(x, FLOATS, True)[1])
        _, rows = self._evaluate(x, numbers, True)
        scale, number = self.scale, numbers.number
        return [[number(row[0] * scale), number(row[1] * scale), number(row[2]), number(row[3])]
                for row in rows]

    def residual_and_jacobian(self, x):
        """Both at once in floats (one evaluation of the shared trigonometry)."""
        values, rows = self._evaluate(x, FLOATS, True)
        return np.array(values), self._float_jacobian(rows)

    @property
    def _branches(self) -> bool:
        """Whether the formulas branch per point (not for :data:`ARRAYS`): the deflated torque."""
        return self.conditioned and self.name == "dr_no_roll"

    def _columns(self, ys) -> list:
        """The columns of the points ``ys`` (``(n, 4)`` chart coordinates), ``gamma`` and
        ``delta`` in radians: the coordinates of :meth:`_unscaled` for every point at once."""
        columns = _split(ys)
        if self.scale != 1.0:
            columns[0] = columns[0] * self.scale
            columns[1] = columns[1] * self.scale
        return columns

    def residuals(self, ys) -> np.ndarray:
        """``H`` at every row of ``ys`` (``(n, 4)`` chart coordinates) at once, ``(n, 3)``:
        the formulas of :meth:`residual` over numpy arrays (:data:`continuation.numbers.ARRAYS`),
        the same numbers row by row. The deflated torque of the conditioned ``dr_no_roll``
        branches on each point's ``beta_L - beta_R``: that form is evaluated point by point."""
        if self._branches:
            return np.array([self.residual(y) for y in np.asarray(ys).reshape(-1, 4)]
                            ).reshape(-1, 3)
        with _quiet():
            values, _ = _rows(self._columns(ys), self.params.k, self.params.c, self.name,
                              self.chart, ARRAYS, jacobian=False, unit=self._unit)
        return np.stack(np.broadcast_arrays(*values), axis=1)

    def residuals_and_jacobians(self, ys) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`residual_and_jacobian` at every row of ``ys`` at once: ``(n, 3)`` and
        ``(n, 3, 4)`` (see :meth:`residuals`)."""
        if self._branches:
            pairs = [self.residual_and_jacobian(y) for y in np.asarray(ys).reshape(-1, 4)]
            return (np.array([h for h, _ in pairs]).reshape(-1, 3),
                    np.array([j for _, j in pairs]).reshape(-1, 3, 4))
        columns = self._columns(ys)
        with _quiet():
            values, rows = _rows(columns, self.params.k, self.params.c, self.name, self.chart,
                                 ARRAYS, jacobian=True, unit=self._unit)
        jacobians = np.empty((len(columns[0]), 3, 4))
        for i, row in enumerate(rows):
            for j, entry in enumerate(row):
                jacobians[:, i, j] = entry * self.scale if j < 2 and self.scale != 1.0 else entry
        return np.stack(np.broadcast_arrays(*values), axis=1), jacobians

    def _float_jacobian(self, rows) -> np.ndarray:
        """The rows of :func:`_rows` (columns of ``gamma`` and ``delta`` in radians) as the
        Jacobian in the chart, ``(3, 4)`` floats (scaled on Python floats: a numpy slice
        product costs more than the arithmetic on a 3 x 4 matrix)."""
        scale = self.scale
        if scale != 1.0:
            rows = [(row[0] * scale, row[1] * scale, row[2], row[3]) for row in rows]
        return np.array(rows)

    def edge_function(self, y, numbers=FLOATS):
        """A function with the sign of ``gamma - delta`` on the boundary, with a simple zero at
        the corner (chart coordinates ``y``).

        On the boundary the horizontal balance holds, ``n_R sin theta_R = q_L P`` with
        ``P = s_L (sin theta_L + k D)`` in rolling sliding (and on the limit curve) and
        ``P = s_L sin theta_L + c A D`` in double rolling. Where ``n_R != 0`` and
        ``s_L > 0`` (``0 < beta_L < pi``) ``sin theta_R``, and so ``gamma - delta``, has the
        sign of ``q_L (sin theta_L + k D) n_R`` (rolling sliding) or ``q_L P n_R`` (double
        rolling); ``q_L`` is odd in ``w``, so the corner ``w = 0``, where ``gamma - delta``
        vanishes to third order on ``rs_no_roll``, is a simple zero of this function.
        """
        x = self._unscaled(y)
        if numbers is not FLOATS:
            x = [numbers.number(v) for v in x]
        gamma, delta = x[0], x[1]
        beta_L, q_L, _, _ = _left_contact(x[2], self.chart, numbers)
        beta_R = numbers.pi - 2.0 * gamma - beta_L
        s_R = numbers.sin(beta_R)
        n_R = s_R * numbers.sqrt(s_R)
        sin_tL = numbers.sin(gamma + delta)
        D = 2.0 * numbers.sin(gamma) * numbers.sin(delta)
        if self.name.startswith("rs") or (self.name.endswith("limit") and self.conditioned):
            P = sin_tL + self.params.k * D
        else:
            P = numbers.sin(beta_L) * sin_tL + self.params.c * (numbers.cos(beta_L) + x[3]) * D
        return q_L * P * n_R

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
        """The largest size of the terms of each equation (paper's form), shape (3,).

        ``|H_i(x)| / scale_i`` is the residual relative to that size, at which rounding is of
        order ``eps`` for every ``k`` and ``c`` (where the terms are much smaller, as near the
        small-``gamma`` end of the limit curve, it is a larger error relative to them): 1 for
        the torque and ``upsilon = 0``, ``max(1, c)`` for the double-rolling horizontal
        balance, ``sqrt(k^2 + c^2)`` for the limit and the rolling right wall, ``1 + k`` for
        the rolling-sliding horizontal balance.
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

    def physical(self, ys, tol: float = 0.0) -> np.ndarray:
        """:meth:`is_physical` at every row of ``ys`` (``(n, 4)`` chart coordinates) at once,
        a boolean array (the validity functions over numpy arrays, the same numbers)."""
        columns = _split(ys)
        physical = np.ones(len(columns[0]), dtype=bool)
        with _quiet():
            for f in self.validity.values():
                physical &= f(columns, numbers=ARRAYS) >= -tol
        return physical


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
    antisymmetrically, ``beta_{L,R} = beta +- e``, its linear part is ``2 f'(beta) e``, so a
    second branch can leave only where
    ``f'(beta) = cos^2 beta / (2 sqrt(sin beta)) - sin^(3/2) beta = 0``, that is
    ``tan beta = 1/sqrt 2``, ``gamma = pi/2 - beta = arctan sqrt 2``, for any ``k`` and ``c``.
    """
    return _symmetric_point(math.atan(math.sqrt(2.0)))


def corner_point() -> np.ndarray:
    """``(pi/4, pi/4, 0, 0)``: the singular end of both ``upsilon = 0`` lines.

    There ``theta_R = 0``, ``beta_L = 0`` (``N_L = 0``) and ``beta_R = pi/2``; every boundary
    residual vanishes, but ``d q_L / d beta_L`` is unbounded.
    """
    return np.array([0.25 * _PI, 0.25 * _PI, 0.0, 0.0])
