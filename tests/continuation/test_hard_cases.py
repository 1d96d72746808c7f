"""Hard cases for special-point detection and failure handling: each reproduces a way an
engine can return a wrong curve with an ok status, and shows the behaviour instead.

Pairs of zeros inside one step, a zero at the start with another in the first step, a fold
next to a terminal event, events that are not finite, exceptions and wrong shapes from the
user's functions, and a cusp where ``|H| <= tol`` holds far from the curve.
"""

import math

import numpy as np
import pytest

from continuation import (
    CallbackError,
    CallbackShapeError,
    ContinuationError,
    Event,
    Options,
    Problem,
    Status,
    box_events,
    trace,
)

#: long steps, so that the special points below fall inside one step
COARSE = Options(ds=0.5, ds_max=0.5, fold_coordinates=(0,), detect_closed=False)


def axis():
    """The x[0]-axis, ``H(x) = x[1]``: every step is exact, only the events matter."""
    return Problem(lambda x: np.array([x[1]]), lambda x: np.array([[0.0, 1.0]]))


def test_two_zeros_of_an_event_inside_one_step_are_both_found():
    # (x - 1)^2 - 1e-4 has zeros at 0.99 and 1.01: one step of length 0.5 holds both, and the
    # event has the same sign at its ends
    pair = Event("pair", lambda x: (x[0] - 1.0) ** 2 - 1e-4)
    curve = trace(axis(), [0.0, 0.0], direction=[1.0, 0.0], events=[pair],
                  options=COARSE.__class__(ds=0.5, ds_max=0.5, max_arclength=3.0))
    assert curve.ok
    zeros = [p.x[0] for p in curve.special("event")]
    assert zeros == pytest.approx([0.99, 1.01], abs=1e-12)


def test_a_symmetric_pair_of_zeros_does_not_cancel():
    # the groove's validity functions are even in w = sqrt(beta_L): k w^2 - 1 has zeros at
    # +-1e-3, symmetric about w = 0, crossed by one step from w = 0.2 to w = -0.2
    even = Event("even", lambda x: 1e6 * x[0] ** 2 - 1.0)
    curve = trace(axis(), [0.2, 0.0], direction=[-1.0, 0.0], events=[even],
                  options=Options(ds=0.4, ds_max=0.4, max_arclength=0.4))
    assert [p.x[0] for p in curve.special("event")] == pytest.approx([1e-3, -1e-3], abs=1e-12)


def test_a_zero_at_the_start_is_no_crossing_but_one_in_the_first_step_is():
    # x (x - 0.01): zero at the start x = 0, whose side is taken from the derivative, and a
    # second zero at 0.01 inside the first step (same sign at the step's ends as at the start)
    event = Event("start and near", lambda x: x[0] * (x[0] - 0.01))
    curve = trace(axis(), [0.0, 0.0], direction=[1.0, 0.0], events=[event],
                  options=Options(ds=0.5, ds_max=0.5, max_arclength=1.0))
    (found,) = curve.special("event")
    assert found.x[0] == pytest.approx(0.01, abs=1e-12)
    assert found.index > 0


@pytest.mark.parametrize("epsilon", [1e-2, 1e-4, 1e-6])
def test_a_fold_next_to_a_terminal_event_is_found(epsilon):
    # x0 = x1^3 - eps x1^2 turns in x0 at x1 = 2 eps / 3 and is stationary at x1 = 0, where the
    # terminal event ends it: the structure of the groove's rs_no_roll next to its corner
    problem = Problem(lambda x: np.array([x[0] - x[1] ** 3 + epsilon * x[1] ** 2]),
                      lambda x: np.array([[1.0, -3.0 * x[1] ** 2 + 2.0 * epsilon * x[1]]]))
    stop = box_events(lower={1: 0.0})
    curve = trace(problem, [1.0 - epsilon, 1.0], direction=[0.0, -1.0], events=stop,
                  options=Options(ds=0.2, ds_max=0.5, fold_coordinates=(0,)))
    assert curve.status is Status.TERMINAL_EVENT
    assert curve.x[-1, 1] == pytest.approx(0.0, abs=1e-12)
    inner = [p for p in curve.special("fold") if p.index < len(curve) - 1]
    assert len(inner) == 1
    assert inner[0].x[1] == pytest.approx(2.0 * epsilon / 3.0, rel=1e-9, abs=1e-12)


