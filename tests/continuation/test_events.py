"""Events and box limits: located to event_tol on the curve, terminal ones end the curve."""

import math

import numpy as np
import pytest

from continuation import Event, Options, Status, box_events, trace


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


def test_max_arclength_is_exact(circle):
    curve = trace(circle, [1.0, 0.0], options=Options(max_arclength=1.0))
    assert curve.status is Status.MAX_ARCLENGTH and curve.ok
    assert curve.s[-1] == 1.0
    assert np.allclose(curve.x[-1], [math.cos(1.0), math.sin(1.0)], atol=1e-9)
