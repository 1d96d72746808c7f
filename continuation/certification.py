r"""Certify a traced curve: a proof in ball arithmetic that it follows one smooth curve of zeros.

:func:`certify` takes a :class:`~continuation.result.Curve` and the problem it was traced from,
written over a numbers namespace (:mod:`continuation.numbers`: ``residual(x, numbers)`` and
``jacobian(x, numbers)``, the same functions that trace it in floats), and proves, in Arb
ball arithmetic (every rounding outwards):

1. *Tubes* (:mod:`continuation.krawczyk`): around each segment between consecutive points a
   tube (a radius per offset coordinate, reaching ``extension`` of its length beyond both
   ends) in which the zeros of ``H`` are exactly one smooth arc, a graph over one coordinate
   (parametrised Krawczyk test; van den Berg, Lessard & Mischaikow, Math. Comp. 79 (2010)).
   A segment with no tube is halved by a point of the arc (:mod:`continuation.refine`).
2. *Points*: every point of the curve is within ``node_distance`` of a zero of ``H`` (the
   zero of its slice), and that zero lies in the tubes on both sides of the point, so the arcs
   of consecutive segments overlap: one smooth branch from the first point to the last.
3. *Folds* (for each fold coordinate) and *events* (:mod:`continuation.zeros`): the zeros of
   the tangent's component and of each event function along the branch are exactly the
   reported ones (in the event's direction), each simple and in a small box proven to hold
   exactly one solution of the augmented system ``(H, phi) = 0``; a zero at an end of the
   curve (a start on an event's zero set, a symmetric start) is proven the same way and
   listed, not counted as a crossing.

For a curve reported closed, its last point must be its first (within ``special_tolerance``)
and the arc is proven to run on from the last point's node to the first point's. The zeros are
those met along the curve from its first point to its last: a zero at the seam is one zero
(listed once; reported at both ends, a failure), and a curve traced twice round meets (and
lists) each zero twice.

Anything else fails with the first segment or point where a test failed and why; a curve is
never reported proven on evidence that is only numerical (every derivative over a box, of
``H`` and of the fold functions, is the residual's own, by forward differentiation in
balls; ``jacobian`` serves in floats only). Branch points are not certified, and no
neighbourhood of a singular end is cut out: a curve ending at a singular point fails.
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass

import numpy as np

from .certificate import Certificate, CertifyOptions, Check, Exclusion, ProvenPoint
from .certify_input import not_certifiable
from .krawczyk import Failure, Frame, derivative, kernel, solve_piece, solve_slice
from .numbers import balls
from .refine import Points
from .result import Curve, SpecialKind, Status
from .zeros import (
    SAME,
    Function,
    Leaf,
    classify,
    count_zeros,
    float_value,
    functions_of,
    one_zero_groups,
    prove_zero,
    reports,
    run_at,
)

__all__ = ["Certificate", "CertifyOptions", "Check", "Exclusion", "ProvenPoint", "certify"]


@dataclass(frozen=True)
class _Failure:
    check: Check
    message: str
    segment: int | None = None
    point: int | None = None
    caller: bool = False  # segment and point in the caller's indices already


@dataclass
class _Segment:
    frame: Frame
    pieces: list
    orientation: int


def _upper(x) -> float:
    return math.inf if not x.is_finite() else math.nextafter(float(abs(x).upper()), math.inf)


class _Run:
    """The state of one certification: tubes, points and the proofs so far."""

    def __init__(self, points: Points, problem, events, B, options: CertifyOptions) -> None:
        self.points, self.problem, self.events = points, problem, tuple(events)
        self.B, self.options = B, options
        self.x = np.asarray(points.curve.x, float)
        self.segments: list[_Segment] = []
        self.nodes: list = []
        self.node_distance = 0.0
        self.proven: list[ProvenPoint] = []
        self._run_signs: dict = {}  # the direction of the run through each zero at a point
        self.start_sides: dict = {}  # event -> Certificate.start_sides
        self._node_jacobians: dict = {}

    # -- tubes and points -------------------------------------------------------------------

    def _tube(self, frame: Frame, first: bool, last: bool):
        """Proven pieces covering the segment and its extensions, or a message.

        Tubes reach beyond the segment's ends by a fraction of its length (so that
        consecutive tubes overlap), and at least by what a point's box may be off (the boxes
        of its points must lie in it). Before the first point only by the latter: a curve
        starts on its seed's zeros, and a tube reaching further back could hold another zero
        of a function that leaves the seed nearly tangentially. Beyond the last point as far
        as a special point's box may be from it (a terminal event's zero a little beyond).

        A piece whose test fails is cut in parts, as many as its contraction suggests
        (``|I - A H' N|`` grows about linearly with the piece's length), at least two.
        """
        L = frame.length
        # beyond each end by a fraction of the length, and at least by what a point's box may
        # be off it: the boxes of the points at both ends must lie in the tube
        scale = 1.0 + max(abs(v) for v in frame.x_a)
        floor = self.options.node_tolerance * scale
        ext = max(self.options.extension * L, 4.0 * floor)
        end = max(ext, 2.0 * self.options.special_tolerance * scale)
        widest = max(self.options.max_radius * L, 8.0 * floor)
        pending, pieces = [(-4.0 * floor if first else -ext, L + (end if last else ext), 0)], []
        orientation = 0
        while pending:
            a, b, level = pending.pop()
            piece = solve_piece(self.problem, frame, self.B, a, b, widest, 4.0 * floor)
            if not isinstance(piece, Failure):
                sigma = frame.speed(kernel(piece.jacobian))
                s = 1 if sigma > 0.0 else -1 if sigma < 0.0 else 0
                if s and orientation in (0, s):
                    orientation = s
                    pieces.append(piece)
                    continue
                piece = Failure("the arc's direction along the chord is not decided")
            if level >= self.options.max_depth:
                return f"{piece} (after {level} cuts, on tau in [{a:.6g}, {b:.6g}])"
            q = piece.contraction
            parts = min(16, max(2, math.ceil(2.0 * q))) if math.isfinite(q) else 2
            edges = [a + (b - a) * j / parts for j in range(parts + 1)]
            edges[-1] = b
            pending += [(edges[j], edges[j + 1], level + 1) for j in reversed(range(parts))]
        pieces.sort(key=lambda p: p.lo)
        return _Segment(frame, pieces, orientation)

    def _node(self, i: int, segment: _Segment, tau: float):
        """The zero of point ``i``'s slice, with its distance from the point (or a failure)."""
        scale = 1.0 + float(np.max(np.abs(self.x[i])))
        piece = next(p for p in (segment.pieces if tau == 0.0 else reversed(segment.pieces))
                     if p.lo <= tau <= p.hi)
        node = solve_slice(self.problem, segment.frame, self.B, piece, tau,
                           self.options.node_tolerance * scale)
        if isinstance(node, str):
            return _Failure(Check.POINT, f"{self.points.point(i)} is not proven on the curve: "
                            f"{node}", point=i)
        distance = max(_upper(b - float(xi)) for b, xi in zip(node.box, self.x[i], strict=True))
        if not distance <= self.options.node_tolerance * scale:
            return _Failure(Check.POINT, f"{self.points.point(i)} is {distance:.3g} from the "
                            f"curve, more than {self.options.node_tolerance * scale:.3g}", point=i)
        self.node_distance = max(self.node_distance, distance)
        return node

    def merged_points(self, x, dropped) -> _Failure | None:
        """Each point merged with the point kept before it (the caller's ``x[r]`` for ``r`` in
        ``dropped``) within the points' accuracy of that point's node, or the first failure."""
        for r, kept, distance in self.points.merged_distances(x, dropped, self.nodes, _upper):
            limit = self.options.node_tolerance * (1.0 + float(np.max(np.abs(x[r]))))
            if not distance <= limit:
                return _Failure(Check.POINT, f"point {r}, merged with point {kept}, is "
                                f"{distance:.3g} from the curve, more than {limit:.3g}",
                                point=r, caller=True)
            self.node_distance = max(self.node_distance, distance)
        return None

    def node_jacobian(self, i: int):
        """``H'`` over the box of point ``i``'s zero (computed once, when needed)."""
        if i not in self._node_jacobians:
            self._node_jacobians[i] = derivative(self.problem, self.nodes[i].box, self.B)
        return self._node_jacobians[i]

    def inside(self, box, s: int, lo: float = -math.inf, hi: float = math.inf) -> bool:
        """Whether the ball vector ``box`` lies in the tube of segment ``s`` (its interior),
        with its ``tau`` in ``[lo, hi]``."""
        segment = self.segments[s]
        tau, y = segment.frame.coordinates(box, self.B)
        if not (tau >= lo and tau <= hi):
            return False
        for piece in segment.pieces:
            if tau >= piece.lo and tau <= piece.hi:
                return all(self.B.error(r).contains_interior(yi)
                           for yi, r in zip(y, piece.radii, strict=True))
        return False

    @property
    def curve(self) -> Curve:
        return self.points.curve

    def arcs(self):
        """Tubes, points and connections, segment by segment; the first failure or None.

        A segment whose tube is not proven is halved by a point of the arc inserted on its
        middle slice (:meth:`Points.insert`), up to ``options.refine`` times.
        """
        i = 0
        while i < len(self.x) - 1:
            m = len(self.x) - 1
            t = self.curve.tangents
            frame = Frame.build(self.x[i], t[i], self.x[i + 1], t[i + 1])
            if isinstance(frame, str):
                return _Failure(Check.TUBE, f"{self.points.segment(i)}: {frame}", segment=i)
            segment = self._tube(frame, i == 0, i == m - 1)
            if isinstance(segment, str):
                if self.points.level[i] < self.options.refine and \
                        self.points.insert(i, frame, self.problem):
                    self.x = np.asarray(self.curve.x, float)
                    continue
                return _Failure(Check.TUBE, f"{self.points.segment(i)}: no tube proven: "
                                f"{segment}", segment=i)
            if self.segments and segment.orientation != self.segments[-1].orientation:
                return _Failure(Check.TUBE, f"{self.points.segment(i)}: the curve's kernel "
                                "turns against the direction of travel (a branch point?)",
                                segment=i)
            self.segments.append(segment)
            node = self._node(i, segment, 0.0)
            if isinstance(node, _Failure):
                return node
            self.nodes.append(node)
            if i > 0 and not self.inside(node.box, i - 1):
                return _Failure(Check.CONNECTION, f"the curve at {self.points.point(i)} does "
                                "not lie in the tubes on both sides: the segments before and "
                                "after it are not proven to be one branch",
                                segment=max(i - 1, 0), point=i)
            i += 1
        m = len(self.x) - 1
        last = self._node(m, self.segments[-1], self.segments[-1].frame.length)
        if isinstance(last, _Failure):
            return last
        if self.curve.status is Status.CLOSED:
            # the last point is the first, and the arc goes on from the last point's node to
            # the first point's, in the last tube: counted up to there (the two nodes are on
            # different slices)
            gap = float(np.max(np.abs(self.x[m] - self.x[0])))
            limit = self.options.special_tolerance * (1.0 + float(np.max(np.abs(self.x[0]))))
            if not gap <= limit:
                return _Failure(Check.CONNECTION, f"the curve is reported closed, but its last "
                                f"point is {gap:.3g} from its first, more than {limit:.3g}",
                                segment=m - 1, point=m)
            if not self.inside(self.nodes[0].box, m - 1):
                return _Failure(Check.CONNECTION, "the curve is reported closed, but the "
                                "curve at point 0 does not lie in the last segment's tube",
                                segment=m - 1, point=0)
            last = self.nodes[0]
        self.nodes.append(last)
        return None

    # -- zeros of fold components and events --------------------------------------------------

    def _fail(self, function: Function, message: str, segment=None, point=None) -> _Failure:
        check = Check.EVENT if function.event is not None else Check.FOLD
        return _Failure(check, f"{function.name}: {message}", segment=segment, point=point)

    def _leaves(self, function: Function, s: int, cache: dict, next_to_zero: bool = False):
        if s not in cache:
            segment = self.segments[s]
            cache[s] = classify(function, segment, self.problem, self.B, segment.orientation,
                                self.options.leaf_depth, centred_slope=next_to_zero)
        return cache[s]

    def _reach(self, s: int) -> float:
        """Where segment ``s``'s count of zeros ends: at the node of point ``s + 1`` (its
        ``tau`` in the segment's frame, upper bound). That node is the arc's point on the
        slice where segment ``s + 1`` starts, at ``tau = L`` only if the two frames' slices
        through the point agree; a point off the curve with frames in different coordinates
        puts it beyond or before ``L``, and the arc between must be counted by one of them."""
        tau, _ = self.segments[s].frame.coordinates(self.nodes[s + 1].box, self.B)
        return _upper(tau)

    def _stretch(self, function: Function, i: int, cache: dict):
        """The monotone runs through point ``i``, ``[(segment, run)]``, or a failure.

        The last run of the segment before and the first of the one after must be monotone
        in one direction and overlap: the first must hold the node of point ``i`` (the arc's
        point on the slice where the second starts; for the last point of a closed curve, the
        first point's node). If the point is off the curve and the
        two frames' slices through it differ, the arc between the slices could hide zeros
        otherwise.
        """
        m = len(self.x) - 1
        stretch = []
        if i > 0:
            before = self._leaves(function, i - 1, cache, next_to_zero=True)
            length = self.segments[i - 1].frame.length
            stretch.append((i - 1, run_at(before, length) if before else None))
        if i < m:
            after = self._leaves(function, i, cache, next_to_zero=True)
            stretch.append((i, run_at(after, 0.0) if after else None))
        runs_ = [run for _, run in stretch if run is not None and not run.excluded]
        if len(runs_) != len(stretch) or len({run.sign for run in runs_}) != 1:
            return self._fail(function, f"the zero at {self.points.point(i)} is not proven to "
                              "be the only one next to it (no monotone stretch through it)",
                              segment=stretch[0][0], point=i)
        if i > 0 and not self.inside(self.nodes[i].box, i - 1, runs_[0].lo, runs_[0].hi):
            return self._fail(function, f"the runs through {self.points.point(i)} on both sides "
                              "are not proven to overlap", segment=i - 1, point=i)
        return [(s, run) for (s, _), run in zip(stretch, runs_, strict=True)]

    def _zero_at(self, function: Function, i: int, reported: bool, cache: dict):
        """Prove the zero of ``phi`` at point ``i``: the only one in the monotone stretch
        through the point (:meth:`_stretch`), within ``special_tolerance (1 + |x_i|)`` of the
        point if reported there, within the
        points' accuracy ``node_tolerance (1 + |x_i|)`` if it is an unreported zero at an end."""
        m = len(self.x) - 1
        stretch = self._stretch(function, i, cache)
        if isinstance(stretch, _Failure):
            return stretch
        direction = stretch[0][1].sign
        self._run_signs[i] = direction
        if reported and function.direction and direction != function.direction:
            return self._fail(function, f"its zero at {self.points.point(i)} is reported but "
                              "crosses the other way", point=i)
        if not reported and 0 < i < m and (not function.direction
                                           or direction == function.direction):
            return self._fail(function, f"vanishes at {self.points.point(i)}, where no zero is "
                              "reported", point=i)
        scale = 1.0 + float(np.max(np.abs(self.x[i])))
        box = prove_zero(function, self.problem, self.x[i], self.B,
                         self.options.special_tolerance * scale)
        if isinstance(box, str):
            return self._fail(function, f"its zero at {self.points.point(i)}: {box}", point=i)
        centre, radius = box
        balls_ = [self.B.arb(c, radius) for c in centre]
        # every run of the stretch is set here (a missing one failed above)
        if not any(self.inside(balls_, s, run.lo, run.hi) for s, run in stretch
                   if run is not None):
            return self._fail(function, f"the box of its zero at {self.points.point(i)} is not "
                              "in the tubes of the stretch through it", point=i)
        distance = float(np.max(np.abs(self.x[i] - np.array(centre)))) + radius
        # the box is centred at a Newton step of any length from the point: a reported zero
        # must be within special_tolerance of it, an unreported one at an end of the curve
        # within the points' accuracy (else a crossing inside the first or last segment, of an
        # event steep across the curve or flat along it, would pass for one at the end)
        at_end = not reported and i in (0, m)
        limit = (self.options.node_tolerance if at_end else self.options.special_tolerance) \
            * scale
        if not distance <= limit:
            where = "next to end" if at_end else "at"
            return self._fail(function, f"its zero {where} {self.points.point(i)} lies "
                              f"{distance:.3g} from it, "
                              f"more than {limit:.3g}", point=i)
        kind = SpecialKind.EVENT if function.event is not None else SpecialKind.FOLD
        self.proven.append(ProvenPoint(kind, i, np.array(centre), radius, distance,
                                       function.coordinate, function.position, reported))
        return None

    def _hull(self, lo: int, hi: int) -> list:
        """A box holding the arcs of segments ``lo`` to ``hi - 1`` (union of their pieces)."""
        boxes = [p.arc for s in range(lo, hi) for p in self.segments[s].pieces]
        hull = list(boxes[0])
        for box in boxes[1:]:
            hull = [a.union(b) for a, b in zip(hull, box, strict=True)]
        return hull

    def _exclude(self, function: Function, lo: int, hi: int, keep: set, excluded: dict) -> None:
        """Mark the segments in ``[lo, hi)`` on whose arcs ``phi`` has one sign, by halving.

        One enclosure over the hull of many segments decides most of an event that stays far
        from zero; segments next to a point in ``keep`` are left to the finer tests.
        """
        if any(lo <= i <= hi for i in keep) and hi - lo == 1:
            return
        if not any(lo <= i <= hi for i in keep):
            box = self._hull(lo, hi)
            J = derivative(self.problem, box, self.B) if function.event is None else None
            value = function.value(box, J, self.B)
            sign = 1 if value > 0.0 else -1 if value < 0.0 else 0
            if sign:
                excluded.update({s: sign for s in range(lo, hi)})
                return
        if hi - lo > 1:
            mid = (lo + hi) // 2
            self._exclude(function, lo, mid, keep, excluded)
            self._exclude(function, mid, hi, keep, excluded)

    def _sign_at(self, function: Function, i: int, excluded: dict) -> int:
        """The sign of ``phi`` at the curve's zero near point ``i`` (0 if not decided)."""
        for s in (i - 1, i):
            if s in excluded:
                return excluded[s]
        J = self.node_jacobian(i) if function.event is None else None
        value = function.value(self.nodes[i].box, J, self.B)
        return 1 if value > 0.0 else -1 if value < 0.0 else 0

    def _vanishes_at_end(self, function: Function, i: int) -> bool:
        """Whether ``phi`` may vanish in the box of an event proven at the end point ``i``.

        A curve ends at a terminal event's zero; its last point may lie a rounding beyond it,
        so a function vanishing there too (a fold component at the corner where the curve
        ends) vanishes between the last two points: a zero at the end, not a crossing.
        """
        return any(self._may_vanish(function, p.centre, p.radius) for p in self.proven
                   if p.index == i and p.kind is SpecialKind.EVENT)

    def _vanishes_near(self, function: Function, i: int) -> bool:
        """Whether ``phi`` may vanish within the points' accuracy, ``node_tolerance (1 + |x_i|)``
        in every coordinate, of point ``i``."""
        radius = self.options.node_tolerance * (1.0 + float(np.max(np.abs(self.x[i]))))
        return self._may_vanish(function, self.x[i], radius)

    def _may_vanish(self, function: Function, centre, radius: float) -> bool:
        """Whether the enclosure of ``phi`` over the box ``|x - centre| <= radius`` holds 0."""
        box = [self.B.arb(float(c), radius) for c in centre]
        J = derivative(self.problem, box, self.B) if function.event is None else None
        value = function.value(box, J, self.B)
        return not (value > 0.0 or value < 0.0)

    def zeros(self, function: Function):
        """Every zero of ``phi`` along the branch is reported (or at an end) and proven.

        If that fails with the signs the nodes' boxes give ``phi`` at the ends, it is tried
        again with a zero at each end where ``phi`` may vanish within the points' accuracy
        (:meth:`_vanishes_near`): a curve started on a zero of ``phi`` (a regime limit at a
        junction) may start a rounding before it, where the node's box is small enough to give
        ``phi`` a sign and the zero reads as a crossing on the first segment. That zero must
        then be proven at the end point like any other (:meth:`_zero_at`): unique in the
        monotone stretch next to it, inside its tubes, and within the points' accuracy of the
        end point. Either proof is a proof; if both fail, the first failure is reported.
        """
        before = len(self.proven)
        failure = self._zeros(function, ())
        m = len(self.x) - 1
        near = [i for i in (0, m) if self._vanishes_near(function, i)] if failure else []
        if near:
            first = self.proven[before:]
            del self.proven[before:]
            if self._zeros(function, near) is None:
                return None
            self.proven[before:] = first
        return failure

    def _zeros(self, function: Function, at_ends):
        """:meth:`zeros`, with a zero at the end points ``at_ends`` whatever their signs."""
        m = len(self.x) - 1
        reported, twice = reports(self.curve, function)
        if twice is not None:
            return self._fail(function, f"it is reported twice at {self.points.point(twice)}",
                              point=twice)
        excluded: dict = {}
        self._exclude(function, 0, m, reported, excluded)
        signs = [self._sign_at(function, i, excluded) for i in range(m + 1)]
        for i in (0, m):
            if signs[i] and (i in at_ends or self._vanishes_at_end(function, i)):
                signs[i] = 0
        at_zero = sorted(reported | {i for i, s in enumerate(signs) if s == 0})
        cache: dict = {s: [Leaf(True, sign)] for s, sign in excluded.items()}  # whole segments
        first, same = len(self.proven), []
        self._run_signs = {}
        for i in at_zero:
            failure = self._zero_at(function, i, i in reported, cache)
            if failure is not None:
                return failure
            signs[i] = 0  # the zero proven at the point: counted there, not on its segments
        if function.event is not None:  # the side the curve starts on (at a zero: leaves to)
            self.start_sides[function.position] = self._run_signs[0] if 0 in at_zero else signs[0]
        for s in range(m):
            if s in excluded:
                continue
            leaves = self._leaves(function, s, cache)
            crossings = None if leaves is None else count_zeros(
                leaves, signs[s], signs[s + 1], self._reach(s))
            if crossings is None:
                return self._fail(function, f"its zeros on {self.points.segment(s)} are not "
                                  "decided", segment=s)
            if crossings == [SAME]:
                same.append(s)
                continue
            for direction in crossings:
                if not function.direction or direction == function.direction:
                    values = (float_value(function, self.problem, self.x[s]),
                              float_value(function, self.problem, self.x[s + 1]))
                    return self._fail(function, f"crosses zero on {self.points.segment(s)}, "
                                      f"from {values[0]:.3g} to {values[1]:.3g}, where no "
                                      "zero is reported", segment=s)
        return self._one_zero(function, same, reported, first)

    def _one_zero(self, function: Function, same: list, reported: set, first: int):
        """Zeros proven at consecutive points with one monotone run between them (segments
        ``same``; for a closed curve also its first and last point, with runs in one direction
        through the first point's node) are one zero: listed once (the reported one, else the
        first), a failure if more than one of them is reported."""
        m, at = len(self.x) - 1, {p.index for p in self.proven[first:]}
        seam = self.curve.status is Status.CLOSED and {0, m} <= at and \
            self._run_signs.get(0) == self._run_signs.get(m)  # runs in one way through node 0
        drop: set = set()
        for group in one_zero_groups(same, m if seam else None):
            points = sorted(group)
            claimed = [i for i in points if i in reported]
            if len(claimed) > 1:
                names = [self.points.point(i) for i in claimed[:2]]
                return self._fail(function, f"the zeros reported at {names[0]} and {names[1]} "
                                  "are one zero (one monotone run between them)",
                                  segment=min(claimed[1] - 1, m - 1), point=claimed[1])
            keep = claimed[0] if claimed else points[0]
            drop |= set(points) - {keep}
        self.proven[first:] = [p for p in self.proven[first:] if p.index not in drop]
        return None