def test_a_fold_inside_a_long_step_is_found_and_the_points_agree():
    # the circle traced with long steps: every fold in x[0] and x[1] is found, and the points
    # turn only where a fold is reported
    circle = Problem(lambda x: np.array([x[0] ** 2 + x[1] ** 2 - 1.0]),
                     lambda x: np.array([[2.0 * x[0], 2.0 * x[1]]]))
    curve = trace(circle, [0.6, 0.8], options=Options(ds=0.4, ds_max=0.4, max_angle=1.5,
                                                       fold_coordinates=(0, 1)))
    assert curve.status is Status.CLOSED
    folds = {(round(p.x[0]), round(p.x[1])) for p in curve.special("fold")}
    assert folds == {(1, 0), (0, 1), (-1, 0), (0, -1)}


def test_an_event_that_is_not_finite_ends_the_curve_as_a_failure():
    hole = Event("hole", lambda x: math.nan if x[0] > 0.7 else x[0] - 2.0)
    curve = trace(axis(), [0.0, 0.0], direction=[1.0, 0.0], events=[hole],
                  options=Options(max_arclength=2.0))
    assert curve.status is Status.EVENT_NOT_FINITE and not curve.ok
    assert "hole" in curve.message and "nan" in curve.message
    assert len(curve) > 1 and np.all(curve.x[:, 0] <= 0.7)


def test_an_event_not_finite_at_the_start_is_a_failure():
    bad = Event("bad", lambda x: math.inf)
    curve = trace(axis(), [0.0, 0.0], direction=[1.0, 0.0], events=[bad])
    assert curve.status is Status.EVENT_NOT_FINITE and "at the start" in curve.message


def test_an_event_whose_zero_cannot_be_reached_is_a_failure_not_ok():
    # the zero of the event at x = 1 lies where the residual is not finite: the step over it
    # cannot be resolved, and the curve ends before it with a failure status
    def residual(x):
        return np.array([x[1] if abs(x[0] - 1.0) > 1e-3 else math.nan])

    problem = Problem(residual, lambda x: np.array([[0.0, 1.0]]))
    curve = trace(problem, [0.0, 0.0], direction=[1.0, 0.0],
                  events=[Event("x = 1", lambda x: x[0] - 1.0)],
                  options=Options(ds=0.5, ds_max=0.5, ds_min=1e-6, max_arclength=3.0))
    assert not curve.ok
    assert curve.status in (Status.NOT_LOCATED, Status.NON_FINITE)
    assert np.all(curve.x[:, 0] < 1.0)


def test_an_exception_in_the_residual_keeps_the_partial_curve():
    def residual(x):
        if x[0] > 0.5:
            raise ZeroDivisionError("model undefined here")
        return np.array([x[1] - x[0] ** 2])

    problem = Problem(residual, lambda x: np.array([[-2.0 * x[0], 1.0]]))
    with pytest.raises(CallbackError, match="residual\\(x\\) raised ZeroDivisionError") as info:
        trace(problem, [-1.0, 1.0], direction=[1.0, 0.0])
    error = info.value
    assert isinstance(error, ContinuationError)
    assert isinstance(error.__cause__, ZeroDivisionError)
    curve = error.curve
    assert curve.status is Status.CALLBACK_FAILED and not curve.ok
    assert len(curve) > 5 and np.all(curve.x[:, 0] <= 0.5)
    assert np.all(np.abs(curve.x[:, 1] - curve.x[:, 0] ** 2) <= 1e-10)


def test_an_exception_in_an_event_names_the_event():
    def event(x):
        if x[0] > 0.3:
            raise KeyError("missing")
        return 1.0

    with pytest.raises(CallbackError, match="event 'fragile' raised KeyError") as info:
        trace(axis(), [0.0, 0.0], direction=[1.0, 0.0], events=[Event("fragile", event)])
    assert len(info.value.curve) >= 1


