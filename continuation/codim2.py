r"""Two-parameter continuation: a fold or an event point followed as the parameter ``p`` moves.

:func:`follow_fold` and :func:`follow_event` trace, in ``z = (x, p)``, the curve of the special
points of the curves ``H(., p) = 0`` of a :class:`~continuation.family.Family`, with the
augmented systems of :mod:`continuation.augmented`, and find its codimension-2 points:

==========================  =================================================================
kind                        what happens (located as)
==========================  =================================================================
``CUSP``                    two folds of ``x_i`` meet and vanish: the fold curve turns in
                            ``p`` (a fold of the fold curve in ``p``, where the fold of the
                            curve ``H(., p) = 0`` is degenerate, ``d^2 x_i/ds^2 = 0``)
``SINGULAR``                where a cusp would be, ``H_x`` has rank ``< n``: the curve
                            ``H(., p) = 0`` is itself singular there (an isola is born or
                            vanishes at a point, or two of its branches cross); not a cusp
``TANGENCY``                two event points meet and vanish: the event curve turns in ``p``
                            (the event is tangent to ``H(., p) = 0`` there)
``EVENT``                   a zero of an event of ``z``: a special point leaves through a
                            boundary (terminal) or meets another special point
``BRANCH_POINT``            two curves of special points cross
==========================  =================================================================

Each is located on the curve like any special point of :func:`continuation.trace` (bracketed
inside a step, Brent on the curve, to ``Options.event_tol``); an event point is then polished
by Newton on its square defining system (the ``n + 1`` equations of the curve and the event),
whose residual it reports with its equations.

Example
-------
The cusp normal form ``x^3 - mu x - lambda = 0``, ``x = (lambda, u)``, ``p = mu``: its folds in
``lambda`` lie on ``lambda = +-2 (mu/3)^(3/2)`` and meet at the cusp ``mu = 0``.

>>> import numpy as np
>>> from continuation import Family, follow_fold
>>> cusp = Family(lambda x, mu: np.array([x[1]**3 - mu * x[1] - x[0]]),
...               lambda x, mu: np.array([[-1.0, 3 * x[1]**2 - mu]]),
...               lambda x, mu: np.array([-x[1]]), names=("lambda", "u"), parameter="mu")
>>> folds = follow_fold(cusp, [-2.0, 1.0], p=3.0, coordinate=0, direction=-1,
...                     parameter_range=(-1.0, 3.0))
>>> [point.kind.value for point in folds.points]   # the cusp, then the end at mu = 3
['cusp', 'event']
>>> bool(abs(folds.special("cusp")[0].z).max() < 1e-10)
True
"""

from __future__ import annotations

import dataclasses
import enum
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import cast

import numpy as np

from .augmented import EventSystem, FoldSystem
from .closing import CLOSE_TOLERANCE
from .errors import ContinuationError
from .events import Event, box_events
from .family import Family
from .options import Options
from .predictor import hermite
from .problem import Problem, as_vector
from .result import Curve, SpecialKind, SpecialPoint, Status
from .tracker import follow

__all__ = ["Codim2Curve", "Codim2Kind", "Codim2Point", "follow_event", "follow_fold"]

_EPS = np.finfo(float).eps

#: a polished point may move at most this far (relative to 1 + max|z|) from the located one
POLISH_JUMP = 1e-8


class Codim2Kind(str, enum.Enum):
    """Kinds of codimension-2 points (see the module's table); values are the names in files."""

    CUSP = "cusp"
    SINGULAR = "singular"
    TANGENCY = "tangency"
    EVENT = "event"
    BRANCH_POINT = "branch_point"

    def __str__(self) -> str:
        return self.value


