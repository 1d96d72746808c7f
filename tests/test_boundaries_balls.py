"""The boundary formulas in ball arithmetic: one source, every float value inside its ball."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from continuation.certify_input import jacobian_mismatch
from continuation.krawczyk import derivative
from continuation.numbers import FLOATS, Jet, jets
from groove_model.model import deflation
from groove_model.model.boundaries import BOUNDARY_NAMES, BoundarySystem
from groove_model.model.parameters import Compliance, Parameters
from groove_model.tracing import trace_boundaries

pytest.importorskip("flint")

from continuation.numbers import balls  # noqa: E402

B = balls()


def systems(params, x):
    for name in BOUNDARY_NAMES:
        for chart in ("beta_L", "sqrt_beta_L"):
            yield BoundarySystem(name, params, chart)
        # The float quadrature of the deflated torque is exact to rounding where both contact
        # angles exceed about 0.3 (along dr_no_roll beta_L + beta_R = pi - 2 gamma >= 1.23);
        # closer to beta = 0 its error grows (1e-10 at beta ~ 0.05), which balls bound.
        if name != "rs_no_roll" and (name != "dr_no_roll" or math.pi - 2 * x[0] >= 1.2):
            yield BoundarySystem(name, params, "sqrt_beta_L", 0.5, conditioned=True)


@st.composite
def points(draw):
    gamma = draw(st.floats(0.05, 0.5 * math.pi - 0.05))
    delta = draw(st.floats(0.0, 1.0)) * gamma
    beta_L = draw(st.floats(0.02, 0.98)) * (math.pi - 2 * gamma)
    return np.array([gamma, delta, beta_L, draw(st.floats(-2.0, 2.0))])


def inside(ball, value: float) -> bool:
    """Whether the float value lies in the ball, up to the float evaluation's own rounding
    (amplified up to 1e-12 where a quotient cancels): a formula that drifted would be off by
    far more."""
    slack = 1e-11 * (1.0 + abs(value))
    return abs(float(ball.mid()) - value) <= float(ball.rad()) + slack


@settings(max_examples=40, deadline=None)
@given(x=points(), k=st.floats(0.01, 1000.0), c=st.sampled_from([1.0, 0.6]),
       width=st.sampled_from([0.0, 1e-9, 1e-4]), offset=st.floats(-1.0, 1.0))
def test_float_values_lie_in_their_balls(x, k, c, width, offset):
    for system in systems(Parameters(k, Compliance(c)), x):
        y = system.from_x(x)
        box = [B.arb(v, width * (1 + abs(v))) for v in y]
        inner = y + offset * width * (1 + np.abs(y)) * 0.99
        H, J = system.residual_and_jacobian(inner)
        Hb, Jb = system.residual(box, B), system.jacobian(box, B)
        assert all(inside(h, v) for h, v in zip(Hb, H)), system
        assert all(inside(Jb[i][j], J[i, j]) for i in range(3) for j in range(4)), system
        for f in system.validity.values():
            assert inside(f(box, B), f(inner))
        assert inside(system.edge_function(box, B), system.edge_function(inner))


@pytest.mark.parametrize("d", [0.0, 1e-9, 1e-3, 0.049, 0.051, 0.2, 0.59, 0.61])
def test_the_deflated_torque_is_enclosed_across_its_switches(d):
    """Floats switch between quadrature and quotient at |d| = 0.05, balls at 0.3 and 0.6."""
    system = BoundarySystem("dr_no_roll", Parameters(10.0), "sqrt_beta_L", conditioned=True)
    gamma = 0.9
    beta_L = 0.5 * (math.pi - 2 * gamma + d)  # beta_L - beta_R = d
    y = [gamma, 0.1, math.sqrt(beta_L), 0.0]
    H, J = system.residual_and_jacobian(np.array(y))
    Hb, Jb = system.residual(y, B), system.jacobian(y, B)
    # the float quotient's rounding is amplified by 1/d^2 next to its switch: 1e-12
    assert abs(float(Hb[0].mid()) - H[0]) <= float(Hb[0].rad()) + 1e-13
    assert float(Hb[0].rad()) < 1e-12
    assert all(abs(float(Jb[0][j].mid()) - J[0, j]) <= float(Jb[0][j].rad()) + 1e-12
               for j in range(4))
    assert max(float(v.rad()) for v in Jb[0]) < 1e-10


def test_jets_of_the_jacobian_match_central_differences():
    system = BoundarySystem("dr_no_roll", Parameters(10.0), "sqrt_beta_L", conditioned=True)
    y = np.array([0.95, 0.02, 0.785, 0.0])
    for j in range(4):
        e = np.eye(4)[j]
        x = [Jet(B.number(v), B.number(e[i])) for i, v in enumerate(y)]
        JJ = system.jacobian(x, jets(B))
        h = 1e-6
        fd = (system.jacobian(y + h * e) - system.jacobian(y - h * e)) / (2 * h)
        for r in range(3):
            for col in range(4):
                d = JJ[r][col].d if type(JJ[r][col]) is Jet else B.number(0.0)
                assert abs(float(d.mid()) - fd[r, col]) <= float(d.rad()) + 1e-7


@pytest.mark.parametrize(("k", "nu"), [(1e-4, 0.3), (1.0, 0.3), (10.0, 0.0), (1e6, 0.5)])
def test_the_jacobians_are_the_derivatives_of_the_residuals_along_the_traced_boundaries(k, nu):
    # the certificate takes each Jacobian to be the derivative of its residual: at every traced
    # point, against the residual's forward-mode jets (certify's own check, to 1e-8)
    params = Parameters(k, Compliance.from_poisson(nu))
    for name, curve in trace_boundaries(params).curves.items():
        if name.endswith("limit"):
            system = BoundarySystem("dr_limit", params, "sqrt_beta_L",
                                    min(1.0, params.gamma_limit), conditioned=True)
        else:
            system = BoundarySystem(name, params, "sqrt_beta_L",
                                    conditioned=name == "dr_no_roll")
        assert jacobian_mismatch(curve.engine[0], system) is None, name


@pytest.mark.parametrize("k", [0.3, 1.0, 10.0])
def test_the_edge_function_has_the_sign_of_gamma_minus_delta_on_the_boundaries(k):
    from groove_model.tracing import trace_boundaries

    params = Parameters(k)
    for name, curve in trace_boundaries(k).curves.items():
        system = BoundarySystem(name, params, "sqrt_beta_L")
        for x in curve.x:
            theta_R = x[0] - x[1]
            value = system.edge_function(system.from_x(x), FLOATS)
            if abs(theta_R) > 1e-9:
                assert np.sign(value) == np.sign(theta_R), (name, x)


@settings(max_examples=25, deadline=None)
@given(x=points(), k=st.floats(0.01, 1000.0), c=st.sampled_from([1.0, 0.6]),
       direction=st.lists(st.floats(-1.0, 1.0), min_size=4, max_size=4),
       width=st.sampled_from([0.0, 1e-9]))
def test_the_jacobians_derivatives_from_the_residual_agree_with_the_jacobians_jets(
        x, k, c, direction, width):
    # certification takes the slopes and curvatures of the fold functions from the residual
    # alone (gradients over jets: second and third derivatives, the quadrature's remainder
    # by Cauchy's estimates); both are enclosures of one thing, so they must overlap
    m = jets(B)
    for system in systems(Parameters(k, Compliance(c)), x):
        y = system.from_x(x)
        box = [B.arb(v, width * (1 + abs(v))) for v in y]
        for second in (False, True):
            line = [Jet(b, B.number(dj), B.number(0.0) if second else None)
                    for b, dj in zip(box, direction, strict=True)]
            ours, theirs = derivative(system, line, m), system.jacobian(line, m)
            for row, their_row in zip(ours, theirs, strict=True):
                for got, want in zip(row, their_row, strict=True):
                    for part in ("v", "d", "dd") if second else ("v", "d"):
                        g, w = (getattr(z, part) if type(z) is Jet else
                                (z if part == "v" else B.number(0.0)) for z in (got, want))
                        assert B.number(g).overlaps(B.number(w)), (system, part, g, w)
                        if width == 0.0 and part != "dd":
                            assert B.is_finite(B.number(g)), (system, part)


@pytest.mark.parametrize("rule", deflation.BALL_RULES)
def test_every_ball_quadrature_of_the_deflated_torque_encloses_it(rule, monkeypatch):
    # the ball quadrature takes the fewest points whose remainder is estimated below
    # BALL_TOLERANCE; each rule, taken first (an infinite tolerance) ahead of the most
    # accurate one, must enclose g and its derivatives with its own remainder (with the
    # remainder of another rule, the cheap ones miss by far)
    mpmath = pytest.importorskip("mpmath")
    mpmath.mp.dps = 50

    def g_exact(gamma, w):
        beta_L = w * w
        beta_R = mpmath.pi - 2 * gamma - beta_L
        d = beta_L - beta_R
        if d == 0:
            return mpmath.diff(lambda b: mpmath.sqrt(mpmath.sin(b)) * mpmath.cos(b), beta_R)
        f = [mpmath.sqrt(mpmath.sin(b)) * mpmath.cos(b) for b in (beta_L, beta_R)]
        return (f[0] - f[1]) / d

    def encloses(ball, exact):
        return abs(float(ball.mid()) - float(exact)) <= float(ball.rad()) * (1 + 1e-9) + 1e-300

    system = BoundarySystem("dr_no_roll", Parameters(10.0), "sqrt_beta_L", conditioned=True)
    monkeypatch.setattr(deflation, "BALL_RULES", (rule, deflation.BALL_RULES[-1]))
    monkeypatch.setattr(deflation, "BALL_TOLERANCE", math.inf)
    for gamma in (0.7, 0.9, 1.1):
        for d in (0.0, 1e-6, 0.01, 0.1, 0.3, 0.59):
            y = [gamma, 0.1, math.sqrt(0.5 * (math.pi - 2 * gamma + d)), 0.0]
            exact = [mpmath.mpf(v) for v in y]
            value = system.residual(y, B)[0]
            assert encloses(value, g_exact(exact[0], exact[2])), (rule, gamma, d)
            row = derivative(system, [B.number(v) for v in y], B)[0]
            for j in (0, 2):  # g depends on gamma and w
                slope = mpmath.diff(lambda t: g_exact(*[exact[i] + (t if i == j else 0)
                                                        for i in (0, 2)]), 0)
                assert encloses(row[j], slope), (rule, gamma, d, j)


def test_the_cheapest_ball_quadrature_is_taken(monkeypatch):
    # close to the symmetric family a few points suffice; the remainder of the one taken is
    # below the tolerance there, and at |d| = 0.5 the cheap rules are not taken
    system = BoundarySystem("dr_no_roll", Parameters(10.0), "sqrt_beta_L", conditioned=True)
    taken = []
    gauss_legendre = B.gauss_legendre

    def recording(n, panels=1):
        taken.append((n, panels))
        return gauss_legendre(n, panels)

    monkeypatch.setattr(B, "gauss_legendre", recording)
    radii = []
    for d in (0.01, 0.5):
        taken.clear()
        radii.append(float(system.residual([0.9, 0.1, math.sqrt(0.5 * (math.pi - 1.8 + d)),
                                            0.0], B)[0].rad()))
        n, panels = taken[0]
        assert (n * panels <= 6) if d == 0.01 else (n * panels >= 10), (d, taken)
    assert radii[0] <= 10.0 * deflation.BALL_TOLERANCE
    # at 128 bits (square_box's second try) the rule is chosen for the balls' rounding, not
    # for 1e-13: a remainder of 4e-15 once stopped it where 53 bits could not decide
    monkeypatch.undo()
    with B.precision(128):
        y = [0.9, 0.1, math.sqrt(0.5 * (math.pi - 1.8 + 0.01)), 0.0]
        assert float(system.residual(y, B)[0].rad()) < 1e-36
