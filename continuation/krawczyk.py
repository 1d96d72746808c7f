r"""Krawczyk's test in ball arithmetic: tubes around curve segments, slices, square systems.

A segment between two curve points ``x_a`` and ``x_b`` (chord ``L v``, ``|v| = 1``) is given
the coordinates ``x = x_a + tau v + N (c(tau) + y)``, where ``N`` picks the coordinates other
than the one the chord moves most in (:class:`Frame`: the curve as a graph over that
coordinate, ``y`` offsets along the axes) and ``c`` is the cubic Hermite interpolant of the
two points and their tangents (error ``O(L^4)``). For the zeros of ``H`` in a piece
``tau in T`` of the tube ``|y_k| <= r_k`` the parametrised Krawczyk operator (Krawczyk 1969;
Neumaier, *Interval Methods for Systems of Equations*, 1990, sec. 5.1; for curves van den Berg,
Lessard & Mischaikow, Math. Comp. 79 (2010) 1565-1584) is

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

from .gradients import Gradient, gradients
from .numbers import FLOATS, Jet, jets

__all__ = ["Failure", "Frame", "Piece", "Slice", "derivative", "determinant", "kernel",
           "inverse", "solve_piece", "solve_slice", "square_box"]


#: segments shorter than this (relative to 1 + |x|) are framed along their tangents
_SHORT = 1e-6


def _matvec(M, v):
    """``M v`` for a float matrix (nested lists) and a vector of numbers."""
    return [sum(m_ij * v_j for m_ij, v_j in zip(row, v, strict=True)) for row in M]


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
                a[r] = [v - f * w for v, w in zip(a[r], a[col], strict=True)]
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
    """The coordinates of one segment's tube: a graph over one coordinate.

    With ``p`` the coordinate in which the curve moves most steadily (the largest of the
    chord's and both tangents' components, all of one sign), a point is
    ``x = x_a + tau v + sum_k (c_k(tau) + y_k) e_{axes[k]}`` (``axes`` the other coordinates):
    the slice ``tau`` is the hyperplane ``x_p = x_a,p + tau v_p`` and ``y`` are offsets along
    the coordinate axes, so a tube may be thinner in one coordinate than in another (a
    coordinate near zero, like ``w`` where a boundary approaches ``beta_L = 0``) and
    coordinates are exact to compute. ``c(tau) = sum_q a_q tau^q`` (``q <= 3``,
    ``coefficients[q] = a_q``) is the cubic Hermite interpolant of the two points and
    tangents (the curve as a graph over ``x_p``, error ``O(L^4)``).
    """

    x_a: list
    v: list
    p: int
    axes: tuple
    length: float
    coefficients: list

    @classmethod
    def build(cls, x_a, t_a, x_b, t_b) -> Frame | str:
        """The frame of the segment; a message if a tangent does not point along the chord."""
        x_a, x_b = [float(v) for v in x_a], [float(v) for v in x_b]
        t_a, t_b = [float(v) for v in t_a], [float(v) for v in t_b]
        d = [b - a for a, b in zip(x_a, x_b, strict=True)]
        length = math.sqrt(sum(di * di for di in d))
        if not (length > 0.0 and math.isfinite(length)):
            return f"its points coincide or are not finite (chord length {length!r})"
        if length <= _SHORT * (1.0 + max(abs(xj) for xj in x_a)):
            return cls._short(x_a, t_a, t_b, d)
        v = [di / length for di in d]
        # the coordinate the curve moves in most steadily: same sign at both ends as the chord
        steady = [j for j in range(len(v)) if v[j] * t_a[j] > 0.0 and v[j] * t_b[j] > 0.0]
        p = max(steady or range(len(v)), key=lambda j: min(abs(t_a[j]), abs(t_b[j]), abs(v[j])))
        along_a, along_b = t_a[p] / v[p], t_b[p] / v[p]
        if not (along_a > 0.0 and along_b > 0.0):
            return (f"a tangent turns against the chord in x[{p}] (ratios {along_a:.3g}, "
                    f"{along_b:.3g}): the curve is not a graph over it")
        axes = tuple(j for j in range(len(v)) if j != p)
        c_b = [d[j] - length * v[j] for j in axes]  # rounding: the chord's end is (L, 0)
        m_a = [t_a[j] / along_a - v[j] for j in axes]
        m_b = [t_b[j] / along_b - v[j] for j in axes]
        # cubic Hermite through (0, 0, m_a) and (L, c_b, m_b), in powers of tau
        a2 = [(3.0 * cb / length - 2.0 * ma - mb) / length
              for cb, ma, mb in zip(c_b, m_a, m_b, strict=True)]
        a3 = [(ma + mb - 2.0 * cb / length) / length ** 2
              for cb, ma, mb in zip(c_b, m_a, m_b, strict=True)]
        return cls(x_a, v, p, axes, length, [[0.0] * len(axes), m_a, a2, a3])

    @classmethod
    def _short(cls, x_a, t_a, t_b, d) -> Frame | str:
        """The frame of a segment too short for its chord's direction to be known (its points
        are only known to rounding): along the mean tangent, the centerline a straight line
        to the second point (the curve is off it by ``kappa L^2``)."""
        t = [a + b for a, b in zip(t_a, t_b, strict=True)]
        size = math.sqrt(sum(tj * tj for tj in t))
        if not (size > 0.0 and math.isfinite(size)):
            return "its tangents cancel or are not finite (a segment too short for its chord)"
        v = [tj / size for tj in t]
        p = max(range(len(v)), key=lambda j: abs(v[j]))
        length = d[p] / v[p]
        if not length > 0.0:
            return "its points are in the wrong order along the tangent"
        axes = tuple(j for j in range(len(v)) if j != p)
        zero = [0.0] * len(axes)
        slope = [(d[j] - length * v[j]) / length for j in axes]
        return cls(x_a, v, p, axes, length, [zero, slope, zero, zero])

    def _c(self, tau, order: int = 0):
        """``c``, ``c'`` or ``c''`` at ``tau`` (a number), by Horner's rule."""
        a0, a1, a2, a3 = self.coefficients
        if order == 0:
            return [((a3[i] * tau + a2[i]) * tau + a1[i]) * tau + a0[i] for i in range(len(a0))]
        if order == 1:
            return [(3.0 * a3[i] * tau + 2.0 * a2[i]) * tau + a1[i] for i in range(len(a0))]
        return [6.0 * a3[i] * tau + 2.0 * a2[i] for i in range(len(a0))]

    def point(self, tau, w) -> list:
        """``x_a + tau v + sum_k w_k e_{axes[k]}`` for a number ``tau`` and offsets ``w``."""
        x = [self.x_a[j] + tau * self.v[j] for j in range(len(self.v))]
        for k, j in enumerate(self.axes):
            x[j] = x[j] + w[k]
        return x

    def tube_box(self, tau, y) -> list:
        """``x_a + tau v + (c(tau) + y)`` along the axes, for a number ``tau`` and offsets ``y``."""
        return self.point(tau, [ci + yi for ci, yi in zip(self._c(tau), y, strict=True)])

    def columns(self, J) -> list:
        """``H' N``: the columns of ``J`` of the axes (the derivative along the offsets)."""
        return [[row[j] for j in self.axes] for row in J]

    def centerline_jets(self, tau) -> list:
        """The centerline ``x_a + tau v + c(tau)`` as jets: value, first and second derivative."""
        p = self.point(tau, self._c(tau))
        p1 = self.point(0.0, self._c(tau, 1))
        p1 = [p1j - x0 + vj for p1j, x0, vj in zip(p1, self.x_a, self.v, strict=True)]
        c2 = self._c(tau, 2)
        p2 = [0.0] * len(p)
        for k, j in enumerate(self.axes):
            p2[j] = c2[k]
        return [Jet(p[j], p1[j], p2[j]) for j in range(len(p))]

    def slope(self, tau) -> list:
        """The centerline's derivative ``v + c'(tau)`` along the axes."""
        out = list(self.v)
        for k, j in enumerate(self.axes):
            out[j] = out[j] + self._c(tau, 1)[k]
        return out

    def speed(self, k):
        """``d tau / d lambda`` along a kernel vector ``k`` (``dx/d lambda = k``): ``k_p / v_p``."""
        return k[self.p] / self.v[self.p]

    def coordinates(self, box, B):
        """``(tau, y)`` of a ball vector ``box`` (exact: ``tau`` from ``x_p``)."""
        tau = (B.number(box[self.p]) - self.x_a[self.p]) / self.v[self.p]
        c = self._c(tau)
        return tau, [box[j] - self.x_a[j] - tau * self.v[j] - ck
                     for ck, j in zip(c, self.axes, strict=True)]


