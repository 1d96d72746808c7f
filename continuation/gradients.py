"""Gradients: a formula's value and its derivatives along every coordinate, in one evaluation.

The vector mode of forward differentiation (Griewank & Walther, *Evaluating Derivatives*, SIAM
2008, ch. 3 and 13) over floats or balls, for formulas written over a numbers namespace
(:mod:`continuation.numbers`). Certification takes ``H'`` over its boxes from the residual this
way (:func:`continuation.krawczyk.derivative`): one evaluation instead of one jet per
coordinate, the elementary functions evaluated once.
"""

from __future__ import annotations

import functools
import math
from itertools import repeat
from operator import add, mul, neg, sub, truediv

from .numbers import _WIDENINGS, FLOATS, Jet, _ComparedByValue, _Derivatives, _Jets, _largest, jets

__all__ = ["Gradient", "gradients"]


class Gradient(_ComparedByValue):
    """A number with its derivatives along every coordinate at once (``d``, a tuple of base
    numbers): one evaluation of a formula gives its whole gradient, where jets
    (:class:`~continuation.numbers.Jet`) need one per coordinate, and the elementary functions
    are evaluated once. Comparisons act on the value, as for jets."""

    __slots__ = ("v", "d")

    def __init__(self, v, d) -> None:
        self.v, self.d = v, d

    def __add__(self, other):
        if type(other) is Gradient:
            return Gradient(self.v + other.v, tuple(map(add, self.d, other.d)))
        return Gradient(self.v + other, self.d)

    __radd__ = __add__

    def __sub__(self, other):
        if type(other) is Gradient:
            return Gradient(self.v - other.v, tuple(map(sub, self.d, other.d)))
        return Gradient(self.v - other, self.d)

    def __rsub__(self, other):
        return Gradient(other - self.v, tuple(map(neg, self.d)))

    def __neg__(self):
        return Gradient(-self.v, tuple(map(neg, self.d)))

    def __mul__(self, other):
        if type(other) is Gradient:
            u, w = self.v, other.v
            return Gradient(u * w, tuple(map(add, map(mul, self.d, repeat(w)),
                                             map(mul, repeat(u), other.d))))
        return Gradient(self.v * other, tuple(map(mul, self.d, repeat(other))))

    __rmul__ = __mul__

    def __truediv__(self, other):
        if type(other) is Gradient:
            return self * other._reciprocal()
        return Gradient(self.v / other, tuple(map(truediv, self.d, repeat(other))))

    def __rtruediv__(self, other):
        return self._reciprocal() * other

    def _reciprocal(self):
        r = 1.0 / self.v
        f1 = -r * r
        return Gradient(r, tuple(map(mul, self.d, repeat(f1))))

    def __abs__(self):
        """As :meth:`Jet.__abs__`: NaN derivatives where the value may be 0."""
        if self.v > 0.0:
            return self
        if self.v < 0.0:
            return -self
        return Gradient(abs(self.v), tuple(a * math.nan for a in self.d))


def _gradient_chain(a, f0, f1):
    """``f(a)`` for a gradient ``a`` from ``f`` and ``f'`` at its value."""
    if type(a) is not Gradient:
        return f0
    return Gradient(f0, tuple(map(mul, repeat(f1), a.d)))


class _Gradients(_Derivatives):
    """Gradients over a base namespace: a formula's derivatives along every coordinate in one
    evaluation (the functions and constants of :func:`~continuation.numbers.jets`, to first
    order)."""

    kind = Gradient
    label = "gradients"

    @staticmethod
    def parts(x) -> tuple:
        return (x.v, *x.d)

    def sin(self, a):
        v = self.value(a)
        return _gradient_chain(a, self.base.sin(v), self.base.cos(v))

    def cos(self, a):
        v = self.value(a)
        return _gradient_chain(a, self.base.cos(v), -self.base.sin(v))

    def sqrt(self, a):
        r = self.base.sqrt(self.value(a))
        return _gradient_chain(a, r, 0.5 / r)

    def sinc(self, a):
        f = self.base.sinc_derivatives(self.value(a), 1)
        return _gradient_chain(a, f[0], f[1])

    def local(self, f, a):
        """``f(a)`` with ``f`` and ``f'`` from one jet through ``f`` (over the base numbers; over
        jets, a second-order jet gives ``f``, ``f'`` and ``f''`` at the value, which the jets of
        ``f(a)`` and ``f'(a)`` need), then the chain rule ``d f(a) = f'(a) da`` on every
        coordinate. Over second-order jets: ``f`` in gradients, as written."""
        if type(a) is not Gradient:
            return f(a, self.base)
        base, v = self.base, a.v
        if type(base) is _Jets and type(v) is Jet:
            if v.dd is not None:
                return f(a, self)
            inner = base.base
            r = f(Jet(v.v, inner.number(1.0), inner.number(0.0)), base)
            if type(r) is not Jet:
                return r
            value, slope = Jet(r.v, r.d * v.d), Jet(r.d, r.dd * v.d)
        else:
            r = f(Jet(v, base.number(1.0)), jets(base) if type(base) is not _Jets else base)
            if type(r) is not Jet:
                return r
            value, slope = r.v, r.d
        return Gradient(value, tuple(map(mul, repeat(slope), a.d)))

    def analytic_error(self, bound, args):
        """The remainder ``E(args)`` and its derivatives along every coordinate: as
        :meth:`_Jets.analytic_error`'s first derivative, Cauchy's estimate ``|E'| <= B speed /
        w`` along each coordinate's direction of the arguments (``speed`` its largest
        component, ``B = bound(args, w)``), the best of a few ``w``."""
        base = self.base
        values = tuple(self.value(a) for a in args)
        error0 = base.analytic_error(bound, values)
        moving = [a for a in args if type(a) is Gradient]
        if not base.rigorous or not moving:
            return error0
        if type(base) is _Jets:
            return Gradient(error0, _mixed_errors(base, bound, values, moving))
        intervals = tuple(base.bounds(v) for v in values)
        sups = [bound(intervals, widen) * (1.0 + 1e-12) for widen in _WIDENINGS]
        d = []
        for j in range(len(moving[0].d)):
            speed = _largest([base.bounds(abs(a.d[j]))[1] for a in moving])
            best = 0.0 if speed == 0.0 else min(
                sup * speed / widen * (1.0 + 1e-12) for sup, widen in zip(sups, _WIDENINGS,
                                                                          strict=True))
            d.append(base.error(best))
        return Gradient(error0, tuple(d))


