"""Every model formula against forces computed from first principles.

The reference is the mechanics written out directly, never a copy of a production formula:
each contact's displacements from the kinematics (``u_n = Z sin beta``,
``u_t = Z (cos beta +- upsilon) - d``, paper Eqs. norm and tang), its normal force from
Hertz (``N = C u_n^(3/2)``), its tangential force from proportional loading
(``T / N = c u_t / u_n``, paper Eq. prop with the compliance ratio ``c``) or from Amontons
(``T = k N`` on a sliding contact), and the balances as vector sums: the net force of the
walls on the ball (paper Eqs. 1-2) and its torque about the centre (Eq. 3), with each wall's
inward normal and up-wall tangent. Units: ``Z = C = 1`` (every force scales with
``C Z^(3/2)``), torques per ``R``.

Points are random (seeded) inside the domain, most of them off any boundary, so that every
term of a residual row matters.
"""

import math

import numpy as np
import pytest

from groove_model.model.boundaries import BOUNDARY_NAMES, boundary_system
from groove_model.model.equilibrium import (
    double_rolling_state,
    regime_validity,
    rolling_sliding_state,
    solve_equilibrium,
)
from groove_model.model.parameters import Compliance, Parameters
from groove_model.tracing import boundary_quantities

PARAMS = [Parameters(k, Compliance(c)) for k, c in
          [(0.05, 1.0), (0.7, 1.0), (1.0, 0.6), (math.sqrt(2.0), 1.0), (3.0, 1.7), (40.0, 0.6)]]
PARAM_IDS = [f"k={p.k:.3g},c={p.c:g}" for p in PARAMS]


# --- the reference: kinematics, Hertz, proportional loading, balances --------------------------

def walls(theta_L, theta_R):
    """Inward unit normals and up-wall unit tangents of the left and right walls, (2, ...) each."""
    normal_L = np.array([np.sin(theta_L), np.cos(theta_L)])
    up_L = np.array([-np.cos(theta_L), np.sin(theta_L)])
    normal_R = np.array([-np.sin(theta_R), np.cos(theta_R)])
    up_R = np.array([np.cos(theta_R), np.sin(theta_R)])
    return normal_L, up_L, normal_R, up_R


def cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def balance(theta_L, theta_R, N_L, T_L, N_R, T_R):
    """Net horizontal and vertical force of the walls on the ball, and its torque per ``R``."""
    normal_L, up_L, normal_R, up_R = walls(theta_L, theta_R)
    F_L = N_L * normal_L + T_L * up_L
    F_R = N_R * normal_R + T_R * up_R
    net = F_L + F_R
    # a contact lies one radius from the centre, against its wall's inward normal
    torque = cross(-normal_L, F_L) + cross(-normal_R, F_R)
    return net[0], net[1], torque


class State:
    """Displacements and contact forces of a kinematic state ``(gamma, delta, beta_L, upsilon)``.

    ``T_L``, ``T_R`` are the proportional-loading forces ``c N u_t / u_n`` with slips ``d_L``,
    ``d_R`` (0: the contact rolls).
    """

    def __init__(self, gamma, delta, beta_L, upsilon, c, d_L=0.0, d_R=0.0):
        self.gamma, self.delta, self.beta_L, self.upsilon = gamma, delta, beta_L, upsilon
        self.theta_L, self.theta_R = gamma + delta, gamma - delta
        # the centre moves along a direction at beta_L to the left wall and beta_R to the
        # right one; the two walls enclose the opening angle pi - 2 gamma
        self.beta_R = math.pi - 2.0 * gamma - beta_L
        self.u_n_L, self.u_n_R = np.sin(beta_L), np.sin(self.beta_R)
        self.u_t_L = np.cos(beta_L) + upsilon - d_L
        self.u_t_R = np.cos(self.beta_R) - upsilon - d_R
        self.N_L, self.N_R = self.u_n_L ** 1.5, self.u_n_R ** 1.5
        self.T_L = c * self.N_L * self.u_t_L / self.u_n_L
        self.T_R = c * self.N_R * self.u_t_R / self.u_n_R

    def balance(self, T_L, T_R):
        return balance(self.theta_L, self.theta_R, self.N_L, T_L, self.N_R, T_R)


