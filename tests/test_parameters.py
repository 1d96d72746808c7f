"""Parameter validation and geometry: every message names the quantity, value and range."""

import math

import numpy as np
import pytest

from groove_model.model.equilibrium import solve_equilibrium
from groove_model.model.parameters import (
    Compliance,
    Parameters,
    check_domain,
    gamma_delta_from_thetas,
    number_text,
    thetas_from_gamma_delta,
)


@pytest.mark.parametrize(
    "k, error, message",
    [
        (0.0, ValueError, "friction coefficient k = 0.0 is outside the allowed range: k must be finite and > 0"),
        (-1.0, ValueError, "friction coefficient k = -1.0 is outside the allowed range"),
        (float("nan"), ValueError, "friction coefficient k = nan is outside the allowed range"),
        (float("inf"), ValueError, "friction coefficient k = inf is outside the allowed range"),
        (-1e7, ValueError, "friction coefficient k = -1e+07 is outside the allowed range"),
        # an integer beyond the floats is out of range, not an OverflowError
        (10**400, ValueError, "friction coefficient k = inf is outside the allowed range"),
        ("1", TypeError, "friction coefficient k must be a real number, got '1' of type str"),
        (None, TypeError, "friction coefficient k must be a real number, got None"),
    ],
)
def test_bad_friction(k, error, message):
    with pytest.raises(error) as info:
        Parameters(k)
    assert str(info.value).startswith(message)


@pytest.mark.parametrize(
    "gamma, delta, message",
    [
        (0.5, 0.6, "delta = 0.6 rad is outside the allowed range 0 <= delta <= gamma (gamma = 0.5 rad)"),
        (2.0, 0.1, "gamma = 2.0 rad is outside the allowed range 0 <= gamma <= pi/2 = 1.57"),
        (-0.1, 0.0, "gamma = -0.1 rad is outside the allowed range 0 <= gamma <= pi/2 = 1.57"),
        # the bound's value is named (it read "0 <= delta <= gamma" alone)
        (0.5, -0.1, "delta = -0.1 rad is outside the allowed range 0 <= delta <= gamma "
                    "(gamma = 0.5 rad)"),
        (0.5, float("inf"), "delta = inf is not a finite number; allowed range: "
                            "0 <= delta <= gamma (gamma = 0.5 rad)"),
        (float("nan"), 0.1, "gamma = nan is not a finite number; allowed range: 0 <= gamma"),
        ([0.1, 0.5], [0.0, 0.7], "delta = 0.7 rad is outside the allowed range"),
        # tiny angles have only the relative slack: delta five times gamma is outside
        (1e-301, 5e-301, "delta = 5e-301 rad is outside the allowed range 0 <= delta <= gamma"),
        (0.0, 1e-300, "delta = 1e-300 rad is outside the allowed range 0 <= delta <= gamma"),
    ],
)
def test_bad_angles(gamma, delta, message):
    with pytest.raises(ValueError) as info:
        check_domain(gamma, delta)
    assert str(info.value).startswith(message)
    with pytest.raises(ValueError):
        solve_equilibrium(gamma, delta, 1.0)


@pytest.mark.parametrize("value, text", [
    (1e7, "1e+07"), (12345678.9, "1.23456789e+07"), (-2e11, "-2e+11"), (1e6, "1e+06"),
    (999999.0, "999999.0"), (0.1 + 0.2, "0.30000000000000004"), (1e-5, "1e-05"),
    (float("inf"), "inf"), (float("nan"), "nan"), (1e16, "1e+16"),
])
def test_number_text_is_short_and_reads_back(value, text):
    assert number_text(value) == text
    assert math.isnan(value) or float(text) == value


def test_domain_accepts_its_closed_edges():
    gamma, delta = check_domain([0.0, math.pi / 2, math.pi / 2], [0.0, 0.0, math.pi / 2])
    assert np.all(delta <= gamma)


def test_domain_takes_delta_a_subnormal_rounding_above_gamma_as_gamma():
    gamma, delta = check_domain([5e-324, 1e-310], [1e-323, 1e-310])
    assert list(delta) == list(gamma) == [5e-324, 1e-310]


def test_angle_conversions_round_trip():
    tL, tR = thetas_from_gamma_delta(0.7, 0.2)
    assert (tL, tR) == pytest.approx((0.9, 0.5))
    assert gamma_delta_from_thetas(tL, tR) == pytest.approx((0.7, 0.2))


def test_parameters_are_immutable_and_compliance_validated():
    p = Parameters(2)
    assert p.k == 2.0 and isinstance(p.k, float) and p.c == 1.0
    assert p.gamma_limit == pytest.approx(math.atan(2.0))
    with pytest.raises(AttributeError):
        p.k = 3.0
    with pytest.raises(ValueError, match=r"compliance ratio = -1.0 is outside the allowed range"):
        Compliance(-1.0)


@pytest.mark.parametrize("angle", ["0.6", True, None])
def test_angles_must_be_numbers(angle):
    # "0.6" was read as 0.6 and None reported as "gamma = nan", while k = "1" was refused
    from groove_model.model.equilibrium import solve_equilibrium

    with pytest.raises(TypeError, match="gamma must be a real number"):
        solve_equilibrium(angle, 0.2, 1.0)
