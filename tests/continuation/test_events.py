"""Events and box limits: located to event_tol on the curve, terminal ones end the curve."""

import math

import numpy as np
import pytest

from continuation import CallbackError, Event, Options, Problem, Status, box_events, trace


def test_box_exit_is_exact(circle):
    # counter-clockwise from (1, 0) the circle leaves y >= -0.5 at (-sqrt(3)/2, -0.5)
    curve = trace(circle, [1.0, 0.0], events=box_events(lower={1: -0.5}))
    assert curve.status is Status.TERMINAL_EVENT
    (event,) = curve.special("event")
    assert event.name == "x[1] >= -0.5"
    assert event.index == len(curve) - 1
    assert abs(curve.x[-1, 1] + 0.5) <= 1e-12
    assert abs(curve.x[-1, 0] + math.sqrt(3) / 2) <= 1e-12
    assert event.residual <= 1e-10
    assert event.accuracy <= 1e-12
    assert curve.s[-1] == pytest.approx(7 * math.pi / 6, abs=1e-6)


def test_box_events_use_names_and_skip_missing_bounds(cubic):
    events = box_events([-10.0, None], (math.inf, 2.0), names=cubic.names)
    assert [e.name for e in events] == ["lambda >= -10.0", "u <= 2.0"]
    assert [e.direction for e in events] == [-1, 1]
    assert all(e.terminal for e in events)
    assert events[1].function(np.array([0.0, 2.5])) == 0.5


def test_box_events_validation():
    with pytest.raises(ValueError, match=r"lower < upper, got lower=1.0, upper=0.0"):
        box_events({0: 1.0}, {0: 0.0})
    with pytest.raises(ValueError, match="index must be an integer >= 0"):
        box_events({-1: 0.0})


def test_non_terminal_event_is_located_and_reported(circle):
    crossing = Event("x = 0", lambda x: x[0])
    curve = trace(circle, [1.0, 0.0], events=[crossing])
    assert curve.status is Status.CLOSED
    events = curve.special("event")
    assert [e.name for e in events] == ["x = 0", "x = 0"]
    assert np.allclose(events[0].x, [0.0, 1.0], atol=1e-12)
    assert np.allclose(events[1].x, [0.0, -1.0], atol=1e-12)
    assert abs(events[0].s - math.pi / 2) < 1e-6
    assert abs(events[1].s - 3 * math.pi / 2) < 1e-6


def test_event_direction_filters_crossings(circle):
    increasing = Event("x increasing", lambda x: x[0], direction=1)
    decreasing = Event("x decreasing", lambda x: x[0], direction=-1)
    curve = trace(circle, [1.0, 0.0], events=[increasing, decreasing])
    assert [(e.name, round(e.x[1])) for e in curve.special("event")] == [
        ("x decreasing", 1), ("x increasing", -1)]


def test_terminal_event_stops_the_curve_there(cubic):
    stop = Event("lambda = 0", lambda x: x[0], direction=1, terminal=True)
    curve = trace(cubic, [-6.0, -2.0], direction=[1.0, 0.0], events=[stop])
    assert curve.status is Status.TERMINAL_EVENT
    assert "lambda = 0" in curve.message
    last = curve.x[-1]
    assert abs(last[0]) <= 1e-12
    # the first increasing crossing of lambda = 0 is on the lower branch, at u = -1
    assert abs(last[1] + 1.0) <= 1e-12
    assert curve.special("event")[0].index == len(curve) - 1


def test_event_at_the_start_is_not_a_crossing(circle):
    curve = trace(circle, [1.0, 0.0], events=box_events(lower={1: 0.0}))
    # starts on the bound y = 0 moving up, leaves at (-1, 0)
    assert curve.status is Status.TERMINAL_EVENT
    assert np.allclose(curve.x[-1], [-1.0, 0.0], atol=1e-12)


def test_event_validation():
    with pytest.raises(ValueError, match="Event.direction must be -1, 0 or 1, got 2"):
        Event("e", lambda x: x[0], direction=2)
    with pytest.raises(TypeError, match="Event.function must be callable"):
        Event("e", 1.0)


def test_linear_event_validation():
    with pytest.raises(ValueError, match="declared linear but has no gradient"):
        Event("e", lambda x: x[0], linear=True)
    with pytest.raises(TypeError, match="Event.linear must be True or False"):
        Event("e", lambda x: x[0], gradient=lambda x: np.array([1.0, 0.0]), linear=1)
    assert all(e.linear for e in box_events({0: -1.0}, {1: 2.0}))


def _counted(function):
    calls = []

    def counted(x):
        calls.append(1)
        return function(x)
    return counted, calls