@dataclass(frozen=True)
class Piece:
    """A proven piece ``lo <= tau <= hi`` of a tube whose offsets are within ``radii``.

    ``tau`` is the ball of the piece, ``y`` the Krawczyk image ``K`` (the arc's offsets for
    every tau in the piece), ``arc`` the box ``x_a + T v + c(T) + K`` holding the arc,
    ``jacobian`` ``H'`` over the tube box, ``A`` the preconditioner and ``bounds`` upper bounds
    of ``|I - A H' N|`` entry by entry (its weighted row sums below 1).
    """

    lo: float
    hi: float
    radii: list
    tau: object
    y: list
    arc: list
    jacobian: list
    A: list = field(repr=False)
    bounds: list = field(repr=False)

    @property
    def radius(self) -> float:
        """The largest offset radius (max-norm, in the curve's coordinates)."""
        return max(self.radii)


@dataclass(frozen=True)
class Slice:
    """The zero of one slice: in ``box`` (balls); ``radius`` bounds its offsets."""

    box: list
    radius: float


def _contraction(frame, B, J, A) -> list:
    """Upper bounds of ``|I - A H'(X) N|``, entry by entry (floats)."""
    C = B.matmul(A, frame.columns(J))
    n = len(C)
    return [[_upper((1.0 if i == j else 0.0) - C[i][j]) for j in range(n)] for i in range(n)]


