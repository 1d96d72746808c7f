"""The atlas: special points followed in k (and in nu) against the tracer at each k, the
thresholds against closed forms and against a bisection on the per-k topology."""

import dataclasses
import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from continuation import Event
from groove_model.model.boundaries import corner_point
from groove_model.model.parameters import Compliance, Parameters
from groove_model.tracing import atlas as atlas_module
from groove_model.tracing import trace_boundaries
from groove_model.tracing.atlas import (
    ATLAS_COLUMNS,
    ATLAS_OPTIONS,
    atlas_in_k,
    trace_atlas,
    trace_atlas_in_poisson,
)
from groove_model.tracing.families import domain_events, edge_event
from groove_model.tracing.topology import thresholds

SQRT2 = math.sqrt(2.0)
RESULTS = Path(__file__).resolve().parents[1] / "results"
#: atlas curve -> (boundary, kind) of the tracer's special point
TRACED = {"junction": ("dr_limit", "junction"),
          "dr_limit_fold_delta": ("dr_limit", "fold_delta"),
          "rs_no_roll_fold_gamma": ("rs_no_roll", "fold_gamma")}


@pytest.fixture(scope="module")
def atlas():
    return trace_atlas((1e-4, 1e6))


def test_the_atlas_has_three_curves_and_three_thresholds(atlas):
    assert atlas.ok and set(atlas.curves) == set(TRACED)
    assert [t.name for t in atlas.thresholds] == ["k_fold", "k_branch", "k_cross"]
    for t in atlas.thresholds:
        assert t.residual <= 1e-14 and t.accuracy <= 1e-12
        assert len(t.equations) == 5  # five equations in (gamma, delta, w, upsilon, log k)
    # the closed forms: k_fold = c / sqrt 2, k_branch = c sqrt 2
    assert atlas.threshold("k_fold").value == pytest.approx(1 / SQRT2, rel=1e-14)
    assert atlas.threshold("k_branch").value == pytest.approx(SQRT2, rel=1e-14)
    # the junction is born at the branch point, the fold enters through the seed
    gamma_b = math.atan(SQRT2)
    assert np.max(np.abs(atlas.threshold("k_branch").x
                         - [gamma_b, 0.0, math.pi / 2 - gamma_b, 0.0])) <= 1e-12
    k_fold = 1 / SQRT2
    assert np.max(np.abs(atlas.threshold("k_fold").x
                         - [math.atan(k_fold), 0.0, math.pi / 2 - math.atan(k_fold), 0.0])) \
        <= 1e-12
    # k_cross: the junction is the maximum of delta along dr_limit, upsilon = 0 there
    cross = atlas.threshold("k_cross")
    assert cross.value == pytest.approx(15.1993961936545, rel=1e-12)
    assert abs(cross.x[3]) <= 1e-14


def test_every_atlas_point_agrees_with_the_tracer_at_50_k(atlas):
    worst = 0.0
    for k in np.geomspace(1e-4, 1e6, 50):
        traced = trace_boundaries(k)
        assert traced.ok, traced.failures
        for name, (boundary, kind) in TRACED.items():
            mine = atlas.curves[name].physical_at(k)
            theirs = [p.x for p in traced.curves[boundary].special(kind)] \
                if boundary in traced.curves else []
            assert len(mine) == len(theirs), (k, name)
            g = min(1.0, math.atan(k))  # the scale of gamma and delta for small k
            for x, y in zip(mine, theirs):
                difference = np.abs(x - y)
                difference[:2] /= g
                worst = max(worst, float(difference.max()))
    assert worst <= 1e-10


def test_the_junction_has_beta_L_arctan_c_over_k_and_the_fold_reaches_the_corner(atlas):
    junction = atlas.curves["junction"]
    k = junction.values
    assert np.max(np.abs(junction.x[:, 2] - np.arctan(1.0 / k))) <= 1e-12
    assert np.all(junction.x[:, 3] == 0.0)
    # the fold in gamma of rs_no_roll approaches (pi/4, pi/4) with beta_L ~ (2/(3k))^2
    fold = atlas.curves["rs_no_roll_fold_gamma"]
    (x,) = fold.at(1e6)
    assert x[2] * (1.5e6) ** 2 == pytest.approx(1.0, rel=1e-5)
    assert np.max(np.abs(x[:2] - math.pi / 4)) <= 1e-6


