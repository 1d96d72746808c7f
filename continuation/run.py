"""The state of one continuation run: its growing lists and the curve it becomes."""

from __future__ import annotations

import logging
import math

import numpy as np

from .errors import ContinuationError
from .events import Event
from .linear import LinearEvents
from .node import EventNotFinite, Node, event_value
from .options import Options
from .problem import Evaluator, Problem
from .result import Curve, SpecialPoint, Status

__all__ = ["Run"]

logger = logging.getLogger(__name__)


class Run:
    """Growing lists of a run and the bookkeeping of special points (internal)."""

    def __init__(self, problem: Problem, options: Options, events: tuple[Event, ...],
                 evaluator: Evaluator) -> None:
        self.problem = problem
        self.options = options
        self.events = events
        self.evaluator = evaluator
        self.x: list[np.ndarray] = []
        self.s: list[float] = []
        self.tangents: list[np.ndarray] = []
        self.iterations: list[int] = []
        self.residuals: list[float] = []
        self.special: list[SpecialPoint] = []
        self.rejected = 0
        #: the linear events and their constant gradients, evaluated once
        self.linear = LinearEvents(events)

    def node(self, x, s, tangent, det, residual, iterations, jacobian=None) -> Node:
        """A curve point with its event values; :class:`EventNotFinite` if one is not finite.
        ``jacobian``: ``H'(x)`` if already evaluated there."""
        values = [event_value(event, x, self.problem.describe) for event in self.events]
        for event, value in zip(self.events, values, strict=True):
            if not math.isfinite(value):
                raise EventNotFinite(f"event '{event.name}' is {value!r} at "
                                     f"x={self.problem.describe(x)}")
        return Node(x, s, tangent, det, residual, iterations, values, jacobian)

    def append(self, x, s, tangent, residual, iterations) -> int:
        self.x.append(x)
        self.s.append(s)
        self.tangents.append(tangent)
        self.residuals.append(residual)
        self.iterations.append(iterations)
        return len(self.s) - 1

    def mark(self, kind, name, index, accuracy, coordinate=None, event=None) -> SpecialPoint:
        point = SpecialPoint(kind=kind, name=name, index=index, x=self.x[index],
                             s=self.s[index], residual=self.residuals[index],
                             accuracy=accuracy, coordinate=coordinate,
                             tangent=self.tangents[index], event=event)
        self.special.append(point)
        logger.info("%s '%s' at s=%.12g, x=%s (accuracy %.2g)", kind, name, point.s,
                    self.problem.describe(point.x), accuracy)
        return point

    def curve(self, status: Status, message: str, n1: int, raise_failure: bool = True) -> Curve:
        if self.s:
            self.mark("end", status.name.lower(), len(self.s) - 1,
                      self.options.tol)
        s = np.array(self.s, dtype=float)
        curve = Curve(
            x=np.array(self.x, dtype=float).reshape(-1, n1),
            s=s,
            tangents=np.array(self.tangents, dtype=float).reshape(-1, n1),
            ds=np.diff(s, prepend=s[:1]) if s.size else s.copy(),
            newton_iterations=np.array(self.iterations, dtype=int),
            special_points=tuple(sorted(self.special, key=lambda p: (p.index, p.s))),
            status=status,
            message=message,
            residual_evals=self.evaluator.residual_evals,
            jacobian_evals=self.evaluator.jacobian_evals,
            rejected_steps=self.rejected,
            residuals=np.array(self.residuals, dtype=float),
            problem=self.problem,
            options=self.options,
        )
        if status.failed:
            logger.warning("continuation failed: %s", message)
            if self.options.raise_on_failure and raise_failure:
                raise ContinuationError(message, curve)
        return curve
