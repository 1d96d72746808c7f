r"""The boundaries as one-parameter families ``H(y, p) = 0``, for the atlas of special points.

The atlas (:mod:`groove_model.tracing.atlas`) follows the special points of the boundaries as a
parameter ``p`` moves: ``p = log k`` at a fixed compliance (ten decades of ``k`` are a few
units of ``p``), or ``p = nu``, the Poisson ratio, at a fixed ``k`` (the compliance ratio
``c(nu) = 2 (1 - nu)/(2 - nu)``, :meth:`~groove_model.model.parameters.Compliance.from_poisson`).
Here each boundary becomes a :class:`continuation.Family` in the tracer's chart
``y = (gamma/g, delta/g, w, upsilon)``, ``beta_L = w^2`` (:mod:`groove_model.model.boundaries`),
with the events the atlas needs, and the special points at one ``p`` are found by tracing the
boundary there, as the tracer does.

* The limit curve (``dr_limit`` = ``rs_limit``) in its conditioned form, in units
  ``g = arctan(k/c)`` (smooth in ``p``, unlike the tracer's ``min(1, arctan(k/c))``): the same
  zero set, and its coordinates of order one from ``k = 1e-4`` to ``1e6``.
* ``rs_no_roll`` as the paper writes it, ``g = 1``.
* ``dr_no_roll`` in its deflated form, ``g = 1``: the junction is the point of ``dr_no_roll``
  where ``T/N_L = k``, which it crosses transversally for every ``k``
  (:func:`junction_event`); with ``upsilon = 0``, ``T/N_L = c cot beta_L``, so there
  ``beta_L = arctan(c/k)`` exactly.

``dH/dp`` is a central difference of the residual in ``p`` (the equations are not touched);
it only enters Jacobians, so Newton still converges to full accuracy.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from continuation import Curve, Event, Family, Options, Problem, SpecialKind, trace

from ..model.boundaries import BoundarySystem, Condition, dr_no_roll_branch_point, limit_seed
from ..model.parameters import Compliance, Parameters
from .assembly import into_domain

__all__ = ["AXES", "START_OPTIONS", "Axis", "BoundaryFamily", "domain_events", "edge_event",
           "junction_event", "special_points"]

AXES = ("k", "nu")

#: settings of the traces at one parameter value that find the atlas's starting points
START_OPTIONS = Options(tol=1e-12, ds=0.02, ds_min=1e-12, ds_max=0.1, max_steps=5000,
                        detect_branch_points=False, detect_closed=False)

#: where the limit curve's start trace stops on its way to the origin, in units of g
GAMMA_MIN = 1e-2

_UP = np.array([0.0, 1.0, 0.0, 0.0])
_CACHE_SIZE = 64


@dataclass(frozen=True)
class Axis:
    """What the continuation parameter ``p`` is: ``log k`` at a fixed compliance ratio, or the
    Poisson ratio ``nu`` at a fixed ``k``.

    Attributes
    ----------
    name : str
        ``"k"`` or ``"nu"``.
    fixed : float
        The compliance ratio ``c`` (axis ``"k"``) or the friction coefficient ``k`` (``"nu"``).
    """

    name: str
    fixed: float

    def __post_init__(self) -> None:
        if self.name not in AXES:
            raise ValueError(f"axis = {self.name!r} is not one of {', '.join(AXES)}")
        Parameters(self.fixed if self.name == "nu" else 1.0,
                   Compliance(self.fixed if self.name == "k" else 1.0))

    @property
    def parameter(self) -> str:
        """The name of ``p``: ``"log_k"`` or ``"nu"``."""
        return "log_k" if self.name == "k" else "nu"

    def friction_and_ratio(self, p: float) -> tuple[float, float]:
        """``(k, c)`` at ``p``, unchecked (the hot path of the events)."""
        if self.name == "k":
            return math.exp(p), self.fixed
        return self.fixed, 2.0 * (1.0 - p) / (2.0 - p)

    def params(self, p: float) -> Parameters:
        """The model parameters at ``p``."""
        k, c = self.friction_and_ratio(p)
        # Mindlin's ratio, unchecked in nu: a difference quotient at nu = 1/2 steps past it
        return Parameters(k, Compliance(c) if self.name == "k" else Compliance(c, poisson=p))

    def value(self, p):
        """``k = exp(p)`` or ``nu = p``."""
        return np.exp(p) if self.name == "k" else np.asarray(p, dtype=float) + 0.0

    def to_p(self, value: float) -> float:
        """The inverse of :meth:`value`."""
        return math.log(value) if self.name == "k" else float(value)


class BoundaryFamily:
    """One boundary's equations in the chart ``y``, for every ``p`` of an axis.

    Parameters
    ----------
    boundary : str
        ``"dr_limit"`` (the conditioned limit curve, scaled), ``"rs_no_roll"`` or
        ``"dr_no_roll"`` (deflated).
    axis : Axis
    """

    def __init__(self, boundary: str, axis: Axis) -> None:
        self.boundary = boundary
        self.axis = axis
        self.scaled = boundary == "dr_limit"
        self.conditioned = boundary in ("dr_limit", "dr_no_roll")
        self._systems: dict[float, BoundarySystem] = {}
        self.family = Family(self.residual, self.jacobian, names=("gamma", "delta", "w",
                                                                  "upsilon"),
                             parameter=axis.parameter)

    def scale(self, p: float) -> float:
        """The unit ``g = arctan(k/c)`` (limit curve) or 1 of gamma and delta in the chart."""
        if not self.scaled:
            return 1.0
        k, c = self.axis.friction_and_ratio(p)
        return math.atan2(k, c)

    def system(self, p: float) -> BoundarySystem:
        """The boundary's system at ``p`` (kept for the last few ``p``)."""
        p = float(p)
        system = self._systems.get(p)
        if system is None:
            if len(self._systems) >= _CACHE_SIZE:
                self._systems.clear()
            system = BoundarySystem(self.boundary, self.axis.params(p), "sqrt_beta_L",
                                    self.scale(p), conditioned=self.conditioned)
            self._systems[p] = system
        return system

    def residual(self, y, p) -> np.ndarray:
        return self.system(p).residual(y)

    def jacobian(self, y, p) -> np.ndarray:
        return self.system(p).jacobian(y)

    def to_x(self, z: np.ndarray) -> np.ndarray:
        """``z = (y, p)`` (one point or rows) to ``x = (gamma, delta, beta_L, upsilon)``.

        A point outside the domain by rounding only (a threshold on the edge ``delta = 0``
        computed as ``delta = -8e-14``) is put on the edge, as the tracer does
        (:func:`~groove_model.tracing.assembly.into_domain`).
        """
        z = np.atleast_2d(z)
        g = np.array([self.scale(p) for p in z[:, -1]])
        x = z[:, :4].copy()
        x[:, :2] *= g[:, None]
        x[:, 2] = x[:, 2] ** 2
        return into_domain(x)[0]

    def from_x(self, x: np.ndarray, p: float) -> np.ndarray:
        """``x`` (``beta_L >= 0``) to chart coordinates at ``p``."""
        return self.system(p).from_x(x)

    def physical(self, z: np.ndarray) -> bool:
        """Whether the boundary's regime is valid at ``z`` (to rounding)."""
        return self.system(z[-1]).is_physical(z[:4], tol=1e-12)

    def validity_events(self, skip=()) -> list[Event]:
        """Non-terminal events of ``z`` where the boundary's regime stops being valid.

        The validity functions of :class:`~groove_model.model.boundaries.BoundarySystem`
        (``T/N <= k`` on a rolling wall, ``d_L >= 0`` on a sliding one), each divided by
        ``sqrt(k^2 + c^2)``, written here in ``z`` so that a step in ``p`` builds no system.
        """
        conditions = self.system(0.0).validity  # the same conditions at every p
        return [Event(f"{self.boundary}: {condition}", self._validity(condition))
                for condition in conditions if condition not in skip]

    def _validity(self, condition: Condition):
        axis, scale = self.axis, self.scale
        sign = -1.0 if condition is Condition.SLIP_LEFT else 1.0

        def function(z):
            k, c = axis.friction_and_ratio(z[-1])
            beta_L = z[2] * z[2]
            if condition is Condition.T_OVER_N_R:
                beta_R = math.pi - 2.0 * scale(z[-1]) * z[0] - beta_L
                value = k * math.sin(beta_R) - c * (math.cos(beta_R) - z[3])
            else:
                value = sign * (k * math.sin(beta_L) - c * (math.cos(beta_L) + z[3]))
            return value / math.hypot(k, c)
        return function