def slip_for_friction_limit(u_t_rolling, u_n, k, c):
    """The slip ``d`` that brings a contact to ``T / N = k``: ``c (u_t_rolling - d) / u_n = k``."""
    return u_t_rolling - k * u_n / c


def random_points(rng, m, upsilon=2.0, margin=0.03):
    """``m`` points ``(gamma, delta, beta_L, upsilon)`` strictly inside the domain."""
    gamma = rng.uniform(margin, 0.5 * math.pi - margin, m)
    delta = rng.uniform(0.0, 1.0 - margin, m) * gamma
    beta_L = rng.uniform(margin, 1.0 - margin, m) * (math.pi - 2.0 * gamma)
    return np.column_stack([gamma, delta, beta_L, rng.uniform(-upsilon, upsilon, m)])


def residuals(name, params, points, chart="beta_L"):
    system = boundary_system(name, params, chart)
    return np.array([system.residual(system.from_x(x)) for x in points])


def reference(points, params):
    g, d, b, u = points.T
    return State(g, d, b, u, params.c)


@pytest.fixture(params=PARAMS, ids=PARAM_IDS)
def params(request):
    return request.param


@pytest.fixture
def points(params):
    return random_points(np.random.default_rng(round(1000 * params.k)), 200)


# --- residual rows of the boundary systems -----------------------------------------------------

@pytest.mark.parametrize("name", ["dr_limit", "dr_no_roll"])
def test_torque_residual_matches_equal_tangential_forces(name, params, points):
    """Row 0 of a double-rolling system is ``(T_L - T_R) / c`` with both contacts rolling."""
    s = reference(points, params)
    _, _, torque = s.balance(s.T_L, s.T_R)
    assert np.allclose(torque, s.T_R - s.T_L, atol=1e-13)  # Eq. 3 is T_L = T_R
    assert np.allclose(residuals(name, params, points)[:, 0], -torque / params.c,
                       rtol=1e-12, atol=1e-13)


@pytest.mark.parametrize("name", ["dr_limit", "dr_no_roll"])
def test_horizontal_dr_residual_matches_horizontal_force_balance(name, params, points):
    """Row 1 of a double-rolling system is the net horizontal force (Eq. 2).

    On the torque-balanced states (``upsilon`` chosen so that ``T_L = T_R``) it is the full
    Eq. 2; elsewhere the common tangential force is the left contact's.
    """
    s = reference(points, params)
    horizontal, _, _ = s.balance(s.T_L, s.T_L)
    assert np.allclose(residuals(name, params, points)[:, 1], horizontal, rtol=1e-12, atol=1e-13)

    # T_L - T_R is linear in upsilon: the torque-balanced upsilon from two evaluations
    g, d, b, _ = points.T
    f0 = State(g, d, b, 0.0, params.c)
    f1 = State(g, d, b, 1.0, params.c)
    gap0, gap1 = f0.T_L - f0.T_R, f1.T_L - f1.T_R
    balanced = np.column_stack([g, d, b, -gap0 / (gap1 - gap0)])
    s = reference(balanced, params)
    horizontal, _, torque = s.balance(s.T_L, s.T_R)
    assert np.max(np.abs(torque)) <= 1e-13
    rows = residuals(name, params, balanced)
    assert np.max(np.abs(rows[:, 0])) <= 1e-13
    assert np.allclose(rows[:, 1], horizontal, rtol=1e-12, atol=1e-13)


@pytest.mark.parametrize("name", ["rs_limit", "rs_no_roll"])
def test_right_rolls_residual_matches_rolling_force_at_left_friction_limit(name, params, points):
    """Row 0 of a rolling-sliding system is ``T_R - k N_L``: the rolling right contact's force
    equals the sliding left one's (torque, Eq. 3, with ``T_L = k N_L``)."""
    s = reference(points, params)
    expected = s.T_R - params.k * s.N_L
    assert np.allclose(residuals(name, params, points)[:, 0], expected, rtol=1e-12, atol=1e-13)


