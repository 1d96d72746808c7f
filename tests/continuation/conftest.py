"""Catalog of analytic continuation problems with their known special points."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pytest

from continuation import Event, Options, Problem, Status, box_events

SQRT3 = math.sqrt(3.0)


@dataclass(frozen=True)
class Case:
    """A problem, how to trace it, and what the curve must contain."""

    name: str
    problem: Problem
    x0: tuple[float, ...]
    direction: object
    options: Options
    status: Status
    events: tuple[Event, ...] = ()
    # kind -> analytic points, in order along the curve
    special: dict = field(default_factory=dict)
    accuracy: float = 1e-10


def circle_problem() -> Problem:
    return Problem(lambda x: np.array([x[0] ** 2 + x[1] ** 2 - 1.0]),
                   lambda x: np.array([[2.0 * x[0], 2.0 * x[1]]]))


def cubic_problem() -> Problem:
    # x = (lambda, u): u^3 - u - lambda = 0
    return Problem(lambda x: np.array([x[1] ** 3 - x[1] - x[0]]),
                   lambda x: np.array([[-1.0, 3.0 * x[1] ** 2 - 1.0]]),
                   names=("lambda", "u"))


def pitchfork_problem() -> Problem:
    # x = (lambda, u): u (lambda - u^2) = 0, trivial branch u = 0, other lambda = u^2
    return Problem(lambda x: np.array([x[1] * (x[0] - x[1] ** 2)]),
                   lambda x: np.array([[x[1], x[0] - 3.0 * x[1] ** 2]]))


def transcritical_problem() -> Problem:
    # x = (lambda, u): u (lambda - u) = 0, branches u = 0 and u = lambda
    return Problem(lambda x: np.array([x[1] * (x[0] - x[1])]),
                   lambda x: np.array([[x[1], x[0] - 2.0 * x[1]]]))


def ellipse_problem() -> Problem:
    # no Jacobian: central finite differences
    return Problem(lambda x: np.array([(x[0] / 2.0) ** 2 + (x[1] / 0.5) ** 2 - 1.0]))


def great_circle_problem() -> Problem:
    # n = 2: unit sphere cut by the plane x + y + z = 0
    return Problem(
        lambda x: np.array([x @ x - 1.0, x.sum()]),
        lambda x: np.array([2.0 * x, np.ones(3)]),
    )


def lemniscate_problem() -> Problem:
    # Bernoulli's lemniscate (x^2 + y^2)^2 = 2 (x^2 - y^2): a figure eight whose
    # crossing at the origin is a simple branch point passed twice
    return Problem(lambda x: np.array([(x @ x) ** 2 - 2.0 * (x[0] ** 2 - x[1] ** 2)]),
                   lambda x: np.array([4.0 * (x @ x) * x - 4.0 * np.array([x[0], -x[1]])]))


FOLD = 2.0 / (3.0 * SQRT3)
R3 = SQRT3 / 2.0
Z_MAX = math.sqrt(2.0 / 3.0)

CATALOG = (
    Case("circle", circle_problem(), (1.0, 0.0), None,
         Options(fold_coordinates=(0, 1)), Status.CLOSED,
         special={"fold": [(0.0, 1.0), (-1.0, 0.0), (0.0, -1.0), (1.0, 0.0)]},
         accuracy=1e-12),
    Case("cubic", cubic_problem(), (-6.0, -2.0), (1.0, 0.0),
         Options(fold_coordinates=(0,)), Status.TERMINAL_EVENT,
         events=tuple(box_events(upper={1: 2.0})),
         special={"fold": [(FOLD, -1.0 / SQRT3), (-FOLD, 1.0 / SQRT3)],
                  "event": [(6.0, 2.0)]}),
    Case("pitchfork", pitchfork_problem(), (-1.0, 0.0), (1.0, 0.0),
         Options(max_arclength=2.0), Status.MAX_ARCLENGTH,
         special={"branch_point": [(0.0, 0.0)]}),
    Case("transcritical", transcritical_problem(), (-1.0, 0.0), (1.0, 0.0),
         Options(max_arclength=2.0), Status.MAX_ARCLENGTH,
         special={"branch_point": [(0.0, 0.0)]}),
    Case("lemniscate", lemniscate_problem(), (math.sqrt(2.0), 0.0), None,
         Options(fold_coordinates=(0, 1)), Status.CLOSED,
         special={"branch_point": [(0.0, 0.0), (0.0, 0.0)],
                  "fold": [(R3, 0.5), (-R3, -0.5), (-math.sqrt(2.0), 0.0), (-R3, 0.5),
                           (R3, -0.5), (math.sqrt(2.0), 0.0)]}),
    Case("ellipse, finite differences", ellipse_problem(),
         (2.0 * math.cos(0.3), 0.5 * math.sin(0.3)), None,
         Options(fold_coordinates=(0, 1)), Status.CLOSED,
         special={"fold": [(0.0, 0.5), (-2.0, 0.0), (0.0, -0.5), (2.0, 0.0)]}),
    Case("great circle", great_circle_problem(), (1 / math.sqrt(2), -1 / math.sqrt(2), 0.0),
         (0.0, 0.0, 1.0), Options(fold_coordinates=(2,)), Status.CLOSED,
         special={"fold": [(-1 / math.sqrt(6), -1 / math.sqrt(6), Z_MAX),
                           (1 / math.sqrt(6), 1 / math.sqrt(6), -Z_MAX)]}),
)


@pytest.fixture(params=CATALOG, ids=lambda case: case.name)
def case(request) -> Case:
    return request.param


@pytest.fixture
def circle() -> Problem:
    return circle_problem()


@pytest.fixture
def cubic() -> Problem:
    return cubic_problem()


@pytest.fixture
def pitchfork() -> Problem:
    return pitchfork_problem()


@pytest.fixture
def transcritical() -> Problem:
    return transcritical_problem()
