"""Two-parameter continuation: folds and event points followed in p, against closed forms."""

import math

import numpy as np
import pytest

from continuation import (
    Codim2Kind,
    Event,
    Family,
    Options,
    SpecialKind,
    Status,
    box_events,
    check_jacobian,
    follow_event,
    follow_fold,
    trace,
)
from continuation.augmented import BORDER_QUALITY, EventSystem, FoldSystem

OPTIONS = Options(tol=1e-12)


def cusp_family(derivatives: bool = True) -> Family:
    """``u^3 - mu u - lambda = 0`` in ``x = (lambda, u)``, ``p = mu``."""
    if not derivatives:
        return Family(lambda x, mu: np.array([x[1] ** 3 - mu * x[1] - x[0]]),
                      names=("lambda", "u"), parameter="mu")
    return Family(lambda x, mu: np.array([x[1] ** 3 - mu * x[1] - x[0]]),
                  lambda x, mu: np.array([[-1.0, 3.0 * x[1] ** 2 - mu]]),
                  lambda x, mu: np.array([-x[1]]), names=("lambda", "u"), parameter="mu")


def circle_family() -> Family:
    """``x^2 + y^2 = r^2``: circles of radius ``p = r``."""
    return Family(lambda x, r: np.array([x[0] ** 2 + x[1] ** 2 - r ** 2]),
                  lambda x, r: np.array([[2.0 * x[0], 2.0 * x[1]]]), names=("x", "y"),
                  parameter="r")


def rotating_family() -> Family:
    """``(u^3 - u - lambda, v) = 0`` with ``(u, v)`` the coordinates ``(a, b)`` turned by
    ``p``: the folds in ``lambda`` are ``u = +-1/sqrt 3``, ``(a, b) = u (cos p, sin p)``, and the
    null vector of the fold turns with ``p``."""
    def residual(x, p):
        lam, a, b = x
        u = math.cos(p) * a + math.sin(p) * b
        v = -math.sin(p) * a + math.cos(p) * b
        return np.array([u ** 3 - u - lam, v])

    def jacobian(x, p):
        u = math.cos(p) * x[1] + math.sin(p) * x[2]
        slope = 3.0 * u ** 2 - 1.0
        return np.array([[-1.0, slope * math.cos(p), slope * math.sin(p)],
                         [0.0, -math.sin(p), math.cos(p)]])
    return Family(residual, jacobian, names=("lambda", "a", "b"), parameter="p")


@pytest.mark.parametrize("derivatives, tol, accuracy", [(True, 1e-12, 1e-10),
                                                          (False, 1e-10, 1e-9)])
def test_cusp_normal_form_fold_curve_and_cusp(derivatives, tol, accuracy):
    # without dH/dx the fold test is built on a difference quotient, accurate to ~1e-10
    family = cusp_family(derivatives)
    options = Options(tol=tol)
    # the fold found by trace at mu = 3 (lambda = -2 at u = 1) is the start
    curve = trace(family.at(3.0), [-8.125, -2.5], direction=[1.0, 0.0],
                  options=Options(tol=1e-12, fold_coordinates=(0,)),
                  events=box_events(upper={1: 2.5}))
    fold = next(p for p in curve.special(SpecialKind.FOLD) if p.x[1] > 0)
    folds = follow_fold(family, fold, p=3.0, direction=-1, options=options,
                        parameter_range=(-1.0, 3.0))
    assert folds.ok and folds.status.name == "TERMINAL_EVENT"
    lam, u, mu = folds.z.T
    # lambda = -+2 (mu/3)^(3/2) on u = +-sqrt(mu/3), every point
    assert np.max(np.abs(mu - 3.0 * u ** 2)) <= accuracy
    assert np.max(np.abs(lam + 2.0 * u ** 3)) <= accuracy
    assert np.max(np.abs(np.abs(lam) - 2.0 * (np.maximum(mu, 0.0) / 3.0) ** 1.5)) <= accuracy
    (cusp,) = folds.special(Codim2Kind.CUSP)
    assert np.max(np.abs(cusp.z)) <= accuracy
    assert "two folds meet" in cusp.equations[-1]
    # it turned at the cusp onto the other fold and left through mu = 3 at (2, -1)
    end = folds.points[-1]
    assert end.kind is Codim2Kind.EVENT and end.terminal and end.name == "mu <= 3.0"
    assert np.allclose(end.z, [2.0, -1.0, 3.0], atol=10 * tol)
    # dense output: both folds at mu = 1
    points = folds.at(1.0)
    assert len(points) == 2
    assert sorted(p[0] for p in points) == pytest.approx([-2 / 3 ** 1.5, 2 / 3 ** 1.5],
                                                         abs=10 * tol)


