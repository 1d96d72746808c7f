"""The special points of one accepted step: bracketed, located, and added to the curve in order.

:func:`scan_step` brackets every zero of the events, of the fold coordinates' tangent
components and of the branch-point determinant inside the step (:mod:`continuation.scan`) and
locates each (:mod:`continuation.locate`), terminal events first; :func:`add_step` appends
the step's points and its special points to the run in their order along the curve;
:func:`fold_inconsistency` checks that the points never turn where no fold was reported, and
:func:`drop_unresolved_folds` removes folds in a coordinate the points do not resolve.
"""

from __future__ import annotations

import math
from typing import NamedTuple, cast

import numpy as np

from .bifurcation import branch_tangent_pair
from .corrector import Correction, correct
from .events import Event
from .linalg import all_finite
from .locate import Located, locate_zero, refine_branch_point
from .node import LocateError, Node, StepUnresolved, event_value
from .predictor import arc_length, hermite
from .problem import probe_jacobian
from .result import SpecialKind, SpecialPoint, Status
from .run import Run
from .scan import StepScan

__all__ = ["Found", "add_step", "append_end", "drop_unresolved_folds", "fold_inconsistency",
           "jacobian_at_special_points", "scan_step"]

#: components of a singular start's tangent at most this large are taken as zero
BRANCH_TANGENT_NOISE = 1e-7

#: a coordinate whose tangent component stays at most this large is flat along a stretch
#: (:func:`drop_unresolved_folds`); the rounding noise of a constant coordinate is 1e-8 or less
TANGENT_FLAT = 1e-6

#: a coordinate flat (within its noise) from a fold to an end of the curve over more than this
#: many points has stopped moving there: the fold is dropped (:func:`drop_unresolved_folds`)
SATURATED = 3


class Found(NamedTuple):
    located: Located
    kind: SpecialKind
    name: str
    coordinate: int | None
    terminal: bool
    event: int | None = None


def scan_step(run: Run, a: Node, b: Node, previous: Node | None = None) -> list[Found]:
    """Bracket and locate the special points of step ``(a, b]``, in order along it.

    ``previous``: the curve point before ``a``, if any (it makes the branch-point screen of a
    step cost no Jacobian: :meth:`StepScan.det_clear`).

    Raises
    ------
    LocateError
        If a special point was bracketed but could not be located (the step may
        be too long for the Hermite arc to predict its inside); an
        :class:`EventNotFinite` if an event is not finite inside the step; a
        :class:`StepUnresolved` if the step does not follow one smooth curve (with
        ``detect_branch_points``, on a step whose determinant nears zero:
        :meth:`StepScan.check_turn`).
    """
    options, evaluator = run.options, run.evaluator
    describe = run.problem.describe
    scan = StepScan(evaluator, options, run.events, a, b, run.linear)
    scan.check_linear_events()
    branches = options.detect_branch_points and not scan.det_clear(previous)
    if branches:
        # before locating anything: a step that jumped to another branch is rejected (a jump
        # near a branch point is never clear: the determinant nears zero on both branches)
        scan.check_turn()
    found: list[Found] = []
    what = "a special point"
    try:
        brackets = [(j, bracket) for j in scan.candidates()
                    for bracket in scan.event_brackets(j, run.events[j].direction)]
        end = None  # where the curve ends: the first terminal zero located so far
        for j, (lo, hi, f_lo, f_hi) in sorted(brackets, key=lambda item: _locate_order(
                run.events[item[0]], item[0], *item[1])):
            event = run.events[j]
            what = f"event '{event.name}'"
            if end is not None and hi.s > end.s:
                # the curve ends inside this bracket: only a zero before the end matters,
                # and there is one exactly when the event has changed sign at the end
                if lo.s >= end.s:
                    continue
                f_end = end.events[j]
                if f_end != 0.0 and (f_end > 0.0) == (f_lo > 0.0):
                    continue
                hi, f_hi = end, f_end
            located = locate_zero(evaluator, options,
                                  lambda c, e=event: event_value(e, c.x, describe),
                                  lo, hi, f_lo, f_hi, False)
            found.append(Found(located, SpecialKind.EVENT, event.name, None, event.terminal, j))
            if event.terminal and (end is None or located.s < end.s):
                end = _located_node(run, located)
        # the order along the step, events at one point in the order of the run's events
        found.sort(key=lambda item: (item.located.s, item.event))
        # folds only up to the first terminal event, where the curve ends
        for i in options.fold_coordinates:
            name = f"fold {run.problem.coordinate_name(i)}"
            what = f"'{name}'"
            for lo, hi, f_lo, f_hi in scan.fold_brackets(i, BRANCH_TANGENT_NOISE, end):
                located = locate_zero(evaluator, options, lambda c, i=i: c.tangent[i],
                                      lo, hi, f_lo, f_hi, True)
                found.append(Found(located, SpecialKind.FOLD, name, i, False))
        if branches:
            what = "a branch point"
            for lo, hi, f_lo, f_hi in scan.branch_brackets(end):
                # det [H'; b^T] with the interpolated tangent b: equal to det [H'; t^T] at
                # the bracket's ends, and smooth through the branch point where t is not
                located = locate_zero(evaluator, options, lambda c: c.border_det, lo, hi, f_lo,
                                      f_hi, True)
                if located.node is None:
                    refined = refine_branch_point(evaluator, options, located, lo, hi)
                    located = refined if refined is not located else _arc_tangent(located, a, b)
                found.append(Found(located, SpecialKind.BRANCH_POINT, "branch point", None,
                                   False))
            if found and found[-1].kind is SpecialKind.BRANCH_POINT and end is None:
                _check_branch_kept(run, scan, a, b, found[-1].located)
    except LocateError as error:
        raise type(error)(f"{what} in the step from s={a.s:.12g} to s={b.s:.12g}, "
                          f"x={describe(a.x)} to x={describe(b.x)}: {error}") from None
    # In order along the step's chord, not of the root finder's parameter: each location
    # refines its own Hermite arcs, whose parametrisations differ by O(h^4), so two special
    # points closer than that (a fold next to an event, near a codimension-2 point) would be
    # put in the wrong order; their projections on the chord are exact to the correction.
    chord = b.x - a.x
    found.sort(key=lambda item: float((_located_x(item.located) - a.x) @ chord))
    return found


