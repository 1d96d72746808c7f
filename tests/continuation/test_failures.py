"""Failure paths: a documented status with a message and the partial curve, or an exception."""

import numpy as np
import pytest

from continuation import ContinuationError, Options, Problem, Status, trace


def parabola_with_a_wall():
    def residual(x):
        if x[0] > 0.5:
            return np.array([np.nan])
        return np.array([x[1] - x[0] ** 2])

    return Problem(residual, lambda x: np.array([[-2.0 * x[0], 1.0]]))


def test_non_finite_residual_mid_curve_keeps_the_partial_curve():
    curve = trace(parabola_with_a_wall(), [-1.0, 1.0], direction=[1.0, 0.0])
    assert curve.status is Status.NON_FINITE
    assert curve.status.failed and not curve.ok
    assert "ds_min" in curve.message and "x[0]=0.5" in curve.message
    assert "box_events" in curve.message
    assert len(curve) > 5
    assert np.all(curve.x[:, 0] <= 0.5)
    assert curve.x[-1, 0] == pytest.approx(0.5, abs=1e-9)
    assert np.all(np.abs(curve.x[:, 1] - curve.x[:, 0] ** 2) <= 1e-10)
    assert curve.special_points[-1].kind == "end"
    assert curve.special_points[-1].name == "non_finite"


def test_raise_on_failure_carries_the_partial_curve():
    with pytest.raises(ContinuationError, match="not finite ahead of the curve") as info:
        trace(parabola_with_a_wall(), [-1.0, 1.0], direction=[1.0, 0.0],
              options=Options(raise_on_failure=True))
    curve = info.value.curve
    assert curve.status is Status.NON_FINITE
    assert len(curve) > 5 and np.all(curve.x[:, 0] <= 0.5)


def test_start_far_from_the_curve(circle):
    curve = trace(circle, [1e3, 1e3])
    assert curve.status is Status.START_NOT_CONVERGED
    assert curve.status.failed
    assert "x0=(x[0]=1000, x[1]=1000)" in curve.message
    assert "closer to the curve" in curve.message
    assert len(curve) == 0 and curve.x.shape == (0, 2)
    with pytest.raises(ContinuationError, match="Newton did not converge"):
        trace(circle, [1e3, 1e3], options=Options(raise_on_failure=True))


def test_singular_start_without_tangent(pitchfork):
    curve = trace(pitchfork, [0.0, 0.0])
    assert curve.status is Status.SINGULAR_START
    assert "switch_branch" in curve.message
    assert len(curve) == 0


def test_singular_start_with_tangent_is_followed(pitchfork):
    curve = trace(pitchfork, [0.0, 0.0], tangent=[1.0, 0.0],
                  options=Options(max_arclength=1.0))
    assert curve.status is Status.MAX_ARCLENGTH
    assert np.allclose(curve.x[-1], [1.0, 0.0], atol=1e-10)


def test_start_with_non_finite_residual(circle):
    problem = Problem(lambda x: np.array([np.inf]))
    assert trace(problem, [0.0, 0.0]).status is Status.NON_FINITE


def test_step_too_small_names_where_and_what_to_change():
    # the curve u = |lambda|^(1/2) ... has a cusp-like corner: H = u^2 - lambda^2 (cross at 0)
    # with branch point detection off, the corner at lambda = 0 of u = sqrt(lambda^2 + 1e-30)
    # is a kink the corrector cannot pass with a smooth tangent
    problem = Problem(lambda x: np.array([x[1] - np.sqrt(x[0] ** 2 + 1e-24)]),
                      lambda x: np.array([[-x[0] / np.sqrt(x[0] ** 2 + 1e-24), 1.0]]))
    curve = trace(problem, [-1.0, 1.0], direction=[1.0, 0.0],
                  options=Options(ds_min=1e-6, max_arclength=4.0))
    assert curve.status is Status.STEP_TOO_SMALL, curve.message
    assert "after step" in curve.message and "s=" in curve.message
    assert "ds_min" in curve.message
    assert curve.x[-1, 0] < 0.0 < curve.x[-1, 0] + 1e-3
    assert curve.rejected_steps > 0


