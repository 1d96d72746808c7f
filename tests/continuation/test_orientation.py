"""Orientation of tangents: the first tangent of ``trace`` and the bordered solve of ``tangent_at``.

The promise under test (Allgower & Georg, sec. 2.1): at a regular point the unit tangent ``t``
with ``H'(x) t = 0`` is oriented by the sign of ``det [H'(x); t^T]``; ``trace`` starts along
the one with a positive determinant unless told ``direction=-1``. Every determinant here is
computed with numpy from the returned tangent, never taken from the engine.
"""

import numpy as np
import pytest

from continuation import Options, Problem, trace
from continuation.corrector import tangent_at
from continuation.problem import Evaluator

SEEDS = range(6)
FEW_STEPS = Options(max_steps=3, ds=0.05)


def linear_problem(rng, n1):
    """``H(x) = A (x - x0)`` with a random ``A`` of shape ``(n1 - 1, n1)``; returns problem, x0."""
    A = rng.standard_normal((n1 - 1, n1))
    x0 = rng.standard_normal(n1)
    return Problem(lambda x: A @ (x - x0), lambda x: A), x0


def nonlinear_problem(rng, n1):
    """``H(x) = A x + sin(B x) / 2 - A x0 - sin(B x0) / 2``: a curve through ``x0``."""
    A = rng.standard_normal((n1 - 1, n1))
    B = rng.standard_normal((n1 - 1, n1))
    x0 = rng.standard_normal(n1)
    offset = A @ x0 + 0.5 * np.sin(B @ x0)

    def residual(x):
        return A @ x + 0.5 * np.sin(B @ x) - offset

    def jacobian(x):
        return A + 0.5 * np.cos(B @ x)[:, None] * B

    return Problem(residual, jacobian), x0


def oriented_det(J, t):
    return float(np.linalg.det(np.vstack([J, t])))


def assert_first_tangent_oriented(problem, x0, sign):
    curve = trace(problem, x0, direction=None if sign > 0 else -1, options=FEW_STEPS)
    assert len(curve.x) >= 2, curve.message
    x, t = curve.x[0], curve.tangents[0]
    J = problem.jacobian(x)
    assert np.linalg.norm(t) == pytest.approx(1.0, abs=1e-12)
    assert np.max(np.abs(J @ t)) <= 1e-9 * np.max(np.abs(J))
    det = oriented_det(J, t)
    # t is a unit null vector of J, so det [J; t^T]^2 = det (J J^T): the sign is well defined
    assert abs(det) == pytest.approx(np.sqrt(np.linalg.det(J @ J.T)), rel=1e-8)
    assert sign * det > 0
    # and the curve really leaves along it
    assert float((curve.x[1] - x) @ t) > 0
    return curve


@pytest.mark.parametrize("n1", [3, 4, 5])
@pytest.mark.parametrize("seed", SEEDS)
@pytest.mark.parametrize("make", [linear_problem, nonlinear_problem])
def test_first_tangent_has_positive_det_and_minus_one_reverses_it(make, seed, n1):
    problem, x0 = make(np.random.default_rng(1000 * n1 + seed), n1)
    forward = assert_first_tangent_oriented(problem, x0, +1)
    backward = assert_first_tangent_oriented(problem, x0, -1)
    assert np.allclose(backward.tangents[0], -forward.tangents[0], atol=1e-12)


def test_first_tangent_of_a_circle_in_space_is_the_positive_one():
    # unit circle in the plane z = 0: H = (x^2 + y^2 - 1, z); at (1, 0, 0) the tangent is
    # (0, +-1, 0) and det [[2, 0, 0], [0, 0, 1], t] = -2 t_y, so trace starts with t_y = -1
    problem = Problem(lambda x: np.array([x[0] ** 2 + x[1] ** 2 - 1.0, x[2]]),
                      lambda x: np.array([[2 * x[0], 2 * x[1], 0.0], [0.0, 0.0, 1.0]]))
    curve = trace(problem, [1.0, 0.0, 0.0], options=FEW_STEPS)
    assert np.allclose(curve.tangents[0], [0.0, -1.0, 0.0], atol=1e-12)
    assert curve.x[1][1] < 0


def constant_jacobian_evaluator(J):
    return Evaluator(Problem(lambda x: np.zeros(J.shape[0]), lambda x: J))


@pytest.mark.parametrize("n1", [2, 3, 4, 5, 8])
@pytest.mark.parametrize("seed", SEEDS)
def test_tangent_at_solves_the_bordered_system_like_numpy(n1, seed):
    rng = np.random.default_rng(7 * n1 + seed)
    J = rng.standard_normal((n1 - 1, n1))
    border = rng.standard_normal(n1)
    evaluator = constant_jacobian_evaluator(J)

    t, det = tangent_at(evaluator, rng.standard_normal(n1), border)

    assert evaluator.jacobian_evals == 1
    assert np.linalg.norm(t) == pytest.approx(1.0, abs=1e-14)
    assert np.max(np.abs(J @ t)) <= 1e-13 * np.max(np.abs(J))
    assert float(border @ t) > 0
    null = np.linalg.svd(J)[2][-1]
    assert np.allclose(t, np.sign(border @ null) * null, atol=1e-12)
    expected = oriented_det(J, t)
    assert np.sign(det) == np.sign(expected)
    assert det == pytest.approx(expected, rel=1e-10)


@pytest.mark.parametrize("seed", SEEDS)
def test_tangent_at_flips_tangent_and_det_with_the_border(seed):
    rng = np.random.default_rng(seed)
    J = rng.standard_normal((3, 4))
    border = rng.standard_normal(4)
    evaluator = constant_jacobian_evaluator(J)
    t, det = tangent_at(evaluator, np.zeros(4), border)
    t_minus, det_minus = tangent_at(evaluator, np.zeros(4), -border)
    assert np.allclose(t_minus, -t, atol=1e-14)
    assert det_minus == pytest.approx(-det, rel=1e-12)
    assert det * det_minus < 0


@pytest.mark.parametrize("J, border", [
    ([[1.0, 0.0, 0.0], [0.0, 0.0, 0.0]], [0.0, 1.0, 1.0]),  # rank-deficient Jacobian
    ([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], [1.0, 1.0, 0.0]),  # border orthogonal to the tangent
    ([[1.0, np.nan, 0.0], [0.0, 1.0, 0.0]], [0.0, 0.0, 1.0]),  # not finite
])
def test_tangent_at_reports_no_tangent_for_a_singular_bordered_matrix(J, border):
    t, det = tangent_at(constant_jacobian_evaluator(np.array(J)), np.zeros(3), np.array(border))
    assert t is None and det == 0.0
