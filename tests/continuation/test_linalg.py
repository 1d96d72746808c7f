"""The tiny-vector helpers agree with their numpy counterparts."""

import math

import numpy as np
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
    assert math.isclose(norm(v), float(np.linalg.norm(v)), rel_tol=1e-14, abs_tol=0.0)