@pytest.mark.parametrize("direction", [0, 1, -1])
def test_a_linear_event_has_the_same_zeros_for_fewer_calls(circle, direction):
    # x - 0.3 y + 0.1 crosses zero twice on the unit circle; declared linear it is not
    # sampled inside the steps, and its zeros (located on the curve) are the same
    gradient = np.array([1.0, -0.3])
    results = []
    for linear in (False, True):
        function, calls = _counted(lambda x: x[0] - 0.3 * x[1] + 0.1)
        event = Event("line", function, direction, gradient=lambda x: gradient, linear=linear)
        curve = trace(circle, [1.0, 0.0], events=[event])
        assert curve.ok
        results.append(([p.x for p in curve.special("event")], len(calls), curve.x))
    (zeros, sampled_calls, x), (linear_zeros, linear_calls, linear_x) = results
    assert len(zeros) == (2 if direction == 0 else 1)
    assert np.array_equal(np.array(zeros), np.array(linear_zeros))
    assert np.array_equal(x, linear_x)
    assert linear_calls <= sampled_calls - (len(x) - 1)
    for point in linear_zeros:
        assert abs(point[0] - 0.3 * point[1] + 0.1) <= 1e-12
        assert abs(math.hypot(*point) - 1.0) <= 1e-12


def test_an_event_declared_linear_that_is_not_fails_loudly(circle):
    # x^2 has zeros the samples it is spared would show; declared linear it must not pass
    event = Event("x^2 - 0.3", lambda x: x[0] ** 2 - 0.3, gradient=lambda x: np.array([1.0, 0.0]),
                  linear=True)
    with pytest.raises(CallbackError, match="'x\\^2 - 0.3' is declared linear but is not affine "
                       "along the curve") as raised:
        trace(circle, [1.0, 0.0], events=[event])
    assert raised.value.curve.status is Status.CALLBACK_FAILED
    # an affine event with a gradient that is not finite is refused as well
    bad = Event("x", lambda x: x[0], gradient=lambda x: np.array([np.nan, 0.0]), linear=True)
    with pytest.raises(CallbackError, match="gradient of event 'x' is not finite"):
        trace(circle, [1.0, 0.0], events=[bad])


@pytest.mark.parametrize(("centre", "radius"), [(1e3, 1e-4), (1e6, 1.0), (1e5, 1e-2)])
def test_an_affine_event_far_from_the_origin_passes_the_check(centre, radius):
    # x + y - 2c on a small circle around (c, c): the terms cancel to far less than their
    # rounding (some 1e-16 of |x|), which the affine check must allow for, not report
    circle = Problem(lambda x: np.array([(x[0] - centre) ** 2 + (x[1] - centre) ** 2
                                         - radius ** 2]),
                     lambda x: np.array([[2 * (x[0] - centre), 2 * (x[1] - centre)]]))
    options = Options(ds=0.05 * radius, ds_max=0.2 * radius)
    zeros = []
    for linear in (False, True):
        event = Event("x + y = 2c", lambda x: x[0] + x[1] - 2 * centre,
                      gradient=lambda x: np.array([1.0, 1.0]), linear=linear)
        curve = trace(circle, [centre + radius, centre], events=[event], options=options)
        assert curve.status is Status.CLOSED
        zeros.append(np.array([p.x for p in curve.special("event")]))
    assert zeros[0].shape == (2, 2)
    assert np.array_equal(zeros[0], zeros[1])
    for x, y in zeros[1]:  # on the circle (to tol) and on the line (to the rounding of x, y)
        assert abs((x - centre) ** 2 + (y - centre) ** 2 - radius ** 2) <= 1e-10
        assert abs((x - centre) + (y - centre)) <= 8 * np.finfo(float).eps * centre


def test_max_arclength_is_exact(circle):
    curve = trace(circle, [1.0, 0.0], options=Options(max_arclength=1.0))
    assert curve.status is Status.MAX_ARCLENGTH and curve.ok
    assert curve.s[-1] == 1.0
    assert np.allclose(curve.x[-1], [math.cos(1.0), math.sin(1.0)], atol=1e-9)


def _line():
    from continuation import Problem

    # x = (lambda, y), y = lambda: the event's argument is the arclength / sqrt 2
    return Problem(lambda x: np.array([x[1] - x[0]]), lambda x: np.array([[-1.0, 1.0]]))


@pytest.mark.parametrize("ds_max", [0.2, 0.5])
@pytest.mark.parametrize("omega", [30.0, 60.0, 100.0])
def test_an_event_faster_than_the_step_shows_every_zero(omega, ds_max):
    # cos(omega lambda) has up to 11 zeros inside one step here; the ends' values and slopes
    # alone showed 45 of its 95 zeros for omega = 30 and ds_max = 0.5, with status ok; the
    # samples at a third and two thirds of each step, checked on the curve, show them all
    length = 10.0
    event = Event("cos", lambda x: math.cos(omega * x[0]))
    curve = trace(_line(), [0.0, 0.0], 1, Options(ds_max=ds_max, max_arclength=length * math.sqrt(2)),
                  events=[event])
    assert curve.status is Status.MAX_ARCLENGTH
    found = sorted(abs(p.x[0]) for p in curve.special("event"))
    exact = [(0.5 + n) * math.pi / omega for n in range(int(length * omega / math.pi) + 1)]
    exact = [z for z in exact if z < length]
    assert len(found) == len(exact)
    assert max(abs(f - z) for f, z in zip(found, exact, strict=True)) <= 1e-10


