"""Branch points: located on a branch, tangents from the bifurcation equation, switching."""

import math
from dataclasses import replace

import numpy as np
import pytest

from continuation import (
    Event,
    Options,
    Problem,
    SpecialPoint,
    Status,
    branch_tangents,
    locate_branch_point,
    switch_branch,
    trace,
)
from continuation.events import crossed

OPTIONS = Options(max_arclength=2.0)


@pytest.fixture
def trivial_branch(pitchfork):
    return trace(pitchfork, [-1.0, 0.0], direction=[1.0, 0.0], options=OPTIONS)


def test_branch_point_located_on_the_trivial_branch(trivial_branch):
    (point,) = trivial_branch.special("branch_point")
    assert np.max(np.abs(point.x)) <= 1e-10
    assert point.s == pytest.approx(1.0, abs=1e-10)
    assert point.accuracy <= 1e-11
    assert np.allclose(np.abs(point.tangent), [1.0, 0.0])


def test_no_branch_point_reported_at_folds(cubic):
    curve = trace(cubic, [-6.0, -2.0], direction=[1.0, 0.0],
                  options=Options(fold_coordinates=(0,), max_arclength=16.0))
    assert len(curve.special("fold")) == 2
    assert curve.special("branch_point") == ()


def test_branch_tangents_of_the_pitchfork(pitchfork):
    tangents = branch_tangents(pitchfork, [0.0, 0.0])
    directions = sorted(tuple(np.round(np.abs(t), 12)) for t in tangents)
    assert directions == [(0.0, 1.0), (1.0, 0.0)]


def test_branch_tangents_of_the_transcritical(transcritical):
    tangents = branch_tangents(transcritical, [0.0, 0.0])
    products = sorted(abs(t[0] * t[1]) for t in tangents)
    assert products == pytest.approx([0.0, 0.5], abs=1e-9)


def test_branch_tangents_reject_a_regular_point(pitchfork):
    with pytest.raises(ValueError, match="is not a branch point"):
        branch_tangents(pitchfork, [1.0, 1.0])


def test_branch_tangents_reject_a_double_root_split_by_the_differences_error():
    # x^2 = lam^3 exp(lam) is a cusp at the origin, not a crossing: c = H_lam_lam = 0 there,
    # but the central differences of its Jacobian give c = -4 h^2 < 0, as if two branches met
    # at an angle of 2e-5 rad
    cusp = Problem(
        residual=lambda y: np.array([y[0] ** 2 - y[1] ** 3 * np.exp(y[1])]),
        jacobian=lambda y: np.array([[2 * y[0], -(3 * y[1] ** 2 + y[1] ** 3) * np.exp(y[1])]]))
    with pytest.raises(ValueError, match="beyond the differences' error"):
        branch_tangents(cusp, [0.0, 0.0])


def test_branch_tangents_of_branches_crossing_at_a_small_angle():
    # x^2 = 1e-9 lam^2: a true crossing at 2 atan(sqrt(1e-9)) = 6.3e-5 rad, kept
    narrow = Problem(residual=lambda y: np.array([y[0] ** 2 - 1e-9 * y[1] ** 2]),
                     jacobian=lambda y: np.array([[2 * y[0], -2e-9 * y[1]]]))
    first, second = branch_tangents(narrow, [0.0, 0.0])
    for t in (first, second):
        assert abs(t[0]) == pytest.approx(math.sqrt(1e-9 / (1 + 1e-9)), rel=1e-6)
    assert first[0] * first[1] * second[0] * second[1] < 0


@pytest.mark.parametrize("delta, offset", [(0.003, 100.0), (0.03, 100.0), (0.03, 1000.0)])
def test_branch_tangents_at_a_small_angle_far_from_the_origin(delta, offset):
    # (u - l)(u - (1 + delta) l)(1 + u^2), l = lambda - offset: the differences' step grows
    # with |x|, and so does their error; a first version of the check against a double root
    # refused these crossings (review of 2026-11-29). The extrapolated form also gives the
    # angle better than the plain differences did (1.348e-2 for 1.478e-2 at 0.03, 1000).
    def residual(x):
        u, lam = x[0], x[1] - offset
        return np.array([(u - lam) * (u - (1 + delta) * lam) * (1 + u * u)])

    def jacobian(x):
        u, lam = x[0], x[1] - offset
        q = (u - lam) * (u - (1 + delta) * lam)
        return np.array([[(2 * u - (2 + delta) * lam) * (1 + u * u) + 2 * q * u,
                          (-(2 + delta) * u + 2 * (1 + delta) * lam) * (1 + u * u)]])

    first, second = branch_tangents(Problem(residual, jacobian), [0.0, offset])
    angle = math.acos(min(1.0, abs(float(first @ second))))
    assert angle == pytest.approx(math.atan(1 + delta) - math.pi / 4, rel=1e-3)


