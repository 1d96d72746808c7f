"""The point solver: balance equations, the delta = 0 line, regime exclusivity, edges."""

import math

import numpy as np
import pytest

from groove_model.model.dimensional import dimensional_state
from groove_model.model.equilibrium import (
    double_rolling_equation,
    double_rolling_state,
    regime_validity,
    solve_equilibrium,
    wall_terms,
)
from groove_model.model.parameters import Compliance, Parameters

KS = [0.01, 0.3, 1.0, math.sqrt(2.0), 2.0, 10.0, 1000.0]


def domain_grid(n_gamma=80, n_ratio=41, edges=True):
    gamma = np.linspace(0.0, 0.5 * math.pi, n_gamma)
    ratio = np.linspace(0.0, 1.0, n_ratio)
    if not edges:
        gamma, ratio = gamma[1:-1], ratio[1:-1]
    G, R = np.meshgrid(gamma, ratio)
    return G, R * G


def balance_residuals(eq, k, c=1.0):
    """Paper Eqs. 2 and 3 (unreduced) and the contact laws, from the solver's own state."""
    tL, tR = eq.theta_L, eq.theta_R
    # T_L from the left contact: proportional loading if it sticks/rolls, Amontons if it slides.
    sliding_L = np.asarray(eq.d_L) > 0.0
    sliding_R = np.asarray(eq.d_R) > 0.0
    sL, sR = np.sin(eq.beta_L), np.sin(eq.beta_R)
    T_L = np.where(sliding_L, k * eq.n_L, c * np.sqrt(sL) * (np.cos(eq.beta_L) + eq.upsilon))
    T_R = np.where(sliding_R, k * eq.n_R, c * np.sqrt(sR) * (np.cos(eq.beta_R) - eq.upsilon))
    horizontal = -T_L * np.cos(tL) + eq.n_L * np.sin(tL) + T_R * np.cos(tR) - eq.n_R * np.sin(tR)
    torque = T_L - T_R
    # Sliding contact: u_t/u_n = T/N = k with u_t = Z (cos beta_L + upsilon) - d_L.
    slide_law = np.where(sliding_L, c * (np.cos(eq.beta_L) + eq.upsilon - eq.d_L) - k * sL, 0.0)
    return horizontal, torque, slide_law


@pytest.mark.parametrize("k", KS)
def test_balance_equations_hold_at_every_solver_state(k):
    G, D = domain_grid()
    eq = solve_equilibrium(G, D, k)
    for residual in balance_residuals(eq, k):
        assert np.max(np.abs(residual)) <= 1e-12
    assert np.all(np.asarray(eq.d_L) >= 0.0) and np.all(np.asarray(eq.d_R) >= 0.0)
    assert np.allclose(eq.beta_L + eq.beta_R, math.pi - 2.0 * G, atol=1e-14)


def test_balance_with_another_compliance_ratio():
    params = Parameters(2.0, Compliance(0.6))
    G, D = domain_grid(edges=False)
    eq = solve_equilibrium(G, D, params)
    for residual in balance_residuals(eq, 2.0, 0.6):
        assert np.max(np.abs(residual)) <= 1e-12
    assert np.all(np.asarray(eq.T_over_N_L) <= 2.0 + 1e-12)


@pytest.mark.parametrize("k", KS)
def test_symmetric_line(k):
    gamma = np.linspace(0.0, 0.5 * math.pi, 201)
    eq = solve_equilibrium(gamma, 0.0 * gamma, k)
    below = gamma < math.atan(k)
    assert np.allclose(eq.beta_L, 0.5 * math.pi - gamma, atol=1e-15)
    assert np.allclose(eq.beta_R, 0.5 * math.pi - gamma, atol=1e-15)
    assert np.all(eq.upsilon == 0.0)
    assert np.allclose(eq.T_over_N_L[below], np.tan(gamma[below]), rtol=1e-13, atol=1e-15)
    assert np.all(eq.regime[below] == "double_rolling")
    assert np.all(eq.regime[~below] == "double_sliding")
    assert np.all(eq.rotation == "none")
    slip = np.sin(gamma[~below]) - k * np.cos(gamma[~below])
    assert np.allclose(eq.d_L[~below], slip) and np.allclose(eq.d_R[~below], slip)


@pytest.mark.parametrize("k", KS + [0.1, 100.0])
def test_exactly_one_regime_holds_inside_the_domain(k):
    G, D = domain_grid(121, 61, edges=False)
    dr_valid, rs_valid = regime_validity(G, D, k)
    assert np.all(dr_valid ^ rs_valid)
    eq = solve_equilibrium(G, D, k)
    assert np.array_equal(eq.regime == "double_rolling", dr_valid)


def test_domain_edges_are_solved_without_failure():
    k = 1.0
    gamma = np.array([0.0, 1e-12, 1e-6, 0.3, 0.5 * math.pi - 1e-9, 0.5 * math.pi])
    for delta in (0.0 * gamma, gamma, 0.5 * gamma, gamma * (1 - 1e-9)):
        eq = solve_equilibrium(gamma, delta, k)
        assert np.all(np.isfinite(eq.beta_L)) and np.all(np.isfinite(eq.upsilon))
        assert np.all(np.isin(eq.regime, ["double_rolling", "rolling_sliding", "double_sliding"]))
    # On delta = gamma (theta_R = 0) the left wall carries no load: beta_L = 0, rolling sliding.
    edge = solve_equilibrium(0.4, 0.4, k)
    assert edge.beta_L == 0.0 and edge.regime == "rolling_sliding"


