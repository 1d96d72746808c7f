"""The tracer: where each boundary starts and ends, junctions, folds, rotation sides, sweeps."""

import math

import numpy as np
import pytest

from groove_model.model.boundaries import BoundarySystem
from groove_model.model.equilibrium import solve_equilibrium
from groove_model.model.parameters import Compliance, Parameters
from groove_model.tracing import trace_boundaries

SQRT2 = math.sqrt(2.0)
CORNER = (math.pi / 4, math.pi / 4)


@pytest.fixture(scope="module")
def k1():
    return trace_boundaries(1.0)


@pytest.fixture(scope="module")
def k10():
    return trace_boundaries(10.0)


def only(curve, kind):
    points = curve.special(kind)
    assert len(points) == 1, [p.kind for p in curve.special_points]
    return points[0]


def assert_on_curve(bs):
    """Every reported point satisfies its boundary's equations (x form) to 1e-10."""
    params = Parameters(bs.k)
    for name, curve in bs.curves.items():
        system = BoundarySystem(name, params)
        for x in curve.x[curve.x[:, 2] > 0]:
            assert np.max(np.abs(system.residual(x))) <= 1e-10, (name, x)
        assert curve.residual <= 1e-10


def test_k1_matches_the_paper(k1):
    assert k1.ok and set(k1.curves) == {"dr_limit", "rs_limit", "rs_no_roll"}
    assert any("dr_no_roll has no physical part" in note for note in k1.notes)
    dr = k1.curves["dr_limit"]
    assert only(dr, "start").x[:2] == pytest.approx([math.atan(1.0), 0.0], abs=1e-14)
    end = only(dr, "end").x
    assert end[0] == pytest.approx(1e-3, abs=1e-12) and end[1] / end[0] > 0.9999
    rs = k1.curves["rs_no_roll"]
    assert only(rs, "start").x[:2] == pytest.approx([math.atan(1.0), 0.0], abs=1e-14)
    corner = only(rs, "end")
    assert corner.x[:2] == pytest.approx(CORNER, abs=1e-10) and "singular corner" in corner.note
    # The paper's remark that rs_no_roll is not a graph over gamma: it turns back once.
    fold = only(rs, "fold_gamma")
    assert fold.x[0] < math.pi / 4 - 0.05
    assert_on_curve(k1)


def test_k10_matches_the_paper(k10):
    assert k10.ok and set(k10.curves) == {"dr_limit", "rs_limit", "dr_no_roll", "rs_no_roll"}
    dr, drn, rsn = (k10.curves[n] for n in ("dr_limit", "dr_no_roll", "rs_no_roll"))
    assert only(dr, "start").x[:2] == pytest.approx([math.atan(10.0), 0.0], abs=1e-14)
    junction = only(dr, "junction").x
    assert abs(junction[3]) <= 1e-12  # upsilon = 0 on dr_limit
    # dr_no_roll: from the branch point (arctan sqrt 2, 0) to the junction, where T/N_L = k.
    assert only(drn, "branch_point").x[:2] == pytest.approx([math.atan(SQRT2), 0.0], abs=1e-12)
    assert only(drn, "junction").x == pytest.approx(junction, abs=1e-9)
    assert drn.x[-1] == pytest.approx(junction, abs=1e-9)
    # rs_no_roll: from the junction to the corner.
    assert only(rsn, "junction").x == pytest.approx(junction, abs=1e-12)
    assert rsn.x[0] == pytest.approx(junction, abs=1e-12)
    assert only(rsn, "end").x[:2] == pytest.approx(CORNER, abs=1e-10)
    # The upsilon = 0 double-rolling line lives in pi/4 <= gamma <= arctan sqrt 2.
    assert np.all(drn.x[:, 0] >= math.pi / 4 - 1e-12)
    assert np.all(drn.x[:, 0] <= math.atan(SQRT2) + 1e-12)
    assert_on_curve(k10)