@pytest.mark.parametrize("direction, sign", [(1, 1.0), (-1, -1.0)])
def test_switch_branch_follows_the_pitchfork_both_ways(pitchfork, trivial_branch, direction,
                                                       sign):
    (point,) = trivial_branch.special("branch_point")
    curve = switch_branch(pitchfork, point, direction=direction, options=OPTIONS)
    assert curve.status is Status.MAX_ARCLENGTH, curve.message
    assert curve.special_points[0].kind == "branch_point"
    assert curve.special_points[0].index == 0
    assert np.array_equal(curve.x[0], point.x)
    assert np.all(curve.x[1:, 1] * sign > 0)
    residuals = np.abs(curve.x[:, 1] * (curve.x[:, 0] - curve.x[:, 1] ** 2))
    assert np.all(residuals <= OPTIONS.tol)
    assert np.max(np.abs(curve.x[1:, 0] - curve.x[1:, 1] ** 2)) <= 1e-9
    assert curve.s[-1] == 2.0
    # no spurious branch point right after the start
    assert curve.special("branch_point") == (curve.special_points[0],)


def test_switch_branch_with_a_direction_array(pitchfork, trivial_branch):
    (point,) = trivial_branch.special("branch_point")
    curve = switch_branch(pitchfork, point, direction=[0.0, -1.0], options=OPTIONS)
    assert np.all(curve.x[1:, 1] < 0)


def test_switch_branch_from_an_approximate_point(pitchfork):
    curve = switch_branch(pitchfork, [0.01, 0.003], direction=1, options=OPTIONS)
    assert np.max(np.abs(curve.x[0])) <= 1e-10
    assert np.all(curve.x[1:, 1] > 0)
    assert np.max(np.abs(curve.x[1:, 0] - curve.x[1:, 1] ** 2)) <= 1e-9
    # the location and the tangents are counted
    assert curve.jacobian_evals > len(curve)


@pytest.mark.parametrize("direction, branch", [([0.0, 1.0], "parabola"), ([0.0, -1.0], "parabola"),
                                               ([1.0, 0.0], "trivial"), ([-1.0, 0.1], "trivial")])
def test_switch_branch_at_an_exact_point_chooses_by_direction(pitchfork, direction, branch):
    curve = switch_branch(pitchfork, [0.0, 0.0], direction=direction, options=OPTIONS)
    assert curve.status is Status.MAX_ARCLENGTH
    assert np.all(curve.x[1:] @ np.array(direction) > 0)
    if branch == "parabola":
        assert np.max(np.abs(curve.x[1:, 0] - curve.x[1:, 1] ** 2)) <= 1e-9
    else:
        assert np.max(np.abs(curve.x[:, 1])) <= 1e-10


def test_an_exact_branch_point_is_used_as_given_and_an_inexact_one_is_located(pitchfork):
    # (0, 0) is the branch point exactly: no search, so only the check and the tangents
    # cost evaluations; a point 1e-6 away is located by tracing through it
    exact = switch_branch(pitchfork, [0.0, 0.0], direction=[0.0, 1.0], options=OPTIONS)
    near = switch_branch(pitchfork, [1e-6, 0.0], direction=[0.0, 1.0], options=OPTIONS)
    for curve in (exact, near):
        start = curve.special_points[0]
        assert start.kind == "branch_point" and np.max(np.abs(start.x)) <= 1e-12
        assert np.max(np.abs(curve.x[1:, 0] - curve.x[1:, 1] ** 2)) <= 1e-9
    assert exact.special_points[0].accuracy == 0.0
    assert np.array_equal(exact.x[0], [0.0, 0.0])
    assert exact.jacobian_evals < near.jacobian_evals - 10