@pytest.mark.parametrize("which, pattern", [
    ("residual", r"residual\(x\) returned shape \(2,\), expected \(1,\) \(n = 1 equations"),
    ("jacobian", r"jacobian\(x\) returned shape \(2, 2\), expected \(1, 2\)"),
])
def test_a_wrong_shape_mid_curve_names_the_function_and_the_shapes(which, pattern):
    def residual(x):
        value = np.array([x[1] - x[0]])
        return np.append(value, 0.0) if which == "residual" and x[0] > 0.5 else value

    def jacobian(x):
        value = np.array([[-1.0, 1.0]])
        return np.vstack([value, value]) if which == "jacobian" and x[0] > 0.5 else value

    with pytest.raises(CallbackShapeError, match=pattern) as info:
        trace(Problem(residual, jacobian), [0.0, 0.0], direction=[1.0, 1.0])
    assert isinstance(info.value, ValueError)
    curve = info.value.curve
    assert curve.status is Status.CALLBACK_FAILED and len(curve) >= 2
    assert np.all(curve.x[:, 0] <= 0.5)


@pytest.mark.parametrize("which", ["residual", "jacobian", "gradient"])
def test_complex_values_are_an_error_not_made_real(which):
    # numpy's float conversion drops an imaginary part with only a warning: the curve of
    # H + 1e-3j would be traced as that of H, |H| = 1e-3 off at every point, status ok
    def residual(x):
        return np.array([x[1] - x[0]]) + (1e-3j if which == "residual" else 0.0)

    def jacobian(x):
        return np.array([[-1.0, 1.0]]) + (0j if which == "jacobian" else 0.0)

    def gradient(x):
        return np.array([1.0, 0.0]) + (0j if which == "gradient" else 0.0)

    events = [Event("x = 2", lambda x: 2.0 - x[0], terminal=True, gradient=gradient)]
    error = CallbackShapeError if which != "gradient" else CallbackError
    with pytest.raises(error, match="complex"):
        trace(Problem(residual, jacobian), [0.0, 0.0], direction=[1.0, 1.0], events=events)


def test_no_point_off_the_curve_is_accepted_at_a_cusp():
    # y^2 = x^3 has a cusp at the origin, where H' = 0: near it |H| <= tol holds far from the
    # curve (at x = -1e-4, y = 0 it is 1e-12), and only the size of the Newton correction
    # tells; a corrector that accepts its last iterate with |H| <= tol after Newton failed
    # walks past the cusp into x < 0, where there is no curve at all
    problem = Problem(lambda x: np.array([x[1] ** 2 - x[0] ** 3]),
                      lambda x: np.array([[-3.0 * x[0] ** 2, 2.0 * x[1]]]))
    curve = trace(problem, [1.0, 1.0], direction=[-1.0, -1.0],
                  options=Options(max_arclength=3.0))
    x, y = curve.x[:, 0], curve.x[:, 1]
    # within the cusp's own neighbourhood (where H' ~ r^2 makes every point within ~1e-7
    # indistinguishable at tol = 1e-10) the points stay on the real curve |y| = x^(3/2)
    nearest = np.hypot(np.minimum(x, 0.0), np.abs(y) - np.maximum(x, 0.0) ** 1.5)
    assert np.all(nearest <= 1e-6)
    # and the run does not pass the cusp as if nothing happened
    assert curve.status is Status.STEP_TOO_SMALL


def test_a_huge_tangent_component_gives_no_zero_tangent():
    # a given tangent with a tiny component: the bordered solve's null vector is scaled by
    # 1e170, whose norm overflows a naive sqrt(v . v); the corrector must never report a zero
    # tangent as a converged point
    J = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    curve = trace(Problem(lambda x: J @ x, lambda x: J), np.zeros(3), tangent=[1.0, 0.0, 1e-170],
                  options=Options(max_steps=3))
    assert np.all(np.isfinite(curve.tangents))
    assert np.allclose(np.linalg.norm(curve.tangents, axis=1), 1.0)


def test_a_wrong_length_start_is_suggested_as_the_cause():
    # a circle started from (1, 0, 0): the message blamed only the residual's shape
    circle = Problem(lambda x: np.array([x[0] ** 2 + x[1] ** 2 - 1.0]),
                     lambda x: np.array([[2.0 * x[0], 2.0 * x[1]]]))
    with pytest.raises(CallbackShapeError, match="or x0 has the wrong length: 1 equations "
                                                 "need 2 unknowns"):
        trace(circle, [1.0, 0.0, 0.0])


@pytest.mark.parametrize("events", [lambda x: x[0], Event("x = 1", lambda x: 1.0 - x[0])])
def test_events_that_are_not_a_sequence_are_named(events):
    with pytest.raises(TypeError, match="events must be a sequence of Event"):
        trace(axis(), [0.0, 0.0], direction=[1.0, 0.0], events=events)


