r"""Zeros of a scalar function along a proven arc: fold components and event functions.

Along the arc proven by :mod:`continuation.krawczyk` a function ``phi`` is either an event
``e(x)`` or, for a fold coordinate ``c``, the Cramer component ``k_c = (-1)^c det H'_{-c}`` of
the kernel of ``H'`` (the tangent's component ``c`` up to a positive factor, so its zeros are
the folds in ``x_c``). On each segment ``phi`` is either *excluded* from zero (its enclosure
over the tube does not contain 0) or *monotone* (its derivative along the arc, from jets in
the direction of the kernel ``k``, has one sign), possibly after cutting the segment into
leaves; a monotone stretch has at most one zero, and it has one exactly when ``phi`` has
opposite signs at its ends (the proven points of the curve). ``H'`` and its derivatives along
the arc are the residual's own (:func:`continuation.krawczyk.derivative` over jets: gradients
over jets), never ``problem.jacobian``: a Jacobian right at the points only would give the
slope of another function.

At a point where a zero is reported (or at an end of the curve where ``phi`` vanishes) the
zero is proven by Krawczyk's test on the augmented system ``(H, phi) = 0`` in a small box:
exactly one solution, a regular one, so the zero is simple (for a fold: ``d k_c / ds != 0``,
a quadratic turning point). If ``phi`` is monotone on both segments next to the point and the
box lies in their tubes, that solution is the only zero of ``phi`` on both.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .krawczyk import Failure, derivative, determinant, kernel, solve_piece, solve_slice, square_box
from .numbers import FLOATS, Jet, jets
from .result import SpecialKind

__all__ = ["SAME", "Function", "Leaf", "classify", "count_zeros", "functions_of",
           "one_zero_groups", "prove_zero", "reports", "run_at", "runs"]


@dataclass(frozen=True)
class Function:
    """A scalar function along the curve: an event (``event`` its position) or a fold
    component (``coordinate``). ``direction``: the event's direction (0 for folds)."""

    name: str
    event: object = None          # the Event, or None for a fold component
    position: int | None = None
    coordinate: int | None = None
    direction: int = 0

    def value(self, box, J, B):
        """Enclosure of ``phi`` over ``box`` (``J``: ``H'`` over the box, for folds)."""
        if self.event is not None:
            return B.number(self.event.function(box, B))
        return kernel(J)[self.coordinate]

    def slope(self, box, k, problem, B):
        """Enclosure of ``D phi [k]`` over ``box`` for kernel vectors in ``k``."""
        J2 = jets(B)
        x = [Jet(b, kj) for b, kj in zip(box, k, strict=True)]
        if self.event is not None:
            value = self.event.function(x, J2)
        else:
            value = kernel(derivative(problem, x, J2))[self.coordinate]
        return value.d if type(value) is Jet else B.number(0.0)

    def curvature(self, box, k, problem, B):
        """Enclosure over ``box`` of the derivative of ``D phi [kappa]`` in the direction of
        kernel vectors ``k`` (``kappa`` the kernel of ``H'``, ``k`` enclosing it):
        ``D^2 phi [k, k] + D phi [D kappa [k]]``, from second-order jets along ``k`` and
        first-order jets along ``D kappa [k]``."""
        J2 = jets(B)
        zero = B.number(0.0)
        line = [Jet(b, kj, zero) for b, kj in zip(box, k, strict=True)]
        turn = kernel(derivative(problem, [Jet(b, kj) for b, kj in zip(box, k, strict=True)],
                                 J2))
        w = [c.d if type(c) is Jet else zero for c in turn]
        along = [Jet(b, wj) for b, wj in zip(box, w, strict=True)]
        if self.event is not None:
            second, first = self.event.function(line, J2), self.event.function(along, J2)
        else:
            second = kernel(derivative(problem, line, J2))[self.coordinate]
            first = kernel(derivative(problem, along, J2))[self.coordinate]
        return ((second.dd if type(second) is Jet else zero)
                + (first.d if type(first) is Jet else zero))

    def augmented(self, problem):
        """``(F, DF)`` of the augmented system ``(H, phi) = 0`` over any numbers."""
        def F(x, m):
            H = list(problem.residual(x, m))
            if self.event is not None:
                return H + [self.event.function(x, m)]
            return H + [kernel(derivative(problem, x, m))[self.coordinate]]

        def DF(x, m):
            rows = derivative(problem, x, m)
            J1 = jets(m)
            gradient = []
            for j in range(len(x)):
                xj = [Jet(xi, 1.0 if i == j else 0.0) for i, xi in enumerate(x)]
                if self.event is not None:
                    value = self.event.function(xj, J1)
                else:
                    value = kernel(derivative(problem, xj, J1))[self.coordinate]
                gradient.append(value.d if type(value) is Jet else 0.0)
            return rows + [gradient]

        return F, DF


def _sign(x) -> int:
    """+1 or -1 if the ball excludes 0, else 0."""
    return 1 if x > 0.0 else -1 if x < 0.0 else 0


