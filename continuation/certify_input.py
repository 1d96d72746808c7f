"""What :func:`continuation.certify` accepts: arguments that cannot be right raise (with what
to write instead), and a curve that cannot be certified gets its reason (check ``input``)."""

from __future__ import annotations

from typing import cast

import numpy as np

from .krawczyk import derivative
from .numbers import FLOATS, Jet, jets
from .result import Curve, SpecialKind

__all__ = ["JACOBIAN_TOL", "jacobian_mismatch", "not_certifiable"]

#: problem.jacobian may differ from the residual's derivative (in floats) by this
#: fraction of ``1 + max |row|`` at a point of the curve (rounding is some 1e-16 of it)
JACOBIAN_TOL = 1e-8


def _probe(name: str, function, x) -> None:
    """Call ``function`` once in floats and once in jets (the proof's derivatives): a
    ``TypeError`` that says what to write if it fails (``math.sin`` of a jet fails, where of a
    ball it would quietly take the ball's midpoint)."""
    try:
        function(x, FLOATS)
        function([Jet(v, 1.0) for v in x], jets(FLOATS))
    except (TypeError, AttributeError) as exc:
        raise TypeError(f"{name} must take (x, numbers) and be written over the numbers "
                        f"namespace (continuation.numbers: m.sin, not math.sin or np.sin) to "
                        f"be certified: {exc}") from None


def _inconsistent(curve: Curve) -> tuple | None:
    """Where the curve's arrays disagree with each other (a curve edited after its run): the
    reason and the point, or ``None``. A special point is a row of the curve, bit for bit."""
    m = len(curve.x)
    if curve.x.ndim != 2 or curve.tangents.shape != curve.x.shape or curve.s.shape != (m,):
        return (f"its arrays disagree in shape: x {curve.x.shape}, tangents "
                f"{curve.tangents.shape}, s {curve.s.shape}", None)
    for p in curve.special_points:
        if not 0 <= p.index < m:
            return f"special point {p.name} has index {p.index}, outside [0, {m - 1}]", None
        row = p.index
        if not (np.array_equal(p.x, curve.x[row]) and p.s == curve.s[row]
                and (p.tangent is None or np.array_equal(p.tangent, curve.tangents[row]))):
            return (f"special point {p.name} is not point {row} of the curve (its x, s or "
                    "tangent differ from that row's)", row)
    return None


def jacobian_mismatch(curve: Curve, problem) -> tuple | None:
    """Where ``problem.jacobian`` is not the derivative of ``problem.residual``: the reason and
    the point, or ``None``.

    The proof differentiates the residual itself; ``jacobian`` traced the curve and serves the
    proof in floats only (preconditioners). A wrong one would make the proof fail somewhere
    obscure, so it is named here: at every point of the curve it is compared, in floats, with
    the residual's forward-mode derivative (:func:`continuation.krawczyk.derivative`), to
    :data:`JACOBIAN_TOL`. A check at the points: one wrong only between them is not caught
    here (nor trusted by the proof).
    """
    for i, x in enumerate(curve.x.tolist()):
        J = np.array(problem.jacobian(x, FLOATS), dtype=float)
        D = np.array(derivative(problem, x, FLOATS), dtype=float)
        size = np.max(np.where(np.isfinite(J), np.abs(J), 0.0), axis=1)  # (NaN: its own entry)
        excess = np.abs(J - D) - JACOBIAN_TOL * (1.0 + size)[:, None]
        if not np.all(excess <= 0.0):  # (NaN included)
            r, j = np.unravel_index(int(np.argmax(np.nan_to_num(excess, nan=np.inf))),
                                    J.shape)
            return (f"problem.jacobian is not the derivative of problem.residual at point "
                    f"{i}: entry ({r}, {j}) is {float(J[r, j])!r}, the residual's derivative "
                    f"{float(D[r, j])!r}", i)
    return None


def not_certifiable(curve: Curve, problem, events, fold_coordinates) -> tuple | None:
    """Arguments that cannot be right raise; for a curve that cannot be certified, the reason
    and the point it concerns (or ``None``); ``None`` if it can be."""
    if not isinstance(curve, Curve):
        raise TypeError(f"curve must be a continuation.Curve, got {type(curve).__name__}")
    if getattr(problem, "jacobian", None) is None or getattr(problem, "residual", None) is None:
        raise ValueError("certify needs problem.residual(x, numbers) and "
                         "problem.jacobian(x, numbers), written over a numbers namespace")
    n1 = curve.x.shape[1] if curve.x.ndim == 2 else 0
    for c in fold_coordinates:
        if not (isinstance(c, (int, np.integer)) and 0 <= c < n1):
            raise ValueError(f"fold coordinate {c!r} is outside [0, {n1 - 1}]")
    if len(set(fold_coordinates)) != len(fold_coordinates):
        raise ValueError(f"fold_coordinates = {tuple(fold_coordinates)!r} repeats a coordinate "
                         "(its folds would be counted twice)")
    # a fold's coordinate and an event's position are ints (SpecialPoint)
    folds = {cast(int, p.coordinate) for p in curve.special_points
             if p.kind is SpecialKind.FOLD}
    if not folds <= set(fold_coordinates):
        raise ValueError(f"the curve reports folds in coordinates {sorted(folds)}, but "
                         f"fold_coordinates = {tuple(fold_coordinates)!r}: pass them all")
    used = [cast(int, p.event) for p in curve.special_points if p.kind is SpecialKind.EVENT]
    if used and max(used) >= len(events):
        raise ValueError(f"the curve reports event {max(used)}, but certify was given "
                         f"{len(events)} event(s): pass every event of the run, in its order")
    if len(curve) < 2:
        return f"the curve has {len(curve)} point(s); at least two are needed", None
    broken = _inconsistent(curve)
    if broken is not None:
        return broken
    x0 = [float(v) for v in curve.x[0]]
    _probe("problem.residual", problem.residual, x0)
    _probe("problem.jacobian", problem.jacobian, x0)
    for event in events:
        _probe(f"the function of event '{event.name}'", event.function, x0)
    if not curve.ok:
        return f"the run failed ({curve.status.name}): {curve.message}", None
    for p in curve.special_points:
        if p.kind is SpecialKind.BRANCH_POINT:
            return (f"branch point at point {p.index}: the solution set is not one smooth arc "
                    "there, which is not certified", p.index)
    return jacobian_mismatch(curve, problem)