@pytest.mark.parametrize("name", ["rs_limit", "rs_no_roll"])
def test_horizontal_rs_residual_matches_horizontal_force_balance_with_sliding_left(
        name, params, points):
    """Row 1 of a rolling-sliding system is Eq. 2 with ``T_L = T_R = k N_L``."""
    s = reference(points, params)
    T = params.k * s.N_L
    horizontal, _, torque = s.balance(T, T)
    assert np.max(np.abs(torque)) <= 1e-13
    assert np.allclose(residuals(name, params, points)[:, 1], horizontal, rtol=1e-12, atol=1e-13)


def test_limit_residual_matches_left_friction_limit_and_zero_slip(params, points):
    """Row 2 of the limit systems: ``sin beta_L (T_L / N_L - k)`` with the left contact rolling
    (``dr_limit``), which is ``c d_L``, the left slip at ``T_L = k N_L`` (``rs_limit``)."""
    s = reference(points, params)
    expected = s.u_n_L * (s.T_L / s.N_L - params.k)
    slip = slip_for_friction_limit(s.u_t_L, s.u_n_L, params.k, params.c)
    sliding = State(*points.T, params.c, d_L=slip)
    assert np.allclose(sliding.T_L, params.k * sliding.N_L, rtol=1e-12, atol=1e-14)
    for name in ("dr_limit", "rs_limit"):
        rows = residuals(name, params, points)
        assert np.allclose(rows[:, 2], expected, rtol=1e-12, atol=1e-13), name
        assert np.allclose(rows[:, 2], params.c * slip, rtol=1e-12, atol=1e-13), name


def test_no_roll_residual_is_the_rolling(params, points):
    for name in ("dr_no_roll", "rs_no_roll"):
        assert np.array_equal(residuals(name, params, points)[:, 2], points[:, 3]), name


@pytest.mark.parametrize("name", BOUNDARY_NAMES)
def test_sqrt_chart_residual_matches_beta_L_chart(name, params):
    """``w = sqrt(beta_L)`` changes only the coordinate, also where ``sin(w^2)/w^2`` is a series."""
    rng = np.random.default_rng(5)
    points = random_points(rng, 100)
    points[:50, 2] = rng.uniform(1e-6, 1.5e-2, 50) ** 2  # w^2 <= 1e-4 and around it
    expected = residuals(name, params, points)
    got = residuals(name, params, points, chart="sqrt_beta_L")
    assert np.allclose(got, expected, rtol=1e-13, atol=1e-15)


# --- Jacobian rows ----------------------------------------------------------------------------

ROWS = {
    "torque": ("dr_limit", 0),
    "horizontal_dr": ("dr_no_roll", 1),
    "right_rolls": ("rs_limit", 0),
    "horizontal_rs": ("rs_no_roll", 1),
    "limit": ("dr_limit", 2),
    "no_roll": ("rs_no_roll", 2),
}


@pytest.mark.parametrize("chart", ["beta_L", "sqrt_beta_L"])
@pytest.mark.parametrize("row", list(ROWS))
def test_jacobian_row_matches_central_differences(row, chart, params):
    name, i = ROWS[row]
    system = boundary_system(name, params, chart)
    rng = np.random.default_rng(len(row))
    h = 1e-5
    for x in random_points(rng, 40):
        y = system.from_x(x)
        J = system.jacobian(y)[i]
        fd = np.array([(system.residual(y + h * e)[i] - system.residual(y - h * e)[i]) / (2 * h)
                       for e in np.eye(4)])
        assert np.allclose(J, fd, rtol=1e-7, atol=1e-7 * (1.0 + np.abs(fd).max())), (x, J, fd)


# --- validity functions -----------------------------------------------------------------------

