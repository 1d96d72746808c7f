"""The result of a continuation run: a curve, its special points and a status."""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field

import numpy as np

from .corrector import correct
from .errors import CallbackError, CallbackShapeError, ContinuationError
from .options import Options
from .predictor import hermite
from .problem import Evaluator, Problem

__all__ = [
    "SPECIAL_KINDS",
    "SpecialKind",
    "CallbackError",
    "CallbackShapeError",
    "ContinuationError",
    "Curve",
    "SpecialPoint",
    "Status",
]

class SpecialKind(str, enum.Enum):
    """Kinds of :class:`SpecialPoint`; the values are the names used in files and logs.

    A ``str`` enum, so that ``point.kind == "fold"`` keeps working.
    """

    START = "start"
    END = "end"
    FOLD = "fold"
    BRANCH_POINT = "branch_point"
    EVENT = "event"
    CLOSED = "closed"

    def __str__(self) -> str:
        return self.value


#: the values of :class:`SpecialKind`
SPECIAL_KINDS = tuple(kind.value for kind in SpecialKind)


class Status(enum.Enum):
    """How a run ended; the value is a readable message."""

    CLOSED = "the curve closed on its start point"
    TERMINAL_EVENT = "a terminal event stopped the curve"
    MAX_STEPS = "reached the maximum number of steps"
    MAX_ARCLENGTH = "reached the maximum arclength"
    STEP_TOO_SMALL = "the step size fell below its minimum"
    START_NOT_CONVERGED = "the start point could not be corrected onto the curve"
    SINGULAR_START = "the Jacobian is singular at the start point"
    NON_FINITE = "the residual or Jacobian returned non-finite values"
    EVENT_NOT_FINITE = "an event function returned a non-finite value"
    NOT_LOCATED = "a special point was bracketed but could not be located"
    INCONSISTENT = "the special points found disagree with the traced points"
    CALLBACK_FAILED = "a residual, Jacobian or event function raised or returned a wrong shape"
    JACOBIAN_MISMATCH = "the Jacobian disagrees with differences of the residual"

    @property
    def failed(self) -> bool:
        """Whether the run ended in a failure rather than a normal end."""
        return self in _FAILURES


_FAILURES = frozenset({Status.STEP_TOO_SMALL, Status.START_NOT_CONVERGED,
                       Status.SINGULAR_START, Status.NON_FINITE, Status.EVENT_NOT_FINITE,
                       Status.NOT_LOCATED, Status.INCONSISTENT, Status.CALLBACK_FAILED,
                       Status.JACOBIAN_MISMATCH})


@dataclass(frozen=True, eq=False)
class SpecialPoint:
    """A located point of interest on a curve.

    Parameters
    ----------
    kind : SpecialKind
        ``START``, ``END``, ``FOLD``, ``BRANCH_POINT``, ``EVENT`` or ``CLOSED``
        (equal to the strings ``'start'``, ``'end'``, ...).
    name : str
        Event name, ``'fold <coordinate>'``, ``'branch point'``, ``'start'``,
        ``'closed'``, or for ``'end'`` the lower-case status name.
    index : int
        Index of the point in ``Curve.x`` (special points are points of the
        curve).
    x : ndarray, shape (n + 1,)
        The point.
    s : float
        Its arclength (``Curve.s[index]``).
    residual : float
        ``max |H(x)|``.
    accuracy : float
        Width in arclength of the final root bracket (0 if the located
        function vanished exactly at a corrected point; for start and end
        points, the Newton tolerance; for a branch point passed to
        ``switch_branch``, the accuracy of its location). It bounds the error
        of the zero along the curve's own arc, not that of ``x``: folds and
        events are exact to it and to the Newton tolerance, a branch point
        (located on a Hermite arc across the singular point) to about
        ``1e-11`` relative to the scale of ``x`` at tight tolerances, but no
        better than about ``sqrt(tol)`` (there ``H`` is quadratic in the distance
        from it: at ``tol = 5e-8`` a branch point was 2e-4 off), or where two
        branch points lie closer than about ``sqrt(tol)`` (the branches nearly
        touch), to about ``tol`` over their distance.
    coordinate : int or None
        The coordinate of a fold, else ``None``.
    tangent : ndarray, shape (n + 1,) or None
        Unit tangent of the traced branch at the point.
    event : int or None
        For an event, its position in the ``events`` passed to ``trace`` (events are
        identified by position, never by name), else ``None``.
    """

    kind: SpecialKind
    name: str
    index: int
    x: np.ndarray = field(repr=False)
    s: float
    residual: float
    accuracy: float
    coordinate: int | None = None
    tangent: np.ndarray | None = field(default=None, repr=False)
    event: int | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "kind", SpecialKind(self.kind))