@pytest.mark.parametrize("centre", np.linspace(1.0, 2.0, 7).tolist())
def test_a_dip_narrower_than_the_step_between_flat_ends_is_seen(centre):
    # 1 - 1.5 exp(-((lambda - c)/w)^2) is flat at both ends of a step of 0.35 in lambda and
    # dips below zero over 0.064 of it: 4 of these 7 pairs were missed, status ok
    width = 0.05
    event = Event("dip", lambda x: 1.0 - 1.5 * math.exp(-((x[0] + centre) / width) ** 2))
    curve = trace(_line(), [0.0, 0.0], 1, Options(ds_max=0.5, max_arclength=4 * math.sqrt(2)),
                  events=[event])
    half = width * math.sqrt(math.log(1.5))
    found = sorted(-p.x[0] for p in curve.special("event"))
    assert found == pytest.approx([centre - half, centre + half], abs=1e-10)


def test_an_event_steep_across_the_curve_but_slow_along_it_is_not_split(circle):
    # the samples lie on the step's arc, O(h^4) off the curve: an event that is steep across
    # the curve differs there from its model by far more than along the curve, where it is
    # the slow x - 0.3. Each such disagreement is checked again on the curve, where it goes
    # away, so no step is split.
    import continuation.scan as scan

    event = Event("steep", lambda x: 1e5 * (x[0] ** 2 + x[1] ** 2 - 1.0) + (x[0] - 0.3))
    checked, added = [], []
    corrected, add = scan.StepScan._corrected, scan.StepScan.add
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(scan.StepScan, "_corrected",
                      lambda self, lo, hi, s: checked.append(s) or corrected(self, lo, hi, s))
        patch.setattr(scan.StepScan, "add", lambda self, node: added.append(node) or add(self, node))
        curve = trace(circle, [1.0, 0.0], options=Options(ds_max=0.5), events=[event])
    assert curve.status is Status.CLOSED
    assert checked, "the samples on the arc should have disagreed with the model somewhere"
    assert added == []
    points = curve.special("event")
    assert np.allclose([p.x[0] for p in points], 0.3, atol=1e-9)
    assert sorted(p.x[1] for p in points) == pytest.approx([-math.sqrt(0.91), math.sqrt(0.91)],
                                                          abs=1e-9)


def test_an_event_that_vanishes_along_a_stretch_without_changing_sign_has_no_zero():
    # max(0, |lambda + 1| - 0.3) touches zero over [-1.3, -0.7] and never changes sign; a
    # sample node inside the stretch used to read as a crossing there
    event = Event("flat", lambda x: max(0.0, abs(x[0] + 1.0) - 0.3))
    curve = trace(_line(), [0.0, 0.0], 1, Options(ds_max=0.5, max_arclength=4.0), events=[event])
    assert curve.status is Status.MAX_ARCLENGTH
    assert curve.special("event") == ()


def test_an_event_not_finite_on_the_curve_inside_a_step_fails_loudly():
    # not finite over 0.2 in lambda, between the step's ends: a sample there, corrected onto
    # the curve, shows it (the ends alone did not: the run ended ok)
    event = Event("holey", lambda x: math.nan if abs(x[0] + 1.07) < 0.1 else x[0] + 1.5)
    curve = trace(_line(), [0.0, 0.0], 1, Options(ds_max=0.5, max_arclength=4.0), events=[event])
    assert curve.status is Status.EVENT_NOT_FINITE
    assert "event 'holey' is nan" in curve.message


def test_an_event_located_at_a_singular_point_reports_how_far_it_may_be():
    # the folium x^3 + y^3 = 3 x y through its node at the origin, with the event x = y: near
    # the node the corrected trials jump, and the bracket closed (to 7e-13) on a point where
    # x - y is 1.5e-6, reported with accuracy 7e-13 (a new-user review). The accuracy is now
    # at least the distance the value leaves at the step's slope; a regular zero keeps its own.
    folium = Problem(lambda x: np.array([x[0] ** 3 + x[1] ** 3 - 3.0 * x[0] * x[1]]),
                     lambda x: np.array([[3 * x[0] ** 2 - 3 * x[1], 3 * x[1] ** 2 - 3 * x[0]]]))
    diagonal = Event("x = y", lambda x: x[0] - x[1])
    curve = trace(folium, [1.5, 1.4], options=Options(fold_coordinates=(0, 1)),
                  events=[*box_events(lower={0: -2.0, 1: -2.0}, upper={0: 3.0, 1: 3.0}),
                          diagonal])
    zeros = [p for p in curve.special("event") if p.name == "x = y"]
    assert len(zeros) == 2
    regular, at_node = zeros
    assert abs(regular.x[0] - regular.x[1]) <= 1e-12 and regular.accuracy <= 1e-10
    assert at_node.accuracy >= 0.5 * abs(at_node.x[0] - at_node.x[1])
