"""The numbers namespaces: floats as math, balls only when python-flint is there."""

import dataclasses
import math
import subprocess
import sys

import numpy as np
import pytest

from continuation import Event, Options, Problem, certify, trace
from continuation.numbers import ARRAYS, FLOATS, Jet, balls, jets, quotient, require_flint


def test_floats_are_math_with_nan_outside_the_domain():
    assert FLOATS.sin is math.sin and FLOATS.cos is math.cos and FLOATS.pi == math.pi
    assert math.isnan(FLOATS.sqrt(-1e-300)) and FLOATS.sqrt(4.0) == 2.0
    assert FLOATS.sinc(0.0) == 1.0 and FLOATS.sinc(1.0) == math.sin(1.0)
    assert FLOATS.analytic_error(None, ()) == 0.0 and not FLOATS.rigorous


def test_arrays_give_the_floats_numbers_elementwise():
    u = np.concatenate([np.random.default_rng(3).uniform(-7.0, 7.0, 2000),
                        [0.0, 1e-5, -1e-5, 1e-4, 2e-4, -3.0, 1e-300]])
    for array_f, float_f in ((ARRAYS.sin, FLOATS.sin), (ARRAYS.cos, FLOATS.cos),
                             (ARRAYS.sqrt, FLOATS.sqrt), (ARRAYS.sinc, FLOATS.sinc)):
        expected = np.array([float_f(float(v)) for v in u])
        assert np.array_equal(array_f(u), expected, equal_nan=True)
    assert ARRAYS.pi == math.pi and not ARRAYS.rigorous


def test_quotient_is_elementwise_over_arrays_and_a_plain_branch_otherwise():
    den = np.array([2.0, 0.0, -4.0, 0.0])
    assert np.array_equal(quotient(np.array([1.0, 1.0, 1.0, -1.0]), den, -math.inf),
                          [0.5, -math.inf, -0.25, -math.inf])
    assert quotient(1.0, 4.0, math.inf) == 0.25 and quotient(1.0, 0.0, math.inf) == math.inf
    assert quotient(Jet(1.0, 1.0), Jet(2.0, 0.0), math.inf).v == 0.5


def test_float_jets_differentiate():
    m = jets(FLOATS)
    y = m.cos(Jet(0.3, 1.0)) * 2.0
    assert y.v == 2.0 * math.cos(0.3) and y.d == -2.0 * math.sin(0.3) and y.dd is None


def test_without_python_flint_certification_names_the_extra(monkeypatch):
    monkeypatch.setitem(sys.modules, "flint", None)  # import flint now fails
    balls.cache_clear()
    try:
        with pytest.raises(ImportError, match=r"groove-continuation\[certify\]"):
            require_flint()
        with pytest.raises(ImportError, match="python-flint"):
            balls()
    finally:
        balls.cache_clear()