@dataclass(frozen=True)
class Codim2Point:
    """A codimension-2 point of a curve of special points.

    Attributes
    ----------
    kind : Codim2Kind
    name : str
        The event's name, ``"cusp"``, ``"tangency"`` or ``"branch point"``.
    z : ndarray, shape (n + 2,)
        The point ``(x, p)``; for an event, polished by Newton on its defining equations.
    index : int
        Row of the located point in :attr:`Codim2Curve.z`.
    s : float
        Arclength of that row.
    accuracy : float
        Width in arclength of the final root bracket of the location: of the zero of the test
        function as computed. For a cusp that test is a tangent component built on the fold
        test's gradient, a difference quotient, so the point can lie further from the true
        cusp along the curve than this (for ``lambda = p u - u^4/4 + eps u^2/2``, whose cusps
        are ``u = +-sqrt(eps/3)``: ``3e-11`` for ``eps = 1``, ``1e-8`` for ``eps = 1e-6``); the
        point is on the fold curve to ``residual`` all the same.
    residual : float
        ``max |F(z)|`` over the defining equations at ``z`` (for an event, including the event).
    equations : tuple of str
        The defining equations in words.
    event : int or None
        For an event, its position in the ``events`` passed to the driver.
    terminal : bool
        Whether the curve ends there.
    """

    kind: Codim2Kind
    name: str
    z: np.ndarray = field(repr=False)
    index: int
    s: float
    accuracy: float
    residual: float
    equations: tuple[str, ...] = ()
    event: int | None = None
    terminal: bool = False

    @property
    def x(self) -> np.ndarray:
        """The point of the curve ``H(., p) = 0``."""
        return self.z[:-1]

    @property
    def p(self) -> float:
        """The parameter value."""
        return float(self.z[-1])


@dataclass(frozen=True, eq=False)
class Codim2Curve:
    """A curve of special points in ``z = (x, p)``, in one or more engine pieces.

    Attributes
    ----------
    what : str
        ``"fold of <coordinate>"`` or ``"event '<name>'"``.
    z : ndarray, shape (m, n + 2)
        Points, every one on the curve (the pieces joined; a piece starts where the last
        ended, where the fold test's borders were renewed).
    s, tangents, residuals : ndarray
        Arclength from the start, unit tangents, ``max |F|`` per point.
    points : tuple of Codim2Point
        Codimension-2 points in order along the curve.
    status : continuation.Status
        How the last piece ended (or the first piece that failed): ``CLOSED`` where the
        curve came back to its first point (in any piece), ``MAX_STEPS`` or ``MAX_ARCLENGTH``
        where the options' limits, which hold for the whole curve over its pieces (a point
        inserted at a special point counting as a step), ran out.
    message : str
    equations : tuple of str
        The curve's defining equations in words.
    pieces : tuple of Curve
        The engine's curves (each with its own augmented problem, for dense output).
    residual_evals, jacobian_evals, rejected_steps : int
        Summed over the pieces.
    """

    what: str
    z: np.ndarray = field(repr=False)
    s: np.ndarray = field(repr=False)
    tangents: np.ndarray = field(repr=False)
    residuals: np.ndarray = field(repr=False)
    points: tuple[Codim2Point, ...]
    status: Status
    message: str
    equations: tuple[str, ...]
    pieces: tuple[Curve, ...] = field(repr=False)
    residual_evals: int = 0
    jacobian_evals: int = 0
    rejected_steps: int = 0

    def __len__(self) -> int:
        return int(self.s.size)

    @property
    def ok(self) -> bool:
        """Whether the run ended normally."""
        return not self.status.failed

    @property
    def x(self) -> np.ndarray:
        return self.z[:, :-1]

    @property
    def p(self) -> np.ndarray:
        return self.z[:, -1]

    def special(self, kind: Codim2Kind | str) -> tuple[Codim2Point, ...]:
        """The codimension-2 points of one kind."""
        kind = Codim2Kind(kind)
        return tuple(point for point in self.points if point.kind is kind)

    def dense(self, per_step: int = 8) -> np.ndarray:
        """Points on the cubic Hermite arcs between the computed points, for drawing.

        ``per_step`` points per step (the computed points included), not corrected onto the
        curve: their distance to it is ``O(h^4)`` in the step ``h`` (use :meth:`at` for exact
        points).
        """
        if len(self) < 2:
            return self.z.copy()
        rows = []
        for i in range(len(self) - 1):
            h = float(self.s[i + 1] - self.s[i])
            for sigma in np.linspace(0.0, h, per_step, endpoint=False):
                point, _ = hermite(self.z[i], self.tangents[i], self.z[i + 1],
                                   self.tangents[i + 1], h, sigma)
                rows.append(point)
        rows.append(self.z[-1])
        return np.array(rows)

    def at(self, p: float) -> list[np.ndarray]:
        """Every point of the curve with parameter ``p``, in order along it.

        Each is corrected onto the curve by Newton with ``z[-1] = p`` as its border equation
        (:meth:`continuation.Curve.point_where` on the piece that spans ``p``).

        Raises
        ------
        ValueError
            If a correction fails (at a cusp or tangency, where ``p`` is stationary).
        """
        found: list[np.ndarray] = []
        for piece in self.pieces:
            column = piece.x[:, -1]
            if not (column.size and column.min() <= p <= column.max()):
                continue
            points = piece.point_where(piece.x.shape[1] - 1, float(p))
            for point in points if isinstance(points, list) else [points]:
                if not any(np.array_equal(point, other) for other in found):
                    found.append(point)
        return found


