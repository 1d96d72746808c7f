"""Problem, finite differences, Jacobian check and Options validation."""

import math

import numpy as np
import pytest

from continuation import Options, Problem, check_jacobian, finite_difference_jacobian, trace


def test_finite_difference_jacobian_matches_analytic(cubic):
    x = np.array([0.3, -1.2])
    assert np.allclose(finite_difference_jacobian(cubic.residual, x), cubic.jacobian(x),
                       rtol=0, atol=1e-9)


def test_check_jacobian_accepts_a_correct_jacobian(cubic):
    assert check_jacobian(cubic, None, [0.3, -1.2], raise_on_error=True) < 1e-8


def test_check_jacobian_catches_a_wrong_jacobian(cubic):
    def wrong(x):
        return np.array([[-1.0, 3.0 * x[1] ** 2]])  # forgot the -1

    with pytest.raises(ValueError, match=r"dH\[0\]/du at .* is 4.32, central differences "
                                         r"give 3.32"):
        check_jacobian(cubic, wrong, [0.3, -1.2], raise_on_error=True)
    assert check_jacobian(cubic.residual, wrong, [0.3, -1.2]) == pytest.approx(1.0)


def test_check_jacobian_needs_a_jacobian():
    with pytest.raises(ValueError, match="needs a jacobian"):
        check_jacobian(Problem(lambda x: x[:1]), None, [0.0, 0.0])


def test_finite_difference_trace_counts_residual_calls(circle):
    fd = Problem(circle.residual)
    exact = trace(circle, [1.0, 0.0])
    approximate = trace(fd, [1.0, 0.0])
    assert approximate.status is exact.status
    assert len(approximate) == len(exact)
    assert np.allclose(approximate.x, exact.x, atol=1e-8)
    # 2 (n + 1) = 4 residual calls per finite-difference Jacobian; the exact Jacobian is
    # checked at the start with 2 residual calls (a finite-difference one is not)
    assert approximate.residual_evals == exact.residual_evals - 2 + 4 * approximate.jacobian_evals


def test_problem_validation():
    with pytest.raises(TypeError, match="Problem.residual must be callable"):
        Problem(1.0)
    with pytest.raises(TypeError, match="Problem.names must be a tuple of str"):
        Problem(lambda x: x, names=(1, 2))
    assert Problem(lambda x: x, names=["a", "b"]).names == ("a", "b")
    assert Problem(lambda x: x).coordinate_name(3) == "x[3]"


@pytest.mark.parametrize("kwargs, message", [
    ({"tol": 0.0}, "Options.tol must be a finite number > 0, got 0.0"),
    ({"tol": math.nan}, "Options.tol must be a finite number > 0, got nan"),
    ({"ds": 1.0}, ("Options.ds must satisfy ds_min <= ds <= ds_max, got ds=1.0 with "
                   "ds_min=1e-12, ds_max=0.2")),
    ({"ds_min": 0.5, "ds": 0.6, "ds_max": 0.4},
     "Options.ds_min must be <= ds_max, got ds_min=0.5, ds_max=0.4"),
    ({"max_steps": 0}, "Options.max_steps must be an integer >= 1, got 0"),
    ({"max_steps": 10.5}, "Options.max_steps must be an integer >= 1, got 10.5"),
    ({"max_newton": True}, "Options.max_newton must be an integer >= 1, got True"),
    ({"max_arclength": -1.0}, "Options.max_arclength must be > 0 (inf allowed), got -1.0"),
    ({"newton_contraction": 1.0}, "Options.newton_contraction must be in (0, 1), got 1.0"),
    ({"max_angle": 2.0}, "Options.max_angle must be in (0, pi/2] radians, got 2.0"),
    ({"event_tol": -1e-12}, "Options.event_tol must be a finite number > 0, got -1e-12"),
    ({"fold_coordinates": (0, -1)},
     "Options.fold_coordinates must be a tuple of coordinate indices >= 0, got (0, -1)"),
])
def test_options_validation_messages(kwargs, message):
    with pytest.raises(ValueError) as info:
        Options(**kwargs)
    assert str(info.value) == message


def test_options_type_errors():
    message = "Options.fold_coordinates must be a tuple of coordinate indices >= 0, got 3"
    with pytest.raises(TypeError) as info:
        Options(fold_coordinates=3)
    assert str(info.value) == message
    with pytest.raises(TypeError, match="Options.detect_closed must be True or False, got 1"):
        Options(detect_closed=1)
    with pytest.raises(TypeError, match="indices >= 0, got \\(0.5,\\)"):
        Options(fold_coordinates=(0.5,))


def test_options_are_frozen_and_normalised():
    options = Options(fold_coordinates=[1, 0])
    assert options.fold_coordinates == (1, 0)
    with pytest.raises(AttributeError):
        options.tol = 1.0  # type: ignore[misc]