def test_switch_branch_from_the_exact_singular_point(pitchfork):
    point = locate_branch_point(pitchfork, [0.0, 0.0])
    assert np.max(np.abs(point.x)) <= 1e-10
    # from the singular point itself the current branch must be named
    curve = switch_branch(pitchfork, point, direction=-1, options=OPTIONS,
                          tangent_hint=[1.0, 0.0])
    assert np.all(curve.x[1:, 1] < 0)
    assert np.max(np.abs(curve.x[1:, 0] - curve.x[1:, 1] ** 2)) <= 1e-9


def test_switch_branch_on_the_transcritical(transcritical):
    trivial = trace(transcritical, [-1.0, 0.0], direction=[1.0, 0.0], options=OPTIONS)
    (point,) = trivial.special("branch_point")
    assert np.max(np.abs(point.x)) <= 1e-10
    for direction in (1, -1):
        curve = switch_branch(transcritical, point, direction=direction, options=OPTIONS)
        assert np.max(np.abs(curve.x[:, 1] - curve.x[:, 0])) <= 1e-9
        assert np.all(np.sign(curve.x[1:, 0]) == direction)


def test_switch_branch_needs_to_know_the_current_branch(pitchfork):
    point = SpecialPoint("branch_point", "branch point", 0, np.zeros(2), 0.0, 0.0, 0.0)
    with pytest.raises(ValueError, match="cannot tell the new branch"):
        switch_branch(pitchfork, point, options=OPTIONS)


def test_no_branch_point_nearby(circle):
    with pytest.raises(ValueError, match="no branch point found"):
        locate_branch_point(circle, [1.0, 0.1])


def test_branch_points_on_a_curved_branch_and_switching_at_both():
    # the parabola u = lambda^2 / 2 crosses the line u = lambda at (0, 0) and (2, 2)
    problem = Problem(
        lambda x: np.array([(x[1] - x[0] ** 2 / 2) * (x[0] - x[1])]),
        lambda x: np.array([[-x[0] * (x[0] - x[1]) + (x[1] - x[0] ** 2 / 2),
                             (x[0] - x[1]) - (x[1] - x[0] ** 2 / 2)]]))
    parabola = trace(problem, [-1.0, 0.5], direction=[1.0, 0.0],
                     options=Options(max_arclength=5.0))
    points = parabola.special("branch_point")
    assert len(points) == 2
    for point, expected in zip(points, ([0.0, 0.0], [2.0, 2.0])):
        assert np.max(np.abs(point.x - expected)) <= 1e-10
        for direction in (1, -1):
            line = switch_branch(problem, point, direction=direction,
                                 options=Options(max_arclength=0.5))
            assert line.status is Status.MAX_ARCLENGTH
            assert np.max(np.abs(line.x[:, 1] - line.x[:, 0])) <= 1e-10
            assert np.sign(line.x[-1, 0] - expected[0]) == direction


def test_no_fold_reported_at_the_start_of_a_switched_branch():
    # a pitchfork at (0.3, 0.7): the new branch lambda - 0.3 = (u - 0.7)^2 is stationary in
    # lambda at the branch point itself. That is the start, not a fold of the first step,
    # though the computed branch tangent has a lambda component of +-2e-17.
    shifted = Problem(lambda x: np.array([(x[1] - 0.7) * (x[0] - 0.3 - (x[1] - 0.7) ** 2)]),
                      lambda x: np.array([[x[1] - 0.7, x[0] - 0.3 - 3.0 * (x[1] - 0.7) ** 2]]))
    options = replace(OPTIONS, fold_coordinates=(0,))
    for start in ([0.3, 0.7], [0.3 + 1e-6, 0.7]):
        for direction in ([0.0, 1.0], [0.0, -1.0]):
            curve = switch_branch(shifted, start, direction=direction, options=options)
            assert curve.ok and not curve.special("fold"), (start, direction)


def _branch_pair(gap: float) -> Problem:
    # x = (lambda, u): u ((lambda - 1)(lambda - 1 - gap) - u^2); on u = 0 the determinant
    # det [H'; t^T] = (lambda - 1)(lambda - 1 - gap) (times the orientation) dips below zero
    # between two branch points, at lambda = 1 and 1 + gap
    return Problem(
        lambda x: np.array([x[1] * ((x[0] - 1.0) * (x[0] - 1.0 - gap) - x[1] ** 2)]),
        lambda x: np.array([[x[1] * (2.0 * x[0] - 2.0 - gap),
                             (x[0] - 1.0) * (x[0] - 1.0 - gap) - 3.0 * x[1] ** 2]]))