def _image(AG, bounds, radii, B) -> list:
    """``K = -A G + (I - A H' N) Y`` with ``|Y_j| <= radii[j]``, from the entry bounds."""
    return [-AG[i] + B.error(sum(b * r for b, r in zip(bounds[i], radii, strict=True))
                             * (1.0 + 1e-12))
            for i in range(len(AG))]


def _inside(K, radii, B) -> bool:
    return all(B.error(r).contains_interior(k) for k, r in zip(K, radii, strict=True))


def _needed(steps, bounds, floor: float) -> list | None:
    """Radii ``r`` with ``steps + bounds r < r`` (the Krawczyk condition from the entry bounds):
    ``r = (I - bounds)^{-1} (steps + floor)`` with a margin; ``None`` if there are none."""
    n = len(steps)
    M = [[(1.0 if i == j else 0.0) - bounds[i][j] for j in range(n)] for i in range(n)]
    Minv = inverse(M)
    if Minv is None:
        return None
    rhs = [1.001 * s + floor for s in steps]
    radii = [1.01 * sum(m * r for m, r in zip(row, rhs, strict=True)) for row in Minv]
    return radii if all(r > 0.0 and math.isfinite(r) for r in radii) else None


def derivative(problem, x, B) -> list:
    """``H'`` over the ball vector ``x``: rows of ``n + 1`` balls, the residual's derivatives
    by forward differentiation in balls, every column in one evaluation
    (:mod:`continuation.gradients`).

    Not ``problem.jacobian``: the proof rests on the residual alone. A Jacobian that is right
    in floats at the curve's points can be wrong over a box (a ``math.cos`` of a ball is the
    cosine of its midpoint; a formula simplified with ``H = 0`` is right on the curve only),
    and Krawczyk's operator with it can prove a unique arc where several lie.
    """
    zero, one = B.number(0.0), B.number(1.0)
    n1 = len(x)
    units = [tuple(one if c == j else zero for c in range(n1)) for j in range(n1)]
    row = problem.residual([Gradient(v, units[j]) for j, v in enumerate(x)], gradients(B))
    return [list(r.d) if type(r) is Gradient else [zero] * n1 for r in row]