@pytest.mark.parametrize("chart", ["beta_L", "sqrt_beta_L"])
def test_validity_functions_match_force_ratios_and_slip(chart, params, points):
    """``T_over_N_L <= k`` is ``sin beta_L (k - T_L/N_L) / r``, ``T_over_N_R <= k`` is
    ``sin beta_R (k - T_R/N_R) / r`` (rolling contacts), ``d_L >= 0`` is ``c d_L / r``, with
    ``r = sqrt(k^2 + c^2)``; the rolling-sliding boundaries carry only ``d_L >= 0`` (their
    ``T/N_R = mu <= k`` holds on the whole domain, see the steeper-wall test)."""
    s = reference(points, params)
    r = math.hypot(params.k, params.c)
    expected = {
        "T_over_N_L <= k": s.u_n_L * (params.k - s.T_L / s.N_L) / r,
        "T_over_N_R <= k": s.u_n_R * (params.k - s.T_R / s.N_R) / r,
        "d_L >= 0": params.c * slip_for_friction_limit(s.u_t_L, s.u_n_L, params.k, params.c) / r,
    }
    checks = {"dr_limit": ["T_over_N_R <= k"], "rs_limit": [],
              "dr_no_roll": ["T_over_N_L <= k", "T_over_N_R <= k"],
              "rs_no_roll": ["d_L >= 0"]}
    for name, keys in checks.items():
        system = boundary_system(name, params, chart)
        assert sorted(system.validity) == sorted(keys), name
        for key in keys:
            got = [system.validity[key](system.from_x(x)) for x in points]
            assert np.allclose(got, expected[key], rtol=1e-12, atol=1e-13), (name, key)


# --- quantities reported along a boundary -----------------------------------------------------

@pytest.mark.parametrize("name", BOUNDARY_NAMES)
def test_boundary_quantities_match_force_ratios_and_slip(name, params, points):
    q = boundary_quantities(name, points, params)
    s = reference(points, params)
    assert np.array_equal(q["beta_L"], points[:, 2]) and np.array_equal(q["upsilon"], points[:, 3])
    assert np.allclose(q["theta_L"], s.theta_L, rtol=1e-15)
    assert np.allclose(q["theta_R"], s.theta_R, rtol=1e-15, atol=1e-16)
    assert np.allclose(q["beta_R"], s.beta_R, rtol=1e-14)
    assert np.allclose(q["T_over_N_R"], s.T_R / s.N_R, rtol=1e-12, atol=1e-13)
    if name.startswith("dr"):
        assert np.allclose(q["T_over_N_L"], s.T_L / s.N_L, rtol=1e-12, atol=1e-13)
        assert np.all(q["d_L"] == 0.0)
    else:
        assert np.all(q["T_over_N_L"] == params.k)
        slip = slip_for_friction_limit(s.u_t_L, s.u_n_L, params.k, params.c)
        assert np.allclose(q["d_L"], slip, rtol=1e-12, atol=1e-13)
        assert np.allclose(State(*points.T, params.c, d_L=q["d_L"]).T_L, params.k * s.N_L,
                           rtol=1e-11, atol=1e-13)


def test_boundary_quantities_T_over_N_L_is_inf_where_N_L_vanishes():
    x = np.array([[math.pi / 4, math.pi / 4, 0.0, 0.0]])
    q = boundary_quantities("dr_no_roll", x, Parameters(2.0))
    assert q["T_over_N_L"][0] == math.inf and q["T_over_N_R"][0] == pytest.approx(0.0, abs=1e-15)


# --- the point solver -------------------------------------------------------------------------

def solver_points(params, m=300):
    rng = np.random.default_rng(round(100 * params.k) + 1)
    gamma = rng.uniform(0.03, 0.5 * math.pi - 0.03, m)
    return gamma, rng.uniform(0.01, 0.98, m) * gamma


def force_scale(s):
    return np.maximum(s.N_L, s.N_R)