def _check_branch_kept(run: Run, scan: StepScan, a: Node, b: Node, located: Located) -> None:
    """:class:`StepUnresolved` unless the step's end ``b`` lies on the branch that ``a`` came
    along, past the branch point ``located``; at a ``b`` on the branch point, its tangent
    becomes that branch's.

    Where two branches cross at a small angle ``theta`` the corrector converges to either
    beyond the branch point, and neither the determinant nor the tangents show a jump. The
    incoming branch's tangent ``t_in`` at the branch point is the root of the bifurcation
    equation nearest ``t_a`` carried there with its curvature (the other is ``theta`` away;
    the step is too long when the two are not clearly told apart); the incoming branch is then
    corrected, from ``x* + d t_in + (d^2/2) kappa_a``, onto the hyperplane through ``b`` normal
    to its tangent, and must meet it at ``b`` (the other branch is about ``theta d`` away).
    Where ``theta d / 4`` is below the points' accuracy ``tol (1 + max|x|)``, ``b`` is on the
    branch point itself.
    """
    if a.det == 0.0:
        return  # a singular start: the step begins at the branch point, on the branch given
    c = located.node if located.node is not None else cast(Correction, located.correction)
    x_star, s_star = c.x, located.s
    try:
        pair = branch_tangent_pair(run.evaluator, x_star, scan.width)
    except (ValueError, np.linalg.LinAlgError):
        return  # not a simple branch point to rounding: no pair of branches to tell apart
    kappa = scan.turning(a)
    guess = a.tangent + (s_star - a.s) * kappa
    guess = guess / float(np.linalg.norm(guess))
    tangents = [t if float(t @ guess) > 0.0 else -t for t in pair]
    angles = [math.acos(max(-1.0, min(1.0, float(t @ guess)))) for t in tangents]
    theta = math.acos(min(1.0, abs(float(pair[0] @ pair[1]))))
    incoming = tangents[0] if angles[0] <= angles[1] else tangents[1]
    where = (f"the step from s={a.s:.12g} to s={b.s:.12g} passed the branch point at "
             f"x={run.problem.describe(x_star)}, where branches cross at {theta:.3g} rad")
    if min(angles) > 0.25 * theta or max(angles) < 0.75 * theta:
        raise StepUnresolved(f"{where}: too long to tell which branch it came along")
    d = b.s - s_star
    if 0.25 * theta * d <= run.options.tol * (1.0 + float(np.max(np.abs(b.x)))):
        # b is on the branch point, to the points' accuracy: the tangent computed there is noise
        b.tangent = incoming
        return
    along = kappa - float(kappa @ incoming) * incoming
    p = x_star + d * incoming + 0.5 * d * d * along
    check = correct(run.evaluator, p, b.tangent, run.options.newton, target=float(b.tangent @ b.x),
                    max_correction=theta * d, need_tangent=False)
    if not check.ok or float(np.linalg.norm(check.x - b.x)) > 0.25 * theta * d:
        raise StepUnresolved(f"{where}: its end is not on the branch it came along (it may have "
                             "jumped to the other)")


