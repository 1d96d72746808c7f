"""Boundary systems: analytic Jacobians against central differences, seeds, validity."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from continuation.numbers import FLOATS
from groove_model.model.boundaries import (
    BOUNDARY_NAMES,
    BoundarySystem,
    boundary_system,
    corner_point,
    dr_no_roll_branch_point,
    limit_seed,
)
from groove_model.model.equilibrium import solve_equilibrium
from groove_model.model.parameters import Compliance, Parameters


def central_differences(f, x, h=1e-6):
    return np.column_stack([(f(x + h * e) - f(x - h * e)) / (2 * h) for e in np.eye(len(x))])


@st.composite
def interior_points(draw):
    gamma = draw(st.floats(0.05, 0.5 * math.pi - 0.05))
    delta = draw(st.floats(0.0, 1.0)) * gamma
    omega = math.pi - 2 * gamma
    beta_L = draw(st.floats(0.05, 0.95)) * omega
    upsilon = draw(st.floats(-2.0, 2.0))
    return np.array([gamma, delta, beta_L, upsilon])


@pytest.mark.parametrize("chart", ["beta_L", "sqrt_beta_L"])
@pytest.mark.parametrize("name", BOUNDARY_NAMES)
@settings(max_examples=60, deadline=None)
@given(x=interior_points(), k=st.floats(0.01, 1000.0), c=st.sampled_from([1.0, 0.6]))
def test_jacobian_matches_central_differences(name, chart, x, k, c):
    system = boundary_system(name, Parameters(k, Compliance(c)), chart)
    x = system.from_x(x)
    J = system.jacobian(x)
    assert J.shape == (3, 4)
    J_fd = central_differences(system.residual, x)
    scale = 1.0 + np.abs(J).max()
    assert np.max(np.abs(J - J_fd)) <= 1e-6 * scale
    H, J2 = system.residual_and_jacobian(x)
    assert np.array_equal(H, system.residual(x)) and np.array_equal(J, J2)


@pytest.mark.parametrize("form", [("beta_L", 1.0, False), ("sqrt_beta_L", 1.0, False),
                                  ("sqrt_beta_L", 0.05, False), ("sqrt_beta_L", 0.05, True)])
@pytest.mark.parametrize("name", BOUNDARY_NAMES)
@settings(max_examples=15, deadline=None)
@given(points=st.lists(interior_points(), min_size=1, max_size=6), k=st.floats(1e-4, 1e6),
       c=st.sampled_from([1.0, 2.0 / 3.0]))
def test_whole_curve_evaluations_are_the_point_evaluations(name, form, points, k, c):
    """residuals, residuals_and_jacobians and physical (numpy arrays, every point at once)
    give the numbers of residual, residual_and_jacobian and is_physical point by point, to
    the last bit."""
    chart, scale, conditioned = form
    if conditioned and name == "rs_no_roll":
        conditioned = False
    system = BoundarySystem(name, Parameters(k, Compliance(c)), chart, scale, conditioned)
    ys = system.from_x(np.array(points))
    ys = np.vstack([ys, [np.nan] * 4])  # a non-finite point stays non-finite, not an error
    H, J = system.residuals_and_jacobians(ys)
    assert np.array_equal(system.residuals(ys), H, equal_nan=True)
    for y, h, j in zip(ys, H, J, strict=True):
        h1, j1 = system.residual_and_jacobian(y)
        assert np.array_equal(h, h1, equal_nan=True) and np.array_equal(j, j1, equal_nan=True)
    for tol in (0.0, 1e-3):
        assert system.physical(ys, tol).tolist() == [system.is_physical(y, tol) for y in ys]
    assert system.residuals(np.zeros((0, 4))).shape == (0, 3)


@pytest.mark.parametrize("chart", ["beta_L", "sqrt_beta_L"])
@pytest.mark.parametrize("name", BOUNDARY_NAMES)
def test_whole_curve_evaluations_at_the_contact_ends_are_quiet(name, chart):
    """At the ends of the contact (beta_L = 0, beta_R = 0) the point evaluations give inf or
    NaN entries silently; so do the array ones (the tests turn warnings into errors), with
    the same numbers. A row that is not finite gives NaN where ``math`` would raise."""
    system = BoundarySystem(name, Parameters(1.0), chart)
    x = np.array([[0.7, 0.2, 0.0, 0.3], [0.5 * math.pi, 0.0, 0.0, 0.0],
                  [0.4, 0.1, math.pi - 0.8, 0.1], [0.0, 0.0, 0.0, 0.0]])
    ys = system.from_x(x)
    H, J = system.residuals_and_jacobians(ys)
    for y, h, j in zip(ys, H, J, strict=True):
        h1, j1 = system.residual_and_jacobian(y)
        assert np.array_equal(h, h1, equal_nan=True) and np.array_equal(j, j1, equal_nan=True)
    H, J = system.residuals_and_jacobians(np.array([[math.inf, 0.1, 0.5, 0.0]]))
    assert np.isnan(H).any() and np.isnan(system.residuals([[math.inf, 0.1, 0.5, 0.0]])).any()
    if system.validity:  # (rs_limit has no validity condition: every row is physical)
        assert not system.physical(np.array([[0.3, 0.1, math.inf, 0.0]]))[0]


@pytest.mark.parametrize("form", [("beta_L", 1.0, False), ("sqrt_beta_L", 1.0, False),
                                  ("sqrt_beta_L", 0.05, False), ("sqrt_beta_L", 0.05, True)])
@pytest.mark.parametrize("name", BOUNDARY_NAMES)
@settings(max_examples=15, deadline=None)
@given(x=interior_points(), other=interior_points(), k=st.floats(1e-4, 1e6))
def test_jacobian_after_a_residual_is_the_jacobian_evaluated_afresh(name, form, x, other, k):
    """The Jacobian at the point of the last residual reuses that evaluation's rows: the same
    numbers as a system that never evaluated anything, at that point and at any other, and a
    point with the same coordinates in another array (a copy) is the same point. The residual
    itself is that of its own formulas, without the rows."""
    chart, scale, conditioned = form
    if conditioned and name == "rs_no_roll":
        return
    params = Parameters(k)
    system = BoundarySystem(name, params, chart, scale, conditioned)

    def fresh(y):
        return BoundarySystem(name, params, chart, scale, conditioned).jacobian(y)

    y, z = system.from_x(x), system.from_x(other)
    H = system.residual(y)
    assert np.array_equal(system.jacobian(y.copy()), fresh(y), equal_nan=True)
    assert np.array_equal(system.jacobian(z), fresh(z), equal_nan=True)
    assert np.array_equal(system.jacobian(y), fresh(y), equal_nan=True)
    # the residual evaluated with the rows is the one of the residual's formulas alone
    assert np.array_equal(H, np.array(system.residual(y, numbers=FLOATS)), equal_nan=True)


def test_residual_where_only_the_jacobian_divides_by_zero():
    """At ``beta_R = 0`` the deflated torque's derivative divides by ``q_R = 0`` while the
    torque itself is finite: the residual is still evaluated (its rows are not kept), and the
    Jacobian fails there as it did before any residual."""
    system = BoundarySystem("dr_no_roll", Parameters(2.0), "beta_L", conditioned=True)
    y = np.array([1.0, 0.1, math.pi - 2.0, 0.0])  # beta_R = pi - 2 gamma - beta_L = 0 exactly
    H = system.residual(y)
    assert np.isfinite(H).all()
    assert np.array_equal(H, system.residual(y, numbers=FLOATS))
    with pytest.raises(ZeroDivisionError):
        system.jacobian(y)

@pytest.mark.parametrize("chart", ["beta_L", "sqrt_beta_L"])
@pytest.mark.parametrize("name", BOUNDARY_NAMES)
@settings(max_examples=40, deadline=None)
@given(x=interior_points(), k=st.floats(1e-4, 1e6), c=st.sampled_from([1.0, 0.6]),
       scale=st.sampled_from([1.0, 0.05]))
def test_validity_gradients_match_central_differences(name, chart, x, k, c, scale):
    if chart == "beta_L":
        scale = 1.0
    system = BoundarySystem(name, Parameters(k, Compliance(c)), chart, scale)
    y = system.from_x(x)
    assert set(system.validity_gradient) == set(system.validity)
    for condition, function in system.validity.items():
        gradient = system.validity_gradient[condition](y)
        assert gradient.shape == (4,)
        fd = central_differences(lambda v, f=function: np.array([f(v)]), y)[0]
        assert np.max(np.abs(gradient - fd)) <= 1e-7 * (1.0 + np.abs(gradient).max())


@pytest.mark.parametrize("k", [0.1, 1.0, math.sqrt(2), 10.0])
def test_seeds_are_exact_solutions(k):
    params = Parameters(k)
    seed = limit_seed(params)
    assert seed[0] == pytest.approx(math.atan(k), abs=1e-15)
    for name in ("dr_limit", "rs_limit", "rs_no_roll"):
        # The limit equation c A - k s_L carries terms of size k.
        assert np.max(np.abs(boundary_system(name, params).residual(seed))) <= 4e-16 * (1 + k)
    bp = dr_no_roll_branch_point()
    assert bp[0] == pytest.approx(math.atan(math.sqrt(2)), abs=1e-15)
    system = boundary_system("dr_no_roll", params)
    assert np.max(np.abs(system.residual(bp))) <= 1e-15
    # A branch point: the 3 x 4 Jacobian loses rank there.
    assert np.linalg.svd(system.jacobian(bp), compute_uv=False)[-1] <= 1e-14
    for name in ("dr_no_roll", "rs_no_roll"):
        assert np.max(np.abs(boundary_system(name, params).residual(corner_point()))) <= 1e-15


def test_symmetric_family_solves_dr_no_roll_for_every_gamma():
    system = boundary_system("dr_no_roll", 10.0)
    for gamma in np.linspace(0.05, 1.5, 30):
        x = np.array([gamma, 0.0, 0.5 * math.pi - gamma, 0.0])
        assert np.max(np.abs(system.residual(x))) <= 1e-15


@pytest.mark.parametrize("k", [0.5, 3.0])
def test_solver_states_satisfy_their_regime_equations(k):
    """A double-rolling state satisfies the DR pair; a rolling-sliding one the RS pair."""
    gamma, delta = np.meshgrid(np.linspace(0.1, 1.4, 15), np.linspace(0.05, 0.95, 9))
    delta = delta * gamma
    eq = solve_equilibrium(gamma, delta, k)
    dr, rs = boundary_system("dr_no_roll", k), boundary_system("rs_no_roll", k)
    for i in np.ndindex(gamma.shape):
        x = np.array([eq.gamma[i], eq.delta[i], eq.beta_L[i], eq.upsilon[i]])
        system = dr if eq.regime[i] == "double_rolling" else rs
        assert np.max(np.abs(system.residual(x)[:2])) <= 1e-12
        assert system.is_physical(x, tol=1e-12)


def test_validity_signs():
    k = 1.0
    dr = boundary_system("dr_no_roll", k)
    eq = solve_equilibrium(0.6, 0.2, k)  # rolling sliding: d_L > 0
    x = np.array([eq.gamma, eq.delta, eq.beta_L, eq.upsilon])
    assert boundary_system("rs_no_roll", k).validity["d_L >= 0"](x) > 0
    eq = solve_equilibrium(0.4, 0.1, k)  # double rolling: T/N_L < k
    x = np.array([eq.gamma, eq.delta, eq.beta_L, eq.upsilon])
    assert dr.validity["T_over_N_L <= k"](x) > 0 and dr.is_physical(x)


def test_unknown_boundary_name():
    with pytest.raises(ValueError, match="boundary = 'foo' is not one of dr_limit, rs_limit"):
        boundary_system("foo", 1.0)


def test_residual_outside_contact_range_is_nan_not_an_exception():
    system = boundary_system("dr_limit", 1.0)
    assert np.all(np.isnan(system.residual(np.array([0.5, 0.1, -0.1, 0.0]))[:2]))


@pytest.mark.parametrize("name", ["dr_no_roll", "rs_no_roll"])
def test_sqrt_chart_makes_the_corner_regular(name):
    """In w = sqrt(beta_L) the corner (pi/4, pi/4) is a regular point (full-rank Jacobian)."""
    system = boundary_system(name, 10.0, "sqrt_beta_L")
    y = system.from_x(corner_point())
    assert np.max(np.abs(system.residual(y))) <= 1e-15
    assert np.linalg.svd(system.jacobian(y), compute_uv=False)[-1] >= 0.3
    # ... and the Jacobian is smooth through w = 0, including on the mirror side w < 0.
    for w in (-1e-3, 1e-3):
        y_w = y + np.array([0.0, 0.0, w, 0.0])
        fd = central_differences(system.residual, y_w, h=1e-7)
        assert np.allclose(system.jacobian(y_w), fd, atol=1e-6)


def test_chart_round_trip_and_validation():
    system = boundary_system("dr_limit", 1.0, "sqrt_beta_L")
    x = np.array([0.5, 0.2, 0.3, -0.1])
    assert np.allclose(system.to_x(system.from_x(x)), x, rtol=1e-15)
    with pytest.raises(ValueError, match="chart = 'w' is not one of beta_L, sqrt_beta_L"):
        boundary_system("dr_limit", 1.0, "w")