@pytest.mark.parametrize("gap", [0.005, 0.01, 0.05, 0.1, 0.15])
def test_two_branch_points_inside_one_step_are_both_found(gap):
    # the determinant has the same sign at both ends of the step that holds both (a sign
    # test of the ends alone misses them); its model from the exact slopes dips through zero
    curve = trace(_branch_pair(gap), [0.0, 0.0], direction=[1.0, 0.0],
                  options=Options(max_arclength=3.0))
    assert curve.ok
    points = curve.special("branch_point")
    assert [round(float(p.x[0]), 9) for p in points] == [1.0, round(1.0 + gap, 9)]
    for point in points:
        assert abs(point.x[1]) <= 1e-12


def test_branch_points_where_a_line_cuts_a_circle_near_its_tangent():
    # a line that nearly touches a circle cuts it at two close points: both are branch
    # points of (line)(circle) = 0 traced along the line (before, 50 of 100 such lines
    # showed neither)
    rng = np.random.default_rng(7)
    for _ in range(100):
        angle = rng.uniform(0.0, np.pi)
        v = np.array([np.cos(angle), np.sin(angle)])
        n = np.array([-v[1], v[0]])
        centre, radius = rng.uniform(-1.0, 1.0, 2), 10.0 ** rng.uniform(-2.0, 0.0)
        distance = radius * rng.uniform(0.0, 1.0) ** 0.2
        foot = centre + distance * n

        def residual(x, n=n, foot=foot, centre=centre, radius=radius):
            return np.array([(n @ (x - foot)) * ((x - centre) @ (x - centre) - radius ** 2)])

        def jacobian(x, n=n, foot=foot, centre=centre, radius=radius):
            line, circle = n @ (x - foot), (x - centre) @ (x - centre) - radius ** 2
            return np.array([n * circle + 2.0 * line * (x - centre)])

        half = np.sqrt(radius ** 2 - distance ** 2)
        curve = trace(Problem(residual, jacobian), foot - (half + 1.0) * v, direction=v,
                      options=Options(max_arclength=2.0 * half + 2.0))
        points = curve.special("branch_point")
        assert curve.ok and len(points) == 2, (2.0 * half, curve.message)
        for point, expected in zip(points, (foot - half * v, foot + half * v), strict=True):
            assert np.max(np.abs(point.x - expected)) <= 1e-8


def test_det_slope_is_the_derivative_of_the_determinant_along_the_curve():
    from continuation.options import Options as _Options
    from continuation.problem import Evaluator
    from continuation.node import Node
    from continuation.scan import StepScan

    gap = 0.1
    evaluator = Evaluator(_branch_pair(gap))
    nodes = []
    for lam in (0.5, 1.05, 1.7):
        x, t = np.array([lam, 0.0]), np.array([1.0, 0.0])
        bordered = np.vstack([evaluator.jacobian(x), t])
        nodes.append(Node(x, lam, t, float(np.linalg.det(bordered)), 0.0, 0, []))
    scan = StepScan(evaluator, _Options(), [], nodes[0], nodes[-1])
    for node in nodes:
        lam = node.x[0]
        # det [[0, (l - 1)(l - 1 - g)], [1, 0]] = -(l - 1)(l - 1 - g)
        assert node.det == pytest.approx(-(lam - 1.0) * (lam - 1.0 - gap), abs=1e-15)
        assert scan.det_slope(node) == pytest.approx(-(2.0 * lam - 2.0 - gap), abs=1e-6)


@pytest.mark.parametrize("mu", [0.01, 0.011018063301098219, 0.012139771890700746,
                                0.016237767391887217, 0.05])