def test_a_step_below_the_rounding_of_x_ends_the_run_loudly():
    # the line y = x through (1e7, 1e7) with steps of 1e-10, below the rounding of x (1.9e-9):
    # a step that moves no coordinate ends the run, it does not crash on a zero-length step
    problem = Problem(lambda x: np.array([x[1] - x[0]]), lambda x: np.array([[-1.0, 1.0]]))
    curve = trace(problem, [1e7, 1e7], options=Options(ds=1e-10, ds_max=1e-10, ds_min=1e-12))
    assert curve.status is Status.STEP_TOO_SMALL and not curve.ok
    assert "moved no coordinate" in curve.message and "scale" in curve.message
    assert len(curve) == 1


@pytest.mark.parametrize(("centre", "radius"), [(1e7, 1e-6), (1e5, 1e-6), (0.0, 1e-9)])
def test_tolerances_that_do_not_resolve_the_curve_end_the_run_loudly(centre, radius):
    # circles smaller than the tolerances resolve: their residual r^2 is below tol inside
    # them, and around (1e7, 0) the corrections' tolerance tol (1 + max|x|) is 1e-3, far more
    # than r. Points within both but off the circle by much of a step once closed as a loop
    # three times too long (status CLOSED); now the run fails and says why
    problem = Problem(lambda x: np.array([(x[0] - centre) ** 2 + x[1] ** 2 - radius ** 2]),
                      lambda x: np.array([[2 * (x[0] - centre), 2 * x[1]]]))
    curve = trace(problem, [centre + radius, 0.0],
                  options=Options(ds=radius / 10, ds_max=radius / 5, ds_min=1e-3 * radius))
    assert curve.status is Status.STEP_TOO_SMALL and not curve.ok, curve.message
    assert "scale" in curve.message
    assert np.all(np.diff(curve.s) > 0.0)
    distance = np.abs(np.hypot(curve.x[:, 0] - centre, curve.x[:, 1]) - radius)
    assert np.all(distance <= 0.1 * radius)


def test_a_short_last_step_or_an_overshoot_ends_at_max_arclength(circle):
    # a last step cut to a sliver by max_arclength is no unresolved step (its point is as
    # accurate as the others, even at a loose tol); and a step whose arclength exceeds its
    # pseudo-arclength h can pass max_arclength: it is brought back, s never decreases
    for options in (Options(tol=1e-6, max_arclength=0.35002194887826477),
                    Options(ds=0.2, ds_max=0.2, max_arclength=0.40137)):
        curve = trace(circle, [1.0, 0.0], options=options)
        assert curve.status is Status.MAX_ARCLENGTH, curve.message
        assert curve.s[-1] == options.max_arclength
        assert np.all(np.diff(curve.s) > 0.0)
        assert abs(np.hypot(*curve.x[-1]) - 1.0) <= options.tol


def test_max_steps_is_a_normal_end(circle):
    curve = trace(circle, [1.0, 0.0], options=Options(max_steps=3))
    assert curve.status is Status.MAX_STEPS and curve.ok
    assert len(curve) == 4


def test_argument_validation(circle):
    with pytest.raises(ValueError, match="direction must be None, 1, -1"):
        trace(circle, [1.0, 0.0], direction=2)
    with pytest.raises(ValueError, match="x0 must be a finite 1-D array"):
        trace(circle, [[1.0, 0.0]])
    with pytest.raises(ValueError, match=r"residual\(x\) returned shape \(2,\), expected \(1,\)"):
        trace(Problem(lambda x: x), [1.0, 0.0])
    with pytest.raises(ValueError, match="fold_coordinates entries must be < 2, got 5"):
        trace(circle, [1.0, 0.0], options=Options(fold_coordinates=(5,)))
    with pytest.raises(ValueError, match="direction is orthogonal"):
        trace(circle, [1.0, 0.0], direction=[1.0, 0.0])


def cubic_with(d_dy):
    """x[1]^3 - 3 x[1] - x[0] = 0 with the Jacobian's second entry ``d_dy(x[1])``."""
    return Problem(lambda x: np.array([x[1] ** 3 - 3.0 * x[1] - x[0]]),
                   lambda x: np.array([[-1.0, d_dy(x[1])]]))