def _preconditioner(problem, frame, tau: float):
    """``A ~ (H'(x) N)^{-1}`` at the centerline point ``tau`` (floats), or ``None``."""
    x = frame.point(tau, frame._c(tau))
    J = [[float(v) for v in row] for row in problem.jacobian(x, FLOATS)]
    return inverse(frame.columns(J))


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
    slope = _matvec(derivative(problem, p0, B), frame.slope(t0))
    over = problem.residual(frame.centerline_jets(T), jets(B))
    offset = B.error(half)
    square = B.arb(0.5 * half * half, 0.5 * half * half) * (1.0 + 1e-12)
    G = []
    for h0, d, g2 in zip(H0, slope, over, strict=True):
        dd = g2.dd if type(g2) is Jet else 0.0
        G.append(h0 + d * offset + 0.5 * dd * square)
    return T, G


def solve_piece(problem, frame, B, lo: float, hi: float, max_radius: float,
                min_radius: float = 0.0):
    """Krawczyk's test on the piece ``lo <= tau <= hi``: a :class:`Piece` or a :class:`Failure`.

    Each offset's radius starts at twice its Newton step, at least ``min_radius`` (so that
    the small boxes of points and special points fit in the tube), and grows while the test
    fails and the operator contracts.
    """
    A = _preconditioner(problem, frame, 0.5 * (lo + hi))
    if A is None:
        return Failure("the Jacobian is singular or not finite on the segment")
    T, G = _residual_form(problem, frame, B, lo, hi)
    AG = _matvec(A, G)
    steps = [_upper(g) for g in AG]
    if not all(math.isfinite(v) for v in steps):
        return Failure("the residual is not finite on the segment")
    floor = max(min_radius, 1e-3 * max(steps), 1e-300)
    radii = [max(2.0 * v, floor) for v in steps]
    for _ in range(5):
        if not max(radii) <= max_radius:
            return Failure(f"the tube would need a radius of {max(radii):.3g}, more than "
                           f"{max_radius:.3g} (Newton step of the residual {max(steps):.3g})")
        X = frame.tube_box(T, [B.error(r) for r in radii])
        J = derivative(problem, X, B)
        bounds = _contraction(frame, B, J, A)
        K = _image(AG, bounds, radii, B)
        if _inside(K, radii, B):
            return Piece(lo, hi, radii, T, K, frame.tube_box(T, K), J, A, bounds)
        contraction = max(sum(row) for row in bounds)
        need = _needed(steps, bounds, floor) if contraction < 1.0 else None
        if need is None:
            return Failure(f"Krawczyk's operator does not contract (|I - A H'N| = "
                           f"{contraction:.3g})", contraction)
        if all(n_ <= r for n_, r in zip(need, radii, strict=True)):
            # a thinner tube inside this one: the bounds of H' over this one still hold
            K = _image(AG, bounds, need, B)
            if _inside(K, need, B):
                return Piece(lo, hi, need, T, K, frame.tube_box(T, K), J, A, bounds)
        radii = [max(r, 1.2 * n_) for r, n_ in zip(radii, need, strict=True)]
    return Failure("Krawczyk's test fails at every radius tried")


