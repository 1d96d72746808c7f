"""Every catalog problem: status, residuals, tangents and special points against analytic values."""

import numpy as np
import pytest

from continuation import finite_difference_jacobian, trace


@pytest.fixture
def traced(case):
    return trace(case.problem, case.x0, direction=case.direction, options=case.options,
                 events=case.events)


def test_status(case, traced):
    assert traced.status is case.status, traced.message
    assert traced.ok


def test_every_point_on_the_curve(case, traced):
    residuals = np.array([np.max(np.abs(case.problem.residual(x))) for x in traced.x])
    assert np.all(residuals <= case.options.tol)
    assert np.allclose(residuals, traced.residuals, rtol=0, atol=1e-15)
    assert traced.max_residual <= case.options.tol


def test_tangents_are_unit_null_vectors_along_the_curve(case, traced):
    assert np.allclose(np.linalg.norm(traced.tangents, axis=1), 1.0, atol=1e-12)
    for x, t in zip(traced.x, traced.tangents):
        jacobian = finite_difference_jacobian(case.problem.residual, x)
        assert np.max(np.abs(jacobian @ t)) < 1e-7
    # consecutive tangents keep their orientation, and the points follow them
    assert np.all(np.sum(traced.tangents[1:] * traced.tangents[:-1], axis=1) > 0)
    steps = np.diff(traced.x, axis=0)
    assert np.all(np.sum(steps * traced.tangents[:-1], axis=1) > 0)


def test_arclength(case, traced):
    assert traced.s[0] == 0.0 and traced.ds[0] == 0.0
    assert np.all(np.diff(traced.s) > 0)
    assert np.allclose(traced.ds[1:], np.diff(traced.s))
    # the arclength is at least the chord sum and close to it
    chords = np.linalg.norm(np.diff(traced.x, axis=0), axis=1)
    assert np.all(np.diff(traced.s) >= chords * (1 - 1e-12))
    assert traced.s[-1] == pytest.approx(chords.sum(), rel=1e-2)


def test_special_points(case, traced):
    for kind, expected in case.special.items():
        found = traced.special(kind)
        assert len(found) == len(expected), [p.name for p in found]
        for point, x in zip(found, expected):
            assert np.max(np.abs(point.x - np.array(x))) <= case.accuracy, (kind, point.x, x)
            assert point.accuracy <= case.options.event_tol * 10
            assert point.residual <= case.options.tol


def test_special_points_are_points_of_the_curve(traced):
    assert traced.special_points[0].kind == "start" and traced.special_points[0].index == 0
    assert traced.special_points[-1].kind == "end"
    assert traced.special_points[-1].index == len(traced) - 1
    indices = [point.index for point in traced.special_points]
    assert indices == sorted(indices)
    for point in traced.special_points:
        assert np.array_equal(traced.x[point.index], point.x)
        assert traced.s[point.index] == point.s


def test_counters(traced):
    assert len(traced) == traced.x.shape[0] == traced.tangents.shape[0]
    assert traced.newton_iterations.dtype.kind == "i"
    assert traced.residual_evals >= len(traced)
    assert traced.jacobian_evals >= len(traced)
    assert traced.rejected_steps >= 0