def test_double_rolling_equation_is_increasing_and_bracketed():
    """The reduced equation increases on both half-brackets, with a sign change in the chosen one.

    Checks numerically what the docstring proves: ``P(w)`` increasing on ``[0, 1]``, so one root.
    """
    x = np.linspace(0.0, 0.5, 2001)
    for gamma in np.linspace(0.02, 0.5 * math.pi - 0.02, 40):
        for delta in np.linspace(0.02, 0.98, 25) * gamma:
            walls = wall_terms(np.array(gamma), np.array(delta))
            K = walls["E"] * walls["tan_g"]
            chosen = float(walls["rho0"] > 0.125 + 5.0 / 12.0 * K)
            for upper in (0.0, 1.0):
                values = double_rolling_equation(x, upper, walls["rho0"],
                                                  walls["one_minus_rho0"], K)
                assert np.all(np.diff(values) > 0.0), (gamma, delta, upper)
                if upper == chosen:
                    assert values[0] < 0.0 <= values[-1], (gamma, delta, upper)


def test_arrays_give_the_pointwise_results():
    """One vectorised call (both half-brackets, every regime, all scales) equals point calls."""
    rng = np.random.default_rng(1)
    gamma = np.concatenate([10.0 ** rng.uniform(-320, 0.19, 300), [0.0, 0.5 * math.pi, 0.7]])
    gamma = np.minimum(gamma, 0.5 * math.pi)
    ratio = np.concatenate([rng.uniform(0.0, 1.0, 150), 1.0 - 10.0 ** rng.uniform(-16, 0, 150),
                            [0.0, 0.5, 1.0]])
    eq = solve_equilibrium(gamma.reshape(3, -1), (ratio * gamma).reshape(3, -1), 0.3)
    for i, (g, d) in enumerate(zip(gamma, ratio * gamma)):
        point = solve_equilibrium(g, d, 0.3)
        for name, value in point.to_dict().items():
            assert np.ravel(getattr(eq, name))[i] == value or (value != value), (name, g, d)


def test_scalar_input_gives_scalars():
    eq = solve_equilibrium(0.6, 0.2, 1.0)
    assert isinstance(eq.beta_L, float) and isinstance(eq.regime, str)
    assert eq.to_dict()["regime"] == eq.regime


def test_dimensional_results_satisfy_vertical_balance_and_hertz():
    R, E, nu, M, g = 0.01, 2.0e11, 0.3, 0.033, 9.81
    G, D = domain_grid(30, 11, edges=False)
    for k in (0.5, 10.0):
        eq = solve_equilibrium(G, D, k)
        dim = dimensional_state(eq, R, E, nu, M, g)
        T = dim.T
        vertical = (T * np.sin(eq.theta_L) + dim.N_L * np.cos(eq.theta_L)
                    + T * np.sin(eq.theta_R) + dim.N_R * np.cos(eq.theta_R))
        assert np.allclose(vertical, M * g, rtol=1e-12)
        horizontal = (-T * np.cos(eq.theta_L) + dim.N_L * np.sin(eq.theta_L)
                      + T * np.cos(eq.theta_R) - dim.N_R * np.sin(eq.theta_R))
        assert np.max(np.abs(horizontal)) <= 1e-12 * M * g
        Gc = 3 * (1 - nu**2) / (4 * E)
        u_R = (Gc * dim.N_R / math.sqrt(R)) ** (2 / 3)  # Hertz approach, paper Eq. hertz
        assert np.allclose(u_R, dim.Z * np.sin(eq.beta_R), rtol=1e-12)
        assert np.allclose(dim.a_R, np.cbrt(Gc * dim.N_R * R), rtol=1e-14)


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(radius=-1.0), "radius R = -1.0 m is outside the allowed range: finite and > 0"),
        (dict(young=0.0), "Young's modulus E = 0.0 Pa is outside the allowed range"),
        (dict(poisson=0.6), "Poisson ratio nu = 0.6 is outside the allowed range -1 < nu <= 0.5"),
        # overflow is named, not returned as inf and NaN
        (dict(young=1e-300, mass=1e300), "the dimensional results overflow double precision"),
        (dict(mass=float("inf")), "mass M = inf kg is outside the allowed range"),
    ],
)
def test_dimensional_input_errors(kwargs, message):
    eq = solve_equilibrium(0.6, 0.2, 1.0)
    args = dict(radius=0.01, young=2e11, poisson=0.3, mass=0.03) | kwargs
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)")):
        dimensional_state(eq, **args)