def _sup(B, x) -> float:
    """An upper bound of ``|x|`` (0 for ``None`` or an exact 0: ``bounds`` rounds outwards)."""
    return 0.0 if x is None or x == 0.0 else B.bounds(abs(x))[1]


def _jet_sups(B, x) -> tuple:
    """Upper bounds of ``|value|``, ``|d|``, ``|dd|`` of a jet or a number."""
    if type(x) is not Jet:
        return _sup(B, x), 0.0, 0.0
    return _sup(B, x.v), _sup(B, x.d), _sup(B, x.dd)


#: the radii along the jets' direction tried for Cauchy's estimates of mixed derivatives,
#: as fractions of the largest that the polydisc allows there
_S_FRACTIONS = (1.0 / 16.0, 1.0 / 8.0, 1.0 / 4.0, 1.0 / 2.0, 3.0 / 4.0)


def _mixed_errors(J, bound, values, moving) -> tuple:
    """The derivatives along every coordinate ``y_j`` of a remainder ``E(args)`` whose
    arguments are gradients over jets (along ``s``): jets of ``dE/dy_j`` in ``s``.

    The arguments are, to the orders held, the polynomial
    ``P(s, y_j) = a + w s + w2 s^2/2 + y_j (g + h s + q s^2/2)`` (``w, w2`` from the jets,
    ``g, h, q`` from the jets of the gradient's ``j``-th part). Where ``|s| <= r`` and
    ``|y_j| <= t`` keep ``P`` within the polydisc of radius ``widen`` around the arguments,
    ``E(P)`` is analytic with ``|E| <= B = bound(args, widen)``, and Cauchy's estimate on that
    bidisc gives ``|d^p/ds^p d/dy_j E| <= B p! / (r^p t)`` (the derivatives of ``E(P)`` at 0
    are those of ``E(args)`` up to these orders). The best of a few ``widen`` and ``r``.
    """
    B = J.base
    second = any(type(v) is Jet and v.dd is not None for v in values)
    intervals = tuple(B.bounds(J.value(v)) for v in values)
    motion = [_jet_sups(B, v) for v in values]
    w = _largest([m[1] for m in motion])
    w2 = _largest([m[2] for m in motion])
    sups = [bound(intervals, widen) * (1.0 + 1e-12) for widen in _WIDENINGS]
    out = []
    for j in range(len(moving[0].d)):
        parts = [_jet_sups(B, a.d[j]) for a in moving]
        g, h, q = (_largest([p[i] for p in parts]) for i in range(3))
        if g == h == q == 0.0:  # the arguments do not move with y_j
            zero = B.number(0.0)
            out.append(Jet(zero, zero, zero if second else None))
            continue
        best = [math.inf] * 3
        for sup, widen in zip(sups, _WIDENINGS, strict=True):
            best[0] = min(best[0], 0.0 if g == 0.0 else sup * g / widen)
            for r in _s_radii(w, w2, h, q, widen):
                # |P - a| <= w r + w2 r^2/2 + t (g + h r + q r^2/2) <= widen (with a margin)
                room = widen * (1.0 - 1e-9) - w * r - 0.5 * w2 * r * r
                grow = g + h * r + 0.5 * q * r * r
                if room <= 0.0 or grow == 0.0:
                    continue
                t = room / grow
                if r * r * t > 0.0:  # (not underflowed: speeds near 1e200)
                    best[1] = min(best[1], sup / (r * t) * (1.0 + 1e-12))
                    best[2] = min(best[2], 2.0 * sup / (r * r * t) * (1.0 + 1e-12))
        if w == w2 == h == q == 0.0:
            best[1] = best[2] = 0.0  # nothing moves along s
        out.append(Jet(B.error(best[0]), B.error(best[1]),
                       B.error(best[2]) if second else None))
    return tuple(out)


def _s_radii(w: float, w2: float, h: float, q: float, widen: float) -> list:
    """Radii ``r`` along ``s`` to try: fractions of the largest that the jets' own motion
    allows (``w r + w2 r^2/2 < widen``; any ``r`` is sound, these are for tightness)."""
    if w > 0.0 or w2 > 0.0:
        top = widen / w if w2 == 0.0 else (
            2.0 * widen / (w + math.sqrt(w * w + 2.0 * w2 * widen)))
    elif h > 0.0 or q > 0.0:
        top = 1.0  # arguments fixed along s whose derivatives in y_j move: not met in practice
    else:
        return []
    return [f * min(top, 1e100) for f in _S_FRACTIONS]  # (a tiny w: any r is sound)


@functools.lru_cache(maxsize=4)
def gradients(base=FLOATS) -> _Gradients:
    """The gradient namespace over ``base`` (:data:`FLOATS` or :func:`balls`)."""
    return _Gradients(base)