def test_a_step_onto_the_crossing_branch_is_rejected(mu):
    # x = (lambda, u): u (mu lambda - u^2); the parabola lambda = u^2 / mu turns sharply at
    # the branch point (0, 0), where the line u = 0 crosses it. With ds_max = 0.5 a step
    # from the parabola used to land on the line (its tangent turned within max_angle) and
    # the run went on there, ok; the arc of such a step bends unlike the curvature at its
    # ends, so it is rejected and the parabola is followed through the branch point.
    problem = Problem(lambda x: np.array([x[1] * (mu * x[0] - x[1] ** 2)]),
                      lambda x: np.array([[mu * x[1], mu * x[0] - 3.0 * x[1] ** 2]]))
    curve = trace(problem, [0.36 / mu, -0.6], direction=[0.0, 1.0],
                  options=Options(ds_max=0.5, max_arclength=3.0 + 0.36 / mu))
    assert curve.ok
    assert np.all(np.abs(mu * curve.x[:, 0] - curve.x[:, 1] ** 2) <= 1e-8 * (1 + curve.x[:, 0]))
    assert curve.x[-1, 1] > 0.1  # through the branch point, on the parabola
    (point,) = curve.special("branch_point")
    assert np.max(np.abs(point.x)) <= 1e-8


@pytest.mark.parametrize(("a1", "b1", "a2", "b2", "l0", "ds_max"), [
    (-50.55975390074684, 1.5906402313231438, -0.07236779875416668, 1.566259026500276,
     -0.2093150645983881, 1.110594396468765),
    (-2.0002867931385544, -2.3049553211002665, 0.3128284692240248, -2.28940325741729,
     -0.437239338164912, 0.457086854102373),
    (1.7169785705739622, 0.6115973107692956, -0.011037457861826435, 0.6439123452098285,
     -0.24819848724955357, 0.18217300174131434),
    (-1.0247300437535372, -1.024671597860571, -3.4672344662764676, -1.0754124145111699,
     -0.6419323514293872, 1.4360810315562955),
])
def test_a_step_past_a_branch_point_stays_on_its_branch(a1, b1, a2, b2, l0, ds_max):
    # the parabolas u = a_i l^2 + b_i l cross at l = 0 and l = (b2 - b1)/(a1 - a2) at small
    # angles (0.02-0.05 rad); traced along the first, a step past a crossing used to land on
    # the second and go on there, ok. Now a step past a branch point must meet its own branch
    # again, corrected from the branch point along the incoming branch's tangent (from the
    # bifurcation equation), else it is retaken shorter.
    def first(lam):
        return a1 * lam * lam + b1 * lam

    def second(lam):
        return a2 * lam * lam + b2 * lam

    problem = Problem(
        lambda x: np.array([(x[1] - first(x[0])) * (x[1] - second(x[0]))]),
        lambda x: np.array([[-(2 * a1 * x[0] + b1) * (x[1] - second(x[0]))
                             - (2 * a2 * x[0] + b2) * (x[1] - first(x[0])),
                             (x[1] - second(x[0])) + (x[1] - first(x[0]))]]))
    curve = trace(problem, [l0, first(l0)], direction=[1.0, 2 * a1 * l0 + b1],
                  options=Options(ds=min(0.05, ds_max), ds_max=ds_max, max_arclength=4.0))
    assert curve.ok, curve.message
    lam = curve.x[:, 0]
    assert np.max(np.abs(curve.x[:, 1] - first(lam)) / (1.0 + np.abs(curve.x[:, 1]))) <= 1e-4
    crossings = [c for c in (0.0, (b2 - b1) / (a1 - a2)) if lam.min() < c < lam.max()]
    points = curve.special("branch_point")
    assert len(points) == len(crossings)
    for point, crossing in zip(points, sorted(crossings), strict=True):
        assert abs(point.x[0] - crossing) <= 1e-6