def _unit(index: int, other: float = 0.0, other_index: int = 0):
    """The constant gradient ``e_index`` (plus ``other e_other_index``) of an affine event."""
    def gradient(z):
        unit = np.zeros(len(z))
        unit[index] = 1.0
        unit[other_index] += other
        return unit
    return gradient


def domain_events(family: BoundaryFamily) -> list[Event]:
    """Terminal events of ``z`` where a special point leaves ``0 <= delta <= gamma <= pi/2``
    or ``beta_L, beta_R >= 0``; ``delta = 0`` is where one is born or dies on the axis.

    ``delta = gamma`` is ``gamma - delta`` on the limit curve and :func:`edge_event` on the
    ``upsilon = 0`` boundaries."""
    half_pi = 0.5 * math.pi
    if family.boundary.endswith("no_roll"):
        edge = edge_event(family)
    else:
        edge = Event("delta = gamma", lambda z: z[0] - z[1], -1, True, _unit(0, -1.0, 1),
                     linear=True)
    return [
        Event("delta = 0", lambda z: z[1], -1, True, _unit(1), linear=True),
        edge,
        Event("gamma = pi/2", lambda z: half_pi - family.scale(z[-1]) * z[0], -1, True),
        Event("beta_L = 0", lambda z: z[2], -1, True, _unit(2), linear=True),
        Event("beta_R = 0", lambda z: math.pi - 2.0 * family.scale(z[-1]) * z[0] - z[2] ** 2,
              -1, True),
    ]


