"""Events: scalar functions of a curve point whose zeros the engine locates.

How the zeros are found (bracketed inside each step, located by Brent's method
on the curve) is :mod:`continuation.locate`.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["Event", "box_events", "crossed"]


@dataclass(frozen=True)
class Event:
    """A scalar function of the curve point whose zeros are located.

    Parameters
    ----------
    name : str
        Name, reported in ``SpecialPoint.name``.
    function : callable
        ``function(x) -> float`` for ``x`` of shape ``(n + 1,)``; to be certified
        (:func:`continuation.certify`), ``function(x, numbers=FLOATS)``, written over the
        numbers namespace (:mod:`continuation.numbers`).
    direction : {0, 1, -1}, optional
        ``+1``: only zeros where the function increases along the curve,
        ``-1``: only where it decreases, ``0`` (default): both.
    terminal : bool, optional
        Stop the curve at the (first) zero.
    gradient : callable or None, optional
        ``gradient(x) -> ndarray, shape (n + 1,)``, the derivative of
        ``function``. The engine needs the event's rate of change along the
        curve, ``gradient(x) . t``, at every point, to find pairs of zeros
        inside one step and the side of a zero at the start; ``None``
        (default) takes a central difference of ``function`` along the
        tangent (two more calls of ``function`` per point).
    linear : bool, optional
        Whether ``function`` is affine, ``g(x) = a . x + b`` with ``gradient``
        returning ``a`` (required then). Along a step, ``g`` of the step's
        cubic Hermite arc is then exactly the event's cubic model (the model's
        slopes at the ends are ``a . t``, the arc's derivatives ``t``), so the
        samples described below could only repeat the model: they are skipped,
        two calls of ``function`` per step fewer, and the zeros are the same.
        The gradient is evaluated once per run, and every step checks
        ``g(x_b) - g(x_a) = a . (x_b - x_a)`` (to 1e-9 of the sizes involved,
        plus the rounding of ``g``): a function declared linear whose change
        over a step disagrees with its gradient stops the run with a
        :class:`~continuation.CallbackError`. The check sees the step's ends
        only: a deviation from ``a . x + b`` that vanishes at both ends of
        every step (a bump between two nodes) passes it and its zeros are
        lost, so declare linear only what is affine. Default ``False``.

    Notes
    -----
    ``function`` (unless ``linear``) is also called at a third and two thirds
    of every step, on the step's cubic Hermite arc; where those values disagree with the
    event's cubic model near zero, they are computed again on the curve and,
    if they still disagree, the step is split there and its parts checked the
    same way, down to a 27th of the step. In random tests this found every
    zero of oscillations whose zeros were 0.08 of ``ds_max`` apart and more,
    and of dips about a third of ``ds_max`` wide; but fixed samples can miss
    what falls between them (a narrower dip, an oscillation whose period
    fits the samples), so an event that changes on a scale much shorter
    than the steps needs ``ds_max`` below that scale to be sure of its
    zeros. The models assume an event that is smooth along the curve, finite
    on it (where it is not, the run ends with ``EVENT_NOT_FINITE``)
    and changing by more than the corrector's tolerance: kinks, stretches
    where it vanishes identically, or an event that is zero on the whole
    curve can be misread.

    Raises
    ------
    ValueError
        If ``direction`` is not -1, 0 or 1 or the name is empty.
    TypeError
        If ``function`` is not callable.
    """

    name: str
    function: Callable[..., float]
    direction: int = 0
    terminal: bool = False
    gradient: Callable[[np.ndarray], np.ndarray] | None = None
    linear: bool = False

    def __post_init__(self) -> None:
        if not isinstance(self.name, str):
            raise TypeError(f"Event.name must be a non-empty str, got {self.name!r}")
        if not self.name:
            raise ValueError(f"Event.name must be a non-empty str, got {self.name!r}")
        if not callable(self.function):
            raise TypeError(f"Event.function must be callable, got {self.function!r}")
        if self.direction not in (-1, 0, 1) or isinstance(self.direction, bool):
            raise ValueError(f"Event.direction must be -1, 0 or 1, got {self.direction!r}")
        if not isinstance(self.terminal, bool):
            raise TypeError(f"Event.terminal must be True or False, got {self.terminal!r}")
        if self.gradient is not None and not callable(self.gradient):
            raise TypeError(f"Event.gradient must be callable or None, got {self.gradient!r}")
        if not isinstance(self.linear, bool):
            raise TypeError(f"Event.linear must be True or False, got {self.linear!r}")
        if self.linear and self.gradient is None:
            raise ValueError(f"Event '{self.name}' is declared linear but has no gradient: "
                             "give the constant gradient a of g(x) = a . x + b")


def box_events(
    lower: Mapping[int, float] | Sequence[float | None] = (),
    upper: Mapping[int, float] | Sequence[float | None] = (),
    names: Sequence[str] | None = None,
) -> list[Event]:
    """Terminal events that stop a curve where it leaves a box.

    Parameters
    ----------
    lower, upper : dict {int: float} or sequence of float/None
        Bounds per coordinate; in a sequence, ``None`` or an infinite value
        means no bound.
    names : sequence of str or None, optional
        Coordinate names (e.g. ``Problem.names``) used in the event names.

    Returns
    -------
    list of Event
        For a lower bound ``L`` on coordinate ``i`` an event named
        ``"x[i] >= L"`` with function ``x[i] - L`` and direction ``-1``; for an
        upper bound ``U`` one named ``"x[i] <= U"`` with function ``x[i] - U``
        and direction ``+1``. All terminal, and ``linear``.

    Raises
    ------
    ValueError
        If an index is negative, a bound is NaN, or a lower bound is not below
        the upper bound of the same coordinate.
    """
    lows = _bounds("lower", lower)
    highs = _bounds("upper", upper)
    for i in set(lows) & set(highs):
        if not lows[i] < highs[i]:
            raise ValueError(
                f"box bounds of coordinate {i} must satisfy lower < upper, got "
                f"lower={lows[i]!r}, upper={highs[i]!r}"
            )

    def label(i: int) -> str:
        return names[i] if names is not None and i < len(names) else f"x[{i}]"

    events = []
    for i, bound in sorted(lows.items()):
        offset = _Offset(i, bound)
        events.append(Event(f"{label(i)} >= {bound!r}", offset, -1, True, offset.gradient,
                            linear=True))
    for i, bound in sorted(highs.items()):
        offset = _Offset(i, bound)
        events.append(Event(f"{label(i)} <= {bound!r}", offset, 1, True, offset.gradient,
                            linear=True))
    return events


@dataclass(frozen=True)
class _Offset:
    """``x[index] - value`` (a picklable event function; over any numbers, so that
    :func:`continuation.certify` can prove its zeros too)."""

    index: int
    value: float

    def __call__(self, x: np.ndarray, numbers=None) -> float:
        return x[self.index] - self.value

    def gradient(self, x: np.ndarray) -> np.ndarray:
        """The unit vector ``e_index``."""
        unit = np.zeros(len(x))
        unit[self.index] = 1.0
        return unit


def _bounds(which: str, bounds) -> dict[int, float]:
    items: Iterable[tuple[Any, Any]]
    if isinstance(bounds, Mapping):
        items = bounds.items()
    else:
        items = enumerate(bounds)
    result = {}
    for i, bound in items:
        if bound is None:
            continue
        if not isinstance(i, numbers.Integral) or i < 0:
            raise ValueError(f"{which} bound index must be an integer >= 0, got {i!r}")
        bound = float(bound)
        if math.isnan(bound):
            raise ValueError(f"{which} bound of coordinate {i} must not be NaN")
        if math.isinf(bound):
            continue
        result[int(i)] = bound
    return result


def crossed(before: float, after: float, direction: int = 0) -> bool:
    """Whether a function crosses zero on a step, in ``(before, after]``.

    A zero at the step's start is not a crossing (it belongs to the previous
    step, or is the start point); a zero at its end is. The signs are compared, not
    multiplied: a product of two tiny values (a zero at the start stands for ``1e-300`` on
    the side the function moves to) underflows to zero and would read as a crossing.
    """
    if before == 0.0 or math.isnan(before) or math.isnan(after):
        return False
    if not (after == 0.0 or (before > 0.0) != (after > 0.0)):
        return False
    if direction == 0:
        return True
    return (after > before) == (direction > 0)