def test_frames_and_dense_output(atlas):
    frame = atlas.curve_frame("junction")
    assert tuple(frame.columns) == ATLAS_COLUMNS
    assert frame["threshold"].iloc[0] == "k_branch" and (frame["compliance"] == 1.0).all()
    assert (frame["nu"] == 0.0).all()
    table = atlas.thresholds_frame()
    assert list(table["threshold"]) == ["k_fold", "k_branch", "k_cross"]
    values, x = atlas.curves["dr_limit_fold_delta"].dense(4)
    assert len(values) > len(atlas.curves["dr_limit_fold_delta"].p) and x.shape[1] == 4


def test_a_range_without_thresholds_has_no_junction():
    small = trace_atlas((1e-3, 0.5))
    assert small.ok and set(small.curves) == {"dr_limit_fold_delta"} and not small.thresholds
    with pytest.raises(KeyError, match="no threshold 'k_fold'"):
        small.threshold("k_fold")
    with pytest.raises(ValueError, match="k_min < k_max"):
        trace_atlas((2.0, 1.0))


def test_the_atlas_in_nu_at_k_1_finds_where_c_sqrt_2_equals_1():
    in_nu = trace_atlas_in_poisson(1.0)
    (t,) = in_nu.thresholds
    # c(nu) sqrt 2 = 1  <=>  c = 1/sqrt 2  <=>  nu = 2 (1 - c)/(2 - c)
    c = 1.0 / SQRT2
    assert t.name == "nu_branch"
    assert t.value == pytest.approx(2.0 * (1.0 - c) / (2.0 - c), abs=1e-12)


def test_the_atlas_in_nu_at_k_10_and_the_atlas_in_k_agree_on_k_cross():
    in_nu = trace_atlas_in_poisson(10.0)
    (t,) = in_nu.thresholds
    assert t.name == "nu_cross"
    compliance = Compliance.from_poisson(t.value)
    # at that nu, the atlas in k puts k_cross at k = 10
    in_k = trace_atlas((1.0, 100.0), compliance=compliance)
    assert in_k.threshold("k_cross").value == pytest.approx(10.0, rel=1e-10)


def _observed(k, feature):
    """The per-k topology as the tracer sees it (not its check against the table)."""
    curves = trace_boundaries(k).curves
    if feature == "fold":
        return bool(curves["rs_no_roll"].special("fold_gamma"))
    junctions = curves["dr_limit"].special("junction")
    if feature == "branch":
        return bool(junctions)
    (fold,) = curves["dr_limit"].special("fold_delta")
    return bool(junctions) and fold.index < junctions[0].index


@pytest.mark.slow
@pytest.mark.parametrize("name, feature", [("k_fold", "fold"), ("k_branch", "branch"),
                                           ("k_cross", "cross")])
def test_each_threshold_agrees_with_a_bisection_on_the_per_k_topology(name, feature):
    value = thresholds(1.0).value(name)
    low, high = value * (1 - 1e-3), value * (1 + 1e-3)
    assert not _observed(low, feature) and _observed(high, feature)
    while high / low - 1.0 > 1e-10:
        middle = math.sqrt(low * high)
        low, high = (middle, high) if not _observed(middle, feature) else (low, middle)
    band = 1e-9 * value
    assert low - band <= value <= high + band, (low, value, high)


@pytest.mark.parametrize("offset", [1e-2, 1e-8])
def test_the_tracer_checks_the_order_of_junction_and_maximum(atlas, offset):
    # 1e-8 from k_cross the two points are 2e-9 apart along dr_limit, in one step
    k_cross = atlas.threshold("k_cross").value
    for k, order in ((k_cross * (1 - offset), ("junction", "fold_delta")),
                     (k_cross * (1 + offset), ("fold_delta", "junction"))):
        traced = trace_boundaries(Parameters(k))
        assert traced.ok
        inner = [p.kind.value for p in traced.curves["dr_limit"].special_points
                 if p.kind.value in order]
        assert tuple(inner) == order


def test_committed_atlas_results_are_reproduced(atlas):
    for name in TRACED:
        old = pd.read_csv(RESULTS / f"atlas_{name}.csv", keep_default_na=False)
        new = atlas.curve_frame(name)
        assert list(old.columns) == list(new.columns) and len(old) == len(new), name
        for column in ("k", "gamma", "delta", "beta_L", "upsilon"):
            assert np.allclose(new[column], old[column], rtol=1e-9, atol=1e-11), column
    old = pd.read_csv(RESULTS / "atlas_thresholds.csv")
    assert np.allclose(old["value"], [t.value for t in atlas.thresholds], rtol=1e-12)