def _located_x(located: Located) -> np.ndarray:
    # a Located without a node carries its correction
    return located.node.x if located.node is not None else cast(Correction, located.correction).x


def _locate_order(event: Event, j: int, lo: Node, hi: Node, f_lo: float, f_hi: float):
    """The order in which the step's event brackets are located: terminal events first,
    those whose zero looks simple (end slopes that match the secant, ``rate`` near 1) before
    those that look multiple (a triple zero has ``rate`` near 3), then by position.

    Any order gives the same zeros before the curve's end; this one locates the zero where the
    curve ends cheaply first, so that a bracket beyond it is dropped and one that contains
    it is cut at it (a multiple zero costs Brent's method tens of bisections).
    """
    if not event.terminal:
        return (1, 0.0, lo.s, j)
    rate = math.inf
    if lo.slopes is not None and hi.slopes is not None and f_hi != f_lo:
        m_lo, m_hi = lo.slopes[j], hi.slopes[j]
        if m_lo is not None and m_hi is not None:
            rate = 0.5 * (hi.s - lo.s) * (abs(m_lo) + abs(m_hi)) / abs(f_hi - f_lo)
    return (0, abs(math.log(rate)) if 0.0 < rate < math.inf else math.inf, lo.s, j)


def _located_node(run: Run, located: Located) -> Node:
    """A located point as a node with its event values (a bracket's end, or a new node)."""
    if located.node is not None:
        return located.node
    c = cast(Correction, located.correction)  # a Located without a node carries its correction
    return Node(c.x, located.s, c.tangent, c.det, c.residual, c.iterations,
                [event_value(e, c.x, run.problem.describe) for e in run.events], c.jacobian)


def add_step(run: Run, a: Node, b: Node, found: list[Found]) -> SpecialPoint | None:
    """Append the located special points of step ``(a, b]`` and ``b``.

    Returns the terminal event that ends the curve, if any; the curve then ends
    at that event point and the rest of the step is dropped.
    """
    first_terminal = next((item for item in found if item.terminal), None)
    if first_terminal is not None:
        found = found[:found.index(first_terminal) + 1]

    a_index = len(run.s) - 1
    b_index = None
    terminal = None
    previous_s = a.s
    for item in found:
        located = item.located
        if located.node is a:
            index = a_index
        elif located.node is b:
            if b_index is None:
                b_index = append_end(run, a_index, b)
            index = b_index
        elif located.s == previous_s and len(run.s) - 1 != a_index:
            index = len(run.s) - 1
        else:
            c = cast(Correction, located.correction) if located.node is None else located.node
            # the root finder's variable is the Hermite parameter; report arclength
            angle = math.acos(max(-1.0, min(1.0, float(c.tangent @ a.tangent))))
            s = min(b.s, a.s + arc_length(c.x - a.x, angle))
            index = run.append(c.x, max(s, run.s[-1]), c.tangent, c.residual, c.iterations)
        previous_s = located.s
        special = run.mark(item.kind, item.name, index, located.accuracy, item.coordinate,
                           item.event)
        if item is first_terminal:
            terminal = special
    if terminal is None and b_index is None:
        append_end(run, a_index, b)
    return terminal