@pytest.mark.parametrize("k", [1.0, 10.0])
def test_clockwise_on_the_low_gamma_side_of_the_no_roll_lines(k, k1, k10):
    bs = {1.0: k1, 10.0: k10}[k]
    checked = 0
    for name in ("dr_no_roll", "rs_no_roll"):
        if name not in bs.curves:
            continue
        x = bs.curves[name].x
        for i in range(2, len(x) - 2, 3):
            tangent = x[i + 1, :2] - x[i - 1, :2]
            normal = np.array([tangent[1], -tangent[0]]) / np.linalg.norm(tangent)
            if abs(normal[0]) < 0.3:
                continue  # near a fold in gamma the sides are not low/high gamma
            normal *= -np.sign(normal[0])  # points to lower gamma
            eps = 2e-3
            low, high = x[i, :2] + eps * normal, x[i, :2] - eps * normal
            if not (0 < low[1] < low[0] and 0 < high[1] < high[0] < math.pi / 2):
                continue
            assert solve_equilibrium(*low, k).rotation == "clockwise"
            assert solve_equilibrium(*high, k).rotation == "counterclockwise"
            checked += 1
    assert checked >= 5


@pytest.mark.parametrize("k", [1.0, 10.0])
def test_rs_limit_coincides_with_dr_limit(k, k1, k10):
    bs = {1.0: k1, 10.0: k10}[k]
    assert bs.limit_distance <= 1e-9
    params = Parameters(k)
    dr_system = BoundarySystem("dr_limit", params)
    for x in bs.curves["rs_limit"].x:
        assert np.max(np.abs(dr_system.residual(x))) <= 1e-10


def test_dr_limit_separates_double_rolling_below_from_rolling_sliding_above(k10):
    x = k10.curves["dr_limit"].x
    for i in range(3, len(x) - 3, 5):
        g, d = x[i, :2]
        if d < 0.01 or g - d < 0.01:
            continue
        assert solve_equilibrium(g, d - 1e-3, 10.0).regime == "double_rolling"
        assert solve_equilibrium(g, d + 1e-3, 10.0).regime == "rolling_sliding"


SWEEP = [*np.geomspace(1e-2, 1e3, 19), SQRT2, SQRT2 - 1e-4, SQRT2 + 1e-4]


@pytest.mark.parametrize("k", SWEEP, ids=lambda k: f"k={k:.6g}")
def test_sweep_every_expected_boundary_without_failure(k):
    bs = trace_boundaries(k)
    assert bs.ok, bs.failures
    expected = {"dr_limit", "rs_limit", "rs_no_roll"} | ({"dr_no_roll"} if k > SQRT2 else set())
    assert expected <= set(bs.curves)
    for name in expected:
        curve = bs.curves[name]
        assert len(curve.x) >= 2 and curve.special("start") and curve.special("end")
    assert bs.curves["rs_no_roll"].x[-1, :2] == pytest.approx(CORNER, abs=1e-10)
    assert bs.limit_distance <= 1e-9
    assert_on_curve(bs)
    assert_folds_turn_back_in_gamma(bs)


def assert_folds_turn_back_in_gamma(bs):
    """Every reported fold in gamma is a strict local extremum of gamma along its curve."""
    for curve in bs.curves.values():
        for fold in curve.special("fold_gamma"):
            i = fold.index
            assert 0 < i < len(curve.x) - 1, (curve.name, i)
            steps = np.diff(curve.x[i - 1: i + 2, 0])
            assert steps[0] * steps[1] < 0, (curve.name, fold.x)


def test_keep_unphysical_keeps_and_flags_the_rest():
    bs = trace_boundaries(1.0, keep_unphysical=True)
    drn = bs.curves["dr_no_roll"]
    assert not np.any(drn.physical)  # T/N >= sqrt 2 > k all along it
    assert drn.x[-1, :2] == pytest.approx(CORNER, abs=1e-10)
    assert np.all(bs.curves["dr_limit"].physical)