def follow_fold(family: Family, start, p: float | None = None, coordinate: int | None = None,
                direction=1, options: Options | None = None, events: Sequence[Event] = (),
                parameter_range: tuple[float, float] | None = None) -> Codim2Curve:
    """Follow a fold (limit point) of coordinate ``x_i`` as the parameter ``p`` moves.

    Parameters
    ----------
    family : Family
        The curves ``H(x, p) = 0``.
    start : SpecialPoint or array_like
        A fold found by :func:`continuation.trace` on ``family.at(p)`` (a ``SpecialPoint`` of
        kind ``FOLD``, whose coordinate is the default ``coordinate``), or a guess: ``x``
        (shape ``(n + 1,)``, with ``p``) or ``z = (x, p)`` (shape ``(n + 2,)``). It is
        corrected onto the fold curve first.
    p : float, optional
        The parameter value of ``start`` (needed unless ``start`` is a ``z``).
    coordinate : int, optional
        The coordinate ``i`` of ``x`` whose folds are followed.
    direction : {1, -1} or array_like of shape (n + 2,), optional
        ``+1`` (default): towards increasing ``p``; ``-1``: decreasing; an array: the initial
        tangent has a positive dot product with it.
    options : Options, optional
        Engine settings; folds in ``p`` (cusps) are always detected.
    events : sequence of Event
        Events of ``z = (x, p)``; a zero is a codimension-2 point of kind ``EVENT`` (a
        terminal one ends the curve: the fold leaves through a boundary).
    parameter_range : (float, float), optional
        Terminal events at ``p = lo`` and ``p = hi``.

    Returns
    -------
    Codim2Curve
        A failure (``not curve.ok``) keeps everything traced; with
        ``options.raise_on_failure`` a :class:`ContinuationError` is raised instead.

    Raises
    ------
    ValueError
        If an argument is out of range, the start has the wrong shape (an ``x`` without
        ``p``), or ``parameter_range`` does not hold the start's ``p``.

    Notes
    -----
    The curve is the zero set of ``(H, g)`` (:class:`continuation.augmented.FoldSystem`), regular
    at simple folds. Its cusps are its folds in ``p``: there the fold is degenerate, since a
    tangent ``(dx, 0)`` of the fold curve has ``dx`` along the null vector and ``g_x dx = 0``,
    so that ``g``, which vanishes with ``t_i`` to the same order, has a double zero along
    ``H(., p) = 0`` (Govaerts 2000, sec. 4.3 and 6.1).
    """
    if coordinate is None:
        if isinstance(start, SpecialPoint) and start.kind is SpecialKind.FOLD:
            coordinate = start.coordinate
        else:
            raise ValueError("coordinate is needed unless start is a fold SpecialPoint")
    z0 = _start_point(family, start, p)
    n1 = z0.size - 1
    if not (isinstance(coordinate, (int, np.integer)) and 0 <= coordinate < n1):
        raise ValueError(f"coordinate must be an index of x, 0 <= coordinate < {n1}, "
                         f"got {coordinate!r}")
    names = family.names_z(n1)
    first = FoldSystem(family, int(coordinate), z0)
    return _follow(family, lambda z: FoldSystem(family, int(coordinate), z), first, z0,
                   f"fold of {names[coordinate]}", Codim2Kind.CUSP, direction, options,
                   events, parameter_range)