def test_dimensional_results_of_an_incompressible_ball():
    # nu = 1/2 is allowed everywhere else (Mindlin's ratio 2/3); Hertz holds there too
    eq = solve_equilibrium(0.6, 0.2, 1.0)
    half = dimensional_state(eq, radius=0.01, young=2e11, poisson=0.5, mass=0.03)
    near = dimensional_state(eq, radius=0.01, young=2e11, poisson=0.5 - 1e-12, mass=0.03)
    assert half.Z == pytest.approx(near.Z, rel=1e-10) and math.isfinite(half.N_L)


@pytest.mark.parametrize("k", [1.0, math.sqrt(3.0), 10.0])
def test_seed_itself_is_double_rolling(k):
    """At (arctan k, 0) T/N = k exactly: still double rolling, whatever tan rounds to."""
    eq = solve_equilibrium(math.atan(k), 0.0, k)
    assert eq.regime == "double_rolling" and eq.rotation == "none"


def test_dimensional_results_refuse_the_closed_groove():
    eq = solve_equilibrium(0.5 * math.pi, 0.5 * math.pi, 1.0)
    with pytest.raises(ValueError, match=r"no dimensional equilibrium at gamma = 1.5707963267948966 rad"):
        dimensional_state(eq, 0.01, 2e11, 0.3, 0.033)


def test_dimensional_results_name_a_vertical_force_that_underflows_or_is_tiny():
    """On delta = gamma the only loaded contact grazes its wall as gamma -> 0: its vertical
    force underflows below about gamma = 1e-215 (no Z), and above, a tiny force gives a Z that
    overflows; each message names that force, not only the parameters."""
    eq = solve_equilibrium(1e-300, 1e-300, 1.0)
    with pytest.raises(ValueError, match=r"underflows where the one loaded contact meets its "
                                         r"wall at a grazing angle"):
        dimensional_state(eq, 1.0, 1.0, 0.3, 1.0)
    eq = solve_equilibrium(1e-214, 1e-214, 1.0)
    with pytest.raises(ValueError, match=r"overflow double precision \(Z is not finite\) .* "
                                         r"scaled vertical force v = 2\.\d+e-321"):
        dimensional_state(eq, 1.0, 1.0, 0.3, 1.0)


@pytest.mark.parametrize("gamma, delta, k, nu, regime", [
    (0.6557071464778439, 0.3941992214086168, 2.6034760346472745, 0.0, "double_rolling"),
    (0.5851883877175147, 0.40062835471603003, 0.5256492027925755, 0.5, "rolling_sliding"),
    (0.3011915507521871, 0.22178304388535006, 23696.860993294893, 0.0, "double_rolling"),
])
def test_a_double_rolling_root_within_rounding_of_w_one_half_is_found(gamma, delta, k, nu,
                                                                      regime):
    # the half of [0, 1] was chosen by rho0 > 1/8 + 5K/12, which rounded against P(1/2) as
    # evaluated: no sign change in the bracket, and a RuntimeError (groove solve: a traceback).
    # The regimes and w ~ 1/2 (to 5e-17) are from 40-digit solves of the balances.
    params = Parameters(k, Compliance.from_poisson(nu))
    eq = solve_equilibrium(gamma, delta, params)
    assert eq.regime == regime
    dr = double_rolling_state(np.array([gamma]), np.array([delta]), params)
    w = math.sqrt(math.sin(dr["beta_L"][0]) / math.sin(dr["beta_R"][0]))
    assert w == pytest.approx(0.5, abs=1e-15)


@pytest.mark.parametrize("gamma, delta", [(1e-9, 0.9e-9), (1.5707963267, 0.1)])
def test_dimensional_results_where_the_vertical_force_is_small_but_resolved(gamma, delta):
    # refused below an absolute 1e-12 (1.2e-13 and 1.7e-15 here), with a message naming a range
    # the gamma was in; Z = (M g / (C v))^(2/3) is finite
    eq = solve_equilibrium(gamma, delta, 1.0)
    dim = dimensional_state(eq, 0.01, 2e11, 0.3, 0.033)
    assert math.isfinite(float(dim.Z)) and float(dim.Z) > 0.0


def test_friction_is_passed_as_k():
    from groove_model import Parameters, regime_validity, solve_equilibrium

    by_keyword = solve_equilibrium(0.6, 0.2, k=1.0)
    assert by_keyword == solve_equilibrium(0.6, 0.2, 1.0)
    assert by_keyword == solve_equilibrium(0.6, 0.2, k=Parameters(1.0))
    assert regime_validity(0.6, 0.2, k=1.0) == regime_validity(0.6, 0.2, 1.0)


@pytest.mark.parametrize("k", [1e15, 1e16, 1e17, 1e300])
def test_the_closed_groove_slides_on_both_walls_for_every_k(k):
    # at gamma = pi/2 (the float) on delta = 0, T/N = c tan gamma is infinite: double sliding.
    # For k >= 1e16 arctan(k) rounds to pi/2 too, and the state was the double-rolling NaN
    eq = solve_equilibrium(math.pi / 2, 0.0, k)
    assert eq.regime == "double_sliding"
    assert all(math.isfinite(v) for v in (eq.beta_L, eq.beta_R, eq.upsilon, eq.d_L))
    assert eq.T_over_N_L == eq.T_over_N_R == k