def certify(curve: Curve, problem, events=(), *, fold_coordinates=None,
            options: CertifyOptions | None = None, numbers=None) -> Certificate:
    """Prove that a traced curve follows one smooth curve of zeros, with its folds and events.

    Parameters
    ----------
    curve : Curve
        A traced curve (points, unit tangents, special points).
    problem : Problem or object
        ``residual(x, numbers)`` (n values) and ``jacobian(x, numbers)`` (n rows of n + 1),
        written over a numbers namespace (:mod:`continuation.numbers`). The proof evaluates
        and differentiates ``residual`` itself (floats, balls, jets, gradients); ``jacobian``
        serves in floats, checked against it at the points (:mod:`continuation.certify_input`).
    events : sequence of Event
        The run's events, in its order (positions as in ``SpecialPoint.event``), with
        functions ``function(x, numbers)``; an event may be replaced by one with the same
        zeros and signs along the curve.
    fold_coordinates : sequence of int, optional
        Default: the run's ``options.fold_coordinates``.
    options : CertifyOptions, optional
    numbers : namespace, optional
        The ball arithmetic (default :func:`continuation.numbers.balls`, python-flint).

    Returns
    -------
    Certificate
        ``proven``, or the first failing test with its segment or point.

    Raises
    ------
    ImportError
        If python-flint is not installed (the message names the extra to install).
    TypeError
        If a function is not written over the numbers namespace (it fails in floats or jets).
    ValueError
        If the problem has no Jacobian, a fold coordinate is out of range, or the curve
        reports an event that is not passed.
    """
    start = time.perf_counter()
    B = numbers or balls()
    options = options or CertifyOptions()
    if fold_coordinates is None:
        fold_coordinates = () if curve.options is None else curve.options.fold_coordinates
    reason = not_certifiable(curve, problem, events, fold_coordinates)
    failure = None if reason is None else _Failure(Check.INPUT, reason[0], point=reason[1],
                                                   caller=True)
    points, merged = Points.of(curve, _DUPLICATE)
    if failure is None and len(points.curve) < 2:
        failure = _Failure(Check.INPUT, "all its points are one point (to rounding)")
    run = _Run(points, problem, events, B, options)
    if failure is None:
        failure = run.arcs() or run.merged_points(np.asarray(curve.x, float), merged)
    if failure is None:
        for function in functions_of(points.curve, events, fold_coordinates):
            failure = run.zeros(function)
            if failure is not None:
                break
    # in the caller's indices (a zero at an inserted point, unreported, crossing against its
    # event's direction: the caller's point before it)
    proven = [dataclasses.replace(p, index=points.segment_of(p.index)
                                  if points.origin[p.index] is None else points.origin[p.index])
              for p in run.proven]
    pieces = sum(len(s.pieces) for s in run.segments)
    radius = max((p.radius for s in run.segments for p in s.pieces), default=0.0)
    common: dict = dict(
        segments=len(run.segments), pieces=pieces, max_radius=radius,
        node_distance=run.node_distance, special_points=tuple(proven),
        start_sides=tuple(run.start_sides.get(j, 0) for j in range(len(events))),
        inserted_points=points.inserted, seconds=time.perf_counter() - start)
    note = (f" (points {', '.join(map(str, merged))} merged with the point before: the same "
            "point to rounding)" if merged else "") + (
        f" ({points.inserted} point(s) of the arc inserted where a segment's tube was not "
        "proven)" if points.inserted else "")
    if failure is not None:
        point = failure.point if failure.caller or failure.point is None else \
            points.origin[failure.point]
        at = failure.segment
        if at is None and failure.point is not None and point is None:
            at = failure.point  # at an inserted point: the segment it was inserted in
        segment = at if failure.caller or at is None else points.segment_of(at)
        return Certificate(False, f"not proven: {failure.check}: {failure.message}{note}",
                           failure.check, segment, point, **common)
    return Certificate(True, f"proven: {len(curve.x) - 1 - len(merged)} segments ({pieces} "
                       f"tube pieces, radius <= {radius:.2g}), points within "
                       f"{run.node_distance:.2g} of the curve, {len(proven)} zero(s) of folds "
                       f"and events proven{note}", **common)


#: points this close (relative to 1 + |x|) repeat the point before: a special point located twice
_DUPLICATE = 1e-13
