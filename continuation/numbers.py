r"""Number types for formulas written once: floats, Arb balls, and jets (forward derivatives).

A formula written over a *numbers* namespace ``m`` is evaluated in floats for tracing and in
ball arithmetic for certification, from the same source, so the two cannot drift apart. It
may use

* ``+ - * /`` between numbers and Python floats, unary ``-`` and ``**`` with a small integer
  (prefer ``x * x``: over balls python-flint's power is a looser enclosure, and NaN for a ball
  centred at 0, so a proof there fails);
* comparisons (``a >= b``), which mean *certainly* (for a ball: for every value it holds),
  so an ``if`` on one that a ball does not decide takes its ``else`` for every value: only
  for a branch between two forms of one function, each valid wherever it may be taken (not
  a ramp ``x if x > 0 else 0``, whose branches are different functions);
* :func:`quotient` for a division whose denominator may vanish (elementwise over arrays,
  where an ``if`` on a comparison cannot branch);
* ``m.sin``, ``m.cos``, ``m.sqrt`` (NaN, or a non-finite ball, below zero), ``m.sinc``
  (``sin u / u``, 1 at 0) and the constant ``m.pi``;
* ``m.rigorous`` (whether results enclose the exact values), ``m.gauss_legendre(n, panels)``
  (nodes and weights of ``n``-point rules on ``panels`` equal parts of ``[0, 1]``, exact balls
  when rigorous) and ``m.analytic_error(bound, args)``:
  the remainder of an approximation of an analytic function of ``args`` (a ball of radius
  ``bound(args, 0)``; with jets, also its derivatives, by Cauchy's estimate from
  ``bound(args, widen)``, the bound over the complex polydisc of radius ``widen`` around the
  arguments), ``m.bounds(x)`` (floats enclosing a rigorous number's value),
  ``m.resolution(x)`` (its width, or its rounding if more) and
  ``m.local(f, a)``: ``f(a, m)`` for a function of one number, its derivatives through one
  jet (cheaper in gradients than ``f`` over them).

Four implementations: :data:`FLOATS` (``math``; the hot path), :data:`ARRAYS` (numpy float
arrays, elementwise: one formula at many points at once, with the operations of
:data:`FLOATS` on each element; only the elementary functions, no quadrature or error
bounds, and no ``if`` on a comparison, see :func:`quotient`), :func:`balls` (python-flint's
Arb midpoint-radius balls, every operation rounded outwards: the ``[certify]`` extra) and
:func:`jets` (value, first and optionally second derivative along one direction, over floats
or balls, by forward-mode differentiation; Griewank & Walther, *Evaluating Derivatives*,
SIAM 2008, ch. 13). :func:`continuation.gradients.gradients` is a fifth: the value and every
first derivative at once, in one evaluation (the vector mode of the same differentiation).
"""

from __future__ import annotations

import contextlib
import functools
import math
from typing import Any

import numpy as np

__all__ = ["ARRAYS", "FLOATS", "Jet", "balls", "jets", "quotient", "require_flint"]


def _float_sqrt(a: float) -> float:
    return math.sqrt(a) if a >= 0.0 else math.nan


def _float_sinc(u: float) -> float:
    # sin(u)/u = 1 - u^2/6 + u^4/120 - ...: the series where the quotient would cancel
    return math.sin(u) / u if abs(u) > 1e-4 else 1.0 - u * u / 6.0


def _float_sinc_derivatives(u: float, order: int = 2) -> tuple:
    """``(sinc u, sinc' u, ..., sinc^(order) u)`` in floats (at least three)."""
    if order > 2:
        return _sinc_higher(u, order, math.sin, math.cos, _sinc_series(u, order, 12))
    if abs(u) < 1e-2:
        u2 = u * u
        return 1.0 - u2 / 6.0 + u2 * u2 / 120.0, u * (-1.0 / 3.0 + u2 / 30.0), \
            -1.0 / 3.0 + u2 / 10.0
    s0 = math.sin(u) / u
    s1 = (math.cos(u) - s0) / u
    return s0, s1, -s0 - 2.0 * s1 / u


