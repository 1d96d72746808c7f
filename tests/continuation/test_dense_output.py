"""Dense output: points at a given arclength or coordinate value, corrected onto the curve."""

import math

import numpy as np
import pytest

from continuation import Options, Status, trace


@pytest.fixture
def circle_curve(circle):
    return trace(circle, [1.0, 0.0], options=Options(fold_coordinates=(0, 1)))


def on_circle(x):
    return abs(x[0] ** 2 + x[1] ** 2 - 1.0)


@pytest.mark.parametrize("s", [0.0, 0.1234, 1.0, math.pi, 5.0])
def test_point_at(circle_curve, s):
    x = circle_curve.point_at(s)
    assert on_circle(x) <= 1e-10
    assert np.allclose(x, [math.cos(s), math.sin(s)], atol=1e-7)


def test_point_at_outside(circle_curve):
    with pytest.raises(ValueError, match="s must lie in the curve's arclength range"):
        circle_curve.point_at(-0.1)


def test_point_where_single_and_multiple(cubic):
    curve = trace(cubic, [-6.0, -2.0], direction=[1.0, 0.0],
                  options=Options(max_arclength=16.0))
    assert curve.status is Status.MAX_ARCLENGTH
    # lambda = 0 three times: u = -1, 0, 1
    points = curve.point_where(0, 0.0)
    assert len(points) == 3
    for x, u in zip(points, (-1.0, 0.0, 1.0)):
        assert x[0] == pytest.approx(0.0, abs=1e-15)
        assert x[1] == pytest.approx(u, abs=1e-12)
        assert abs(x[1] ** 3 - x[1] - x[0]) <= 1e-10
    # u = 1.5 once
    x = curve.point_where(1, 1.5)
    assert isinstance(x, np.ndarray)
    assert x[1] == pytest.approx(1.5, abs=1e-15)
    assert x[0] == pytest.approx(1.5 ** 3 - 1.5, abs=1e-10)


def test_point_where_never(circle_curve):
    with pytest.raises(ValueError, match=r"x\[0\] never equals 2.0 on the curve"):
        circle_curve.point_where(0, 2.0)
    with pytest.raises(ValueError, match=r"coordinate must be in \[0, 1\]"):
        circle_curve.point_where(2, 0.0)


def test_special_kind_validation(circle_curve):
    with pytest.raises(ValueError, match="kind must be one of"):
        circle_curve.special("turning_point")