def solve_slice(problem, frame, B, piece: Piece, tau: float, tolerance: float):
    """The zero of the slice ``tau`` inside a proven piece: a :class:`Slice` or a message.

    The slice's box ``x_a + tau v + c(tau) + Y`` (``Y`` within the piece's radii) lies in the
    piece's tube box, so the piece's ``A`` and its bounds of ``|I - A H' N|`` serve:
    ``K = -A H(p(tau)) + (I - A H' N) Y``.
    """
    t = B.number(tau)
    AH = _matvec(piece.A, problem.residual(frame.point(t, frame._c(t)), B))
    steps = [_upper(h) for h in AH]
    if not all(math.isfinite(v) for v in steps):
        return "the residual is not finite there"
    radii = _needed(steps, piece.bounds, 1e-3 * max(steps) + 1e-300)
    if radii is None:
        return "Krawczyk's operator does not contract on its slice"
    if not max(radii) <= tolerance:
        return f"the nearest zero is about {max(steps):.3g} away, more than {tolerance:.3g}"
    if not all(r < R for r, R in zip(radii, piece.radii, strict=True)):
        return "its zero is not inside the tube"
    K = _image(AH, piece.bounds, radii, B)
    if not _inside(K, radii, B):
        return "Krawczyk's test fails on its slice"
    return Slice(frame.tube_box(t, K), max(radii))


def _square_test(F, DF, A, centre, B, tolerance: float, floor: float):
    """Krawczyk's test for ``F = 0`` in boxes around ``centre`` (balls): a radius or a message."""
    n = len(centre)
    FA = _matvec(A, F(centre, B))
    size = max(_upper(f) for f in FA)
    if not math.isfinite(size):
        return "its residual is not finite"
    radius = 2.0 * size + floor
    for _ in range(4):
        if not radius <= tolerance:
            return f"its box would need a radius of {radius:.3g}, more than {tolerance:.3g}"
        box = [c + B.error(radius) for c in centre]
        C = B.matmul(A, DF(box, B))
        rows = [sum(_upper((1.0 if i == j else 0.0) - C[i][j]) for j in range(n))
                for i in range(n)]
        K = [-FA[i] + B.error(rows[i] * radius * (1.0 + 1e-12)) for i in range(n)]
        if _inside(K, [radius] * n, B):
            return radius
        if not max(rows) < 1.0:
            return f"Krawczyk's operator does not contract (|I - A DF| = {max(rows):.3g})"
        radius = max(2.0 * radius, 1.5 * max(_upper(k) for k in K))
    return "Krawczyk's test fails at every radius tried"


def square_box(F, DF, x_hat, B, tolerance: float):
    """Krawczyk's test for a square system ``F(x) = 0`` around ``x_hat``.

    ``F(x, numbers)`` and ``DF(box, numbers)`` (a list of rows) are evaluated in balls;
    ``A`` is the inverse of ``DF`` at ``x_hat`` in floats, and the box is centred at the
    Newton point ``x_hat - A F(x_hat)``. Where the system is so ill-conditioned that the
    residual's rounding at that point needs a box too wide for ``DF`` to be nearly constant
    on it (a crossing that is nearly tangent), the test is repeated with the centre refined by
    Newton's method and every ball evaluated at 128 bits. Returns ``(centre, radius)`` (the box
    is ``|x - centre|_inf <= radius``, floats, the radius covering the centre's rounding) or
    a message.
    """
    x_hat = [float(v) for v in x_hat]
    A = inverse([[float(v) for v in row] for row in DF(x_hat, FLOATS)])
    if A is None:
        return "its Jacobian is singular or not finite"
    step = _matvec(A, [float(v) for v in F(x_hat, FLOATS)])
    centre = [x - s for x, s in zip(x_hat, step, strict=True)]
    scale = max(1.0, max(abs(c) for c in centre))
    found = _square_test(F, DF, A, [B.number(c) for c in centre], B, tolerance, 1e-15 * scale)
    if not isinstance(found, str):
        return centre, found
    with B.precision(128):
        balls_ = [B.number(c) for c in centre]
        for _ in range(4):  # Newton's method (chord steps) at 128 bits
            step = _matvec(A, F(balls_, B))
            balls_ = [B.number(c - d).mid() for c, d in zip(balls_, step, strict=True)]
        radius = _square_test(F, DF, A, balls_, B, tolerance, 1e-30 * scale)
        if isinstance(radius, str):
            return found
        rounded = [float(c) for c in balls_]
        slack = max(_upper(c - r) for c, r in zip(balls_, rounded, strict=True))
    return rounded, radius + slack