def test_double_rolling_state_balances_torque_and_horizontal_force(params):
    gamma, delta = solver_points(params)
    dr = double_rolling_state(gamma, delta, params)
    s = State(gamma, delta, dr["beta_L"], dr["upsilon"], params.c)
    horizontal, vertical, torque = s.balance(s.T_L, s.T_R)
    scale = force_scale(s)
    assert np.all(np.abs(torque) <= 1e-12 * scale)
    assert np.all(np.abs(horizontal) <= 1e-12 * scale)
    assert np.all(vertical > 0.0)  # the walls hold the ball up
    assert np.allclose(dr["beta_R"], s.beta_R, rtol=1e-13, atol=1e-15)
    for key, value in (("n_L", s.N_L), ("n_R", s.N_R), ("t", s.T_L),
                       ("T_over_N_L", s.T_L / s.N_L), ("T_over_N_R", s.T_R / s.N_R)):
        assert np.allclose(dr[key], value, rtol=1e-12, atol=1e-14), key


def test_rolling_sliding_state_balances_forces_with_left_at_friction_limit(params):
    gamma, delta = solver_points(params)
    rs = rolling_sliding_state(gamma, delta, params)
    s = State(gamma, delta, rs["beta_L"], rs["upsilon"], params.c, d_L=rs["d_L"])
    # the left contact slides at T_L = k N_L, with the slip its proportional loading needs
    assert np.allclose(s.T_L, params.k * s.N_L, rtol=1e-11, atol=1e-14)
    horizontal, vertical, torque = s.balance(s.T_L, s.T_R)
    scale = force_scale(s)
    assert np.all(np.abs(torque) <= 1e-12 * scale)
    assert np.all(np.abs(horizontal) <= 1e-12 * scale)
    assert np.all(vertical > 0.0)
    assert np.allclose(rs["beta_R"], s.beta_R, rtol=1e-13, atol=1e-15)
    for key, value in (("n_L", s.N_L), ("n_R", s.N_R), ("t", s.T_R), ("mu", s.T_R / s.N_R)):
        assert np.allclose(rs[key], value, rtol=1e-12, atol=1e-14), key


def test_double_sliding_state_on_the_symmetric_line(params):
    """``delta = 0`` beyond ``arctan(k/c)``: both contacts slide at ``T = k N``."""
    gamma = np.linspace(params.gamma_limit + 1e-3, 0.5 * math.pi - 1e-3, 50)
    eq = solve_equilibrium(gamma, 0.0 * gamma, params)
    assert np.all(eq.regime == "double_sliding") and np.all(eq.rotation == "none")
    s = State(gamma, 0.0 * gamma, eq.beta_L, eq.upsilon, params.c, d_L=eq.d_L, d_R=eq.d_R)
    assert np.allclose(s.beta_R, eq.beta_R, rtol=1e-13)
    assert np.allclose(s.T_L, params.k * s.N_L, rtol=1e-12, atol=1e-14)
    assert np.allclose(s.T_R, params.k * s.N_R, rtol=1e-12, atol=1e-14)
    horizontal, vertical, torque = s.balance(s.T_L, s.T_R)
    assert np.max(np.abs(horizontal)) <= 1e-12 and np.max(np.abs(torque)) <= 1e-12
    assert np.all(vertical > 0.0) and np.all(eq.d_L > 0.0)
    for key, value in (("n_L", s.N_L), ("n_R", s.N_R), ("t", s.T_L), ("T_over_N_L", params.k),
                       ("T_over_N_R", params.k)):
        assert np.allclose(getattr(eq, key), value, rtol=1e-12, atol=1e-14), key


def solved_state(params):
    gamma, delta = solver_points(params)
    eq = solve_equilibrium(gamma, delta, params)
    s = State(gamma, delta, eq.beta_L, eq.upsilon, params.c, d_L=eq.d_L, d_R=eq.d_R)
    rs = eq.regime == "rolling_sliding"
    assert np.all(rs | (eq.regime == "double_rolling")) and rs.any()
    # Amontons on the sliding contact, proportional loading on a rolling one
    T_L = np.where(rs, params.k * s.N_L, s.T_L)
    return eq, s, rs, T_L


