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

from .numbers import _WIDENINGS, FLOATS, _ComparedByValue, _Derivatives, _largest

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

    def __pow__(self, n: int):
        if n == 2:
            return self * self
        if n == 3:
            return self * self * self
        raise ValueError(f"Gradient ** {n!r}: only the exponents 2 and 3 are supported")

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
        f0, f1, _ = self.base.sinc_derivatives(self.value(a))
        return _gradient_chain(a, f0, f1)

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


@functools.lru_cache(maxsize=4)
def gradients(base=FLOATS) -> _Gradients:
    """The gradient namespace over ``base`` (:data:`FLOATS` or :func:`balls`)."""
    return _Gradients(base)
