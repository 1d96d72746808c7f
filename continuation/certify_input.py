"""What :func:`continuation.certify` accepts: arguments that cannot be right raise (with what
to write instead), and a curve that cannot be certified gets its reason (check ``input``)."""

from __future__ import annotations

from typing import cast

import numpy as np

from .numbers import FLOATS
from .result import Curve, SpecialKind

__all__ = ["not_certifiable"]


def _probe(name: str, function, x) -> None:
    """Call ``function(x, FLOATS)`` once: a ``TypeError`` that says what to write if it fails."""
    try:
        function(x, FLOATS)
    except TypeError as exc:
        raise TypeError(f"{name} must take (x, numbers) and be written over the numbers "
                        f"namespace (continuation.numbers) to be certified: {exc}") from None


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
    return None