def _sinc_term(u, j: int, k: int, one=1.0):
    """The term ``(-1)^k (2k)! / ((2k - j)! (2k + 1)!) u^(2k - j)`` of ``sinc^(j)(u)``'s series
    (``one``: 1 as a ball for an enclosure of the rational coefficient; the power by products:
    python-flint's is NaN for a ball centred at 0)."""
    c = one * math.factorial(2 * k) / (math.factorial(2 * k - j) * math.factorial(2 * k + 1))
    term = (-c if k % 2 else c) + 0.0 * u
    for _ in range(2 * k - j):
        term = term * u
    return term


def _sinc_series(u, order: int, terms: int, one=1.0):
    """``sinc^(j)(u)`` for ``j <= order`` by ``terms`` terms of their series, or ``None`` where
    ``|u| >= 1/10`` (terms from ``2k >= j``: each falls by more than half there)."""
    if not abs(u) < 0.1:
        return None
    return [sum(_sinc_term(u, j, k, one) for k in range((j + 1) // 2, (j + 1) // 2 + terms))
            for j in range(order + 1)]


def _sinc_higher(u, order: int, sin, cos, series) -> tuple:
    """``sinc^(j)(u)`` for ``j <= order``: ``series`` near 0, else the recurrence
    ``sinc^(j) = (sin^(j) u - j sinc^(j-1)) / u`` (from ``u sinc u = sin u``)."""
    if series is not None:
        return tuple(series)
    s, c = sin(u), cos(u)
    cycle = (s, c, -s, -c)
    values = [s / u]
    for j in range(1, order + 1):
        values.append((cycle[j % 4] - j * values[-1]) / u)
    return tuple(values)


@functools.lru_cache(maxsize=8)
def _float_gauss(n: int, panels: int = 1) -> tuple:
    nodes, weights = np.polynomial.legendre.leggauss(n)
    return tuple(((p + 0.5 * (1.0 + float(t))) / panels, 0.5 * float(w) / panels)
                 for p in range(panels) for t, w in zip(nodes, weights, strict=True))


class _Floats:
    """Python floats with ``math``: fast, not rigorous."""

    name = "floats"
    rigorous = False
    sin = staticmethod(math.sin)
    cos = staticmethod(math.cos)
    sqrt = staticmethod(_float_sqrt)
    sinc = staticmethod(_float_sinc)
    sinc_derivatives = staticmethod(_float_sinc_derivatives)
    pi = math.pi

    @staticmethod
    def number(x) -> float:
        return float(x)

    @staticmethod
    def value(x):
        return x

    @staticmethod
    def gauss_legendre(n: int, panels: int = 1) -> tuple:
        return _float_gauss(n, panels)

    @staticmethod
    def analytic_error(bound, args) -> float:
        return 0.0

    @staticmethod
    def local(f, a):
        """``f(a, numbers)`` for a function ``f`` of one number (see :meth:`_Derivatives.local`)."""
        return f(a, FLOATS)

    @staticmethod
    def is_finite(x) -> bool:
        return math.isfinite(x)


#: the float namespace (``math``), used on the tracer's hot path
FLOATS = _Floats()


def _array_sqrt(a: np.ndarray) -> np.ndarray:
    with np.errstate(invalid="ignore"):
        return np.sqrt(a)  # NaN below zero, as _float_sqrt


def _array_sinc(u: np.ndarray) -> np.ndarray:
    u = np.asarray(u, dtype=float)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(np.abs(u) > 1e-4, np.sin(u) / u, 1.0 - u * u / 6.0)


class _Arrays:
    """numpy float arrays, elementwise: many points of one formula at once, not rigorous.

    Arithmetic is the IEEE arithmetic of Python floats, and ``np.sin`` and ``np.cos`` agree
    with ``math``'s on the platforms tested (the tests check it: some numpy builds differ by
    an ulp), so a formula gives the numbers of :data:`FLOATS` at each point. Comparisons are
    elementwise, so a branch must use :func:`quotient` (or another elementwise choice), not
    ``if``; a formula with such a branch (a quadrature switch, say) is evaluated point by
    point instead. Only ``sin``, ``cos``, ``sqrt``, ``sinc`` and ``pi``: no quadrature
    (``gauss_legendre``), error bounds or conversions (``number``, ``value``): the caller
    passes the formula its arguments as arrays (one per coordinate, all points at once).
    """

    name = "arrays"
    rigorous = False
    sin = staticmethod(np.sin)
    cos = staticmethod(np.cos)
    sqrt = staticmethod(_array_sqrt)
    sinc = staticmethod(_array_sinc)
    pi = math.pi


#: the array namespace (numpy, elementwise), for checks over a whole curve at once
ARRAYS = _Arrays()


def quotient(numerator, denominator, at_zero):
    """``numerator / denominator``, or ``at_zero`` where ``denominator`` is zero, in any of
    the namespaces: elementwise for arrays; for a ball, ``at_zero`` unless it is certainly
    nonzero; a jet is never zero (its derivatives are what it carries)."""
    if type(denominator) is np.ndarray:
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(denominator != 0.0, numerator / denominator, at_zero)
    return numerator / denominator if denominator != 0.0 else at_zero


def require_flint():
    """python-flint's ``arb`` type; ``ImportError`` naming the extra to install if missing."""
    try:
        import flint  # optional: only certification needs it
    except ImportError:
        raise ImportError("certification needs python-flint (Arb ball arithmetic): "
                          "pip install 'groove-continuation[certify]' (or pip install "
                          "python-flint)") from None
    return flint


class _Balls:
    """Arb midpoint-radius balls (python-flint ``arb``), rounded outwards: rigorous."""

    name = "arb"
    rigorous = True

    def __init__(self, flint) -> None:
        self.arb = flint.arb
        self._arb_mat = flint.arb_mat
        self._ctx = flint.ctx
        self._pi: dict = {}
        self._gauss: dict = {}

    @property
    def pi(self):
        """pi as a ball at the current precision."""
        prec = self._ctx.prec
        if prec not in self._pi:
            self._pi[prec] = self.arb.pi()
        return self._pi[prec]

    @contextlib.contextmanager
    def precision(self, bits: int):
        """Evaluate at ``bits`` of precision inside the ``with`` block (python-flint's context)."""
        ctx = self._ctx
        saved = ctx.prec
        ctx.prec = max(bits, saved)
        try:
            yield self
        finally:
            ctx.prec = saved

    def matmul(self, X, Y) -> list:
        """The product of two matrices (nested lists of floats or balls), as nested lists."""
        return (self._arb_mat(X) * self._arb_mat(Y)).tolist()

    def number(self, x):
        return x if type(x) is self.arb else self.arb(x)

    @staticmethod
    def value(x):
        return x

    def sin(self, a):
        return self.number(a).sin()

    def cos(self, a):
        return self.number(a).cos()

    def sqrt(self, a):
        return self.number(a).sqrt()  # NaN ball where any value is negative

    def sinc(self, a):
        return self.number(a).sinc()

    def sinc_derivatives(self, u, order: int = 2):
        """``(sinc u, sinc' u, sinc'' u)``, by their alternating series near 0 (and the
        derivatives up to ``order`` if it is higher: below).

        ``sinc^(j)(u) = sum_k (-1)^k (2k)!/(2k-j)! u^(2k-j)/(2k+1)!``; for ``|u| < 1/10`` the
        terms fall by more than half each, so the tail is within twice the first omitted term
        (beyond, the quotients lose at most a factor 10 to cancellation).
        """
        u = self.number(u)
        if order > 2:
            return self._sinc_higher(u, order)
        s0 = u.sinc()
        if abs(u) < 0.1:
            u2 = u * u
            tail1 = 2.0 * abs(u) * u2 * u2 * u2 / 45360.0
            tail2 = 2.0 * u2 * u2 * u2 / 6480.0
            one = self.arb(1)  # the coefficients as balls: 1/3 is no float
            s1 = u * (-one / 3 + u2 * (one / 30 - u2 / 840)) + self.arb(0, tail1.upper())
            s2 = -one / 3 + u2 * (one / 10 - u2 / 168) + self.arb(0, tail2.upper())
            return s0, s1, s2
        s1 = (u.cos() - s0) / u
        return s0, s1, -s0 - 2.0 * s1 / u

    def _sinc_higher(self, u, order: int) -> tuple:
        """``sinc^(j)(u)`` for ``j <= order``: for ``|u| < 1/10`` six terms of each series, the
        tail within twice the first omitted term (the terms fall by more than half each);
        beyond, the recurrence of :func:`_sinc_higher` (at most a factor 10 lost to
        cancellation per order)."""
        one = self.arb(1)
        series = _sinc_series(u, order, 6, one)
        if series is not None:
            r = self.arb(abs(u).upper())
            series = [v + self.arb(0, (2.0 * abs(_sinc_term(r, j, (j + 1) // 2 + 6, one))).upper())
                      for j, v in enumerate(series)]
        return _sinc_higher(u, order, self.sin, self.cos, series)

    def gauss_legendre(self, n: int, panels: int = 1) -> tuple:
        key = (n, panels, self._ctx.prec)
        if key not in self._gauss:
            roots = [self.arb.legendre_p_root(n, i, weight=True) for i in range(n)]
            self._gauss[key] = tuple(((p + 0.5 * (1.0 + t)) / panels, 0.5 * w / panels)
                                     for p in range(panels) for t, w in roots)
        return self._gauss[key]

    def bounds(self, x) -> tuple[float, float]:
        """``(lo, hi)``: floats with ``lo <= x <= hi`` for every value of the ball ``x``."""
        x = self.number(x)
        return (math.nextafter(float(x.lower()), -math.inf),
                math.nextafter(float(x.upper()), math.inf))

    def resolution(self, x) -> float:
        """The ball's width, or one unit in the last place of its midpoint at the current
        precision if that is more: what an error below it cannot widen much."""
        x = self.number(x)
        ulp = abs(float(x.mid())) * 2.0 ** (1 - self._ctx.prec)
        return max(2.0 * float(x.rad()), ulp, 1e-300)

    def error(self, bound: float):
        """The ball ``[-bound, bound]`` (NaN if ``bound`` is not finite)."""
        return self.arb(0, bound) if math.isfinite(bound) else self.arb.nan()

    def analytic_error(self, bound, args):
        return self.error(bound(tuple(self.bounds(a) for a in args), 0.0))

    def local(self, f, a):
        return f(a, self)

    def is_finite(self, x) -> bool:
        return x.is_finite()


@functools.lru_cache(maxsize=1)
def balls() -> _Balls:
    """The Arb ball namespace (python-flint); ``ImportError`` naming the extra if missing."""
    return _Balls(require_flint())


class _ComparedByValue:
    """Comparisons of numbers with derivatives (``v`` their value): of the values, for
    branches in formulas; and their small integer powers, as products."""

    __slots__ = ()
    v: object

    def __pow__(self, n: int):
        x: Any = self  # (a jet or a gradient: their own products)
        if n == 2:
            return x * x
        if n == 3:
            return x * x * x
        raise ValueError(f"{type(self).__name__} ** {n!r}: only the exponents 2 and 3 are "
                         "supported")

    def __lt__(self, other):
        return self.v < (other.v if type(other) is type(self) else other)

    def __le__(self, other):
        return self.v <= (other.v if type(other) is type(self) else other)

    def __gt__(self, other):
        return self.v > (other.v if type(other) is type(self) else other)

    def __ge__(self, other):
        return self.v >= (other.v if type(other) is type(self) else other)


class Jet(_ComparedByValue):
    """A number with its first (``d``) and optional second (``dd``) derivative in one direction.

    ``v``, ``d`` and ``dd`` are base numbers (floats or balls); ``dd`` is ``None`` for
    first-order jets. Comparisons act on the value (for branches only); ``abs`` is a jet.
    """

    __slots__ = ("v", "d", "dd")

    def __init__(self, v, d, dd=None) -> None:
        self.v, self.d, self.dd = v, d, dd

    def __add__(self, other):
        if type(other) is Jet:
            dd = None if self.dd is None else self.dd + other.dd
            return Jet(self.v + other.v, self.d + other.d, dd)
        if isinstance(other, _ComparedByValue):
            return NotImplemented  # a gradient over jets: a jet is one of its base numbers
        return Jet(self.v + other, self.d, self.dd)

    __radd__ = __add__

    def __sub__(self, other):
        if type(other) is Jet:
            dd = None if self.dd is None else self.dd - other.dd
            return Jet(self.v - other.v, self.d - other.d, dd)
        if isinstance(other, _ComparedByValue):
            return NotImplemented
        return Jet(self.v - other, self.d, self.dd)

    def __rsub__(self, other):
        return Jet(other - self.v, -self.d, None if self.dd is None else -self.dd)

    def __neg__(self):
        return Jet(-self.v, -self.d, None if self.dd is None else -self.dd)

    def __mul__(self, other):
        if type(other) is Jet:
            dd = None if self.dd is None else (self.dd * other.v + 2.0 * self.d * other.d
                                               + self.v * other.dd)
            return Jet(self.v * other.v, self.d * other.v + self.v * other.d, dd)
        if isinstance(other, _ComparedByValue):
            return NotImplemented
        return Jet(self.v * other, self.d * other, None if self.dd is None else self.dd * other)

    __rmul__ = __mul__

    def __truediv__(self, other):
        if type(other) is Jet:
            return self * other._reciprocal()
        if isinstance(other, _ComparedByValue):
            return NotImplemented
        return Jet(self.v / other, self.d / other, None if self.dd is None else self.dd / other)

    def __rtruediv__(self, other):
        return self._reciprocal() * other

    def _reciprocal(self):
        r = 1.0 / self.v
        d = -self.d * r * r
        dd = None if self.dd is None else (2.0 * self.d * self.d * r - self.dd) * r * r
        return Jet(r, d, dd)

    def __abs__(self):
        """``|x|`` as a jet: ``x`` or ``-x`` where the value has one sign (for balls: every
        value); where it may be 0, ``|x|`` has no derivative and they are NaN (a proof fails)."""
        if self.v > 0.0:
            return self
        if self.v < 0.0:
            return -self
        return Jet(abs(self.v), self.d * math.nan,
                   None if self.dd is None else self.dd * math.nan)

    def __repr__(self) -> str:
        return f"Jet({self.v!r}, {self.d!r}, {self.dd!r})"


#: the radii of the complex polydiscs tried for Cauchy's estimates of a remainder's derivatives
_WIDENINGS = (1e-3, 1e-2, 3e-2, 0.1)


def _largest(values) -> float:
    """The largest of the floats (0 if none), NaN if one is (``max`` would drop it)."""
    return math.nan if any(math.isnan(v) for v in values) else max(values, default=0.0)


def _chain(a, f0, f1, f2):
    """``f(a)`` for a jet ``a`` from ``f``, ``f'`` and ``f''`` at its value (``f2`` may be None)."""
    if type(a) is not Jet:
        return f0
    dd = None if a.dd is None else f1 * a.dd + f2 * a.d * a.d
    return Jet(f0, f1 * a.d, dd)


class _Derivatives:
    """What the namespaces of numbers with derivatives share (jets here, and
    :mod:`continuation.gradients`): the base namespace, its constants and quadrature, and
    the value of a number of ``kind`` (its ``v``)."""

    kind: type
    label: str

    def __init__(self, base) -> None:
        self.base = base
        self.name = f"{self.label} over {base.name}"
        self.rigorous = base.rigorous

    @property
    def pi(self):
        return self.base.pi

    def value(self, x):
        return x.v if type(x) is self.kind else x

    def number(self, x):
        return x if type(x) is self.kind else self.base.number(x)

    def gauss_legendre(self, n: int, panels: int = 1) -> tuple:
        return self.base.gauss_legendre(n, panels)

    def bounds(self, x) -> tuple[float, float]:
        """``(lo, hi)`` of the value (rigorous bases only)."""
        return self.base.bounds(self.value(x))

    def resolution(self, x) -> float:
        """The base's resolution of the value (rigorous bases only)."""
        return self.base.resolution(self.value(x))

    def is_finite(self, x) -> bool:
        if type(x) is not self.kind:
            return self.base.is_finite(x)
        return all(self.base.is_finite(p) for p in self.parts(x))

    @staticmethod
    def parts(x) -> tuple:
        """The value and derivatives of a number of ``kind``."""
        raise NotImplementedError

    def local(self, f, a):
        """``f(a, numbers)`` for a function ``f(u, m)`` of one number written over a numbers
        namespace: the same value, and derivatives by the chain rule through ``f``'s own
        derivative where that is cheaper (gradients: one direction inside ``f`` instead of
        every coordinate; Griewank & Walther's preaccumulation). Jets: ``f`` itself."""
        return f(a, self)


class _Jets(_Derivatives):
    """Jets over a base namespace: derivatives of a formula along one direction."""

    kind = Jet
    label = "jets"

    @staticmethod
    def parts(x) -> tuple:
        return (x.v, x.d) if x.dd is None else (x.v, x.d, x.dd)

    def sin(self, a):
        b = self.base
        v = self.value(a)
        s, c = b.sin(v), b.cos(v)
        return _chain(a, s, c, -s)

    def cos(self, a):
        b = self.base
        v = self.value(a)
        s, c = b.sin(v), b.cos(v)
        return _chain(a, c, -s, -c)

    def sqrt(self, a):
        r = self.base.sqrt(self.value(a))
        d1 = 0.5 / r
        return _chain(a, r, d1, -0.5 * d1 / (r * r))

    def sinc(self, a):
        return _chain(a, *self.base.sinc_derivatives(self.value(a)))

    def sinc_derivatives(self, u, order: int = 2) -> tuple:
        """``sinc^(j)(u)`` for ``j <= order`` as jets (for gradients over jets)."""
        if type(u) is not Jet:
            return self.base.sinc_derivatives(u, order)
        f = self.base.sinc_derivatives(u.v, order + 2)
        return tuple(_chain(u, f[j], f[j + 1], f[j + 2]) for j in range(order + 1))

    def analytic_error(self, bound, args):
        """The remainder ``E(args)`` and its derivatives along the jets' direction.

        ``bound(args, w)`` bounds ``|E|`` over the complex polydisc of radius ``w`` around
        the arguments. Along ``args + lam * dargs`` (``|lam| <= rho``) Cauchy's estimate gives
        ``|E'| <= B / rho`` and ``|E''| <= 2 B / rho^2`` with ``B = bound(args, rho |dargs|)``.
        Along a curved path (arguments with second derivatives ``ddargs``) the second
        derivative is ``D^2 E [dargs, dargs] + D E [ddargs]``, the latter bounded the same way
        along ``ddargs``: ``B |ddargs| / w``. The best of a few ``w`` is taken.
        """
        base = self.base
        values = tuple(self.value(a) for a in args)
        error0 = base.analytic_error(bound, values)
        if not base.rigorous or not any(type(a) is Jet for a in args):
            return error0  # (arguments fixed along the direction: a number, of any order)
        intervals = tuple(base.bounds(v) for v in values)
        speed = _largest([base.bounds(abs(a.d))[1] for a in args if type(a) is Jet])
        second_order = any(type(a) is Jet and a.dd is not None for a in args)
        curving = _largest([base.bounds(abs(a.dd))[1] for a in args
                            if type(a) is Jet and a.dd is not None])
        best1 = 0.0 if speed == 0.0 else math.inf
        best2 = 0.0 if speed == 0.0 and curving == 0.0 else math.inf
        for widen in _WIDENINGS if not math.isfinite(best2) else ():
            # the polydisc of radius widen holds the discs |lam| <= widen / speed along dargs
            # and |mu| <= widen / curving along ddargs
            sup = bound(intervals, widen) * (1.0 + 1e-12)
            best1 = min(best1, sup * speed / widen * (1.0 + 1e-12))
            best2 = min(best2, (2.0 * sup * speed * speed / (widen * widen)
                                + sup * curving / widen) * (1.0 + 1e-12))
        return Jet(error0, base.error(best1), base.error(best2) if second_order else None)


@functools.lru_cache(maxsize=4)
def jets(base=FLOATS) -> _Jets:
    """The jet namespace over ``base`` (:data:`FLOATS` or :func:`balls`)."""
    return _Jets(base)

