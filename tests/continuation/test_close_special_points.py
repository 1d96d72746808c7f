"""Special points closer than the Hermite arcs' parametrisation error keep their order.

Near a codimension-2 point two special points of one curve (here a fold and an event) lie
within ``1e-9`` of each other; each is located on its own refinement of the step's Hermite
arcs, whose parameters differ by ``O(h^4)``, so the points are put in order along the step's
chord instead.
"""

import math

import numpy as np
import pytest

from continuation import Event, Options, Problem, box_events, trace

U_FOLD = 1.0 / math.sqrt(3.0)


def cubic():
    # x = (lambda, u): u^3 - u - lambda = 0, a fold in lambda at u = 1/sqrt 3
    return Problem(lambda x: np.array([x[1] ** 3 - x[1] - x[0]]),
                   lambda x: np.array([[-1.0, 3.0 * x[1] ** 2 - 1.0]]))


@pytest.mark.parametrize("gap", [1e-7, 1e-8, 1e-9, 3e-10])
@pytest.mark.parametrize("side", [1, -1])
@pytest.mark.parametrize("ds", [0.13, 0.2, 0.29])
def test_a_fold_and_an_event_a_hair_apart_are_in_order(gap, side, ds):
    event = Event("u = u_fold +- gap", lambda x: x[1] - (U_FOLD + side * gap))
    curve = trace(cubic(), [-6.0, -2.0], direction=[1.0, 0.0],
                  options=Options(tol=1e-12, ds=ds, ds_max=ds, fold_coordinates=(0,)),
                  events=[event, *box_events(upper={1: 2.0})])
    assert curve.ok, curve.message
    near = [p.kind.value for p in curve.special_points
            if p.kind.value in ("event", "fold") and p.index > 0 and abs(p.x[1] - U_FOLD) < 1e-3]
    # u increases along the curve: the event at u_fold - gap comes first
    assert near == (["event", "fold"] if side < 0 else ["fold", "event"])