def _arc_tangent(located: Located, a: Node, b: Node) -> Located:
    """``located`` (a branch point not refined) with the tangent of the step's Hermite arc
    there: the corrector's, from the bordered system at a singular point, is not the traced
    branch's (it was 0.2 rad off, and ``switch_branch`` took the traced branch for the new
    one); the arc's is, to its ``O(h^3)``."""
    correction = cast(Correction, located.correction)
    _, derivative = hermite(a.x, a.tangent, b.x, b.tangent, b.s - a.s, located.s - a.s)
    correction.tangent = derivative / float(np.linalg.norm(derivative))
    return located


def fold_inconsistency(run: Run) -> str:
    """A message if the points turn in a fold coordinate more often than folds were reported.

    The scan of every step is the primary detector; this check of the stored
    points is the backstop: along the points, each fold coordinate ``x_i`` may
    turn (its increments change sign, ignoring increments within ``100 tol`` of
    zero) only at reported folds, so the number of turns cannot exceed the
    number of folds (a fold at the curve's first or last point turns nothing).
    Increments are used rather than tangents: next to a branch point a
    computed tangent is noise, a corrected point is not.
    """
    x = np.array(run.x)
    noise = 100.0 * run.options.tol
    for i in run.options.fold_coordinates:
        steps = np.diff(x[:, i]) if len(x) > 1 else np.zeros(0)
        turns = _sign_changes([float(v) for v in steps if abs(v) > noise])
        folds = sum(1 for p in run.special if p.kind is SpecialKind.FOLD and p.coordinate == i)
        if turns > folds:
            return (f"the points turn {turns} times in {run.problem.coordinate_name(i)} but "
                    f"{folds} folds were located: a fold was missed; lower Options.ds_max")
    return ""


def jacobian_at_special_points(run: Run, at_end: bool = False) -> str:
    """A message if the problem's Jacobian is not the residual's derivative at a located fold
    or branch point (or, with ``at_end``, at the curve's last point), else ``""``.

    The check at the start (``Options.check_jacobian``) cannot see a Jacobian wrong only away
    from it; there Newton still converges onto the curve, but the tangents tilt, and the folds
    and branch points, zeros of the tangent's components and of ``det [H'; t^T]``, are located
    where they are not (``1e-3`` off for an error of ``1e-3``, with an accuracy of ``1e-12``).
    The same probe (:func:`continuation.problem.probe_jacobian`: one Jacobian and 2 residuals,
    6 if in doubt) runs at each such point, and at the end of a run whose steps had collapsed
    (the other sign of a wrong Jacobian). Not without ``check_jacobian``, nor for a problem
    with no Jacobian of its own.
    """
    if not run.options.check_jacobian or run.problem.jacobian is None or not run.x:
        return ""
    points = [(p.name, p.x) for p in run.special
              if p.kind in (SpecialKind.FOLD, SpecialKind.BRANCH_POINT)]
    if at_end:
        points.append(("the last point, where the steps had collapsed", run.x[-1]))
    for name, x in points:
        J = run.evaluator.jacobian(x)
        mismatch = probe_jacobian(run.evaluator, x, J) if all_finite(J) else None
        if mismatch is not None:
            return (f"{Status.JACOBIAN_MISMATCH.value} at {name} x={run.problem.describe(x)}: "
                    f"{mismatch}: the special points located with it are not where they are "
                    "reported. Check the Jacobian with continuation.check_jacobian(problem, "
                    "None, x); Options(check_jacobian=False) skips this check")
    return ""