def test_fold_from_a_guess_and_a_boundary_event():
    family = cusp_family()
    # a guess off the fold curve; the fold leaves through the terminal event u = 1.5
    leave = Event("u = 1.5", lambda z: z[1] - 1.5, terminal=True)
    folds = follow_fold(family, [-2.1, 1.05, 3.1], coordinate=0, direction=1,
                        options=OPTIONS, events=[leave])
    assert folds.ok
    (end,) = folds.points
    assert end.kind is Codim2Kind.EVENT and end.terminal and end.event == 0
    # the exact point: u = 1.5, mu = 3 u^2 = 6.75, lambda = -2 u^3 = -6.75
    assert np.max(np.abs(end.z - [-6.75, 1.5, 6.75])) <= 1e-12
    assert end.residual <= 1e-13
    assert end.equations[-1] == "event 'u = 1.5' = 0"
    assert folds.x.shape == (len(folds), 2) and folds.p.shape == (len(folds),)


def test_event_curve_has_its_closed_form():
    # event points y = x^2 on circles of radius r: r = |x| sqrt(1 + x^2)
    family = circle_family()
    event = Event("y = x^2", lambda z: z[1] - z[0] ** 2)
    curve = trace(family.at(1.0), [1.0, 0.0], events=[family.event_at(event, 1.0)],
                  options=OPTIONS)
    start = curve.special("event")[0]
    points = follow_event(family, event, start, p=1.0, direction=1, options=OPTIONS,
                          parameter_range=(0.01, 5.0))
    assert points.ok and len(points) > 10
    x, y, r = points.z.T
    assert np.max(np.abs(y - x ** 2)) <= 1e-10
    assert np.max(np.abs(r - np.abs(x) * np.sqrt(1.0 + x ** 2))) <= 1e-10
    end = points.points[-1]
    assert end.name == "r <= 5.0" and end.p == pytest.approx(5.0, abs=1e-12)
    # x at r = 5: x^4 + x^2 = 25
    assert end.x[0] == pytest.approx(math.sqrt((-1 + math.sqrt(101)) / 2), abs=1e-11)


def test_tangency_where_two_event_points_meet():
    # y = 1/2 meets the circle of radius r at x = +-sqrt(r^2 - 1/4): the two points meet at
    # r = 1/2, where the event curve turns in r
    family = circle_family()
    event = Event("y = 1/2", lambda z: z[1] - 0.5, gradient=lambda z: np.array([0, 1.0, 0]))
    points = follow_event(family, event, [math.sqrt(0.75), 0.5], p=1.0, direction=-1,
                          options=OPTIONS, parameter_range=(0.1, 1.0))
    (tangency,) = points.special(Codim2Kind.TANGENCY)
    assert np.max(np.abs(tangency.z - [0.0, 0.5, 0.5])) <= 1e-10
    assert "two event points meet" in tangency.equations[-1]
    assert points.points[-1].name == "r <= 1.0"
    assert points.points[-1].x[0] == pytest.approx(-math.sqrt(0.75), abs=1e-12)


def test_borders_are_renewed_as_the_null_vector_turns():
    family = rotating_family()
    u = 1.0 / math.sqrt(3.0)
    start = [u ** 3 - u, u, 0.0]
    folds = follow_fold(family, start, p=0.0, coordinate=0, direction=1, options=OPTIONS,
                        parameter_range=(-1.0, 4.0))
    assert folds.ok and folds.points[-1].name == "p <= 4.0"
    assert len(folds.pieces) >= 3  # the null vector turns by 4 rad
    lam, a, b, p = folds.z.T
    assert np.max(np.abs(lam - (u ** 3 - u))) <= 1e-10
    assert np.max(np.abs(a - u * np.cos(p))) <= 1e-10
    assert np.max(np.abs(b - u * np.sin(p))) <= 1e-10
    assert not folds.special(Codim2Kind.EVENT)[:-1]  # the renewals are no codim-2 points
    for piece in folds.pieces:
        system = FoldSystem(family, 0, piece.x[0])
        assert min(system.quality(piece.x[0])) == pytest.approx(1.0)
    assert BORDER_QUALITY < 1.0