@dataclass(frozen=True, eq=False)
class Curve:
    """A traced piece of the solution curve of ``H(x) = 0``.

    Parameters
    ----------
    x : ndarray, shape (m, n + 1)
        Points, every one with ``max |H| <= tol``, in order of arclength;
        special points are among them.
    s : ndarray, shape (m,)
        Arclength from the start, increasing: each step adds its chord
        ``c`` corrected by the angle ``alpha`` between its end tangents,
        ``|c| (alpha/2) / sin(alpha/2)`` (exact on circular arcs, ``O(h^5)``
        per step otherwise).
    tangents : ndarray, shape (m, n + 1)
        Unit tangents, oriented along the direction of travel.
    ds : ndarray, shape (m,)
        ``s[i] - s[i - 1]``, 0 at the start.
    newton_iterations : ndarray of int, shape (m,)
        Newton steps that produced each point.
    special_points : tuple of SpecialPoint
        Start (or branch point), folds, branch points, events, closure, end,
        ordered by index.
    status : Status
        How the run ended.
    message : str
        What happened, and for failures where and what to change.
    residual_evals, jacobian_evals : int
        Calls of the residual (including those of finite-difference
        Jacobians) and Jacobians.
    rejected_steps : int
        Rejected predictor-corrector steps.
    residuals : ndarray, shape (m,)
        ``max |H|`` at every point.
    problem : Problem
        The problem (for dense output).
    options : Options
        The options of the run (tolerances for dense output).
    """

    x: np.ndarray
    s: np.ndarray
    tangents: np.ndarray
    ds: np.ndarray
    newton_iterations: np.ndarray
    special_points: tuple[SpecialPoint, ...]
    status: Status
    message: str
    residual_evals: int
    jacobian_evals: int
    rejected_steps: int
    residuals: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    problem: Problem | None = field(default=None, compare=False, repr=False)
    options: Options | None = field(default=None, compare=False, repr=False)

    def __len__(self) -> int:
        return int(self.s.size)

    @property
    def ok(self) -> bool:
        """Whether the run ended normally (``not status.failed``)."""
        return not self.status.failed

    @property
    def max_residual(self) -> float:
        """``max |H(x)|`` over all points (0 for an empty curve)."""
        return float(self.residuals.max()) if self.residuals.size else 0.0

    def special(self, kind: SpecialKind | str) -> tuple[SpecialPoint, ...]:
        """Return the special points of one kind, in order along the curve.

        Raises
        ------
        ValueError
            If ``kind`` is not a :class:`SpecialKind` (or its value).
        """
        try:
            kind = SpecialKind(kind)
        except ValueError:
            raise ValueError(f"kind must be one of {SPECIAL_KINDS}, got {kind!r}") from None
        return tuple(point for point in self.special_points if point.kind is kind)

    def point_at(self, s: float) -> np.ndarray:
        """Return the point of the curve at pseudo-arclength ``s``.

        Parameters
        ----------
        s : float
            Arclength, ``self.s[0] <= s <= self.s[-1]``.

        Returns
        -------
        ndarray, shape (n + 1,)
            The cubic Hermite prediction between the neighbouring points,
            corrected by Newton onto the curve in the hyperplane through the
            prediction normal to the interpolated tangent (``|H| <= tol``, the
            correction converged to ``event_tol``); its arclength is ``s`` up
            to the ``O(h^4)`` error of the Hermite arc's parametrisation.

        Raises
        ------
        ValueError
            If ``s`` is outside the curve or the correction fails.
        """
        self._require_problem()
        if not (self.s.size and self.s[0] <= s <= self.s[-1]):
            span = f"[{float(self.s[0])!r}, {float(self.s[-1])!r}]" if self.s.size else "empty"
            raise ValueError(f"s must lie in the curve's arclength range {span}, got {s!r}")
        i = int(np.searchsorted(self.s, s, side="right")) - 1
        if self.s[i] == s:
            return self.x[i].copy()
        h = self.s[i + 1] - self.s[i]
        point, derivative = hermite(self.x[i], self.tangents[i], self.x[i + 1],
                                    self.tangents[i + 1], h, s - self.s[i])
        border = derivative / np.linalg.norm(derivative)
        return self._correct(point, border, None, f"s={s!r}")

    def point_where(self, coordinate: int, value: float) -> np.ndarray | list[np.ndarray]:
        """Return the point(s) of the curve where ``x[coordinate] == value``.

        Parameters
        ----------
        coordinate : int
            Index of the coordinate, ``0 <= coordinate <= n``.
        value : float
            The value it must take.

        Returns
        -------
        ndarray of shape (n + 1,), or list of them
            One array if the curve crosses the value once, else a list in order
            of arclength. Each point is corrected onto the curve by Newton with
            the border equation ``x[coordinate] = value``, not interpolated: to
            ``options.event_tol``, or where the residual's noise does not allow it, to
            ``options.tol`` like the curve's points.

        Raises
        ------
        ValueError
            If the coordinate is out of range, the curve never takes the value,
            or a correction fails (at a fold in this coordinate).
        """
        problem = self._require_problem()
        n1 = self.x.shape[1] if self.x.ndim == 2 else 0
        if not (isinstance(coordinate, (int, np.integer)) and 0 <= coordinate < n1):
            raise ValueError(f"coordinate must be in [0, {n1 - 1}], got {coordinate!r}")
        column = self.x[:, coordinate] - value
        border = np.zeros(n1)
        border[coordinate] = 1.0
        points = []
        for i in range(column.size):
            if column[i] == 0.0:
                points.append(self.x[i].copy())
            elif i + 1 < column.size and column[i] * column[i + 1] < 0:
                h = self.s[i + 1] - self.s[i]
                sigma = _solve_hermite_coordinate(self, i, coordinate, value, h)
                point, _ = hermite(self.x[i], self.tangents[i], self.x[i + 1],
                                   self.tangents[i + 1], h, sigma)
                points.append(self._correct(point, border, float(value),
                                            f"{problem.coordinate_name(coordinate)}="
                                            f"{value!r}"))
        if not points:
            low, high = (float(column.min() + value), float(column.max() + value)) \
                if column.size else (math.nan, math.nan)
            raise ValueError(
                f"{problem.coordinate_name(coordinate)} never equals {value!r} on the "
                f"curve; it ranges over [{low!r}, {high!r}]"
            )
        return points[0] if len(points) == 1 else points

    def _require_problem(self) -> Problem:
        if self.problem is None:
            raise ValueError("dense output needs the curve's problem, but Curve.problem is None")
        return self.problem

    def _correct(self, point, border, target, where) -> np.ndarray:
        """``point`` corrected onto the curve with ``border . x = target``: to ``event_tol``,
        or where Newton cannot get there (a residual with noise above it, e.g. difference
        quotients of difference quotients) to ``tol``, as the curve's own points."""
        options = self.options or Options()
        evaluator = Evaluator(self._require_problem())
        result = correct(evaluator, point, border, options.locate_newton, target=target,
                         need_tangent=False)
        if not result.ok:
            result = correct(evaluator, point, border, options.newton, target=target,
                             need_tangent=False)
        if not result.ok:
            raise ValueError(f"could not correct the point at {where} onto the curve: "
                             f"{result.reason}")
        return result.x


def _solve_hermite_coordinate(curve: Curve, i: int, coordinate: int, value: float,
                              h: float) -> float:
    """Arclength offset where the Hermite arc of step ``i`` has ``x[coordinate] = value``."""
    low, high = 0.0, h
    f_low = curve.x[i, coordinate] - value
    sigma = h * f_low / (f_low - (curve.x[i + 1, coordinate] - value))
    for _ in range(30):
        point, derivative = hermite(curve.x[i], curve.tangents[i], curve.x[i + 1],
                                    curve.tangents[i + 1], h, sigma)
        f = point[coordinate] - value
        if f == 0:
            return sigma
        if (f < 0) == (f_low < 0):
            low = sigma
        else:
            high = sigma
        slope = derivative[coordinate]
        step = sigma - f / slope if slope != 0 else 0.5 * (low + high)
        sigma = step if low < step < high else 0.5 * (low + high)
        if high - low < 1e-14 * h:
            break
    return sigma
