r"""Krawczyk's test in ball arithmetic: tubes around curve segments, slices, square systems.

A segment between two curve points ``x_a`` and ``x_b`` (chord ``L v``, ``|v| = 1``) is given
the coordinates ``x = x_a + tau v + N (c(tau) + y)``, where ``N`` completes ``v`` to an
orthonormal frame (floats, used as exact numbers) and ``c`` is the cubic Hermite interpolant,
over the chord, of the two points and their tangents (the curve as a graph over the chord,
error ``O(L^4)``). For the zeros of ``H`` in a piece ``tau in T`` of the tube ``|y|_inf <= r``
the parametrised Krawczyk operator (Krawczyk 1969; Neumaier, *Interval Methods for Systems of
Equations*, 1990, sec. 5.1; for curves van den Berg, Lessard & Mischaikow, Math. Comp. 79
(2010) 1565-1584) is

.. math::

    K(T, Y) = -A\,G(T) + (I - A\,H'(X) N)\,Y, \qquad X = x_a + T v + N(c(T) + Y),

where ``G(T)`` encloses ``H(x_a + tau v + N c(tau))`` for every ``tau in T`` (a second-order
Taylor form in ``tau``: value and slope at the centre, the second derivative enclosed over
``T`` by jets) and ``A`` approximates ``(H'(x) N)^{-1}`` at the piece's centre. If ``K(T, Y)``
lies in the interior of ``Y``, then for every ``tau in T`` the slice has exactly one zero in
``Y`` (it lies in ``K``) and ``H'`` has full rank on ``X``: the zeros of ``H`` in the piece
are one smooth arc, a graph over ``tau`` (implicit function theorem). The same operator with
a thin ``T`` proves the zero of one slice (a point of the curve).

Vectors of balls are lists; float matrices are nested lists (exact numbers).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .numbers import FLOATS, Jet, jets

__all__ = ["Failure", "Frame", "Piece", "Slice", "determinant", "kernel", "inverse",
           "solve_piece", "solve_slice", "square_box"]


def _matvec(M, v):
    """``M v`` for a float matrix (nested lists) and a vector of numbers."""
    return [sum(m_ij * v_j for m_ij, v_j in zip(row, v)) for row in M]


def determinant(M):
    """Determinant of a small square matrix of numbers (Laplace expansion)."""
    n = len(M)
    if n == 1:
        return M[0][0]
    if n == 2:
        return M[0][0] * M[1][1] - M[0][1] * M[1][0]
    if n == 3:
        a, b, c = M
        return (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0]))
    total = 0
    for j in range(n):
        minor = [row[:j] + row[j + 1:] for row in M[1:]]
        term = M[0][j] * determinant(minor)
        total = total + term if j % 2 == 0 else total - term
    return total


def kernel(J):
    """The Cramer kernel vector ``k_j = (-1)^j det(J without column j)`` of an ``n x (n+1)``
    matrix: ``J k = 0``, ``k != 0`` where ``J`` has full rank (the curve's tangent direction)."""
    out = []
    for j in range(len(J[0])):
        d = determinant([row[:j] + row[j + 1:] for row in J])
        out.append(d if j % 2 == 0 else -d)
    return out


def inverse(M) -> list | None:
    """Inverse of a small float matrix (Gauss-Jordan, partial pivoting); ``None`` if singular."""
    n = len(M)
    a = [[float(v) for v in row] + [1.0 if i == j else 0.0 for j in range(n)]
         for i, row in enumerate(M)]
    for col in range(n):
        pivot = max(range(col, n), key=lambda r: abs(a[r][col]))
        if not abs(a[pivot][col]) > 0.0:
            return None
        a[col], a[pivot] = a[pivot], a[col]
        p = a[col][col]
        a[col] = [v / p for v in a[col]]
        for r in range(n):
            if r != col and a[r][col] != 0.0:
                f = a[r][col]
                a[r] = [v - f * w for v, w in zip(a[r], a[col])]
    inv = [row[n:] for row in a]
    return inv if all(math.isfinite(v) for row in inv for v in row) else None


def _upper(x) -> float:
    """A float ``>= |x|`` for every value of the ball ``x`` (inf if it is not finite)."""
    if not x.is_finite():
        return math.inf
    return math.nextafter(float(abs(x).upper()), math.inf)


@dataclass(frozen=True)
class Failure:
    """Why a Krawczyk test failed; ``contraction`` is ``|I - A H' N|`` where it was computed."""

    message: str
    contraction: float = math.nan

    def __str__(self) -> str:
        return self.message


@dataclass(frozen=True)
class Frame:
    """The coordinates of one segment's tube: ``x = x_a + tau v + N (c(tau) + y)``.

    ``v`` is the unit chord, ``N`` (``n1 x n``) its orthonormal complement (floats, exact as
    numbers), ``length`` the chord's length, and ``c(tau) = sum_p a_p tau^p`` (``p <= 3``,
    ``coefficients[p] = a_p``) the centerline's offset from the chord.
    """

    x_a: list
    v: list
    N: list
    length: float
    coefficients: list
    eta: list = field(default_factory=list, repr=False, compare=False)

    @classmethod
    def build(cls, x_a, t_a, x_b, t_b) -> "Frame | str":
        """The frame of the segment; a message if a tangent does not point along the chord."""
        x_a, x_b = [float(v) for v in x_a], [float(v) for v in x_b]
        t_a, t_b = [float(v) for v in t_a], [float(v) for v in t_b]
        d = [b - a for a, b in zip(x_a, x_b)]
        length = math.sqrt(sum(di * di for di in d))
        if not (length > 0.0 and math.isfinite(length)):
            return f"its points coincide or are not finite (chord length {length!r})"
        v = [di / length for di in d]
        along_a = sum(p * q for p, q in zip(v, t_a))
        along_b = sum(p * q for p, q in zip(v, t_b))
        if not (along_a > 0.0 and along_b > 0.0):
            return (f"a tangent points against the chord (cosines {along_a:.3g}, "
                    f"{along_b:.3g}): the curve is not a graph over it")
        # Householder reflection taking e_1 to -sign(v_0) v; its other columns span v's complement
        u = list(v)
        u[0] += math.copysign(1.0, v[0]) if v[0] != 0.0 else 1.0
        uu = sum(ui * ui for ui in u)
        n1 = len(v)
        N = [[(1.0 if i == j else 0.0) - 2.0 * u[i] * u[j] / uu for j in range(1, n1)]
             for i in range(n1)]
        NT = list(zip(*N))
        c_b = [sum(col[i] * d[i] for i in range(n1)) for col in NT]
        m_a = [sum(col[i] * t_a[i] for i in range(n1)) / along_a for col in NT]
        m_b = [sum(col[i] * t_b[i] for i in range(n1)) / along_b for col in NT]
        # cubic Hermite through (0, 0, m_a) and (L, c_b, m_b), in powers of tau
        a2 = [(3.0 * cb / length - 2.0 * ma - mb) / length for cb, ma, mb in zip(c_b, m_a, m_b)]
        a3 = [(ma + mb - 2.0 * cb / length) / length ** 2 for cb, ma, mb in zip(c_b, m_a, m_b)]
        return cls(x_a, v, N, length, [[0.0] * len(c_b), m_a, a2, a3])

    def _c(self, tau, order: int = 0):
        """``c``, ``c'`` or ``c''`` at ``tau`` (a number), by Horner's rule."""
        a0, a1, a2, a3 = self.coefficients
        if order == 0:
            return [((a3[i] * tau + a2[i]) * tau + a1[i]) * tau + a0[i] for i in range(len(a0))]
        if order == 1:
            return [(3.0 * a3[i] * tau + 2.0 * a2[i]) * tau + a1[i] for i in range(len(a0))]
        return [6.0 * a3[i] * tau + 2.0 * a2[i] for i in range(len(a0))]

    def point(self, tau, w) -> list:
        """``x_a + tau v + N w`` for a number ``tau`` and a vector ``w`` in ``R^n``."""
        Nw = _matvec(self.N, w)
        return [self.x_a[j] + tau * self.v[j] + Nw[j] for j in range(len(self.v))]

    def tube_box(self, tau, y) -> list:
        """``x_a + tau v + N (c(tau) + y)`` for a number ``tau`` and a vector ``y``."""
        return self.point(tau, [ci + yi for ci, yi in zip(self._c(tau), y)])

    def centerline_jets(self, tau) -> list:
        """The centerline ``p(tau) = x_a + tau v + N c(tau)`` as jets: ``p``, ``p'``, ``p''``."""
        p = self.point(tau, self._c(tau))
        p1 = [vj + s for vj, s in zip(self.v, _matvec(self.N, self._c(tau, 1)))]
        p2 = _matvec(self.N, self._c(tau, 2))
        return [Jet(p[j], p1[j], p2[j]) for j in range(len(p))]

    def slope(self, tau) -> list:
        """``p'(tau)``."""
        return [vj + s for vj, s in zip(self.v, _matvec(self.N, self._c(tau, 1)))]

    def coordinates(self, box, B):
        """``(tau, y)`` of a ball vector ``box`` (rigorous), or ``None``.

        ``M = [v N]`` is orthogonal only to rounding: with ``|M^T M - I|_inf <= eta < 1``
        the exact coordinates ``M^{-1} (x - x_a)`` are within ``eta / (1 - eta)`` times
        ``|M^T (x - x_a)|_inf`` of ``M^T (x - x_a)``.
        """
        rows = [self.v] + [list(col) for col in zip(*self.N)]
        if not self.eta:
            S = B.matmul(rows, [list(r) for r in zip(*rows)])
            self.eta.append(max(sum(_upper(S[i][j] - (1.0 if i == j else 0.0))
                                    for j in range(len(S))) for i in range(len(S))))
        eta = self.eta[0]
        if not eta < 0.5:
            return None
        z = _matvec(rows, [b - a for b, a in zip(box, self.x_a)])
        slack = eta / (1.0 - eta) * max(_upper(zi) for zi in z) * (1.0 + 1e-12)
        z = [zi + B.error(slack) for zi in z]
        c = self._c(z[0])
        return z[0], [zi - ci for zi, ci in zip(z[1:], c)]


@dataclass(frozen=True)
class Piece:
    """A proven piece ``lo <= tau <= hi`` of a tube of radius ``radius``.

    ``tau`` is the ball of the piece, ``y`` the Krawczyk image ``K`` (the arc's ``y`` for
    every tau in the piece), ``arc`` the box ``x_a + T v + N (c(T) + K)`` holding the arc,
    ``jacobian`` ``H'`` over the tube box, ``A`` the preconditioner and ``rows`` upper bounds
    of the row sums of ``|I - A H' N|`` (each < 1).
    """

    lo: float
    hi: float
    radius: float
    tau: object
    y: list
    arc: list
    jacobian: list
    A: list = field(repr=False)
    rows: list = field(repr=False)


@dataclass(frozen=True)
class Slice:
    """The zero of one slice: in ``box`` (balls); ``radius`` bounds its ``y``."""

    box: list
    radius: float


def _krawczyk(frame, B, J, AG, A, radius):
    """``K = -A G + (I - A H'(X) N) Y`` for ``Y = [-radius, radius]^n``.

    Returns ``K`` and the upper bounds of the row sums of ``|I - A H'(X) N|``.
    """
    n = len(AG)
    C = B.matmul(A, B.matmul(J, frame.N))
    rows = [sum(_upper((1.0 if i == j else 0.0) - C[i][j]) for j in range(n))
            for i in range(n)]
    K = [-AG[i] + B.error(rows[i] * radius * (1.0 + 1e-15)) for i in range(n)]
    return K, rows


def _contains(radius: float, K, B) -> bool:
    Y = B.error(radius)
    return all(Y.contains_interior(k) for k in K)


def _preconditioner(problem, frame, tau: float):
    """``A ~ (H'(x) N)^{-1}`` at the centerline point ``tau`` (floats), or ``None``."""
    x = frame.point(tau, frame._c(tau))
    J = [[float(v) for v in row] for row in problem.jacobian(x, FLOATS)]
    return inverse([_matvec(list(zip(*frame.N)), row) for row in J])


def _residual_form(problem, frame, B, lo: float, hi: float):
    """``T`` and ``G(T)``, enclosing ``H(p(tau))`` on the centerline for every ``tau in T``.

    ``G(tau_0) + G'(tau_0) (T - tau_0) + G''(T) (T - tau_0)^2 / 2`` (Taylor with Lagrange's
    remainder) with ``G' = H'(p) p'`` at the midpoint in balls and ``G''`` over ``T`` from
    second-order jets along the centerline.
    """
    mid = 0.5 * (lo + hi)
    half = math.nextafter(max(hi - mid, mid - lo), math.inf)
    T, t0 = B.arb(mid, half), B.number(mid)
    p0 = frame.point(t0, frame._c(t0))
    H0 = problem.residual(p0, B)
    slope = _matvec(problem.jacobian(p0, B), frame.slope(t0))
    over = problem.residual(frame.centerline_jets(T), jets(B))
    offset = B.error(half)
    square = B.arb(0.5 * half * half, 0.5 * half * half) * (1.0 + 1e-15)
    G = []
    for h0, d, g2 in zip(H0, slope, over):
        dd = g2.dd if type(g2) is Jet else 0.0
        G.append(h0 + d * offset + 0.5 * dd * square)
    return T, G


def solve_piece(problem, frame, B, lo: float, hi: float, max_radius: float):
    """Krawczyk's test on the piece ``lo <= tau <= hi``: a :class:`Piece` or a :class:`Failure`."""
    A = _preconditioner(problem, frame, 0.5 * (lo + hi))
    if A is None:
        return Failure("the Jacobian is singular or not finite on the segment")
    T, G = _residual_form(problem, frame, B, lo, hi)
    AG = _matvec(A, G)
    size = max(_upper(g) for g in AG)
    if not math.isfinite(size):
        return Failure("the residual is not finite on the segment")
    n = len(AG)
    radius = 2.0 * size + 1e-300
    for _ in range(4):
        if not radius <= max_radius:
            return Failure(f"the tube would need a radius of {radius:.3g}, more than "
                           f"{max_radius:.3g} (Newton step of the residual {size:.3g})")
        X = frame.tube_box(T, [B.error(radius)] * n)
        J = problem.jacobian(X, B)
        K, rows = _krawczyk(frame, B, J, AG, A, radius)
        contraction = max(rows)
        if _contains(radius, K, B):
            return Piece(lo, hi, radius, T, K, frame.tube_box(T, K), J, A, rows)
        if not contraction < 1.0:
            return Failure(f"Krawczyk's operator does not contract (|I - A H'N| = "
                           f"{contraction:.3g})", contraction)
        radius = max(2.0 * radius, 1.5 * max(_upper(k) for k in K))
    return Failure("Krawczyk's test fails at every radius tried")


def solve_slice(problem, frame, B, piece: Piece, tau: float, tolerance: float):
    """The zero of the slice ``tau`` inside a proven piece: a :class:`Slice` or a message.

    The slice's box ``x_a + tau v + N (c(tau) + Y)`` (``Y`` of radius at most the piece's)
    lies in the piece's tube box, so the piece's ``A`` and its bounds of ``|I - A H' N|``
    serve: ``K = -A H(p(tau)) + (I - A H' N) Y``.
    """
    t = B.number(tau)
    AH = _matvec(piece.A, problem.residual(frame.point(t, frame._c(t)), B))
    size = max(_upper(h) for h in AH)
    q = max(piece.rows)
    if not math.isfinite(size):
        return "the residual is not finite there"
    radius = 2.0 * size / (1.0 - q) + 1e-300
    if not radius <= tolerance:
        return f"the nearest zero is about {size:.3g} away, more than {tolerance:.3g}"
    if not radius < piece.radius:
        return f"its zero is not inside the tube (radius {radius:.3g} >= {piece.radius:.3g})"
    K = [-AH[i] + B.error(piece.rows[i] * radius * (1.0 + 1e-15)) for i in range(len(AH))]
    if not _contains(radius, K, B):
        return "Krawczyk's test fails on its slice"
    return Slice(frame.tube_box(t, K), radius)


def square_box(F, DF, x_hat, B, tolerance: float):
    """Krawczyk's test for a square system ``F(x) = 0`` around ``x_hat``.

    ``F(x, numbers)`` and ``DF(box, numbers)`` (a list of rows) are evaluated in balls;
    ``A`` is the inverse of ``DF`` at ``x_hat`` in floats, and the box is centred at the
    Newton point ``x_hat - A F(x_hat)``. Returns ``(centre, radius)`` (floats, the box is
    ``|x - centre|_inf <= radius``) or a message.
    """
    x_hat = [float(v) for v in x_hat]
    A = inverse([[float(v) for v in row] for row in DF(x_hat, FLOATS)])
    if A is None:
        return "its Jacobian is singular or not finite"
    step = _matvec(A, [float(v) for v in F(x_hat, FLOATS)])
    centre = [x - s for x, s in zip(x_hat, step)]
    FA = _matvec(A, F([B.number(c) for c in centre], B))
    size = max(_upper(f) for f in FA)
    if not math.isfinite(size):
        return "its residual is not finite"
    radius = 2.0 * size + 1e-15 * max(1.0, max(abs(c) for c in centre))
    n = len(centre)
    for _ in range(4):
        if not radius <= tolerance:
            return f"its box would need a radius of {radius:.3g}, more than {tolerance:.3g}"
        box = [B.arb(c, radius) for c in centre]
        C = B.matmul(A, DF(box, B))
        rows = [sum(_upper((1.0 if i == j else 0.0) - C[i][j]) for j in range(n))
                for i in range(n)]
        K = [-FA[i] + B.error(rows[i] * radius * (1.0 + 1e-15)) for i in range(n)]
        if _contains(radius, K, B):
            return centre, radius
        if not max(rows) < 1.0:
            return f"Krawczyk's operator does not contract (|I - A DF| = {max(rows):.3g})"
        radius = max(2.0 * radius, 1.5 * max(_upper(k) for k in K))
    return "Krawczyk's test fails at every radius tried"