def test_fold_system_is_regular_at_the_fold_and_its_jacobian_checks():
    family = cusp_family()
    z = np.array([-2.0, 1.0, 3.0])
    system = FoldSystem(family, 0, z)
    assert np.max(np.abs(system.residual(z))) <= 1e-15
    J = system.jacobian(z)
    assert np.linalg.matrix_rank(J) == 2
    assert check_jacobian(system.residual, system.jacobian, z + 0.01, rtol=1e-6,
                          atol=1e-8) <= 1e-6
    events = EventSystem(circle_family(), Event("y", lambda z: z[1]))
    assert check_jacobian(events.residual, events.jacobian, np.array([0.6, 0.8, 1.0])) <= 1e-8


def test_family_at_and_event_at_are_the_curve_at_fixed_p():
    family = circle_family()
    problem = family.at(2.0)
    assert problem.residual(np.array([2.0, 0.0]))[0] == 0.0
    assert problem.names == ("x", "y")
    event = family.event_at(Event("r x", lambda z: z[2] * z[0], 1, True,
                                  lambda z: np.array([z[2], 0.0, z[0]])), 2.0)
    assert event.function(np.array([3.0, 1.0])) == 6.0
    assert np.array_equal(event.gradient(np.array([3.0, 1.0])), [2.0, 0.0])
    assert event.direction == 1 and event.terminal
    assert family.names_z(2) == ("x", "y", "r")
    assert np.allclose(cusp_family(False).jacobian_p(np.array([0.0, 2.0]), 1.0), [-2.0])