@pytest.mark.parametrize("scale", [1.0, 1e-4, 1e-6, 1e-7])
def test_branch_points_of_a_small_curve_near_the_origin(scale):
    # x = scale z, z1 = z0 + 3 z0^2 crossed by z1 = -z0 at z = 0 and (-2/3, 2/3), steps
    # scaled with the curve: the differences along the tangent (curvature, slope of det,
    # branch tangents) must shrink with it (an absolute 1e-7 spans a good part of the
    # curve at 1e-6, and the steps near the branch point were all rejected)
    def residual(x):
        z = x / scale
        return np.array([(z[1] - z[0] - 3.0 * z[0] ** 2) * (z[1] + z[0])])

    def jacobian(x):
        z = x / scale
        first, second = z[1] - z[0] - 3.0 * z[0] ** 2, z[1] + z[0]
        return np.array([[-(1.0 + 6.0 * z[0]) * second + first, first + second]]) / scale

    end = Event("z0 = 1", lambda x: x[0] / scale - 1.0, terminal=True)
    curve = trace(Problem(residual, jacobian), scale * np.array([-1.0, 2.0]),
                  direction=[1.0, -5.0], events=[end],
                  options=Options(ds=0.05 * scale, ds_max=0.2 * scale, ds_min=1e-12 * scale,
                                  max_arclength=100.0 * scale))
    assert curve.status is Status.TERMINAL_EVENT, curve.message
    z = curve.x / scale
    assert np.max(np.abs(z[:, 1] - z[:, 0] - 3.0 * z[:, 0] ** 2)) <= 1e-6
    points = [p.x / scale for p in curve.special("branch_point")]
    assert len(points) == 2
    assert np.max(np.abs(points[0] - [-2.0 / 3.0, 2.0 / 3.0])) <= 1e-6
    assert np.max(np.abs(points[1])) <= 1e-6


@pytest.mark.parametrize(("n", "scale"), [(3, 1e-8), (5, 1e-6), (5, 1e-12)])
def test_switching_where_the_determinant_is_tiny(n, scale):
    # the pitchfork u (lambda - u^2) with n - 1 equations x_j = sin(lambda), all times a
    # small factor: det [H'; t^T] ~ scale^n at the first step from the branch point; the
    # zero at the singular start (1e-300 on the side det moves to) times that underflowed to 0
    # and read as a branch point at the start, and the switch failed after ~30 rejections
    def residual(x):
        return scale * np.array([x[1] * (x[0] - x[1] ** 2)]
                                + [x[j] - math.sin(x[0]) for j in range(2, n + 1)])

    def jacobian(x):
        matrix = np.zeros((n, n + 1))
        matrix[0, 0], matrix[0, 1] = x[1], x[0] - 3.0 * x[1] ** 2
        for j in range(2, n + 1):
            matrix[j - 1, 0], matrix[j - 1, j] = -math.cos(x[0]), 1.0
        return scale * matrix

    problem = Problem(residual, jacobian)
    x0 = np.array([-1.0, 0.0] + [math.sin(-1.0)] * (n - 1))
    line = trace(problem, x0, direction=np.eye(n + 1)[0],
                 events=[Event("lambda = 1", lambda x: x[0] - 1.0, terminal=True)])
    (point,) = line.special("branch_point")
    branch = switch_branch(problem, point, options=Options(max_arclength=1.0))
    assert branch.ok and branch.rejected_steps == 0, branch.message
    assert np.max(np.abs(branch.x[:, 0] - branch.x[:, 1] ** 2)) <= 1e-8


def test_a_crossing_is_judged_by_signs_not_by_a_product_that_underflows():
    assert not crossed(1e-300, 7.5e-25) and crossed(1e-300, -7.5e-25)
    assert crossed(-1e-300, 0.0) and not crossed(0.0, -1.0)
    assert not crossed(1.0, math.nan) and not crossed(math.nan, -1.0)


@pytest.mark.parametrize("c", [300.0, 5000.0, 1e5])
@pytest.mark.parametrize("side", [1.0, -1.0])
def test_a_fold_in_the_first_step_off_a_pitchfork_is_located_where_it_is(c, side):
    # new branch lam = u^2 - c u^4, folds in lam at u = +-1/sqrt(2 c), inside the first step;
    # its tangent (0, 1) at the branch point has t_lam = 0, and trials within 1e-12 of it
    # round to t_lam = 0 as well: the fold was reported there, at the branch point, and the
    # real one was lost (found in review)
    problem = Problem(lambda z: np.array([z[1] * (z[0] - z[1] ** 2 + c * z[1] ** 4)]),
                      lambda z: np.array([[z[1], z[0] - 3 * z[1] ** 2 + 5 * c * z[1] ** 4]]))
    curve = switch_branch(problem, np.zeros(2), direction=np.array([0.0, side]),
                          options=Options(fold_coordinates=(0,), max_steps=20))
    folds = [p.x for p in curve.special("fold")]
    u = side / np.sqrt(2.0 * c)
    assert len(folds) == 1 and folds[0] == pytest.approx([u * u - c * u ** 4, u], abs=1e-10)