def edge_event(family: BoundaryFamily) -> Event:
    r"""``delta = gamma`` on ``rs_no_roll`` or ``dr_no_roll``, in a form computed to relative
    accuracy near the corner ``(pi/4, pi/4)``.

    On these boundaries (``upsilon = 0``, ``n = s q``) the horizontal balance gives
    ``n_R sin(gamma - delta) = q_L P``, with ``P = s_L (sin theta_L + k D)`` (``rs_no_roll``)
    or ``s_L sin theta_L + c cos(beta_L) D`` (``dr_no_roll``), ``D = 2 sin(gamma) sin(delta)``.
    As ``n_R > 0`` for ``0 < beta_R < pi``, on the boundary ``gamma - delta`` has the sign of
    ``q_L P n_R``; the event is that function
    (:meth:`~groove_model.model.boundaries.BoundarySystem.edge_function`, without the factor
    ``s_L > 0`` on ``rs_no_roll``): the same event as ``gamma - delta``, with the same sign at
    every point of the boundary and the same zeros. For ``0 <= delta <= gamma < pi/2`` (not
    both 0) ``P > 0`` on ``rs_no_roll``, and on ``dr_no_roll`` wherever ``beta_L <= pi/2``
    (near the corner): there its only zero is where ``q_L`` (odd in ``w``) changes sign, the
    corner ``beta_L = 0`` itself, where the event ``beta_L = 0`` fires with it. A special point
    of ``rs_no_roll`` with ``beta_L > 0`` is strictly inside, ``delta < gamma``, however close
    to the corner.

    Why not ``gamma - delta`` itself: near the corner it is tiny. The fold in ``gamma`` of
    ``rs_no_roll`` is where ``c q_R cos beta_R - k n_L`` (free of ``delta``) and its derivative
    in ``w`` vanish: ``w = 2c/(3k)``, ``gamma - pi/4 ~ -(2/27) (c/k)^2``, and from the balance
    ``gamma - delta ~ (1 + k) w^3 ~ 8 c^3/(27 k^2)``, ``3e-13`` at ``k = 1e6``, ``c = 1``
    (these agree with the system solved in 60 digits to a relative ``5e-11`` for ``k >= 1e5``).
    That is below the points' accuracy in ``gamma`` and ``delta`` (residuals to ``1e-12``: a few
    ``1e-13``), and the curve of that fold in ``nu`` met ``delta = gamma`` by rounding (at
    ``k = 7e5``, ``nu = 0.3005``, where the true ``gamma - delta`` is ``3.37e-13``). This event
    is ``~ (1 + k) w ~ 2c/3`` there, and its rounding relative.
    """
    def function(z):
        return family.system(z[-1]).edge_function(z[:4])
    return Event("delta = gamma", function, -1, True)