def follow_event(family: Family, event: Event, start, p: float | None = None, direction=1,
                 options: Options | None = None, events: Sequence[Event] = (),
                 parameter_range: tuple[float, float] | None = None) -> Codim2Curve:
    """Follow an event point, a zero of ``e(x, p)`` on ``H(x, p) = 0``, as ``p`` moves.

    Parameters
    ----------
    family : Family
    event : Event
        ``e(z)`` of ``z = (x, p)`` (its ``gradient``, if given, too); ``family.event_at(event,
        p)`` is the same event for :func:`continuation.trace` at a fixed ``p``.
    start : SpecialPoint or array_like
        The event point found by ``trace`` (kind ``EVENT``) or a guess, as for
        :func:`follow_fold`.
    p, direction, options, events, parameter_range
        As for :func:`follow_fold`; folds in ``p`` are ``TANGENCY`` points, where two event
        points meet (the event touches the curve).

    Returns
    -------
    Codim2Curve
    """
    if not isinstance(event, Event):
        raise TypeError(f"event must be an Event, got {type(event).__name__}")
    z0 = _start_point(family, start, p)
    system = EventSystem(family, event)
    return _follow(family, None, system, z0, f"event '{event.name}'", Codim2Kind.TANGENCY,
                   direction, options, events, parameter_range)


def _start_point(family: Family, start, p) -> np.ndarray:
    """``z0 = (x, p)`` from a special point or an array, checked against the family."""
    x = start.x if isinstance(start, SpecialPoint) else as_vector("start", start)
    if p is not None:
        if not math.isfinite(float(p)):
            raise ValueError(f"p must be finite, got {p!r}")
        z = np.append(x, float(p))
    elif isinstance(start, SpecialPoint):
        raise ValueError("p is needed with a SpecialPoint start: the parameter value of the "
                         "curve it was found on")
    else:
        z = x
    try:
        H = family.residual_z(z)
    except Exception as exc:
        if p is not None:
            raise
        # typically an x without its p: the family's functions index past the end of z
        raise ValueError(f"start has {z.size} coordinates and no p was given: pass x with "
                         f"p=, or z = (x, p); the residual at start raised "
                         f"{type(exc).__name__}: {exc}") from exc
    if H.shape != (z.size - 2,):
        raise ValueError(f"start has {z.size - 1} coordinates x and p but the residual has "
                         f"shape {H.shape}: x needs n + 1 = {H.size + 1} coordinates")
    return z


def _options(options: Options | None, n2: int) -> Options:
    options = Options() if options is None else options
    if not isinstance(options, Options):
        raise TypeError(f"options must be an Options, got {type(options).__name__}")
    folds = tuple(dict.fromkeys((*options.fold_coordinates, n2 - 1)))
    return dataclasses.replace(options, fold_coordinates=folds, raise_on_failure=False)


def _direction(direction, n2: int):
    if isinstance(direction, (int, np.integer)) and not isinstance(direction, bool) \
            and direction in (1, -1):
        unit = np.zeros(n2)
        unit[-1] = float(direction)
        return unit
    array = as_vector("direction", direction)
    if array.size != n2:
        raise ValueError(f"direction must be 1, -1 or an array of shape ({n2},), "
                         f"got {direction!r}")
    return array


