"""A one-parameter family of curves ``H(x, p) = 0``, the problem of two-parameter continuation.

For each value of the parameter ``p`` the family gives a curve problem ``H(., p): R^(n+1) ->
R^n`` (:meth:`Family.at`), which :func:`continuation.trace` follows; a special point of that
curve (a fold, an event) moves with ``p``, and :mod:`continuation.codim2` follows it, as a
curve in ``z = (x, p)``, R^(n+2).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from .events import Event
from .problem import Problem, as_vector

__all__ = ["DIFFERENCE_STEP", "Family", "central_gradient"]

_EPS = np.finfo(float).eps

#: relative step of the central differences of the family (in ``p``, along null vectors):
#: ``eps^(1/3)`` balances their truncation error ``O(h^2)`` against rounding ``O(eps / h)``
DIFFERENCE_STEP = _EPS ** (1.0 / 3.0)


@dataclass(frozen=True)
class Family:
    """A family of curves ``H(x, p) = 0``, ``H: R^(n+1) x R -> R^n``.

    Parameters
    ----------
    residual : callable
        ``residual(x, p) -> ndarray, shape (n,)`` for ``x`` of shape ``(n + 1,)`` and a float
        ``p``.
    jacobian : callable or None, optional
        ``jacobian(x, p) -> ndarray, shape (n, n + 1)``, the derivative ``dH/dx``; ``None``
        (default) uses central differences.
    parameter_derivative : callable or None, optional
        ``parameter_derivative(x, p) -> ndarray, shape (n,)``, ``dH/dp``; ``None`` (default)
        uses the central difference with step ``h = eps^(1/3) max(1, |p|)`` (two residual
        evaluations; error ``O(h^2)``, about ``1e-10`` relative). It only enters Jacobians of
        the augmented systems, never their residuals, so Newton still converges to points
        that satisfy the equations to full accuracy.
    names : tuple of str or None, optional
        Names of the ``n + 1`` coordinates of ``x``.
    parameter : str, optional
        Name of ``p`` (default ``"p"``).

    Notes
    -----
    The coordinates of the two-parameter curves are ``z = (x, p)``: ``z[:-1] = x`` and
    ``z[-1] = p``. Events on them (:class:`continuation.Event`) are functions of ``z``;
    :meth:`event_at` turns one into an event of the curve at a fixed ``p``.
    """

    residual: Callable[[np.ndarray, float], np.ndarray]
    jacobian: Callable[[np.ndarray, float], np.ndarray] | None = None
    parameter_derivative: Callable[[np.ndarray, float], np.ndarray] | None = None
    names: tuple[str, ...] | None = None
    parameter: str = "p"

    def __post_init__(self) -> None:
        if not callable(self.residual):
            raise TypeError(f"Family.residual must be callable, got "
                            f"{type(self.residual).__name__}")
        for name in ("jacobian", "parameter_derivative"):
            value = getattr(self, name)
            if value is not None and not callable(value):
                raise TypeError(f"Family.{name} must be callable or None, got "
                                f"{type(value).__name__}")
        if not isinstance(self.parameter, str) or not self.parameter:
            raise TypeError(f"Family.parameter must be a non-empty str, got {self.parameter!r}")
        if self.names is not None:
            object.__setattr__(self, "names", tuple(self.names))

    # --- the curve at one parameter value ---------------------------------------------------
    def at(self, p: float) -> Problem:
        """The curve problem ``H(., p) = 0`` at a fixed ``p``, for :func:`continuation.trace`."""
        p = float(p)
        jacobian_xp = self.jacobian
        jacobian = None if jacobian_xp is None else (lambda x: jacobian_xp(x, p))
        return Problem(lambda x: self.residual(x, p), jacobian, names=self.names)

    def event_at(self, event: Event, p: float) -> Event:
        """The event ``g(x, p)`` of ``z = (x, p)`` as an event of ``x`` at a fixed ``p``."""
        p = float(p)
        gradient_z = event.gradient
        gradient = None if gradient_z is None else (
            lambda x: np.asarray(gradient_z(np.append(x, p)), dtype=float)[:-1])
        return Event(event.name, lambda x: event.function(np.append(x, p)), event.direction,
                     event.terminal, gradient, event.linear)

    # --- derivatives in z = (x, p) ----------------------------------------------------------
    def names_z(self, n1: int) -> tuple[str, ...]:
        """Names of the ``n + 2`` coordinates of ``z = (x, p)``."""
        names = self.names if self.names is not None and len(self.names) == n1 else tuple(
            f"x[{i}]" for i in range(n1))
        return (*names, self.parameter)

    def residual_z(self, z: np.ndarray) -> np.ndarray:
        """``H(x, p)`` at ``z = (x, p)``."""
        return np.asarray(self.residual(z[:-1], float(z[-1])), dtype=float)

    def jacobian_x(self, x: np.ndarray, p: float) -> np.ndarray:
        """``dH/dx`` at ``(x, p)``, shape ``(n, n + 1)``."""
        if self.jacobian is not None:
            return np.asarray(self.jacobian(x, p), dtype=float)
        return central_gradient(lambda y: self.residual(y, p), x)

    def jacobian_p(self, x: np.ndarray, p: float) -> np.ndarray:
        """``dH/dp`` at ``(x, p)``, shape ``(n,)``."""
        if self.parameter_derivative is not None:
            return np.asarray(self.parameter_derivative(x, p), dtype=float)
        h = DIFFERENCE_STEP * max(1.0, abs(p))
        up, down = p + h, p - h
        return (np.asarray(self.residual(x, up), dtype=float)
                - np.asarray(self.residual(x, down), dtype=float)) / (up - down)

    def jacobian_z(self, z: np.ndarray) -> np.ndarray:
        """``[dH/dx, dH/dp]`` at ``z = (x, p)``, shape ``(n, n + 2)``."""
        x, p = z[:-1], float(z[-1])
        return np.column_stack([self.jacobian_x(x, p), self.jacobian_p(x, p)])


def central_gradient(function: Callable[[np.ndarray], npt.ArrayLike], z: np.ndarray) -> np.ndarray:
    """Central differences of ``function`` at ``z``: shape ``(m, z.size)``, or ``(z.size,)``
    for a scalar function; step ``eps^(1/3) max(1, |z_j|)`` per coordinate."""
    z = as_vector("z", z)
    columns = []
    for j in range(z.size):
        h = DIFFERENCE_STEP * max(1.0, abs(z[j]))
        up, down = z.copy(), z.copy()
        up[j] += h
        down[j] -= h
        columns.append((np.asarray(function(up), dtype=float)
                        - np.asarray(function(down), dtype=float)) / (up[j] - down[j]))
    return np.stack(columns, axis=-1)