def test_a_wrong_jacobian_ends_the_run_at_the_start():
    # 3 y^2 - 2.9 instead of 3 y^2 - 3: Newton still converges onto the curve, the tangents
    # and the folds tilt, and the steps collapse to 1e-8 (10000 steps, no fold found)
    curve = trace(cubic_with(lambda y: 3.0 * y ** 2 - 2.9), [-18.0, -3.0], direction=[1.0, 0.0],
                  options=Options(fold_coordinates=(0,)))
    assert curve.status is Status.JACOBIAN_MISMATCH and not curve.ok and len(curve) == 0
    assert "row 0 of the Jacobian" in curve.message and "check_jacobian" in curve.message
    assert curve.residual_evals == 7      # x0, then 2 at each of the 3 steps of the check
    with pytest.raises(ContinuationError, match="disagrees with differences"):
        trace(cubic_with(lambda y: 3.0 * y ** 2 - 2.9), [-18.0, -3.0],
              options=Options(raise_on_failure=True))


def test_the_jacobian_check_passes_good_and_approximate_jacobians_and_can_be_off():
    right = trace(cubic_with(lambda y: 3.0 * y ** 2 - 3.0), [-18.0, -3.0],
                  direction=[1.0, 0.0], options=Options(fold_coordinates=(0,), max_steps=300))
    assert right.ok and [p.kind for p in right.special_points].count("fold") == 2
    # off by 1e-7 relative, as a finite-difference Jacobian is: not reported
    near = trace(cubic_with(lambda y: (3.0 * y ** 2 - 3.0) * (1.0 + 1e-7)), [-18.0, -3.0],
                 options=Options(max_steps=5))
    assert near.status is Status.MAX_STEPS
    # next to the singularity of sqrt, where the differences' truncation error exceeds
    # PROBE_RTOL, the differences over d/16 and d/256 tell it: not reported
    steep = Problem(lambda x: np.array([np.sqrt(x[0]) - x[1]]),
                    lambda x: np.array([[0.5 / np.sqrt(x[0]), -1.0]]))
    assert trace(steep, [1e-4, 1e-2], direction=[1.0, 0.0],
                 options=Options(max_steps=5)).status is Status.MAX_STEPS
    off = trace(cubic_with(lambda y: 3.0 * y ** 2 - 2.9), [-18.0, -3.0],
                options=Options(check_jacobian=False, max_steps=5))
    assert off.status is Status.MAX_STEPS


def test_steps_that_shrink_towards_a_domain_edge_end_as_non_finite():
    # the unit circle with a residual that is NaN for x[0] < -1/2: the steps shrink towards
    # the edge until the last ones fail for another reason (their Newton correction is not
    # resolved at a step of 1e-12); the run still says why it stopped
    def residual(x):
        return np.array([x[0] ** 2 + x[1] ** 2 - 1.0 + 0.0 * np.sqrt(x[0] + 0.5)])

    with np.errstate(invalid="ignore"):
        curve = trace(Problem(residual, lambda x: np.array([[2.0 * x[0], 2.0 * x[1]]])),
                      [1.0, 0.0])
    assert curve.status is Status.NON_FINITE
    assert "not finite ahead of the curve" in curve.message
    assert curve.x[-1] == pytest.approx([-0.5, np.sqrt(0.75)], abs=1e-9)


def test_max_steps_says_when_the_steps_had_collapsed():
    curve = trace(cubic_with(lambda y: 3.0 * y ** 2 - 2.9), [-18.0, -3.0], direction=[1.0, 0.0],
                  options=Options(check_jacobian=False, max_steps=2000))
    assert curve.status is Status.MAX_STEPS and curve.ok
    assert "the step size had fallen to" in curve.message
    assert "check_jacobian" in curve.message
    normal = trace(cubic_with(lambda y: 3.0 * y ** 2 - 3.0), [-18.0, -3.0],
                   options=Options(max_steps=20))
    assert normal.message == "reached the maximum number of steps (20)"


@pytest.mark.parametrize("value, said", [
    (lambda x: np.array([x[0]]), r"returned an array of shape \(1,\)"),
    (lambda x: None, "returned None"),
    (lambda x: complex(x[0], 1.0), r"returned the complex number \(-18\+1j\)"),
])
def test_an_event_that_returns_no_real_number_is_a_shape_error(value, said):
    from continuation import CallbackShapeError, Event  # (only this test's)
    with pytest.raises(CallbackShapeError, match=f"event 'e' {said} at x=.*one real number"):
        trace(cubic_with(lambda y: 3.0 * y ** 2 - 3.0), [-18.0, -3.0], events=[Event("e", value)])