def _follow(family, renew, system, z0, what, turn_kind, direction, options, events,
            parameter_range) -> Codim2Curve:
    """Trace the curve of ``system`` in pieces (renewing a fold test's borders) and join them."""
    n2 = z0.size
    names = family.names_z(n2 - 1)
    user_options = Options() if options is None else options
    options = _options(options, n2)
    events = tuple(events)
    if parameter_range is not None:
        lo, hi = (float(v) for v in parameter_range)
        p0 = float(z0[-1])
        if not lo <= p0 <= hi:
            raise ValueError(f"the start's {names[-1]} = {p0!r} is outside parameter_range = "
                             f"({lo!r}, {hi!r}): it must hold the start, lo <= p <= hi")
        events += tuple(box_events({n2 - 1: lo}, {n2 - 1: hi}, names=names))
    heading = _direction(direction, n2)
    pieces, systems = [], []
    # the user's limits hold for the whole curve: what is left of them for the next piece
    steps, length = options.max_steps, options.max_arclength
    closes_at = None  # a later piece closes the curve on the first piece's start
    exhausted = None
    while True:
        extra = system.border_events() if renew is not None else []
        problem = Problem(system.residual, system.jacobian, names=names)
        curve = follow(problem, z0, direction=heading, events=[*events, *extra],
                       options=dataclasses.replace(options, max_steps=steps,
                                                   max_arclength=length),
                       closes_at=closes_at)
        pieces.append(curve)
        systems.append(system)
        ended = [p for p in curve.special("event") if p.index == len(curve) - 1]
        # an event point's position is an int (SpecialPoint)
        renewing = (curve.status is Status.TERMINAL_EVENT and ended
                    and cast(int, ended[-1].event) >= len(events) and len(curve) > 1)
        if not renewing:
            break
        if closes_at is None:
            closes_at = (curve.x[0], curve.tangents[0])
        elif options.detect_closed and _back_at(curve, *closes_at):
            # the borders are renewed where the curve comes back to its start: a new piece
            # would close after a step of rounding length, with folds of its noise
            exhausted = (Status.CLOSED, f"{Status.CLOSED.value} after {len(pieces)} pieces, "
                         f"length s={sum(float(c.s[-1]) for c in pieces):.12g}")
            break
        steps -= len(curve) - 1  # a point inserted at a special point counts as a step
        length -= float(curve.s[-1])
        if steps <= 0 or not length > 0:
            # stopped for renewing the borders once more, not at an end of the curve
            exhausted = _limit(Status.MAX_STEPS if steps <= 0 else Status.MAX_ARCLENGTH,
                               options, len(pieces))
            break
        z0, heading = curve.x[-1], curve.tangents[-1]
        system = renew(z0)
    if pieces[-1].status in (Status.MAX_STEPS, Status.MAX_ARCLENGTH) and len(pieces) > 1:
        exhausted = _limit(pieces[-1].status, options, len(pieces))  # not the piece's share
    result = _join(pieces, systems, events, what, turn_kind, names, user_options, exhausted)
    if result.status.failed and user_options.raise_on_failure:
        raise ContinuationError(result.message, pieces[-1])
    return result


def _limit(status: Status, options: Options, pieces: int) -> tuple[Status, str]:
    """``(status, message)`` of a curve that reached a limit of ``options`` over its pieces."""
    if status is Status.MAX_STEPS:
        return status, f"{status.value} ({options.max_steps}, over {pieces} pieces)"
    return status, f"{status.value} s={options.max_arclength:.12g} (over {pieces} pieces)"


def _back_at(curve: Curve, x0: np.ndarray, t0: np.ndarray) -> bool:
    """Whether ``curve`` ends on its first piece's start ``x0``, along its tangent ``t0``
    (within the engine's closing tolerance, :data:`continuation.closing.CLOSE_TOLERANCE`)."""
    gap = float(np.max(np.abs(curve.x[-1] - x0)))
    return (gap <= CLOSE_TOLERANCE * (1.0 + float(np.max(np.abs(x0))))
            and float(curve.tangents[-1] @ t0) > 0.0)


def _join(pieces, systems, events, what, turn_kind, names, options,
          exhausted=None) -> Codim2Curve:
    """One :class:`Codim2Curve` from the pieces (each starts at the last one's end);
    ``exhausted``: ``(status, message)`` if the curve closed or the limits ran out at a
    renewal of the borders."""
    z, s, tangents, residuals, points = [], [], [], [], []
    offset_s, offset_i = 0.0, 0
    for k, (curve, system) in enumerate(zip(pieces, systems, strict=True)):
        skip = 1 if k else 0
        z.append(curve.x[skip:])
        s.append(curve.s[skip:] + offset_s)
        tangents.append(curve.tangents[skip:])
        residuals.append(curve.residuals[skip:])
        for point in curve.special_points:
            found = _codim2_point(point, system, events, turn_kind, names, options)
            if found is not None and (point.index or not k):
                points.append(dataclasses.replace(found, index=point.index + offset_i,
                                                  s=point.s + offset_s))
        offset_s += float(curve.s[-1]) if len(curve) else 0.0
        offset_i += len(curve) - 1 if len(curve) else 0
    last = next((c for c in pieces if c.status.failed), pieces[-1])
    status, message = last.status, last.message
    if status is Status.SINGULAR_START and last is pieces[0]:
        # the engine's advice (a branch point of a curve: switch_branch) does not fit here
        message = (f"the start is not a regular point of the curve of {what}: check that it "
                   f"is a {what} at its p (a fold of that coordinate, for follow_fold), not a "
                   f"degenerate one (a cusp); the augmented system's Jacobian is singular there "
                   f"({message.partition(': the start is')[0]})")
    if exhausted is not None:
        status, message = exhausted
    return Codim2Curve(
        what=what, z=np.concatenate(z), s=np.concatenate(s), tangents=np.concatenate(tangents),
        residuals=np.concatenate(residuals), points=tuple(points), status=status,
        message=message, equations=systems[0].equations(names), pieces=tuple(pieces),
        residual_evals=sum(c.residual_evals for c in pieces),
        jacobian_evals=sum(c.jacobian_evals for c in pieces),
        rejected_steps=sum(c.rejected_steps for c in pieces))