def junction_event(axis: Axis) -> Event:
    """``T/N_L = k`` on ``dr_no_roll``: ``(c (cos beta_L + upsilon) - k sin beta_L) / sqrt(k^2 +
    c^2) = 0``, an event of ``z = (y, p)``."""
    def function(z):
        k, c = axis.friction_and_ratio(z[-1])
        beta_L = z[2] * z[2]
        return (c * (math.cos(beta_L) + z[3]) - k * math.sin(beta_L)) / math.hypot(k, c)
    return Event("T/N_L = k", function)


def _start_trace(family: BoundaryFamily, p: float, start, events, folds=()) -> Curve:
    problem = Problem(lambda y: family.residual(y, p), lambda y: family.jacobian(y, p),
                      names=family.family.names)
    options = dataclasses.replace(START_OPTIONS, fold_coordinates=tuple(folds))
    return trace(problem, start, direction=_UP, options=options, events=events)


def _at_p(events, p: float, family: Family) -> list[Event]:
    return [family.event_at(event, p) for event in events]


def special_points(family: BoundaryFamily, p: float):
    """The special points of one boundary at ``p``: ``(junction, folds)``, engine special points.

    The boundary is traced once at ``p``, as the tracer does: ``dr_limit`` and ``rs_no_roll``
    from ``(arctan(k/c), 0)``, ``dr_no_roll`` from its branch point to the junction, the event
    ``T/N_L = k`` (``junction`` is ``None`` for the others, and for ``dr_no_roll`` when it reaches
    the corner first: ``k <= c sqrt 2``, no physical part and no folds reported). ``folds`` are
    its turning points in gamma and delta; one at an end or at the corner ``w = 0`` (where gamma
    and delta are stationary in the chart) is none.

    Raises
    ------
    RuntimeError
        If the boundary cannot be traced at ``p``.
    """
    params = family.axis.params(p)
    events = domain_events(family)
    if family.boundary == "dr_no_roll":
        start = dr_no_roll_branch_point()
        event = junction_event(family.axis)
        events.insert(0, Event(event.name, event.function, terminal=True))
    else:
        start = limit_seed(params)
    if family.scaled:
        floor = min(GAMMA_MIN, 1e-3 / family.scale(p))
        events.append(Event("gamma = gamma_min", lambda z: z[0] - floor, -1, True, _unit(0),
                            linear=True))
    curve = _start_trace(family, p, family.from_x(start, p), _at_p(events, p, family.family),
                         (0, 1))
    if not curve.ok:
        raise RuntimeError(f"{family.boundary} at {family.axis.parameter} = {p!r} could not be "
                           f"traced to find its special points: {curve.message}")
    junction = None
    if family.boundary == "dr_no_roll":
        ends = [point for point in curve.special("event") if point.event == 0 and point.index > 0]
        if not ends:
            return None, []
        junction = ends[0]
    last = len(curve) - 1
    folds = [point for point in curve.special(SpecialKind.FOLD)
             if 0 < point.index < last and abs(point.x[2]) > 1e-9]
    return junction, folds