@pytest.mark.parametrize("nu", [0.24495564743398962, 0.17522534680573087])
def test_a_fold_unresolved_at_the_range_end_is_found_inside(nu):
    # the fold in gamma of rs_no_roll is ~1/k^2 from the corner: at k_max = 1e6 c (c < 1 here)
    # the tracer does not resolve it, and with seeds at the ends only the atlas lost the curve,
    # its threshold k_fold and so the tracer's expected fold for every k (found by a random
    # sweep in (k, nu): trace_boundaries failed, loudly, at k = 189.6, nu = 0.245)
    c = Compliance.from_poisson(nu).ratio
    table = thresholds(c)
    assert [t.name for t in table.points] == ["k_fold", "k_branch", "k_cross"]
    assert table.points[0].value == pytest.approx(c / SQRT2, rel=1e-12)
    assert set(atlas_in_k((1e-4 * c, 1e6 * c), c).curves) == set(TRACED)
    bs = trace_boundaries(Parameters(189.6420639321449, compliance=Compliance(c)))
    assert bs.ok, bs.failures
    assert len(bs.curves["rs_no_roll"].special("fold_gamma")) == 1


@pytest.mark.parametrize("k", [7e5, 9e5, 1e6])
def test_the_fold_next_to_the_corner_is_followed_over_nu_at_large_k(k):
    # the fold in gamma of rs_no_roll is ~3e-13 inside delta = gamma there (8 c^3/(27 k^2)),
    # under its points' accuracy: gamma - delta as the event vanished by rounding on its curve
    # and the atlas failed at these k (a curve in two pieces, none over the whole range)
    atlas = trace_atlas_in_poisson(k)
    assert atlas.ok, atlas.failures
    assert set(atlas.curves) == set(TRACED) and not atlas.thresholds
    for curve in atlas.curves.values():
        assert (curve.p[0], curve.p[-1]) == pytest.approx((0.0, 0.5), abs=1e-9), curve.name
    fold = atlas.curves["rs_no_roll_fold_gamma"]
    c = 2.0 * (1.0 - fold.p) / (2.0 - fold.p)
    assert np.allclose(fold.x[:, 2], (2.0 * c / (3.0 * k)) ** 2, rtol=1e-4, atol=0.0)
    assert np.all(np.abs(fold.x[:, :2] - 0.25 * math.pi) < 1e-11)
    # the event in the form the atlas uses: of order one on the fold, zero at the corner
    family = fold.family
    edge = edge_event(family).function
    rows = zip(fold.x, fold.p, strict=True)
    assert all(edge(np.append(family.from_x(x, p), p)) > 0.1 for x, p in rows)
    corner = np.append(family.from_x(corner_point(), 0.3), 0.3)
    assert edge(corner) == 0.0


def test_events_within_rounding_of_the_corner_fail_the_atlas_instead_of_making_thresholds(
        monkeypatch):
    # with gamma - delta as the event delta = gamma (the form the atlas used), the fold of
    # rs_no_roll at k = 7e5 meets it by rounding, 1.4e-13 from the corner: the safeguard fails
    # the atlas rather than report a threshold or a curve with a gap
    def naive(family):
        return [Event("delta = gamma", lambda z: z[0] - z[1], -1, True)
                if event.name == "delta = gamma" else event for event in domain_events(family)]

    monkeypatch.setattr(atlas_module, "domain_events", naive)
    atlas = trace_atlas_in_poisson(7e5)
    assert not atlas.ok
    assert any("from the singular corner" in f for f in atlas.failures), atlas.failures
    assert not atlas.thresholds


def test_no_atlas_point_leaves_the_domain_by_rounding(atlas):
    # the junction's first row (born on delta = 0 at k_branch) was written as delta = -7.7e-14
    for curve in atlas.curves.values():
        assert np.all(curve.x[:, 1] >= 0.0) and np.all(curve.x[:, 1] <= curve.x[:, 0]), curve.name
        _, dense = curve.dense(6)
        assert np.all(dense[:, 1] >= 0.0), curve.name
    for t in atlas.thresholds:
        assert 0.0 <= t.x[1] <= t.x[0], t.name