def test_a_fold_at_a_sharp_turn_is_where_the_tangent_vanishes():
    # lambda = sqrt(u^2 + eps^2) + c u turns within ~eps: a long step's Hermite arc misses the
    # tangent there by more than 0.1 rad, and the arc's tangent (meant for trials next to a
    # branch point) put the fold 5e-3 from the true one, reported exact to 5e-13
    eps, c = 0.0018477524145810527, 0.5740635524262185
    problem = Problem(lambda x: np.array([x[0] - np.sqrt(x[1] ** 2 + eps ** 2) - c * x[1]]),
                      lambda x: np.array([[1.0, -x[1] / np.sqrt(x[1] ** 2 + eps ** 2) - c]]))
    u0 = -2.8995896075646126
    curve = trace(problem, [np.sqrt(u0 ** 2 + eps ** 2) + c * u0, u0], direction=[0.0, 1.0],
                  options=Options(fold_coordinates=(0,)), events=box_events(upper={1: 5.0}))
    assert curve.ok
    (fold,) = curve.special("fold")
    assert fold.x[1] == pytest.approx(-c * eps / np.sqrt(1.0 - c * c), abs=1e-11)


@pytest.mark.parametrize("e, scale, u0", [
    (5e-4, 0.18, -1.78),                                              # one end nearly a fold
    (5.455079200777126e-05, 0.11414066900906675, -1.8898619914824868),  # a dip inside
])
def test_a_pair_of_close_folds_inside_one_step_is_found(e, scale, u0):
    # lambda/S = (u/S)^3 - e u/S: folds at u = -+S sqrt(e/3), lambda = +-2 S (e/3)^1.5. Both
    # inside one step, t_lambda dips below zero between ends of one sign: the chord's model
    # (and a cubic of the ends' slopes) missed the pair, status ok
    problem = Problem(lambda x: np.array([x[0] / scale - (x[1] / scale) ** 3 + e * x[1] / scale]),
                      lambda x: np.array([[1.0 / scale, -3.0 * x[1] ** 2 / scale ** 3
                                           + e / scale]]))
    start = [scale * (u0 ** 3 - e * u0), u0 * scale]
    curve = trace(problem, start, direction=[0.0, 1.0], options=Options(fold_coordinates=(0,)),
                  events=box_events(upper={1: 2.0 * scale}))
    assert curve.ok
    folds = sorted(p.x[1] for p in curve.special("fold"))
    expected = scale * np.sqrt(e / 3.0)
    assert folds == pytest.approx([-expected, expected], abs=1e-10)


@pytest.mark.parametrize("direction", [1, -1])
def test_a_loop_switched_onto_at_a_branch_point_closes_after_one_lap(direction):
    # u ((lambda - 1)^2 + (u - 1/2)^2 - 5/4) = 0: the line u = 0 and a circle through the
    # branch points (0, 0) and (2, 0). Switched onto at (0, 0), the circle went round 6 or 61
    # times before closing (no Newton converges at the singular start to show it is back)
    from continuation import switch_branch

    def residual(x):
        return np.array([x[1] * ((x[0] - 1.0) ** 2 + (x[1] - 0.5) ** 2 - 1.25)])

    def jacobian(x):
        circle = (x[0] - 1.0) ** 2 + (x[1] - 0.5) ** 2 - 1.25
        return np.array([[2.0 * x[1] * (x[0] - 1.0), circle + 2.0 * x[1] * (x[1] - 0.5)]])

    problem = Problem(residual, jacobian)
    line = trace(problem, [-1.0, 0.0], direction=[1.0, 0.0], options=Options(max_steps=20))
    branch = line.special("branch_point")[0]
    loop = switch_branch(problem, branch, direction=direction,
                         options=Options(fold_coordinates=(0,), max_steps=3000))
    assert loop.status is Status.CLOSED
    assert loop.s[-1] == pytest.approx(2.0 * np.pi * np.sqrt(1.25), rel=1e-6)
    assert len(loop.special("fold")) == 2


