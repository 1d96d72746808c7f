"""Bracketing the special points inside one accepted step.

Every accepted step ``(a, b]`` is scanned for zeros of scalar functions along the
curve: event functions ``g(x)``, tangent components ``t_i`` (folds) and
``det [H'; t^T]`` (branch points). A sign test on the two ends alone misses two
zeros inside one step (they cancel) and a zero at the start; the scan therefore
models each function on the step from the data the step already has, and
subdivides where the model allows zeros the end values do not show
(:class:`StepScan`). Each bracket is then located by :mod:`continuation.locate`.

The models are cubic in the arclength and the step control follows the curve, not the
events, so an event that changes on a scale shorter than a step (it oscillates, or dips
between flat ends) can have zeros no model of the ends' data shows. Each event is
therefore also evaluated at a third and two thirds of every interval (on its Hermite arc):
where those values disagree with the model near zero, on the arc and again on the curve,
the interval is split there at corrected nodes and its thirds checked again
(:meth:`StepScan.event_brackets`), down to ``1/3**RESOLVE_DEPTH`` of the step. What remains
is what fixed samples cannot exclude (a dip that falls between them, an oscillation whose
period fits them): such an event needs ``ds_max`` below its own scale.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from .corrector import correct
from .cubic import (
    CLEAR,
    NEAR_ZERO,
    SAMPLES,
    SPLIT_MARGIN,
    bounded_away,
    critical_points,
    cubic,
    cubic_derivative,
    cubic_value,
    error_term,
    same_sign,
    samples_disagree,
    split_point,
)
from .events import Event, crossed
from .linalg import max_abs, norm
from .linear import LinearEvents, event_gradient
from .node import (
    EventNotFinite,
    LocateError,
    Node,
    StepUnresolved,
    curvature,
    det_slope,
    event_value,
)
from .options import Options
from .predictor import hermite, tangent_beyond
from .problem import Evaluator

__all__ = ["StepScan"]

#: a corrected trial point may move at most this fraction of its Hermite interval
JUMP = 0.1

#: relative step of the central difference of an event along the tangent
SLOPE_STEP = 1e-6

#: the sample check splits an interval in three at most this many times over (down to
#: 1/3**RESOLVE_DEPTH of the step): the resolution of events faster than the step
RESOLVE_DEPTH = 3

#: most nodes a step may need before its scan is declared unresolvable
MAX_NODES = 200

#: a tiny value standing for "zero, on this side"
_TINY = 1e-300

#: a tangent component at most this large at a terminal point is a zero there
TERMINAL_NOISE = 1e-10

#: a step's tangent turn may differ from its curvature's by this fraction of max_angle
TURN_MISMATCH = 0.25

#: a step's end tangent may differ from the one the step before predicts by this fraction of
#: max_angle before the step is checked like one near a branch point (:meth:`StepScan.det_clear`)
SURPRISE = 0.5 * TURN_MISMATCH

#: the cubic Hermite basis (h00, h01, h10, h11) at SAMPLES, the rows of u = 1/3 and 2/3
_SAMPLE_BASIS = np.array([[20.0, 7.0, 4.0, -2.0], [7.0, 20.0, 2.0, -4.0]]) / 27.0


def _event_slope(event: Event, node: Node, describe) -> float:
    """``d g / ds = grad g . t`` at a node: from ``event.gradient`` or a central difference."""
    x, t = node.x, node.tangent
    if event.gradient is not None:
        return float(event_gradient(event, x, describe) @ t)
    step = SLOPE_STEP * (1.0 + max_abs(x))
    forward, backward = x + step * t, x - step * t
    width = float((forward - backward) @ t)
    return (event_value(event, forward, describe) - event_value(event, backward, describe)) / width


class StepScan:
    """The special points of one accepted step ``(a, b]``: brackets of zeros.

    Parameters
    ----------
    evaluator : Evaluator
        Counting evaluator of the problem.
    options : Options
        Tolerances.
    events : sequence of Event
        The run's events (their values are ``Node.events``).
    a, b : Node
        The step's accepted ends.

    Notes
    -----
    For each scalar function ``f`` along the step, a model ``P(u)``,
    ``u = (s - s_a) / (s_b - s_a)``, is built from the data of the interval's
    ends: for an event ``g``, the cubic Hermite interpolant of ``g`` and
    ``dg/ds = grad g . t``; for a fold of coordinate ``i``, the cubic Hermite
    interpolant of ``t_i`` and its exact slope ``dt_i/ds`` (the curvature, from
    second derivatives of ``H``), or at a singular start the derivative of the cubic
    Hermite arc of ``x_i``. A step where ``t_i`` keeps its sign but is not clearly
    away from zero gets one node at the model's extremum first: a pair of folds in a
    sharp dip of ``t_i`` can hide from any model of the ends' data alone. Where the
    model allows zeros the end values do not show
    (:func:`split_point`), a node is corrected onto the curve at the model's
    extremum and both halves are scanned again with their own, more accurate,
    models, until every interval has a model that either keeps its sign or
    changes it once. A zero at an interval's start is taken on the side the
    function moves to (the sign of ``P'(0)``), so a zero at the start of a curve
    is not a crossing while a second zero in the first step is. This is the
    bracketing strategy of event location in ODE solvers with dense output
    (Shampine & Thompson, "Event location for ordinary differential equations",
    Comput. Math. Appl. 39 (2000) 43-54), with the curve's Hermite arc as the
    dense output.
    """

    def __init__(self, evaluator: Evaluator, options: Options, events: Sequence[Event],
                 a: Node, b: Node, linear: LinearEvents | None = None) -> None:
        self.evaluator = evaluator
        self.options = options
        self.events = events
        self.nodes = [a, b]
        #: the step's width, the length scale of its finite differences (:func:`bend`)
        self.width = b.s - a.s
        #: the run's linear events and their constant gradients
        self.linear = LinearEvents(events) if linear is None else linear
        self.describe = evaluator.problem.describe
        #: the uncorrected points of each interval (by its ends' s) at SAMPLES of its arc
        self._samples: dict[tuple[float, float], tuple[np.ndarray, np.ndarray]] = {}
        #: the events there, by interval and event, and the corrected points there
        self._arc_events: dict[tuple[float, float, int], tuple[float, float]] = {}
        self._corrected_samples: dict[tuple[float, float], list[Node]] = {}

    # --- nodes --------------------------------------------------------------------------
    def node_at(self, s: float) -> Node:
        """The curve point at Hermite parameter ``s`` inside the step, corrected, with tangent
        (a node of the step from now on)."""
        nodes = self.nodes
        self._check_capacity()
        k = next(k for k in range(1, len(nodes)) if nodes[k].s >= s)
        node = self._corrected(nodes[k - 1], nodes[k], s)
        nodes.insert(k, node)
        return node

    def _check_capacity(self) -> None:
        """:class:`LocateError` if the step has :data:`MAX_NODES` nodes already."""
        if len(self.nodes) >= MAX_NODES:
            raise LocateError(f"more than {MAX_NODES} nodes needed to resolve the step between "
                              f"s={self.nodes[0].s!r} and s={self.nodes[-1].s!r}")

    def _corrected(self, lo: Node, hi: Node, s: float) -> Node:
        """The curve point at Hermite parameter ``s`` between ``lo`` and ``hi``, corrected."""
        width = hi.s - lo.s
        point, derivative = hermite(lo.x, lo.tangent, hi.x, hi.tangent, width, s - lo.s)
        border = derivative / norm(derivative)
        options = self.options
        result = correct(self.evaluator, point, border, options.locate_newton,
                         max_correction=JUMP * width, accept_fallback=True)
        if not result.ok or result.tangent is None:
            raise LocateError(f"point at s={s!r} inside the step not corrected: {result.reason}")
        if norm(result.x - point) > JUMP * width:
            raise LocateError(f"point at s={s!r} moved {norm(result.x - point)!r} from its "
                              "prediction: it may have jumped to another branch")
        values = [event_value(event, result.x, self.describe) for event in self.events]
        if not all(math.isfinite(v) for v in values):
            j = next(j for j, v in enumerate(values) if not math.isfinite(v))
            raise EventNotFinite(f"event '{self.events[j].name}' is {values[j]!r} at "
                                 f"x={self.describe(result.x)}")
        return Node(result.x, s, result.tangent, result.det, result.residual, result.iterations,
                    values, result.jacobian)

    def slope(self, node: Node, j: int) -> float:
        """``d g_j / ds`` at a node (computed once)."""
        if node.slopes is None:
            node.slopes = [None] * len(self.events)
        value = node.slopes[j]
        if value is None:
            if self.events[j].linear:
                value = float(self.linear_gradient(j) @ node.tangent)
            else:
                value = _event_slope(self.events[j], node, self.describe)
            if not math.isfinite(value):
                raise EventNotFinite(
                    f"the derivative of event '{self.events[j].name}' along the curve is "
                    f"{value!r} at x={self.describe(node.x)}: the event is not defined just off "
                    "the curve; give Event.gradient")
            node.slopes[j] = value
        return value

    def linear_gradient(self, j: int) -> np.ndarray:
        """The constant gradient of linear event ``j`` (:class:`LinearEvents`)."""
        return self.linear.gradients(self.nodes[0].x, self.describe)[self.linear.rows[j]]

    def check_linear_events(self) -> None:
        """:meth:`LinearEvents.check` over the whole step."""
        self.linear.check(self.nodes[0], self.nodes[-1], self.describe)

    # --- brackets -----------------------------------------------------------------------
    def event_brackets(self, j: int, direction: int = 0) -> list[tuple[Node, Node, float, float]]:
        """Brackets ``(lo, hi, g_lo, g_hi)`` of the zeros of event ``j`` in the step.

        Besides the model's own splits (:meth:`_brackets`), every interval where the event at
        ``u = 1/3`` and ``2/3`` disagrees with the model near zero (:func:`samples_disagree`),
        on the Hermite arc and again on the curve, is split there, down to
        ``1/3**RESOLVE_DEPTH`` of the step, so an event that changes faster than the step
        shows its zeros (not for a ``linear`` event, whose model is exact on the arc).
        """

        # an affine event on the arc is its model: samples could only repeat it (Event.linear;
        # that it is affine, check_linear_events checks once per step)
        linear = self.events[j].linear
        clear = len(self.nodes) == 2 and self._clear(j)
        if clear and linear:
            return []

        def model(lo: Node, hi: Node):
            width = hi.s - lo.s
            return cubic(lo.events[j], width * self.slope(lo, j),
                         hi.events[j], width * self.slope(hi, j))

        if clear:
            # the model stays above CLEAR times its smaller end value: samples whose error
            # term stays within 1/NEAR_ZERO of that are trusted (samples_disagree)
            a, b = self.nodes
            alpha, beta = error_term(self._arc_deltas(a, b, j, model(a, b)))
            if NEAR_ZERO * (abs(alpha) + abs(beta)) / 16.0 \
                    < CLEAR * min(abs(a.events[j]), abs(b.events[j])):
                return []  # (a sample that is not finite is checked on the curve below)

        finest = (self.nodes[-1].s - self.nodes[0].s) / 3.0 ** RESOLVE_DEPTH

        def resolve(lo: Node, hi: Node, c, f_lo: float, f_hi: float) -> list[Node]:
            if linear or hi.s - lo.s < 2.0 * finest:
                return []
            deltas = self._arc_deltas(lo, hi, j, c)
            if all(map(math.isfinite, deltas)) and not samples_disagree(c, deltas, f_lo, f_hi):
                return []
            # checked on the curve: the arc is O(h^4) off it, which moves an event that is
            # steep across the curve (not along it) by more than the model's error, and may
            # leave the event's domain (on the curve, a value that is not finite is an error:
            # EventNotFinite, as at any node)
            nodes = self._sample_nodes(lo, hi)
            if nodes[0].events[j] == 0.0 or nodes[1].events[j] == 0.0:
                # an event that vanishes identically along a stretch: a node there would read
                # as a crossing where the event does not change sign
                return []
            deltas = (nodes[0].events[j] - cubic_value(c, SAMPLES[0]),
                      nodes[1].events[j] - cubic_value(c, SAMPLES[1]))
            return nodes if samples_disagree(c, deltas, f_lo, f_hi) else []

        return self._brackets(lambda node: node.events[j], model, direction, list(self.nodes),
                              resolve)

    def _arc_deltas(self, lo: Node, hi: Node, j: int, c) -> tuple[float, float]:
        """Event ``j`` at :data:`SAMPLES` of the interval's cubic Hermite arc (not corrected:
        ``O(h^4)`` off the curve; evaluated once per interval and event) less its model ``c``
        there; NaN where the event is not finite."""
        key = (lo.s, hi.s, j)
        values = self._arc_events.get(key)
        if values is None:
            points = self._sample_points(lo, hi)
            event = self.events[j]
            values = (event_value(event, points[0], self.describe),
                      event_value(event, points[1], self.describe))
            self._arc_events[key] = values
        return values[0] - cubic_value(c, SAMPLES[0]), values[1] - cubic_value(c, SAMPLES[1])

    def _sample_nodes(self, lo: Node, hi: Node) -> list[Node]:
        """The curve points at :data:`SAMPLES` of the interval, corrected (once per interval,
        for all events)."""
        key = (lo.s, hi.s)
        nodes = self._corrected_samples.get(key)
        if nodes is None:
            width = hi.s - lo.s
            nodes = [self._corrected(lo, hi, lo.s + u * width) for u in SAMPLES]
            self._corrected_samples[key] = nodes
        return nodes

    def _sample_points(self, lo: Node, hi: Node) -> tuple[np.ndarray, np.ndarray]:
        """The interval's cubic Hermite arc at :data:`SAMPLES` (computed once per interval)."""
        key = (lo.s, hi.s)
        points = self._samples.get(key)
        if points is None:
            # x_lo h00 + x_hi h01 + h (t_lo h10 + t_hi h11) at u = 1/3 and 2/3, in one product
            width = hi.s - lo.s
            both = _SAMPLE_BASIS @ np.array((lo.x, hi.x, width * lo.tangent,
                                             width * hi.tangent))
            points = (both[0], both[1])
            self._samples[key] = points
        return points

    def _clear(self, j: int) -> bool:
        """Whether event ``j``'s model on the whole step provably neither crosses nor nears zero
        (:func:`~continuation.cubic.bounded_away`): the full scan would find no sign change and
        no extremum within ``APPROACH`` of zero, so it brackets nothing, and this test says so
        without building the model (the common case on most steps)."""
        a, b = self.nodes
        f_a, f_b = a.events[j], b.events[j]
        return same_sign(f_a, f_b) and bounded_away(f_a, f_b, self.slope(a, j),
                                                    self.slope(b, j), b.s - a.s)

    def candidates(self) -> list[int]:
        """The events that may vanish in the step: all but the linear ones that :meth:`_clear`
        clears, tested at once (their end slopes ``a . t`` are one product). A linear event
        not cleared here is tested again in :meth:`event_brackets`, alone, with the slopes the
        rest of the scan uses."""
        a, b = self.nodes
        clear = set()
        if self.linear.indices and len(self.nodes) == 2:
            tangents = np.array((a.tangent, b.tangent)).T
            slopes = (self.linear.gradients(a.x, self.describe) @ tangents).tolist()
            width = b.s - a.s
            clear = {j for j, (m_a, m_b) in zip(self.linear.indices, slopes, strict=True)
                     if same_sign(a.events[j], b.events[j])
                     and bounded_away(a.events[j], b.events[j], m_a, m_b, width)}
        return [j for j in range(len(self.events)) if j not in clear]

    def add(self, node: Node) -> None:
        """Insert a located curve point (e.g. a terminal event) as a node of the step."""
        if all(n.s != node.s for n in self.nodes):
            self.nodes.append(node)
            self.nodes.sort(key=lambda n: n.s)

    def turning(self, node: Node) -> np.ndarray:
        """The curvature ``dt/ds`` at a node (:func:`curvature`), computed once."""
        if node.turning is None:
            kappa = curvature(self.evaluator, node, self.width)
            if kappa is None:
                raise LocateError(f"no curvature at the singular point "
                                  f"x={self.describe(node.x)}")
            node.turning = kappa
        return node.turning

    def det_slope(self, node: Node) -> float:
        """``d det [H'; t^T] / ds`` at a node (:func:`det_slope`), computed once."""
        if node.det_slope is None:
            slope = det_slope(self.evaluator, node, self.width)
            if not math.isfinite(slope):
                raise LocateError(f"the slope of det [H'; t^T] is {slope!r} at "
                                  f"x={self.describe(node.x)}")
            node.det_slope = slope
        return node.det_slope

    def check_turn(self) -> None:
        """:class:`StepUnresolved` if the step's cubic Hermite arc bends otherwise than the curve.

        The arc through ``x_a, t_a, x_b, t_b`` (width ``h``, chord ``c = (x_b - x_a) / h``)
        has second derivatives ``(6 c - 4 t_a - 2 t_b) / h`` and ``(-6 c + 2 t_a + 4 t_b) / h``
        at its ends; on a smooth curve they equal its curvature ``kappa = dt/ds`` there up to
        ``O(h^2)``. An end where ``h`` times their difference (an angle) exceeds
        ``TURN_MISMATCH * max_angle`` means the step did not follow one smooth curve: it landed
        on another branch (near a branch point, where two branches meet, the corrector converges
        as readily to either) or the curve bends faster than the step resolves, and the arc that
        locates the step's special points misrepresents it. Either way the step is too long.
        Not at a singular start (``det = 0``, no curvature there).
        """
        mismatch = self.turn_mismatch()
        limit = TURN_MISMATCH * self.options.max_angle
        if mismatch > limit:
            raise StepUnresolved(f"the step's arc bends {mismatch:.3g} rad (more than "
                                 f"{limit:.3g}) off the curvature at its ends: the step is too "
                                 "long for the curve's bending, or it jumped to another branch")

    def turn_mismatch(self) -> float:
        """The angle by which the step's arc bends off the curvature at its worse end
        (:meth:`check_turn`); 0 at a singular end (no curvature there)."""
        a, b = self.nodes[0], self.nodes[-1]
        if a.det == 0.0 or b.det == 0.0:
            return 0.0
        width = self.width
        # h p''(0) = 6 c - 4 t_a - 2 t_b = u + v, h p''(1) = v - u, with u = 6 c - 3 (t_a + t_b)
        u = (6.0 / width) * (b.x - a.x) - 3.0 * (a.tangent + b.tangent)
        v = b.tangent - a.tangent
        return max(norm(u + v - width * self.turning(a)), norm(v - u - width * self.turning(b)))

    def branch_brackets(self, end: Node | None = None) -> list[tuple[Node, Node, float, float]]:
        """Brackets ``(lo, hi, det_lo, det_hi)`` of the sign changes of ``det [H'; t^T]``.

        The model of the determinant on an interval is the cubic Hermite interpolant of its
        values and exact slopes (:meth:`det_slope`), scanned like a fold's (:meth:`_brackets`),
        so two simple branch points inside one step (the determinant dips through zero and
        back) are both bracketed where their end signs agree. An interval with an end where the
        determinant is exactly zero (a singular start) has the linear model: a branch point
        there is the start, not a crossing. ``end``: where the curve ends (a terminal event);
        only sign changes before it are bracketed. For a step that is not :meth:`det_clear`.
        """
        if end is not None:
            self.add(end)

        def model(lo: Node, hi: Node):
            d_lo, d_hi = lo.det, hi.det
            if d_lo == 0.0 or d_hi == 0.0:
                return (d_lo, d_hi - d_lo, 0.0, 0.0)
            width = hi.s - lo.s
            return cubic(d_lo, width * self.det_slope(lo), d_hi, width * self.det_slope(hi))

        nodes = self.nodes if end is None else [n for n in self.nodes if n.s <= end.s]
        return self._brackets(lambda node: node.det, model, 0, nodes)

    def det_clear(self, previous: Node | None = None) -> bool:
        """Whether the determinant's model on the whole step neither crosses nor nears zero
        (the bound of :meth:`_clear` with the determinant's values and slopes), and the step
        turns as the curve before it predicts.

        The slopes are those of the quadratic through the determinant at ``previous`` (the
        curve point before the step) and the step's ends, which costs nothing; where there is
        no such point (the first step, or one at a singular start), the exact slopes
        (:meth:`det_slope`, a Jacobian each). A step that is not clear is scanned with the
        exact slopes (:meth:`branch_brackets`) and checked by :meth:`check_turn`.

        A step that lands on another branch across a branch point keeps the determinant's
        sign (it changes on both branches there), so the sign alone would pass it. Its end
        tangent is that of the other branch, the crossing angle off the one the step came
        along: a step whose end tangent differs from the one the cubic Hermite arc of the step
        before predicts for it (:func:`tangent_beyond`, free) by more than ``SURPRISE``
        ``max_angle``, or, with no such arc, whose arc bends off the curvature at its ends
        (:meth:`turn_mismatch`, from the Jacobians the exact slopes took) by as much, is not
        clear either, and :meth:`check_turn` decides. (On a smooth curve the prediction errs by
        a small part of the step's turn, itself below ``max_angle``: such steps are rare.) The
        limit grows by what the points' errors, ``tol (1 + max|x|)``, can make of the two: where
        the tolerances do not resolve the step's turn, neither can this screen.
        """
        a, b = self.nodes[0], self.nodes[-1]
        d_a, d_b = a.det, b.det
        if not same_sign(d_a, d_b):
            return False
        width = self.width
        limit = SURPRISE * self.options.max_angle
        # the points' error, up to tol (1 + max|x|) each, moves the arcs' derivatives by up to
        # the weights of the points in them over their spans: a margin on top of the limit
        noise = 2.0 * self.options.tol * (1.0 + max_abs(b.x))
        if previous is not None and previous.det != 0.0 and previous.s < a.s:
            # divided differences: q'(s_a) = f[p,a] + f[p,a,b] h_1, q'(s_b) = ... (h_1 + 2 h_2)
            h_1 = a.s - previous.s
            first = (d_a - previous.det) / h_1
            second = ((d_b - d_a) / width - first) / (h_1 + width)
            m_a, m_b = first + second * h_1, first + second * (h_1 + 2.0 * width)
            u = 1.0 + width / h_1
            return bounded_away(d_a, d_b, m_a, m_b, width) and norm(
                b.tangent - tangent_beyond(previous, a, width)) <= limit + 6.0 * u * (u - 1.0) \
                * noise / h_1
        return bounded_away(d_a, d_b, self.det_slope(a), self.det_slope(b), width) \
            and self.turn_mismatch() <= limit + 6.0 * noise / width

    def fold_brackets(self, i: int, noise: float = 0.0,
                      end: Node | None = None) -> list[tuple[Node, Node, float, float]]:
        """Brackets ``(lo, hi, t_lo, t_hi)`` of the zeros of the tangent component ``t_i``.

        ``noise``: at a node with ``det == 0`` (a singular start whose tangent was
        given, e.g. a branch tangent) a component at most this large is taken as zero.
        ``end``: a node where the curve ends (a terminal event); only zeros before it
        are bracketed. If ``t_i`` vanishes there (within ``TERMINAL_NOISE``), as where a
        curve ends at a point that is stationary in ``x_i``, its sign just before the
        end is taken from the exact curvature: ``-sign(dt_i/ds)``. So a fold next to
        such an end is found however close it is, while the end itself is no fold.
        """
        before_end = 0.0
        if end is not None:
            self.add(end)
            if abs(float(end.tangent[i])) <= TERMINAL_NOISE:
                kappa = float(self.turning(end)[i])
                before_end = -math.copysign(_TINY, kappa) if kappa != 0.0 else 0.0

        def value(node: Node) -> float:
            if node is end and before_end != 0.0:
                return before_end
            t_i = float(node.tangent[i])
            return 0.0 if node.det == 0.0 and abs(t_i) <= noise else t_i

        def model(lo: Node, hi: Node):
            width = hi.s - lo.s
            t_lo, t_hi = value(lo), value(hi)
            if lo.det != 0.0 and hi.det != 0.0:
                # the cubic Hermite model of t_i from its exact slopes dt_i/ds (curvatures):
                # the quadratic below, from the chord, can miss a pair of folds next to a
                # nearly vanishing t_i at an end (a dip the arc's chord does not feel)
                return cubic(t_lo, width * float(self.turning(lo)[i]), t_hi,
                             width * float(self.turning(hi)[i]))
            # at a singular start (no curvature there): t_i on the derivative of the cubic
            # Hermite arc of x_i, a quadratic
            chord = (hi.x[i] - lo.x[i]) / width
            return (t_lo, 6.0 * chord - 4.0 * t_lo - 2.0 * t_hi,
                    -6.0 * chord + 3.0 * t_lo + 3.0 * t_hi, 0.0)

        if end is None and len(self.nodes) == 2:
            if self._fold_clear(i):
                return []
            a, b = self.nodes
            if a.det != 0.0 and b.det != 0.0 and (value(a) > 0.0) == (value(b) > 0.0):
                # not clear, yet no sign change: t_i turns towards zero inside the step, where
                # a pair of folds can hide from any model of the ends' data (a sharp dip);
                # one node at the model's extremum shows the turn (each half is then scanned)
                c = model(a, b)
                critical = critical_points(c)
                u = min(critical, key=lambda v: abs(cubic_value(c, v))) if critical else 0.5
                self.node_at(a.s + min(1.0 - SPLIT_MARGIN, max(SPLIT_MARGIN, u)) * (b.s - a.s))
        nodes = self.nodes if end is None else [n for n in self.nodes if n.s <= end.s]
        return self._brackets(value, model, 0, nodes)

    def _fold_clear(self, i: int) -> bool:
        """Whether ``t_i``'s model on the whole step provably neither crosses nor nears zero.

        The model is the derivative of the cubic Hermite arc of ``x_i``,
        ``P(u) = (1 - u) t_a + u t_b + c_2 (u^2 - u)`` with ``|u^2 - u| <= 1/4`` on ``[0, 1]``,
        so for end values of one sign ``|P| >= min(|t_a|, |t_b|) - |c_2| / 4``; as for
        events (:meth:`_clear`), the full scan would bracket nothing when that stays above
        ``CLEAR`` times the smaller end value. Not at a singular start (``det = 0``).
        """
        a, b = self.nodes
        if a.det == 0.0 or b.det == 0.0:
            return False
        t_a, t_b = float(a.tangent[i]), float(b.tangent[i])
        if not ((t_a > 0.0 and t_b > 0.0) or (t_a < 0.0 and t_b < 0.0)):
            return False
        chord = float(b.x[i] - a.x[i]) / (b.s - a.s)  # a bool, not numpy.bool_, below
        c_2 = -6.0 * chord + 3.0 * t_a + 3.0 * t_b
        return 0.25 * abs(c_2) <= (1.0 - CLEAR) * min(abs(t_a), abs(t_b))

    def _brackets(self, value, model, direction: int, nodes=None, resolve=None):
        """Brackets of the zeros of ``value`` along the step, from the intervals between
        ``nodes``: each interval is split at a corrected node where its ``model`` may hide
        zeros (:func:`split_point`) or at the nodes ``resolve(lo, hi, c, f_lo, f_hi)`` gives
        (the sample check of events)."""
        nodes = self.nodes if nodes is None else nodes
        out = []
        # every interval between the nodes found so far (earlier scans of the step left some)
        stack = list(zip(nodes, nodes[1:], strict=False))[::-1]
        while stack:
            lo, hi = stack.pop()
            c = model(lo, hi)
            f_lo, f_hi = value(lo), value(hi)
            if f_lo == 0.0:
                # a zero at the interval's start belongs to the interval before (or is
                # the curve's start): the function is on the side it moves to
                slope = c[1] if c[1] != 0.0 else c[2]
                f_lo = math.copysign(_TINY, slope) if slope != 0.0 else f_hi
            if f_hi == 0.0:
                # a zero at the end is a crossing of this interval if the function
                # moves on to the other side
                slope = cubic_derivative(c, 1.0)
                f_hi = math.copysign(_TINY, slope) if slope != 0.0 else -f_lo
            if f_lo == 0.0 or f_hi == 0.0:
                continue  # identically zero on the interval's ends and model: no crossing
            split, inside = None, []
            if hi.s - lo.s > 2.0 * self.options.event_tol:
                split = split_point(c, f_lo, f_hi)
                if split is None and resolve is not None:
                    inside = resolve(lo, hi, c, f_lo, f_hi)
            if split is not None:
                inside = [self.node_at(lo.s + split * (hi.s - lo.s))]
            else:
                for node in inside:
                    self._check_capacity()
                    self.add(node)
            if inside:
                ends = [lo, *inside, hi]
                stack.extend(zip(ends[-2::-1], ends[:0:-1], strict=True))
            elif crossed(f_lo, f_hi, direction):
                out.append((lo, hi, f_lo, value(hi)))
        out.sort(key=lambda item: item[0].s)
        return out