@dataclass(frozen=True)
class Leaf:
    """A stretch ``lo <= tau <= hi`` of one segment: ``sign`` of ``phi`` (``excluded``) or of
    ``d phi / d tau`` (monotone)."""

    excluded: bool
    sign: int
    lo: float = -math.inf
    hi: float = math.inf

    def same(self, other: Leaf) -> bool:
        return self.excluded == other.excluded and self.sign == other.sign


def runs(leaves) -> list:
    """Consecutive leaves of the same kind and sign merged (their ranges joined)."""
    out: list = []
    for leaf in leaves:
        if out and out[-1].same(leaf):
            out[-1] = Leaf(leaf.excluded, leaf.sign, out[-1].lo, leaf.hi)
        else:
            out.append(leaf)
    return out


def _leaf(function, piece, frame, problem, B, orientation: int, centred_slope: bool):
    """The leaf of one tube piece, or ``None`` if no test decides.

    ``phi`` is excluded from zero if its enclosure over the piece's arc box is, or if its
    centred form in ``tau`` is: ``phi(x(tau_0)) + (d phi / d tau)(T) (T - tau_0)``, with the
    value at the arc's point on the slice ``tau_0`` (proven in a thin box) and
    ``d phi / d tau = D phi [k] / (d tau / d lambda)``. It is monotone if ``D phi [k]`` has
    one sign over the arc box, or its centred form in ``tau`` has (mean value theorem on
    ``g = D phi [kappa]`` along the arc, whose derivative is :meth:`Function.curvature`
    divided by ``d tau / d lambda``; only if ``centred_slope``: it costs four more evaluations
    and decides little that halving does not, except next to a zero at a point).
    """
    s = _sign(function.value(piece.arc, piece.jacobian, B))
    if s:
        return Leaf(True, s, piece.lo, piece.hi)
    k = kernel(piece.jacobian)
    slope = function.slope(piece.arc, k, problem, B)
    d = _sign(slope)
    if d:
        return Leaf(False, d * orientation, piece.lo, piece.hi)
    mid = 0.5 * (piece.lo + piece.hi)
    thin = solve_slice(problem, frame, B, piece, mid, math.inf)  # the arc's point at tau_0
    centre = thin.box if not isinstance(thin, str) else frame.tube_box(B.number(mid), piece.y)
    J = derivative(problem, centre, B) if function.event is None else None
    sigma = frame.speed(k)
    half = max(piece.hi - mid, mid - piece.lo) * (1.0 + 1e-15)
    s = _sign(function.value(centre, J, B) + slope / sigma * B.error(half))
    if s or not centred_slope:
        return Leaf(True, s, piece.lo, piece.hi) if s else None
    # the slope's centred form: D phi [kappa] at tau_0 plus its derivative along the arc,
    # (D^2 phi [k, k] + D phi [D kappa [k]]) / (d tau / d lambda), over the piece (a slope
    # that is small at an end of the piece and grows along it: a curve leaving an event's
    # zero nearly tangentially)
    J0 = J if J is not None else derivative(problem, centre, B)
    slope0 = function.slope(centre, kernel(J0), problem, B)
    if not _sign(slope0):
        return None  # no sign at tau_0 itself: the centred form cannot have one
    curvature = function.curvature(piece.arc, k, problem, B) / sigma
    d = _sign(slope0 + curvature * B.error(half))
    return Leaf(False, d * orientation, piece.lo, piece.hi) if d else None


#: most tube pieces one segment may be cut into to decide one function on it
LEAF_BUDGET = 200


def classify(function, segment, problem, B, orientation: int, depth: int = 40,
             centred_slope: bool = False):
    """The leaves of ``phi`` on one segment (a list in order of ``tau``), or ``None``.

    ``segment`` has ``pieces`` (proven tube pieces) and ``frame``. A piece that neither test
    decides is cut in halves, each with its own, thinner tube (Krawczyk's test again on the
    shorter piece: the arc there is the same, being the only zero in either tube); only the
    undecided halves are cut again, so next to a zero with a small slope the leaves get as
    short as the slope needs, down to ``depth`` cuts and :data:`LEAF_BUDGET` pieces.
    ``centred_slope``: try the slope's centred form too (next to a zero of ``phi`` at a point
    of the curve, where halving alone cannot decide a slope that vanishes nearby).
    """
    found, budget = [], LEAF_BUDGET
    for piece in segment.pieces:
        stack = [(piece, 0)]
        while stack:
            current, level = stack.pop()
            leaf = _leaf(function, current, segment.frame, problem, B, orientation,
                         centred_slope)
            if leaf is not None:
                found.append(leaf)
                continue
            budget -= 2
            if level >= depth or budget < 0:
                return None
            mid = 0.5 * (current.lo + current.hi)
            for a, b in ((mid, current.hi), (current.lo, mid)):
                sub = solve_piece(problem, segment.frame, B, a, b, current.radius)
                if isinstance(sub, Failure):
                    return None
                stack.append((sub, level + 1))
    return sorted(found, key=lambda leaf: leaf.lo)