def drop_unresolved_folds(run: Run) -> None:
    """Remove the folds in a coordinate that the points do not resolve (a constant coordinate).

    Where ``x_i`` is constant along a curve (a trivial branch ``u = c``), its tangent component
    is rounding noise and changes sign at random: each change is located as a fold. Between two
    consecutive folds of ``x_i`` the coordinate is monotone, so each fold has a *persistence*,
    how far ``x_i`` moves to its neighbours (the folds beside it, or the curve's ends). As in
    the simplification of a function's extrema by persistence, the adjacent pair of folds
    closest in ``x_i`` is removed while it is flat: closer in ``x_i`` than the points' noise,
    ``100 tol (1 + max|x|)``, with ``|t_i| <= TANGENT_FLAT`` at every point from the one before
    the pair to the one after it (a real pair next to a cusp is as close in ``x_i``, but ``x_i``
    moves between its folds at a rate far above rounding). Then a fold left within that noise
    of both ends of a curve that is flat in ``x_i`` throughout goes too, and so does one where
    ``x_i`` stops (or starts) moving for good: flat, and within that noise of the fold, from it
    to an end of the curve over at least :data:`SATURATED` points, as where ``tanh`` rounds to
    1 or ``exp(-x)`` underflows (``t_i`` becomes exactly 0 there and stays 0: a zero of ``t_i``,
    but no turn of ``x_i``). A genuine fold next to an end of the curve is kept: ``x_i`` moves
    back after it, and ``t_i`` grows with the distance from it.
    """
    if not run.x:
        return
    tangents = np.abs(np.array(run.tangents))
    removed: set[int] = set()
    for i in run.options.fold_coordinates:
        folds = sorted((p for p in run.special
                        if p.kind is SpecialKind.FOLD and p.coordinate == i),
                       key=lambda p: (p.index, p.s))
        removed |= {id(p) for p in _unresolved(run, folds, i, tangents[:, i])}
    if removed:
        run.special = [p for p in run.special if id(p) not in removed]


def _unresolved(run: Run, folds: list[SpecialPoint], i: int,
                tangents: np.ndarray) -> list[SpecialPoint]:
    """The folds of coordinate ``i`` (in order) that :func:`drop_unresolved_folds` removes;
    ``tangents``: ``|t_i|`` at every point of the curve."""
    values = [float(p.x[i]) for p in folds]
    noises = [100.0 * run.options.tol * (1.0 + float(np.max(np.abs(p.x)))) for p in folds]
    last = len(tangents) - 1

    def flat(a: int, b: int) -> bool:
        lo, hi = max(0, folds[a].index - 1), min(last, folds[b].index + 1)
        return bool(np.max(tangents[lo:hi + 1]) <= TANGENT_FLAT)

    live = list(range(len(folds)))
    while True:
        pairs = [(abs(values[a] - values[b]), a, b) for a, b in zip(live, live[1:], strict=False)
                 if abs(values[a] - values[b]) <= max(noises[a], noises[b]) and flat(a, b)]
        if not pairs:
            break
        _, a, b = min(pairs)
        live = [k for k in live if k not in (a, b)]
    if len(live) == 1:
        k = live[0]
        ends = max(abs(values[k] - float(run.x[0][i])), abs(values[k] - float(run.x[-1][i])))
        if ends <= noises[k] and float(np.max(tangents)) <= TANGENT_FLAT:
            live = []
    coordinate = np.array([float(x[i]) for x in run.x])

    def saturated(k: int) -> bool:
        index = folds[k].index
        for stretch in (slice(index, None), slice(0, index + 1)):
            if len(tangents[stretch]) > SATURATED and np.max(tangents[stretch]) <= TANGENT_FLAT \
                    and np.max(np.abs(coordinate[stretch] - values[k])) <= noises[k]:
                return True
        return False

    live = [k for k in live if not saturated(k)]
    return [folds[k] for k in range(len(folds)) if k not in live]


def _sign_changes(values: list[float]) -> int:
    return sum(1 for p, q in zip(values, values[1:], strict=False) if (p > 0.0) != (q > 0.0))


def append_end(run: Run, a_index: int, b: Node) -> int:
    """Append the step's end; after inserted points, its arclength is re-measured
    from the last of them, so that every increment is at least its chord (an
    end placed exactly at ``max_arclength`` keeps that value)."""
    if len(run.s) - 1 != a_index and b.s != run.options.max_arclength:
        x, t = run.x[-1], run.tangents[-1]
        angle = math.acos(max(-1.0, min(1.0, float(t @ b.tangent))))
        b.s = run.s[-1] + arc_length(b.x - x, angle)
    return run.append(b.x, b.s, b.tangent, b.residual, b.iterations)