@pytest.mark.parametrize("c0", [0.7, 1e-3, 123.4])
@pytest.mark.parametrize("lam0", [-1.0, -2.3])
def test_no_folds_in_a_coordinate_that_is_constant_along_the_curve(c0, lam0):
    # the trivial branch u = c0 of (u - c0)(lambda - (u - c0)^2): u moves only by the
    # corrector's 1e-10, its tangent component is noise whose sign changes were 6 to 10 folds
    problem = Problem(
        lambda x: np.array([(x[1] - c0) * (x[0] - (x[1] - c0) ** 2)]),
        lambda x: np.array([[x[1] - c0, x[0] - 3.0 * (x[1] - c0) ** 2]]))
    curve = trace(problem, [lam0, c0], direction=[1.0, 0.0],
                  options=Options(fold_coordinates=(0, 1), max_arclength=3.0))
    assert curve.ok
    assert curve.special("fold") == ()
    assert len(curve.special("branch_point")) == 1


def test_a_close_pair_of_folds_and_a_fold_next_to_the_start_are_kept():
    # u^3 - e u = lambda: folds at u = -+sqrt(e/3), 8e-7 apart in lambda for e = 1e-4 (far
    # above the points' noise); and a curve that starts 1e-7 before a fold, whose lambda there
    # is within 1e-14 of the start's: the fold is kept (lambda moves on beyond it)
    e = 1e-4
    problem = Problem(lambda x: np.array([x[1] ** 3 - e * x[1] - x[0]]),
                      lambda x: np.array([[-1.0, 3.0 * x[1] ** 2 - e]]))
    curve = trace(problem, [-1.0, -1.0], direction=[1.0, 0.0],
                  options=Options(fold_coordinates=(0,), max_arclength=4.0))
    folds = curve.special("fold")
    assert curve.ok and len(folds) == 2
    root = math.sqrt(e / 3.0)
    for fold, u in zip(folds, (-root, root), strict=True):
        assert abs(fold.x[1] - u) <= 1e-9
    start = -root - 1e-7
    curve = trace(problem, [start ** 3 - e * start, start], direction=[0.0, 1.0],
                  options=Options(fold_coordinates=(0,), max_arclength=0.1))
    assert curve.ok
    assert [round(float(p.x[1] / root), 8) for p in curve.special("fold")] == [-1.0, 1.0]


@pytest.mark.parametrize(("e", "offset"), [(5e-6, None), (1e-6, None), (0.05, 1e6), (0.02, 1e6)])
def test_a_real_pair_of_folds_close_in_its_coordinate_is_kept(e, offset):
    # next to the cusp of u^3 - e u = lambda the two folds are 8.6e-9 apart in lambda for
    # e = 5e-6 (below 100 tol), or a coordinate y = 1e6 raises the points' noise above their
    # gap; lambda still moves between them at a rate e, far above rounding: both are kept
    if offset is None:
        problem = Problem(lambda x: np.array([x[1] ** 3 - e * x[1] - x[0]]),
                          lambda x: np.array([[-1.0, 3.0 * x[1] ** 2 - e]]))
        x0, direction = [-1.0 + e, -1.0], [0.0, 1.0]
    else:
        problem = Problem(
            lambda x: np.array([x[1] ** 3 - e * x[1] - x[0], x[2] - offset]),
            lambda x: np.array([[-1.0, 3.0 * x[1] ** 2 - e, 0.0], [0.0, 0.0, 1.0]]))
        x0, direction = [-1.0 + e, -1.0, offset], [0.0, 1.0, 0.0]
    curve = trace(problem, x0, direction=direction,
                  options=Options(fold_coordinates=(0,), max_arclength=4.0))
    assert curve.ok, curve.message
    root = math.sqrt(e / 3.0)
    assert [round(float(p.x[1] / root), 6) for p in curve.special("fold")] == [-1.0, 1.0]


@pytest.mark.parametrize(("tol", "ds"), [(1e-5, 1e-2), (1e-4, 1e-2), (1e-3, 1e-2), (3e-5, 1e-3)])
def test_a_closed_curve_at_a_loose_tolerance_closes_after_one_lap(tol, ds):
    # the corrector accepts points tol / |H'| off the circle: the closing point was 3e-6 from
    # the start at tol = 1e-5, beyond the fixed 1e-6, and the run went round again, ok
    circle = Problem(lambda x: np.array([x[0] ** 2 + x[1] ** 2 - 1.0]),
                     lambda x: np.array([[2.0 * x[0], 2.0 * x[1]]]))
    curve = trace(circle, [1.0, 0.0],
                  options=Options(tol=tol, ds=ds, ds_max=ds, max_arclength=7.0, max_steps=10000))
    assert curve.status is Status.CLOSED, curve.message
    assert curve.s[-1] == pytest.approx(2.0 * math.pi, rel=1e-3)


