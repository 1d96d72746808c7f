r"""The augmented systems of two-parameter continuation: a fold and an event point in z = (x, p).

Both add one scalar equation to ``H(x, p) = 0``, so that the special point of the curve
``H(., p) = 0`` becomes a regular point of a curve in ``z`` (``n + 1`` equations in ``n + 2``
unknowns) that :func:`continuation.trace` follows:

* :class:`FoldSystem`: ``H = 0`` and the minimally augmented fold test ``g = 0`` of a chosen
  coordinate ``x_i`` (Govaerts, *Numerical Methods for Bifurcations of Dynamical Equilibria*,
  SIAM 2000, sec. 4.3; the fold continuation of MATCONT);
* :class:`EventSystem`: ``H = 0`` and an event ``e(x, p) = 0``.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.linalg.lapack import dgetrf, dgetrs

from .events import Event
from .family import DIFFERENCE_STEP, Family, central_gradient
from .linalg import max_abs, norm

__all__ = ["BORDER_QUALITY", "EventSystem", "FoldSystem"]

#: the borders of a fold test are renewed where the cosine between a border and its null
#: vector falls below this (the bordered matrix stays well conditioned above it)
BORDER_QUALITY = 0.5


class FoldSystem:
    r"""``H(x, p) = 0`` and the bordered fold test of coordinate ``x_i``: ``n + 1`` equations.

    Parameters
    ----------
    family : Family
    coordinate : int
        The coordinate ``i`` of ``x`` whose folds are followed (``0 <= i <= n``).
    z : ndarray, shape (n + 2,)
        Where the borders are chosen: the singular vectors of ``A(z)`` for its smallest
        singular value.

    Notes
    -----
    A fold of ``x_i`` on the curve ``H(., p) = 0`` is a point where the tangent has
    ``t_i = 0``: the ``n x n`` matrix ``A = dH/dx`` without its column ``i`` is singular there.
    With borders ``b, c`` (unit vectors near the left and right null vectors of ``A``) the
    bordered system

    .. math::

        \begin{pmatrix} A & b \\ c^T & 0 \end{pmatrix}
        \begin{pmatrix} v \\ g \end{pmatrix} = \begin{pmatrix} 0 \\ 1 \end{pmatrix},
        \qquad
        \begin{pmatrix} A^T & c \\ b^T & 0 \end{pmatrix}
        \begin{pmatrix} w \\ g \end{pmatrix} = \begin{pmatrix} 0 \\ 1 \end{pmatrix}

    is regular near the fold and defines ``g(z)``, which vanishes exactly where ``A`` is
    singular (then ``A v = 0``) and, at a simple fold, has a nonzero gradient (Govaerts 2000,
    Prop. 3.1.2 and sec. 4.3): the system ``(H, g) = 0`` is regular at the fold, unlike
    ``det A = 0`` scaled badly or ``t_i = 0`` whose sign is that of an orientation. Its
    gradient is ``g_z = -w^T A_z v``: with ``v~`` the vector ``v`` with ``0`` inserted at
    ``i``, ``A_z v = H_xz[v~]``, the derivative of the Jacobian along ``v~``, which central
    differences of two Jacobians give for every ``x_j`` at once; the ``p`` column is the
    central difference of ``A v`` in ``p``. ``g`` itself is exact, so Newton converges to the
    fold to full accuracy even though its Jacobian is a difference quotient.

    ``c^T v = 1`` and ``b^T w = 1``, so ``1/|v|`` and ``1/|w|`` are the cosines between the
    borders and the null vectors; :meth:`quality` reports them and the driver renews the
    borders where one falls below :data:`BORDER_QUALITY` (MATCONT renews them every step).
    """

    def __init__(self, family: Family, coordinate: int, z: np.ndarray) -> None:
        self.family = family
        self.coordinate = coordinate
        self._key: bytes | None = None
        self._solution: tuple[float, np.ndarray, np.ndarray, np.ndarray] | None = None
        A = self._matrix(family.jacobian_x(z[:-1], float(z[-1])))
        if not np.all(np.isfinite(A)):
            raise ValueError(f"the Jacobian is not finite at z = {z!r}: no fold test there")
        left, _, right = np.linalg.svd(A)
        self.b = left[:, -1].copy()
        self.c = right[-1].copy()

    def _matrix(self, jacobian_x: np.ndarray) -> np.ndarray:
        return np.delete(jacobian_x, self.coordinate, axis=1)

    def solve(self, z: np.ndarray):
        """``(g, v, w, dH/dx)`` at ``z`` (the last point's values are reused)."""
        key = z.tobytes()
        if key == self._key:
            return self._solution
        Jx = self.family.jacobian_x(z[:-1], float(z[-1]))
        A = self._matrix(Jx)
        n = A.shape[0]
        M = np.zeros((n + 1, n + 1))
        M[:n, :n] = A
        M[:n, n] = self.b
        M[n, :n] = self.c
        lu, piv, info = dgetrf(M)
        unit = np.zeros(n + 1)
        unit[n] = 1.0
        if info != 0 or not np.all(np.isfinite(M)):
            nan = np.full(n, math.nan)
            solution = (math.nan, nan, nan, Jx)
        else:
            right = dgetrs(lu, piv, unit)[0]
            left = dgetrs(lu, piv, unit, trans=1)[0]
            solution = (float(right[n]), right[:n], left[:n], Jx)
        self._key, self._solution = key, solution
        return solution

    def test(self, z: np.ndarray) -> float:
        """The fold test ``g(z)``."""
        return self.solve(z)[0]

    def residual(self, z: np.ndarray) -> np.ndarray:
        """``(H(x, p), g(x, p))``, shape ``(n + 1,)``."""
        return np.append(self.family.residual_z(z), self.test(z))

    def jacobian(self, z: np.ndarray) -> np.ndarray:
        """``d(H, g)/dz``, shape ``(n + 1, n + 2)``; ``g_z`` by central differences."""
        family = self.family
        x, p = z[:-1], float(z[-1])
        _, v, w, Jx = self.solve(z)
        null = np.insert(v, self.coordinate, 0.0)
        length = norm(null)
        if not 0.0 < length < math.inf:
            row = np.full(z.size, math.nan)
        else:
            h = DIFFERENCE_STEP * (1.0 + max_abs(x)) / length
            g_x = -(w @ (family.jacobian_x(x + h * null, p)
                         - family.jacobian_x(x - h * null, p))) / (2.0 * h)
            hp = DIFFERENCE_STEP * max(1.0, abs(p))
            up, down = p + hp, p - hp
            g_p = -(w @ ((family.jacobian_x(x, up) - family.jacobian_x(x, down)) @ null)) \
                / (up - down)
            row = np.append(g_x, g_p)
        return np.vstack([np.column_stack([Jx, family.jacobian_p(x, p)]), row])

    def quality(self, z: np.ndarray) -> tuple[float, float]:
        """Cosines ``(1/|v|, 1/|w|)`` between the borders and the null vectors at ``z``."""
        _, v, w, _ = self.solve(z)
        return 1.0 / norm(v), 1.0 / norm(w)

    def border_events(self) -> list[Event]:
        """Terminal events where a border's cosine falls to :data:`BORDER_QUALITY`."""
        return [Event("fold test: right border", lambda z: self.quality(z)[0] - BORDER_QUALITY,
                      direction=-1, terminal=True),
                Event("fold test: left border", lambda z: self.quality(z)[1] - BORDER_QUALITY,
                      direction=-1, terminal=True)]

    def equations(self, names: tuple[str, ...]) -> tuple[str, ...]:
        """The defining equations in words."""
        i = names[self.coordinate]
        return ("H(x, p) = 0",
                f"g = 0: dH/dx without its column {i} is singular (a fold of {i}; "
                "minimally augmented test)")


class EventSystem:
    """``H(x, p) = 0`` and an event ``e(x, p) = 0``: ``n + 1`` equations in ``z = (x, p)``.

    Parameters
    ----------
    family : Family
    event : Event
        Its ``function`` (and ``gradient``, if given) take ``z = (x, p)``; without a gradient
        the row of the Jacobian is a central difference (``2 (n + 2)`` calls).
    """

    def __init__(self, family: Family, event: Event) -> None:
        self.family = family
        self.event = event

    def residual(self, z: np.ndarray) -> np.ndarray:
        return np.append(self.family.residual_z(z), float(self.event.function(z)))

    def gradient(self, z: np.ndarray) -> np.ndarray:
        """The event's gradient in ``z``."""
        if self.event.gradient is not None:
            return np.asarray(self.event.gradient(z), dtype=float)
        return central_gradient(lambda y: float(self.event.function(y)), z)

    def jacobian(self, z: np.ndarray) -> np.ndarray:
        return np.vstack([self.family.jacobian_z(z), self.gradient(z)])

    def equations(self, names: tuple[str, ...]) -> tuple[str, ...]:
        return ("H(x, p) = 0", f"event '{self.event.name}' = 0")