@pytest.mark.parametrize("call, message", [
    (lambda: trace_atlas((1e-6, 1e8)), "k = 1e-06 is outside the range the boundaries"),
    (lambda: trace_atlas((0.0, 10.0)), r"k = 0.0 is outside the range .* 1e-4 <= k <= 1e6"),
    (lambda: trace_atlas((1e5, 1e7)), "k = 1e\\+07 is outside the range"),
    (lambda: trace_atlas((1.0, 10.0), compliance=0.3), "compliance ratio c = 0.3 is outside"),
    (lambda: trace_atlas_in_poisson(1e7), "k = 1e\\+07 is outside the range"),
    (lambda: trace_atlas_in_poisson(1.0, (-0.5, 0.5)), "Poisson ratio nu = -0.5 is outside"),
])
def test_the_atlas_refuses_what_is_not_traced(call, message):
    # trace_atlas((1e-6, 1e8)) ended in a bare RuntimeError from the engine, (1e5, 1e7) and
    # c = 0.3 were traced unchecked (with a "cusp" for c = 0.3)
    with pytest.raises(ValueError, match=message):
        call()


def test_an_atlas_in_nu_stays_inside_its_range():
    # rows at nu = -2.1e-13 (c = 1.000000000000105) were written, just outside 0 <= nu <= 1/2
    atlas = trace_atlas_in_poisson(10.0)
    for curve in atlas.curves.values():
        assert curve.values.min() >= 0.0 and curve.values.max() <= 0.5, curve.name


def test_a_curve_answers_only_inside_the_range_of_its_atlas():
    # the junction exists for every k > k_branch; outside the atlas's range the atlas cannot
    # say, so it refuses instead of answering "no point" (an empty list)
    atlas = trace_atlas((0.5, 20.0))
    junction = atlas.curves["junction"]
    assert len(junction.at(10.0)) == 1 and len(junction.at(20.0)) == 1
    assert junction.at(1.0) == []  # inside the range, below k_branch: it does not exist
    for value in (100.0, 0.49, float("nan"), -1.0, 0.0):
        with pytest.raises(ValueError, match=r"0.5 <= k <= 20, the range of the atlas"):
            junction.at(value)
        with pytest.raises(ValueError, match="range of the atlas"):
            junction.physical_at(value)
    with pytest.raises(TypeError, match="real number"):
        junction.at("10")


@pytest.mark.parametrize("bad", [1.0, (1.0, 2.0, 3.0), "12", None])
def test_a_range_that_is_not_a_pair_is_named(bad):
    with pytest.raises(TypeError, match="k_range must be a pair"):
        trace_atlas(bad)


@pytest.mark.parametrize("nu", [0.1, 0.3, 0.123456789])
def test_the_poisson_ratio_of_an_atlas_is_the_one_given(nu):
    # the atlas follows the compliance ratio; its tables write the nu given (0.3, where
    # inverting Mindlin's formula gives 0.30000000000000004)
    atlas = trace_atlas((1.0, 3.0), Compliance.from_poisson(nu))
    rows = atlas.curve_table("dr_limit_fold_delta")
    assert rows and all(row[ATLAS_COLUMNS.index("nu")] == nu for row in rows)


@pytest.mark.parametrize("limit", [{"max_steps": 5}, {"max_arclength": 3.0}])
def test_a_curve_stopped_by_the_options_limits_fails_the_atlas(limit):
    # it was ok with no failure: k_fold missing and the curves cut in pieces with gaps in k
    atlas = trace_atlas(options=dataclasses.replace(ATLAS_OPTIONS, **limit))
    assert not atlas.ok
    assert any("stopped before the curve's end" in failure and "raise Options.max_steps"
               in failure for failure in atlas.failures)


def test_the_atlas_takes_numbers_for_k_not_parameters():
    # Parameters(1, Compliance(0.8)) as an end of the range had its compliance dropped
    from groove_model.model.parameters import Compliance, Parameters  # (only this test's)
    with pytest.raises(TypeError, match="friction coefficient k must be a real number"):
        trace_atlas((Parameters(1.0, Compliance(0.8)), 10.0))
    with pytest.raises(TypeError, match="friction coefficient k must be a real number"):
        trace_atlas_in_poisson(Parameters(1.0))


@pytest.mark.parametrize("k_min, listed", [
    (math.sqrt(2.0) * (1.0 - 1e-14), ["k_cross"]),   # the end comes first: not listed
    (math.sqrt(2.0), ["k_cross"]),
    (math.sqrt(2.0) * (1.0 - 1e-8), ["k_branch", "k_cross"]),
])
def test_a_threshold_at_the_range_end_is_not_listed_under_another_name(k_min, listed):
    """Within rounding of k_min the junction's curve, followed down, reaches the range's end
    together with k_branch, where a validity monitor of dr_no_roll vanishes too: that point is
    dropped with the end, not listed as a threshold of the monitor's name; with a margin,
    k_branch is listed under its name."""
    atlas = trace_atlas((k_min, 100.0))
    assert atlas.ok and [t.name for t in atlas.thresholds] == listed