def run_at(leaves, tau: float):
    """The run (merged leaves) holding ``tau``, or ``None``."""
    return next((run for run in runs(leaves) if run.lo <= tau <= run.hi), None)


#: :func:`count_zeros`: the zeros at both ends of the segment are one and the same
SAME = 0


def count_zeros(leaves, left: int, right: int, length: float):
    """Zeros of ``phi`` on a segment between its end points (``tau = 0`` and ``length``), whose
    signs are ``left`` and ``right``; 0 for an end where ``phi`` vanishes (a zero proven there,
    in the monotone run holding that end, which is not counted here). Runs only in the
    tube's extensions beyond the ends belong to the neighbouring segments and are left out.

    Returns a list of crossing directions (``+1`` increasing along the curve), or ``None``
    when the count is open (a turning point between two monotone runs, or a run
    inconsistent with the signs); ``[SAME]`` when the zeros proven at both ends are one
    (one monotone run between them).
    """
    stretch = [run for run in runs(leaves) if run.hi > 0.0 and run.lo < length]
    if not stretch:
        return None
    if left == 0 and right == 0 and len(stretch) == 1:
        # one monotone run with a zero proven at both ends: one zero (a monotone function
        # vanishes once), e.g. a crossing located a rounding after the start: SAME
        return [SAME] if not stretch[0].excluded else None
    if left == 0:
        if stretch[0].excluded:
            return None
        current, stretch = stretch[0].sign, stretch[1:]  # past the zero: the slope's sign
    else:
        current = left
    if right == 0:
        if not stretch or stretch[-1].excluded:
            return None
        target, stretch = -stretch[-1].sign, stretch[:-1]  # before the zero
    else:
        target = right
    crossings = []
    for i, run in enumerate(stretch):
        if run.excluded:
            if run.sign != current:
                return None  # cannot happen on a true arc; no claim
            continue
        following = stretch[i + 1] if i + 1 < len(stretch) else None
        if following is None:
            end = target
        elif following.excluded:
            end = following.sign
        else:
            return None
        if end != current:
            if run.sign != end:
                return None
            crossings.append(run.sign)
        current = end
    return crossings if current == target else None


def prove_zero(function, problem, x_hat, B, tolerance: float):
    """Krawczyk's test for the augmented system ``(H, phi) = 0`` near ``x_hat``:
    ``(centre, radius)`` or a message."""
    F, DF = function.augmented(problem)
    return square_box(F, DF, x_hat, B, tolerance)


def float_value(function, problem, x) -> float:
    """``phi`` at a float point (for messages)."""
    if function.event is not None:
        return float(function.event.function(x, FLOATS))
    J = [[float(v) for v in row] for row in problem.jacobian(x)]
    d = determinant([row[:function.coordinate] + row[function.coordinate + 1:] for row in J])
    return d if function.coordinate % 2 == 0 else -d


def functions_of(curve, events, fold_coordinates) -> list[Function]:
    """Events reported at an end first, then the other events, then folds: the boxes proven
    at the ends are consulted for the functions after them (``continuation.certification``)."""
    names = curve.problem.names if curve.problem is not None and curve.problem.names else None
    ends = {p.event for p in curve.special_points if p.kind is SpecialKind.EVENT
            and p.index in (0, len(curve) - 1)}
    functions = [Function(f"event '{event.name}'", event=event, position=j,
                          direction=event.direction) for j, event in enumerate(events)]
    functions.sort(key=lambda f: f.position not in ends)
    for c in fold_coordinates:
        label = names[c] if names and c < len(names) else f"x[{c}]"
        functions.append(Function(f"fold in {label}", coordinate=c))
    return functions


def one_zero_groups(same: list, seam: int | None = None) -> list:
    """The points whose zeros are one, as sets: ``s`` and ``s + 1`` for each segment ``s`` in
    ``same`` (:data:`SAME`), joined where they share a point; with ``seam = m`` (a closed
    curve's last point) also ``0`` and ``m``."""
    groups = [{s, s + 1} for s in same] + ([{0, seam}] if seam is not None else [])
    joined: list = []
    for group in groups:
        for other in [g for g in joined if g & group]:
            joined.remove(other)
            group = group | other
        joined.append(group)
    return joined


def reports(curve, function) -> tuple[set, int | None]:
    """The points where the curve reports a zero of ``phi`` (a fold in its coordinate or the
    event at its position), and a point where it reports one twice (or ``None``)."""
    kind = SpecialKind.FOLD if function.event is None else SpecialKind.EVENT
    which = function.coordinate if function.event is None else function.position
    seen: set = set()
    twice = None
    for p in curve.special_points:
        if p.kind is kind and (p.coordinate if kind is SpecialKind.FOLD else p.event) == which:
            if p.index in seen and twice is None:
                twice = p.index
            seen.add(p.index)
    return seen, twice