def test_the_package_imports_and_traces_without_python_flint():
    code = ("import sys; sys.modules['flint'] = None\n"
            "import continuation, groove_model\n"
            "from groove_model import trace_boundaries\n"
            "assert trace_boundaries(1.0).ok\n"
            "try:\n"
            "    trace_boundaries(1.0, certify=True)\n"
            "except ImportError as exc:\n"
            "    assert '[certify]' in str(exc)\n"
            "else:\n"
            "    raise AssertionError('no ImportError')\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr


@pytest.mark.parametrize("d, dd", [((0.3, -0.2), None), ((0.3, -0.2), (0.0, 0.0)),
                                   ((1e-6, 1e-6), (1.0, 1.0)), ((0.0, 0.0), (2.0, -0.5)),
                                   ((0.5, 0.5), (-1.0, 3.0))])
def test_the_remainder_of_a_quadrature_encloses_its_derivatives_along_a_curved_path(d, dd):
    """``E(a) = eps sin(a0 + a1)`` with Cauchy's bound ``eps cosh(2 w)`` on the polydisc of
    radius ``w``: along ``a(t)`` with ``a' = d``, ``a'' = dd`` the jets' remainder holds
    ``E'`` and ``E'' = D^2 E [d, d] + D E [dd]``; the second term was missing once (a path
    curved, with little speed: the chart ``beta_L = w^2`` of the deflated torque)."""
    pytest.importorskip("flint")
    B = balls()
    m = jets(B)
    eps, a = 1e-9, (0.4, 0.7)

    def bound(intervals, w):
        return eps * math.cosh(2.0 * w)

    args = tuple(Jet(B.number(ai), B.number(di), None if dd is None else B.number(ddi))
                 for ai, di, ddi in zip(a, d, dd or (0.0, 0.0), strict=True))
    error = m.analytic_error(bound, args)
    s, speed = a[0] + a[1], d[0] + d[1]
    assert error.v.contains(eps * math.sin(s))
    assert error.d.contains(eps * math.cos(s) * speed)
    if dd is None:
        assert error.dd is None
    else:
        second = -eps * math.sin(s) * speed ** 2 + eps * math.cos(s) * (dd[0] + dd[1])
        assert error.dd.contains(second)


def test_a_nan_derivative_makes_the_remainder_nan():
    pytest.importorskip("flint")
    B = balls()
    args = (B.number(0.4), Jet(B.number(0.7), B.arb("nan")))
    error = jets(B).analytic_error(lambda intervals, w: 1e-9 * math.cosh(2.0 * w), args)
    assert not B.is_finite(error.d)


def test_abs_of_a_jet_keeps_its_derivatives_or_makes_them_nan():
    """``abs`` on a jet returned its value alone: a formula with ``abs`` (of an argument that
    keeps one sign, so it is smooth) lost its derivatives, and ``certify`` proved an event with
    two zeros on a segment monotone, with none (``abs(u^2 + 0.01)`` along a line)."""
    pytest.importorskip("flint")
    B = balls()
    for base in (FLOATS, B):
        m = jets(base)
        x = Jet(base.number(-0.5), base.number(2.0), base.number(1.0))
        y = abs(m.sin(x))  # sin(-0.5) < 0: |sin x| = -sin x
        s = m.sin(x)
        assert type(y) is Jet
        for got, want in ((y.v, s.v), (y.d, s.d), (y.dd, s.dd)):
            assert float(got) == pytest.approx(-float(want), rel=1e-15)
        assert abs(x) > 0.4 and abs(x) < 0.6  # still a comparison of the value
    straddling = abs(Jet(B.arb(0, 1e-3), B.number(1.0), B.number(0.0)))
    assert straddling.v.contains(0.0) and not B.is_finite(straddling.d)
    assert not B.is_finite(straddling.dd)


def test_an_event_written_with_abs_is_not_proven_monotone_across_its_zeros():
    pytest.importorskip("flint")
    line = Problem(lambda x, m=FLOATS: [x[1]], lambda x, m=FLOATS: [[0.0 * x[0], 1.0]])
    event = Event("phi", lambda x, m=FLOATS: abs((x[0] - 0.5) * (x[0] - 0.5) + 0.01) - 0.05
                  + 1e-3 * x[0])  # > 0 at x = 0 and 1, < 0 at x = 1/2
    traced = trace(line, [0.0, 0.0], direction=[1.0, 0.0],
                   options=Options(ds=0.5, ds_max=1.0, max_steps=2))
    curve = dataclasses.replace(traced, x=np.array([[0.0, 0.0], [1.0, 0.0]]),
                                tangents=np.array([[1.0, 0.0], [1.0, 0.0]]),
                                s=np.array([0.0, 1.0]), ds=traced.ds[:2],
                                newton_iterations=traced.newton_iterations[:2],
                                residuals=traced.residuals[:2], special_points=())
    cert = certify(curve, line, [event], fold_coordinates=())
    assert not cert.proven and "phi" in cert.message, cert.message


@pytest.mark.parametrize("u", [0.0, 1e-8, -0.003, 0.05, 0.0999, 0.1, 0.5, -3.7, 20.0])
def test_higher_derivatives_of_sinc_are_enclosed(u):
    # gradients over jets (the fold functions' slopes in certification) need sinc^(j) up to
    # j = 4: against python-flint's power series of sin(u + t) / (u + t) at 300 bits
    flint = pytest.importorskip("flint")
    B = balls()
    floats = FLOATS.sinc_derivatives(u, 4)
    for bits in (53, 128):  # 128: square_box's second try
        with B.precision(bits):
            got = [B.sinc_derivatives(u, 4), B.sinc_derivatives(u, 2)]
            if u == 0.0:
                one = flint.arb(1)
                want = [one, 0 * one, -one / 3, 0 * one, one / 5]  # exact: 1/3 is no float
                # a ball centred at 0 (python-flint's power of one is NaN)
                got.append(B.sinc_derivatives(B.arb(0.0, 1e-10), 4))
            else:
                with B.precision(300):
                    t = flint.arb_series([flint.arb(u), 1], prec=5)
                    coefficients = (t.sin() / t).coeffs()
                    want = [coefficients[j] * math.factorial(j) for j in range(5)]
            for values in got:
                for value, exact in zip(values, want):
                    assert value.contains(exact) and float(value.rad()) < 1e-9, (bits, value)
    for j in range(5):
        assert floats[j] == pytest.approx(float(want[j]), rel=1e-10, abs=1e-11)


@pytest.mark.parametrize("g, h, q", [((0.3, -0.1), (0.0, 0.0), (0.0, 0.0)),
                                     ((1.0, 2.0), (0.5, -0.7), (0.0, 0.0)),
                                     ((0.0, 0.0), (1.0, 1.0), (2.0, 0.0)),
                                     ((2.0, -1.0), (0.4, 0.4), (-3.0, 1.0)),
                                     ((0.0, 0.0), (0.0, 0.0), (0.0, 0.0))])
@pytest.mark.parametrize("second", [False, True])
def test_the_remainder_of_a_quadrature_encloses_its_mixed_derivatives(g, h, q, second):
    """Gradients over jets (the slopes of the fold functions, from the residual): the
    remainder's derivative along a coordinate ``y`` and its derivatives along ``s``, for
    ``E(a) = eps sin(a0 + a1)`` with ``a(s, y) = a + d s + dd s^2/2 + y (g + h s + q s^2/2)``."""
    pytest.importorskip("flint")
    from continuation.gradients import Gradient, gradients

    B = balls()
    m = gradients(jets(B))
    eps, a, d, dd = 1e-9, (0.4, 0.7), (0.3, -0.8), (1.5, 0.5)

    def bound(intervals, w):
        return eps * math.cosh(2.0 * w)

    def jet(v, dv, ddv):
        return Jet(B.number(v), B.number(dv), B.number(ddv) if second else None)

    args = tuple(Gradient(jet(a[i], d[i], dd[i]), (jet(g[i], h[i], q[i]), jet(0.0, 0.0, 0.0)))
                 for i in range(2))
    error = m.analytic_error(bound, args)
    S, W, W2 = sum(a), sum(d), sum(dd)
    G, H, Q = sum(g), sum(h), sum(q)
    c, s = eps * math.cos(S), eps * math.sin(S)
    along = error.d[0]
    assert along.v.contains(c * G)
    assert along.d.contains(-s * W * G + c * H)
    if second:
        assert along.dd.contains(-c * W * W * G - s * W2 * G - 2.0 * s * W * H + c * Q)
    else:
        assert along.dd is None
    assert error.d[1].v == 0.0 and error.d[1].d == 0.0  # nothing moves along y_1
    assert error.v.v.contains(s) and error.v.d.contains(c * W)


def test_a_jet_is_a_number_of_gradients_over_jets():
    # a jet (constant along the gradients' coordinates) plus a gradient put the gradient
    # inside the jet's value, and derivative() dropped its derivatives: H = E + (y^3 - a y)
    # with a remainder E of constant arguments lost dH/dy (an adversarial review)
    pytest.importorskip("flint")
    from continuation.gradients import Gradient, gradients

    B = balls()
    m = gradients(jets(B))
    y = Gradient(Jet(B.number(0.01), B.number(1.0)), (Jet(B.number(1.0), B.number(0.0)),))
    constant = Jet(B.number(2.0), B.number(3.0))
    for value in (constant + y, y + constant, constant - y, constant * y, constant / y):
        assert type(value) is Gradient and type(value.v) is Jet
    assert (constant * y).d[0].v.contains(2.0) and (constant * y).d[0].d.contains(3.0)
    assert (constant - y).d[0].v.contains(-1.0)
    # a remainder whose arguments do not move is a base number, of any order
    for second in (None, B.number(0.0)):
        x = Jet(B.number(0.3), B.number(1.0), second)
        E = jets(B).analytic_error(lambda intervals, w: 1e-12, (0.5,))
        total = x * x + E
        assert type(total) is Jet and (total.dd is None) == (second is None)
    E = m.analytic_error(lambda intervals, w: 1e-12, (0.5,))
    assert type(y * y * y + E) is Gradient


def test_mixed_remainder_derivatives_at_absurd_speeds_are_not_finite_not_a_crash():
    # r t underflowed to 0 at speeds near 1e200: ZeroDivisionError
    pytest.importorskip("flint")
    from continuation.gradients import Gradient, gradients

    B = balls()
    m = gradients(jets(B))
    for speed in (1e200, 1e300, math.inf):
        args = tuple(Gradient(Jet(B.number(0.4), B.number(speed), B.number(0.0)),
                              (Jet(B.number(1.0), B.number(speed), B.number(0.0)),))
                     for _ in range(2))
        error = m.analytic_error(lambda intervals, w: 1e-9 * math.cosh(2.0 * w), args)
        assert type(error) is Gradient  # finite or not, an enclosure


@pytest.mark.parametrize("second", [False, True])
def test_local_gives_the_numbers_of_the_function_itself(second):
    # m.local(f, a): f of one number with its derivative through one jet and the chain rule
    # (the deflated torque's quadrature); the same value and derivatives as f over m
    pytest.importorskip("flint")
    from continuation.gradients import Gradient, gradients

    def f(u, m):
        s, c = m.sin(u), m.cos(u)
        q = m.sqrt(s)
        return c * c / (2.0 * q) - s * q + m.sinc(u * u)

    B = balls()
    for base in (FLOATS, B, jets(B)):
        m = gradients(base)
        if base is FLOATS:
            v = 0.7
        elif base is B:
            v = B.arb(0.7, 1e-9)
        else:
            v = Jet(B.arb(0.7, 1e-9), B.number(0.4), B.number(-0.3) if second else None)
        a = Gradient(v, (base.number(1.5), base.number(0.0), base.number(-2.0)))
        ours, plain = m.local(f, 3.0 * a - 1.4), f(3.0 * a - 1.4, m)
        for x, y in zip(m.parts(ours), m.parts(plain)):
            for p, q in zip(*((z.v, z.d) + (() if z.dd is None else (z.dd,))
                              if type(z) is Jet else (z,) for z in (x, y))):
                if base is FLOATS:
                    assert p == pytest.approx(q, rel=1e-13, abs=1e-14)
                else:
                    assert B.number(p).overlaps(B.number(q)) and B.is_finite(B.number(p))
    assert FLOATS.local(f, 0.7) == f(0.7, FLOATS) and jets(B).local(f, B.arb(0.7)) is not None


def test_small_powers_of_jets_and_gradients_are_products():
    from continuation.gradients import Gradient

    for x in (Jet(2.0, 1.0, 0.5), Gradient(2.0, (1.0, -3.0))):
        square, cube = x ** 2, x ** 3
        assert square.v == 4.0 and cube.v == 8.0
        d = square.d if type(x) is Jet else square.d[1]
        assert d == (4.0 if type(x) is Jet else -12.0)  # 2 x x'
        with pytest.raises(ValueError, match=rf"{type(x).__name__} \*\* 4: only the exponents "
                                             "2 and 3"):
            x ** 4