def _codim2_point(point: SpecialPoint, system, events, turn_kind, names, options):
    """The codimension-2 point an engine special point of the augmented curve stands for."""
    equations = system.equations(names)
    n2 = len(names)
    if point.kind is SpecialKind.FOLD and point.coordinate == n2 - 1:
        what = ("the fold is degenerate (d^2 x_i/ds^2 = 0): two folds meet" if turn_kind is
                Codim2Kind.CUSP else "the event is tangent to the curve: two event points meet")
        kind = turn_kind
        if turn_kind is Codim2Kind.CUSP and _rank_deficient(system, point.x):
            kind, what = Codim2Kind.SINGULAR, (
                "H_x has rank < n: the curve H(., p) = 0 is singular here (an isola is born or "
                "vanishes, or two of its branches cross), no fold is defined, not a cusp")
        return Codim2Point(kind, kind.value, point.x.copy(), point.index, point.s,
                           point.accuracy, point.residual,
                           (*equations, f"the tangent has no {names[-1]} component: {what}"))
    if point.kind is SpecialKind.BRANCH_POINT:
        return Codim2Point(Codim2Kind.BRANCH_POINT, "branch point", point.x.copy(), point.index,
                           point.s, point.accuracy, point.residual,
                           (*equations, "det [F'; t^T] changes sign: two curves cross"))
    if point.kind is SpecialKind.EVENT and point.event is not None and point.event < len(events):
        event = events[point.event]
        z, residual = _polish(system, event, point.x, options)
        return Codim2Point(Codim2Kind.EVENT, event.name, z, point.index, point.s,
                           point.accuracy, residual, (*equations, f"event '{event.name}' = 0"),
                           point.event, event.terminal)
    return None


#: ``H_x`` with a smallest singular value below this fraction of ``max |H_z|`` has rank < n
RANK_DEFICIENT = 1e-6


def _rank_deficient(system, z: np.ndarray) -> bool:
    """Whether ``H_x`` at ``z = (x, p)`` has rank ``< n``, against the size of ``H_z``
    (with ``H_p``): a cusp needs rank ``n``, where only the fold's second derivative
    vanishes, not the curve's Jacobian."""
    family = system.family
    smallest = np.linalg.svd(family.jacobian_x(z[:-1], float(z[-1])), compute_uv=False)[-1]
    return bool(smallest <= RANK_DEFICIENT * np.abs(family.jacobian_z(z)).max())


def _polish(system, event: Event, z: np.ndarray, options: Options) -> tuple[np.ndarray, float]:
    """Newton on the square system ``(F, e) = 0`` from a located event point.

    Returns the polished point and ``max |(F, e)|`` there; the located point if Newton does not
    improve the residual or moves farther than :data:`POLISH_JUMP`.
    """
    events_system = EventSystem(system.family, event)

    def equations(y):
        return np.append(system.residual(y), float(event.function(y)))

    best, best_residual = z, float(np.max(np.abs(equations(z))))
    y = z.copy()
    for _ in range(8):
        G = equations(y)
        J = np.vstack([system.jacobian(y), events_system.gradient(y)])
        try:
            step = np.linalg.solve(J, -G)
        except np.linalg.LinAlgError:
            break
        if not np.all(np.isfinite(step)):
            break
        y = y + step
        residual = float(np.max(np.abs(equations(y))))
        if residual <= best_residual and np.max(np.abs(y - z)) <= POLISH_JUMP * (
                1.0 + np.max(np.abs(z))):
            best, best_residual = y.copy(), residual
        if np.max(np.abs(step)) <= 4.0 * _EPS * (1.0 + np.max(np.abs(y))):
            break
    return best, best_residual