@pytest.mark.parametrize("pitch", [1e-2, 1e-3, 1e-4])
def test_a_helix_whose_turns_the_tolerance_resolves_is_not_closed(pitch):
    # x = cos(z / c), y = sin(z / c): each turn comes back `pitch` above the start; at
    # tol = 1e-5 the points are good to about 3e-5, so a pitch of 1e-4 or more is no closure
    c = pitch / (2.0 * math.pi)
    helix = Problem(lambda x: np.array([x[0] - np.cos(x[2] / c), x[1] - np.sin(x[2] / c)]),
                    lambda x: np.array([[1.0, 0.0, np.sin(x[2] / c) / c],
                                        [0.0, 1.0, -np.cos(x[2] / c) / c]]))
    curve = trace(helix, [1.0, 0.0, 0.0], direction=[0.0, 1.0, 0.0],
                  options=Options(tol=1e-5, ds=0.01, ds_max=0.01, max_arclength=3.0 * math.pi,
                                  max_steps=10000))
    assert curve.status is Status.MAX_ARCLENGTH, curve.message


@pytest.mark.parametrize("factor", [1.0, 1e-3, 1e-6])
def test_a_helix_is_not_closed_whatever_the_scale_of_its_residual(factor):
    # a closing test within tol / sigma_min(H') took a helix of pitch 1e-4 at tol = 1e-10 as
    # closed once H was scaled by 1e-6; the points are good to tol (1 + max|x|) whatever H's
    # scale (the corrector's bound on its next correction)
    c = 1e-4 / (2.0 * math.pi)
    helix = Problem(
        lambda x: factor * np.array([x[0] - np.cos(x[2] / c), x[1] - np.sin(x[2] / c)]),
        lambda x: factor * np.array([[1.0, 0.0, np.sin(x[2] / c) / c],
                                     [0.0, 1.0, -np.cos(x[2] / c) / c]]))
    curve = trace(helix, [1.0, 0.0, 0.0], direction=[0.0, 1.0, 0.0],
                  options=Options(ds=0.01, ds_max=0.01, max_arclength=3.0 * math.pi,
                                  max_steps=10000))
    assert curve.status is Status.MAX_ARCLENGTH, curve.message


@pytest.mark.parametrize("y, dy, start, end", [
    (np.tanh, lambda x: 1.0 - np.tanh(x) ** 2, -40.0, 40.0),            # rounds to +-1 for |x| > 19
    (lambda x: np.exp(-x), lambda x: -np.exp(-x), 0.0, 800.0),          # underflows at x = 745
    (lambda x: np.tanh(x / 0.01), lambda x: (1.0 - np.tanh(x / 0.01) ** 2) / 0.01, -1.0, 1.0),
])
def test_a_coordinate_that_stops_moving_in_floats_has_no_fold(y, dy, start, end):
    """y = tanh x is increasing, but in floats it reaches 1.0 and stays there: t_y becomes
    exactly 0 and stays 0. Where it first did, a fold in y was reported (accuracy 0.0), with
    the status a success; a coordinate that stops (or starts) moving for good turns nothing."""
    problem = Problem(lambda x: np.array([x[1] - y(x[0])]), lambda x: np.array([[-dy(x[0]), 1.0]]))
    curve = trace(problem, [start, float(y(start))], direction=[1.0, 0.0],
                  options=Options(fold_coordinates=(1,)), events=box_events(upper={0: end}))
    assert curve.status is Status.TERMINAL_EVENT
    assert not curve.special("fold")


def test_a_fold_just_before_the_end_is_kept():
    """The saturation rule keeps a genuine fold next to an end: the circle's top, a step or two
    before the curve ends just past it (t_y grows again after the fold)."""
    circle = Problem(lambda x: np.array([x[0] ** 2 + x[1] ** 2 - 1.0]),
                     lambda x: np.array([[2.0 * x[0], 2.0 * x[1]]]))
    curve = trace(circle, [1.0, 0.0], direction=[0.0, 1.0],
                  options=Options(fold_coordinates=(1,)), events=box_events(lower={0: -0.02}))
    folds = curve.special("fold")
    assert len(folds) == 1 and np.allclose(folds[0].x, [0.0, 1.0], atol=1e-10)