def test_solve_equilibrium_balances_forces_with_its_slips(params):
    eq, s, rs, T_L = solved_state(params)
    assert np.all(eq.d_R == 0.0) and np.all(eq.d_L[~rs] == 0.0) and np.all(eq.d_L[rs] >= 0.0)
    # the reported slip is the one that brings the sliding contact to T_L = k N_L
    assert np.allclose(s.T_L[rs], params.k * s.N_L[rs], rtol=1e-11, atol=1e-14)
    horizontal, vertical, torque = s.balance(T_L, s.T_R)
    assert np.all(np.abs(torque) <= 1e-12 * force_scale(s))
    assert np.all(np.abs(horizontal) <= 1e-12 * force_scale(s))
    assert np.all(vertical > 0.0)
    assert np.allclose(eq.theta_L, s.theta_L, rtol=1e-15)
    assert np.allclose(eq.theta_R, s.theta_R, rtol=1e-15, atol=1e-16)
    assert np.allclose(eq.beta_R, s.beta_R, rtol=1e-13, atol=1e-15)


def test_solve_equilibrium_forces_and_ratios_match_its_state(params):
    eq, s, _, T_L = solved_state(params)
    for key, value in (("n_L", s.N_L), ("n_R", s.N_R), ("t", s.T_R),
                       ("T_over_N_L", T_L / s.N_L), ("T_over_N_R", s.T_R / s.N_R),
                       ("N_L_over_N_R", s.N_L / s.N_R)):
        assert np.allclose(getattr(eq, key), value, rtol=1e-11, atol=1e-14), key
    assert np.all(eq.T_over_N_L <= params.k * (1 + 1e-12))
    assert np.all(eq.T_over_N_R <= params.k * (1 + 1e-12))


def test_solve_equilibrium_rotation_is_the_sign_of_upsilon(params):
    eq, _, _, _ = solved_state(params)
    clockwise, counterclockwise = eq.upsilon < 0, eq.upsilon > 0
    assert clockwise.any() and counterclockwise.any()
    assert np.all(eq.rotation[clockwise] == "clockwise")
    assert np.all(eq.rotation[counterclockwise] == "counterclockwise")


def test_steeper_wall_has_the_larger_force_ratio(params):
    """For ``delta > 0`` the left (steeper) wall is the first to reach ``T = k N`` (paper,
    "Rolling solutions" and ``mu < k``): double rolling has ``T/N_R < T/N_L`` and rolling
    sliding ``T/N_R = mu < k``. So the right-wall conditions of the regime tests never decide."""
    gamma, delta = solver_points(params)
    dr = double_rolling_state(gamma, delta, params)
    s = State(gamma, delta, dr["beta_L"], dr["upsilon"], params.c)
    assert np.all(s.T_R / s.N_R < s.T_L / s.N_L)
    rs = rolling_sliding_state(gamma, delta, params)
    s = State(gamma, delta, rs["beta_L"], rs["upsilon"], params.c)
    assert np.all(s.T_R / s.N_R < params.k)


def test_regime_validity_matches_force_ratios_and_slip(params):
    """Double rolling is valid where its ``T/N <= k`` on both walls, rolling sliding where its
    left slip is ``>= 0`` and its right ``T/N <= k``; points near a threshold are skipped."""
    gamma, delta = solver_points(params)
    dr_valid, rs_valid = regime_validity(gamma, delta, params)
    dr = double_rolling_state(gamma, delta, params)
    s = State(gamma, delta, dr["beta_L"], dr["upsilon"], params.c)
    margin_dr = np.minimum(params.k - s.T_L / s.N_L, params.k - s.T_R / s.N_R)
    rs = rolling_sliding_state(gamma, delta, params)
    s = State(gamma, delta, rs["beta_L"], rs["upsilon"], params.c)
    slip = slip_for_friction_limit(s.u_t_L, s.u_n_L, params.k, params.c)
    margin_rs = np.minimum(slip, params.k - s.T_R / s.N_R)
    clear = (np.abs(margin_dr) > 1e-9) & (np.abs(margin_rs) > 1e-9)
    assert clear.sum() > 250
    assert np.array_equal(dr_valid[clear], margin_dr[clear] > 0)
    assert np.array_equal(rs_valid[clear], margin_rs[clear] > 0)