def test_bad_arguments_name_the_quantity():
    family = cusp_family()
    with pytest.raises(ValueError, match="coordinate is needed"):
        follow_fold(family, [0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="coordinate must be an index of x"):
        follow_fold(family, [0.0, 0.0, 0.0], coordinate=2)
    with pytest.raises(ValueError, match="x needs n \\+ 1 = 2 coordinates"):
        follow_fold(family, [0.0, 0.0, 0.0, 1.0], coordinate=0)
    with pytest.raises(ValueError, match="direction must be 1, -1 or an array"):
        follow_fold(family, [-2.0, 1.0], p=3.0, coordinate=0, direction=[1.0, 0.0])
    curve = trace(family.at(3.0), [-8.125, -2.5], direction=[1.0, 0.0],
                  options=Options(fold_coordinates=(0,)), events=box_events(upper={1: 2.5}))
    with pytest.raises(ValueError, match="p is needed with a SpecialPoint"):
        follow_fold(family, curve.special("fold")[0])
    with pytest.raises(TypeError, match="event must be an Event"):
        follow_event(family, "u", [0.0, 0.0], p=0.0)
    with pytest.raises(TypeError, match="Family.residual must be callable"):
        Family(None)


def test_the_limits_hold_for_the_whole_curve_over_its_pieces():
    # each piece had the whole max_steps, and the curve stopped after 200 renewals of the
    # borders however far from its end, reported ok (at p = 41.9 of 50)
    u = 1.0 / math.sqrt(3.0)
    folds = follow_fold(rotating_family(), [u ** 3 - u, u, 0.0], p=0.0, coordinate=0,
                        options=Options(tol=1e-12, max_steps=30),
                        parameter_range=(-1.0, 40.0))
    assert len(folds.pieces) > 1 and folds.status is Status.MAX_STEPS
    assert len(folds) <= 31 and "over" in folds.message and "pieces" in folds.message
    far = follow_fold(turned_family(5.0, lambda p: 1.0), [u ** 3 - u, u, 0.0], p=0.0,
                      coordinate=0, parameter_range=(-1.0, 45.0))
    assert far.status is Status.TERMINAL_EVENT and len(far.pieces) > 200
    assert far.p[-1] == pytest.approx(45.0, abs=1e-12)
    longest = follow_fold(rotating_family(), [u ** 3 - u, u, 0.0], p=0.0, coordinate=0,
                          options=Options(tol=1e-12, max_arclength=20.0),
                          parameter_range=(-1.0, 40.0))
    assert longest.status is Status.MAX_ARCLENGTH
    assert longest.s[-1] == pytest.approx(20.0, abs=1e-9)


def turned_family(turn: float, a) -> Family:
    """``(U^3 - a(p) U - lambda, V) = 0`` with ``(U, V)`` the coordinates ``(a, b)`` turned by
    ``turn p``: the folds in ``lambda`` are ``3 U^2 = a(p)``, ``V = 0``; with ``a = cos`` one
    closed loop in ``p`` with two cusps, at ``p = +-pi/2`` (``U = 0``). With ``turn != 0``
    the fold test's borders are renewed on the way (every ~0.2 in ``p`` for ``turn = 5``)."""
    def residual(x, p):
        c, s = math.cos(turn * p), math.sin(turn * p)
        u, v = c * x[1] + s * x[2], -s * x[1] + c * x[2]
        return np.array([u ** 3 - a(p) * u - x[0], v])

    return Family(residual, names=("lambda", "a", "b"), parameter="p")


@pytest.mark.parametrize("turn", [0.0, 1.0, 5.0])
@pytest.mark.parametrize("p0", [0.0, 0.3, -1.4])
def test_a_closed_curve_of_folds_closes_once_with_its_borders_renewed(turn, p0):
    # renewed borders: it went round until the limit of pieces, each cusp reported 50 times,
    # and ok; a piece ending at the start closed after a step of 1e-11 with two noise folds
    u = math.sqrt(math.cos(p0) / 3.0)
    c, s = math.cos(turn * p0), math.sin(turn * p0)
    folds = follow_fold(turned_family(turn, math.cos), [u ** 3 - math.cos(p0) * u, c * u, s * u], p=p0,
                        coordinate=0, parameter_range=(-3.0, 3.0))
    assert folds.status is Status.CLOSED and (len(folds.pieces) > 1) == (turn != 0.0)
    cusps = folds.special("cusp")
    assert sorted(round(point.p, 6) for point in cusps) == [-1.570796, 1.570796]
    assert np.max(np.abs(folds.z[-1] - folds.z[0])) <= 1e-9
    assert folds.p.max() == pytest.approx(math.pi / 2, abs=1e-6)


def test_a_start_outside_the_parameter_range_is_refused():
    # it was followed from mu = 3 through the whole range (5, 6) and reported ok
    with pytest.raises(ValueError, match=r"mu = 3.0 is outside parameter_range = \(5.0, 6.0\)"):
        follow_fold(cusp_family(), [-2.0, 1.0], p=3.0, coordinate=0, parameter_range=(5, 6))


def test_an_x_start_without_p_names_the_missing_p():
    with pytest.raises(ValueError, match="start has 2 coordinates and no p was given"):
        follow_fold(cusp_family(), [-2.0, 1.0], coordinate=0)


def test_a_start_that_is_no_fold_of_the_coordinate_is_named_so():
    # (2, -1) at mu = 3 is a fold of lambda, not of u: the engine's advice for a singular
    # start (a branch point: switch_branch) would mislead here
    curve = follow_fold(cusp_family(), [2.0, -1.0], p=3.0, coordinate=1, direction=-1,
                        parameter_range=(-1.0, 3.0))
    assert curve.status is Status.SINGULAR_START
    assert "not a regular point of the curve of fold of u" in curve.message
    assert "switch_branch" not in curve.message
    # the engine's finding is kept whole (it was cut at its first " (", which a point's
    # description can hold)
    assert "the Jacobian has rank < n at the start" in curve.message
    assert "smallest/largest singular value" in curve.message


def test_points_at_p_of_a_fold_curve_traced_with_difference_quotients():
    # Newton to event_tol could not contract on the noise of difference quotients of
    # difference quotients: at() raised for 18% of p on a regular curve (its rows are fine)
    family = turned_family(1.0, lambda p: 1.0 + 0.5 * math.sin(3.0 * p))
    u = math.sqrt(1.0 / 3.0)
    folds = follow_fold(family, [u ** 3 - u, u, 0.0], p=0.0, coordinate=0,
                        parameter_range=(0.0, 1.0))
    assert folds.status is Status.TERMINAL_EVENT
    for p in np.linspace(0.001, 0.999, 100):
        (z,) = folds.at(p)
        assert z[-1] == p
        assert np.max(np.abs(family.residual_z(z))) <= 1e-9


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_where_the_curve_itself_is_singular_the_point_is_no_cusp(sign):
    # x0^2 + sign x1^2 = p: at p = 0 the curve is one point (an isola is born, sign = 1) or two
    # crossing lines (sign = -1); H_x = 0 there, so no fold is defined; it was called a cusp
    family = Family(lambda x, p: np.array([sign * x[1] ** 2 + x[0] ** 2 - p]),
                    lambda x, p: np.array([[2.0 * x[0], 2.0 * sign * x[1]]]), parameter="p")
    folds = follow_fold(family, [1.0, 0.0], p=1.0, coordinate=0, direction=-1,
                        parameter_range=(-1.0, 1.0))
    assert [q.kind for q in folds.points] == [Codim2Kind.SINGULAR, Codim2Kind.EVENT]
    assert np.max(np.abs(folds.points[0].z)) < 1e-10
    assert "not a cusp" in folds.points[0].equations[-1]
    assert folds.special(Codim2Kind.CUSP) == ()
