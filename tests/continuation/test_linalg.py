"""The tiny-vector helpers agree with their numpy counterparts."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from continuation.linalg import all_finite, max_abs, norm

floats = st.floats(allow_nan=True, allow_infinity=True, width=64)


@given(arrays(np.float64, st.integers(0, 8), elements=floats))
def test_max_abs_matches_numpy_and_propagates_nan(v):
    expected = float(np.max(np.abs(v))) if v.size else 0.0
    got = max_abs(v)
    if math.isnan(expected):
        assert math.isnan(got)
    else:
        assert got == expected


@given(arrays(np.float64, st.tuples(st.integers(1, 4), st.integers(1, 5)),
              elements=st.floats(-1e300, 1e300) | st.sampled_from([math.inf, -math.inf, math.nan])))
def test_all_finite_matches_numpy_for_values_that_cannot_overflow(a):
    assert all_finite(a) == bool(np.isfinite(a).all())


def test_all_finite_is_conservative_on_overflow():
    assert not all_finite(np.array([1.7e308, 1.7e308]))


@given(arrays(np.float64, st.integers(0, 8), elements=st.floats(-1e100, 1e100)))
def test_norm_matches_numpy(v):
    # numpy's norm squares its entries: compare where that neither overflows nor underflows,
    # by scaling the vector by a power of two first (exact)
    exponent = int(np.frexp(np.max(np.abs(v)))[1]) if v.size and np.any(v) else 0
    expected = math.ldexp(float(np.linalg.norm(np.ldexp(v, -exponent))), exponent)
    assert math.isclose(norm(v), expected, rel_tol=1e-14, abs_tol=0.0)


FINITE = [3.0, -7.5, 0.25, -0.0, 2.0]


@pytest.mark.parametrize("position", range(len(FINITE)))
@pytest.mark.parametrize("bad", [math.nan, -math.nan])
def test_max_abs_is_nan_wherever_the_nan_is(position, bad):
    v = np.array(FINITE[:position] + [bad] + FINITE[position:])
    assert math.isnan(max_abs(v))
    assert math.isnan(max_abs(np.array([math.inf, *v])))  # numpy: max(inf, nan) is nan


@pytest.mark.parametrize("position", range(len(FINITE)))
@pytest.mark.parametrize("bad", [math.inf, -math.inf])
def test_max_abs_is_inf_wherever_an_infinity_is(position, bad):
    assert max_abs(np.array(FINITE[:position] + [bad] + FINITE[position:])) == math.inf


@pytest.mark.parametrize("v, expected", [
    ([-3.0, 2.0], 3.0), ([2.0, -3.0], 3.0), ([-1e-300, -2e-300], 2e-300), ([-0.0], 0.0),
    ([5.0], 5.0), ([], 0.0), ([-math.inf], math.inf),
])
def test_max_abs_of_negative_and_short_vectors(v, expected):
    got = max_abs(np.array(v, dtype=float))
    assert got == expected and isinstance(got, float)
    assert not math.copysign(1.0, got) < 0  # never -0.0


@pytest.mark.parametrize("shape", [(5,), (2, 3), (2, 2, 2)])
@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_all_finite_finds_a_bad_value_at_every_position(shape, bad):
    a = np.arange(1.0, 1.0 + math.prod(shape)).reshape(shape) * np.where(
        np.arange(math.prod(shape)).reshape(shape) % 2, -1.0, 1.0)
    assert all_finite(a)
    for index in np.ndindex(shape):
        b = a.copy()
        b[index] = bad
        assert not all_finite(b), (index, bad)


@pytest.mark.parametrize("a, expected", [
    (np.zeros(0), True), (np.zeros((0, 4)), True), (np.array([[-1e300, 1e300]]), True),
    (np.array([math.inf, -math.inf]), False), (np.array([-math.inf]), False),
    (np.array([5e-324, -5e-324]), True),
])
def test_all_finite_edge_cases_agree_with_numpy(a, expected):
    assert bool(np.isfinite(a).all()) is expected
    assert all_finite(a) is expected


@given(arrays(np.float64, st.integers(0, 8),
              elements=st.floats(-1e150, 1e150) | st.sampled_from([math.inf, -math.inf, math.nan])))
def test_norm_matches_numpy_with_nan_and_infinities(v):
    # IEEE hypot: infinite if any entry is infinite (even beside a NaN), else NaN if any is NaN
    got = norm(v)
    if np.any(np.isinf(v)):
        assert got == math.inf
    elif np.any(np.isnan(v)):
        assert math.isnan(got)
    else:
        exponent = int(np.frexp(np.max(np.abs(v)))[1]) if v.size and np.any(v) else 0
        expected = math.ldexp(float(np.linalg.norm(np.ldexp(v, -exponent))), exponent)
        assert got == pytest.approx(expected, rel=1e-14, abs=0.0)


def test_norm_does_not_overflow_below_the_largest_float():
    # sqrt(v . v) overflows (with a RuntimeWarning) above sqrt(max float) ~ 1.34e154
    assert norm(np.array([3e200, -4e200])) == pytest.approx(5e200, rel=1e-15)


@pytest.mark.parametrize("v, expected", [
    ([], 0.0), ([-3.0, -4.0], 5.0), ([3.0, -4.0], 5.0), ([-2.0], 2.0),
    ([1.0, -math.inf], math.inf), ([math.nan, 1.0], math.nan), ([-1.0, 1.0, -1.0, 1.0], 2.0),
])
def test_norm_of_negative_short_and_non_finite_vectors(v, expected):
    got = norm(np.array(v, dtype=float))
    assert isinstance(got, float)
    assert math.isnan(got) if math.isnan(expected) else got == expected