def test_bad_friction_is_rejected():
    with pytest.raises(ValueError, match="friction coefficient k = -1.0 is outside"):
        trace_boundaries(-1.0)


def test_keep_unphysical_says_what_it_does_not_trace():
    # above k_branch rs_no_roll starts at the junction: its part from the seed (d_L < 0) is
    # not traced even with keep_unphysical, and the result says so instead of leaving it out
    kept = trace_boundaries(10.0, keep_unphysical=True)
    assert any("rs_no_roll is traced from the junction" in note for note in kept.notes)
    assert not any("rs_no_roll is traced from the junction" in note
                   for note in trace_boundaries(10.0).notes)
    below = trace_boundaries(1.0, keep_unphysical=True)  # from the seed: nothing left out
    assert not any("rs_no_roll is traced from the junction" in note for note in below.notes)


@pytest.mark.parametrize("nu", [0.0, 0.3])
@pytest.mark.parametrize("below", [1e-9, 3e-10, 1e-11])
def test_keep_unphysical_next_below_k_branch(nu, below):
    # within the threshold band either side's topology is accepted, but a dr_no_roll kept with
    # no physical part (the side where it is absent) was asked to start at the branch point
    compliance = Compliance.from_poisson(nu)
    bs = trace_boundaries(Parameters(compliance.ratio * SQRT2 * (1.0 - below), compliance),
                          keep_unphysical=True)
    assert bs.ok, bs.failures


@pytest.mark.parametrize("k", [SQRT2 * (1.0 + 1e-9), 10.0, 1e6])
def test_s_is_the_arclength_of_the_rows_as_written(k):
    # s was summed before the junction (from dr_no_roll) and the corner were put in place:
    # 97% short of the chord to a junction moved by 6.7e-10 just above k_branch
    for curve in trace_boundaries(k, keep_unphysical=True).curves.values():
        chords = np.linalg.norm(np.diff(curve.x, axis=0), axis=1)
        assert np.all(np.diff(curve.s) >= chords - 4.0 * np.finfo(float).eps * curve.s[1:])


def test_options_of_the_user_keep_the_tracers_own_switches():
    # Options(ds_max=0.1) has fold_coordinates=(): given whole to the engine, it turned the
    # folds off and every boundary failed its topology check
    from continuation import Options  # (only this test's)
    from groove_model.tracing import TraceError  # (only this test's)
    result = trace_boundaries(2.0, options=Options(ds_max=0.1))
    assert result.ok, result.failures
    assert {p.kind for c in result.curves.values() for p in c.special_points} >= {"fold_delta"}
    default = trace_boundaries(2.0)
    assert sum(len(c.x) for c in result.curves.values()) \
        < sum(len(c.x) for c in default.curves.values())      # longer steps: fewer points
    with pytest.raises(TraceError):
        trace_boundaries(2.0, options=Options(max_steps=3, raise_on_failure=True))
    with pytest.raises(TypeError, match="options must be a continuation.Options"):
        trace_boundaries(2.0, options={"ds_max": 0.1})


def test_the_compliance_can_be_given_to_trace_boundaries_as_to_trace_many():
    ratio = trace_boundaries(1.0, compliance=0.8)
    whole = trace_boundaries(Parameters(1.0, Compliance(0.8)))
    assert ratio.ok and ratio.params == whole.params
    assert ratio.to_frame().equals(whole.to_frame())
    assert trace_boundaries(np.array(1.0)).params.k == 1.0     # a 0-d array is a number
    with pytest.raises(TypeError, match="give the compliance once"):
        trace_boundaries(Parameters(1.0), compliance=0.8)
    with pytest.raises(ValueError, match="compliance ratio c = 0.5 is outside the range"):
        trace_boundaries(1.0, compliance=0.5)
