"""Linear events: their constant gradients, evaluated once per run, and the check of their
change over each step.

An event declared ``Event(..., linear=True)`` is ``g(x) = a . x + b``. Its values on a step's
cubic Hermite arc are then its cubic model exactly, so the scan does not sample it inside the
steps (:mod:`continuation.scan`); in exchange every step checks that it changed as its gradient
says, ``g(x_b) - g(x_a) = a . (x_b - x_a)``, so that a function declared linear whose change
over a step disagrees with its gradient stops the run instead of losing the zeros the samples
would have shown. The check compares the step's ends only: a deviation from ``a . x + b`` that
vanishes at both ends of a step is invisible to it, so ``linear`` is a promise the caller keeps.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from .errors import CallbackError
from .events import Event

__all__ = ["AFFINE_TOL", "ROUNDING", "LinearEvents", "event_gradient"]

#: a linear event's change over a step may differ from its gradient's prediction by at most
#: this fraction of the sizes involved (rounding is some 1e-16 of them, a curved event's
#: deviation over a step of the curve many orders more)
AFFINE_TOL = 1e-9
#: and, beyond that, by this multiple of the rounding in evaluating ``g = a . x + b`` at both
#: ends (a few units of ``|a| . |x|`` each, far more than ``|g|`` where the terms cancel)
ROUNDING = 64 * np.finfo(float).eps

_FLOAT = np.dtype(float)


def event_gradient(event: Event, x: np.ndarray, describe) -> np.ndarray:
    """``event.gradient(x)`` as a float array of the shape of ``x``; a raised exception or a
    wrong result becomes a :class:`CallbackError`."""
    function = event.gradient
    if function is None:
        raise TypeError(f"event '{event.name}' has no gradient")
    try:
        gradient = function(x)
        if type(gradient) is np.ndarray and gradient.dtype == _FLOAT \
                and gradient.shape == x.shape:
            return gradient  # the common case, without the checks below
        gradient = np.asarray(gradient)
        if gradient.dtype.kind == "c":
            raise TypeError(f"it returned complex values (dtype {gradient.dtype}), not real")
        gradient = gradient.astype(float, copy=False)
    except Exception as exc:
        raise CallbackError(f"gradient of event '{event.name}' raised "
                            f"{type(exc).__name__}: {exc} at x={describe(x)}") from exc
    if gradient.shape != x.shape:
        raise CallbackError(f"gradient of event '{event.name}' returned shape "
                            f"{gradient.shape}, expected {x.shape}")
    return gradient


class LinearEvents:
    """The linear events of a run (``Event.linear``) and their constant gradients, evaluated
    once, at the first step that needs them, as the rows of one matrix.

    Parameters
    ----------
    events : sequence of Event
        The run's events (only the linear ones are kept, by position).
    """

    def __init__(self, events: Sequence[Event]) -> None:
        self.events = events
        self.indices = [j for j, event in enumerate(events) if event.linear]
        #: event position -> row of the gradient matrix
        self.rows = {j: row for row, j in enumerate(self.indices)}
        self._matrix: np.ndarray | None = None
        #: ``|a_ij|``: the sizes of the terms of each prediction
        self.magnitudes = np.zeros((0, 0))

    def gradients(self, x: np.ndarray, describe) -> np.ndarray:
        """The gradients, one row per linear event (evaluated at ``x`` the first time)."""
        if self._matrix is None:
            rows = [event_gradient(self.events[j], x, describe) for j in self.indices]
            for j, row in zip(self.indices, rows, strict=True):
                if not all(map(math.isfinite, row.tolist())):
                    raise CallbackError(f"gradient of event '{self.events[j].name}' is not "
                                        f"finite at x={describe(x)}: {row.tolist()!r}")
            self._matrix = np.array(rows, dtype=float).reshape(len(rows), x.size)
            self.magnitudes = np.abs(self._matrix)
        return self._matrix

    def check(self, a, b, describe) -> None:
        """:class:`CallbackError` if a linear event changed between the nodes ``a`` and ``b``
        (with ``x`` and ``events``) by more than its gradient allows: to :data:`AFFINE_TOL` of
        ``|g(a)| + |g(b)| + |a| . |x_b - x_a|``, plus :data:`ROUNDING` times
        ``|g(a)| + |g(b)| + |a| . (|x_a| + |x_b|)`` for the rounding in ``g`` itself."""
        if not self.indices:
            return
        gradients = self.gradients(a.x, describe)
        chord = b.x - a.x
        predicted = (gradients @ chord).tolist()
        sizes = (self.magnitudes @ np.abs(chord)).tolist()
        for row, (j, change, size) in enumerate(zip(self.indices, predicted, sizes, strict=True)):
            f_a, f_b = a.events[j], b.events[j]
            ends = abs(f_a) + abs(f_b)
            deviation, allowed = abs(f_b - f_a - change), AFFINE_TOL * (ends + size)
            if deviation <= allowed:
                continue
            # the rounding term, only where needed (rarely: its terms cancel in g)
            terms = float(self.magnitudes[row] @ (np.abs(a.x) + np.abs(b.x)))
            if not deviation <= allowed + ROUNDING * (ends + terms):
                raise CallbackError(
                    f"event '{self.events[j].name}' is declared linear but is not affine along "
                    f"the curve: from x={describe(a.x)} to x={describe(b.x)} it changed by "
                    f"{f_b - f_a!r}, its gradient gives {change!r}; declare it linear=False")