@pytest.mark.parametrize("residual, jacobian, x0", [
    # a Hill function of width 3e-6 (molar units): the differences over 7.6e-6 miss its slope
    (lambda x: np.array([x[1] - x[0] ** 4 / (3e-6 ** 4 + x[0] ** 4)]),
     lambda x: np.array([[-4.0 * 3e-6 ** 4 * x[0] ** 3 / (3e-6 ** 4 + x[0] ** 4) ** 2, 1.0]]),
     [2e-6, 2e-6 ** 4 / (3e-6 ** 4 + 2e-6 ** 4)]),
    # tanh of width 1e-6
    (lambda x: np.array([x[1] - np.tanh(x[0] / 1e-6)]),
     lambda x: np.array([[-1e6 / np.cosh(x[0] / 1e-6) ** 2, 1.0]]), [0.0, 0.0]),
    # exactly linear, with a residual of 1.5e8 at the start: its rounding is 3e-8
    (lambda x: np.array([x[0] + x[1] - 1.5e8]), lambda x: np.array([[1.0, 1.0]]), [0.0, 0.0]),
])
def test_a_right_jacobian_is_not_reported(residual, jacobian, x0):
    # (these were reported when the check compared one step only, found in review)
    curve = trace(Problem(residual, jacobian), x0, options=Options(max_steps=5))
    assert curve.status is not Status.JACOBIAN_MISMATCH, curve.message


def test_a_singular_point_near_a_nan_region_is_not_called_the_domains_edge():
    # the cusp y^2 = x^3 ends the run STEP_TOO_SMALL; a NaN region 0.05 beyond it, which a long
    # predictor step once met, does not make it NON_FINITE
    def residual(x):
        return np.array([x[1] ** 2 - x[0] ** 3 + (np.nan if x[0] < -0.05 else 0.0)])

    curve = trace(Problem(residual, lambda x: np.array([[-3.0 * x[0] ** 2, 2.0 * x[1]]])),
                  [1.0, -1.0], direction=[-1.0, 1.0])
    assert curve.status is Status.STEP_TOO_SMALL


def test_long_steps_are_not_called_collapsed():
    circle = Problem(lambda x: np.array([x @ x - 1.0]), lambda x: np.array([2.0 * x]))
    curve = trace(circle, [1.0, 0.0],
                  options=Options(ds=1.0, ds_max=1e7, max_steps=10, detect_closed=False))
    assert curve.message == "reached the maximum number of steps (10)"


def _cubic_with_a_jacobian_error(size: float) -> Problem:
    """``u^3 - u - lambda`` with a Jacobian off by ``size (u + 2)^2``: right at the start
    ``u = -2``, where the run's first check looks, wrong at the folds (``u = -+1/sqrt 3``)."""
    return Problem(lambda x: np.array([x[1] ** 3 - x[1] - x[0]]),
                   lambda x: np.array([[-1.0, 3.0 * x[1] ** 2 - 1.0 + size * (x[1] + 2.0) ** 2]]))


def test_a_jacobian_wrong_away_from_the_start_fails_at_the_folds_it_moved():
    # the folds were reported 6e-4 off (u = -0.57677 for -0.57735) with an accuracy of 5e-13,
    # and the run a success
    from continuation import box_events

    stop = box_events(upper={1: 2.0})
    curve = trace(_cubic_with_a_jacobian_error(1e-3), [-6.0, -2.0], direction=[1.0, 0.0],
                  options=Options(fold_coordinates=(0,)), events=stop)
    assert curve.status is Status.JACOBIAN_MISMATCH and curve.status.failed
    assert "at fold x[0]" in curve.message and "not where they are reported" in curve.message
    unchecked = trace(_cubic_with_a_jacobian_error(1e-3), [-6.0, -2.0], direction=[1.0, 0.0],
                      options=Options(fold_coordinates=(0,), check_jacobian=False), events=stop)
    assert unchecked.status is Status.TERMINAL_EVENT  # the check is the option's


def test_a_jacobian_wrong_where_the_steps_collapse_fails_there():
    # with a larger error the steps collapsed and the run ended MAX_STEPS, not failed, part way
    from continuation import box_events

    curve = trace(_cubic_with_a_jacobian_error(0.1), [-6.0, -2.0], direction=[1.0, 0.0],
                  options=Options(fold_coordinates=(0,)), events=box_events(upper={1: 2.0}))
    assert curve.status is Status.JACOBIAN_MISMATCH, curve.message
    assert "at the last point, where the steps had collapsed" in curve.message
