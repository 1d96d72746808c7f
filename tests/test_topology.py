"""The expected topology per k: thresholds computed from the equations, and the tracer's use
of them (a curve that differs from it is a failure, never an ok)."""

import dataclasses
import math
import re

import numpy as np
import pytest

from groove_model.cli.main import main
from groove_model.model.parameters import Compliance, Parameters
from groove_model.tracing import DEFAULT_OPTIONS, Where, topology, trace_boundaries
from groove_model.tracing import atlas as atlas_module
from groove_model.tracing import tracer as tracer_module
from groove_model.tracing.topology import expected_topology, format_table, thresholds


@pytest.mark.parametrize("c", [0.5, 2.0 / 3.0, 1.0, 1.7])
def test_thresholds_match_their_closed_forms(c):
    # k_fold: at the seed a tangent without gamma component needs tan^2 beta = 2
    # (linearised right-rolling equation); k_branch: the seed arctan(k/c) meets arctan sqrt 2
    t = thresholds(c)
    assert t.k_fold == pytest.approx(c / math.sqrt(2.0), rel=4e-15)
    assert t.k_branch == pytest.approx(c * math.sqrt(2.0), rel=4e-15)


def test_the_docstring_table_quotes_the_computed_thresholds():
    t = thresholds(1.0)
    quoted = dict(re.findall(r"``(k_fold|k_branch|k_cross)``\s+(\d+\.\d+)", topology.__doc__))
    assert float(quoted["k_fold"]) == pytest.approx(t.k_fold, abs=1e-14)
    assert float(quoted["k_branch"]) == pytest.approx(t.k_branch, abs=1e-14)


def test_the_docstring_topology_table_is_the_generated_one():
    doc = topology.__doc__
    block = doc[doc.index("::\n\n") + 4:doc.index("\n\nExactly at")]
    quoted = "\n".join(line[4:] for line in block.splitlines())
    assert quoted == format_table(thresholds(1.0))


def test_the_table_has_the_ranges_between_the_atlas_thresholds():
    t = thresholds(1.0)
    assert [p.name for p in t.points] == ["k_fold", "k_branch", "k_cross"]
    assert [(r.k_low, r.k_high) for r in t.ranges] == [
        (0.0, t.k_fold), (t.k_fold, t.k_branch), (t.k_branch, t.k_cross), (t.k_cross, math.inf)]
    sequences = [r.curves["dr_limit"].sequence for r in t.ranges]
    assert sequences == [("fold_delta",), ("fold_delta",), ("junction", "fold_delta"),
                         ("fold_delta", "junction")]
    assert t.near(t.k_cross * (1 + 1e-10)) and not t.near(t.k_cross * (1 + 1e-8))


@pytest.mark.parametrize("k, branch, fold", [
    (0.1, False, False), (0.8, False, True), (1.0, False, True), (2.0, True, True),
    (1e5, True, True)])
def test_expected_topology_by_range(k, branch, fold):
    expected = expected_topology(Parameters(k))
    assert expected["dr_limit"].junctions == int(branch)
    assert expected["dr_no_roll"].present is branch
    assert expected["rs_no_roll"].start == ("junction" if branch else "seed")
    assert expected["rs_no_roll"].folds_gamma == int(fold)
    assert expected["dr_limit"].folds_delta == 1 and expected["dr_limit"].folds_gamma == 0


def test_within_the_band_of_a_threshold_either_topology_is_accepted():
    k = math.sqrt(2.0) * (1.0 + 1e-12)
    expected = expected_topology(Parameters(k))
    assert expected["dr_limit"].junctions is None and expected["dr_no_roll"].present is None
    assert expected_topology(Parameters(1 / math.sqrt(2.0)))["rs_no_roll"].folds_gamma is None


@pytest.mark.parametrize(("nu", "k"), [
    (0.0, math.sqrt(2.0) * (1.0 - 1e-12)), (0.0, math.sqrt(2.0) * (1.0 - 5e-13)),
    (0.0, 1.4142135623723),
    (0.25, 1.2121830534614408), (0.5, 0.9428090415811206),
    # the paper's k = 1 with the Poisson ratio 1e-12 below where c sqrt 2 = 1
    (0.45308183932151985, 1.0)])
def test_just_below_k_branch_a_rounding_stub_of_dr_no_roll_is_accepted(nu, k):
    # within rounding below k_branch the branch point's T/N = c sqrt 2 exceeds k by ~1e-12:
    # dr_no_roll has a physical part of two rows (to the validity's tolerance) that ends where
    # T/N_R reaches k, not at a junction; inside the band either topology is accepted, so its
    # end is not checked (a random search found these valid k refused with exit code 1)
    params = Parameters(k, Compliance.from_poisson(nu))
    assert expected_topology(params)["dr_no_roll"].end is None
    bs = trace_boundaries(params)
    assert bs.ok, bs.failures
    stub = bs.curves.get("dr_no_roll")
    if stub is not None:
        assert np.max(np.abs(stub.x[stub.physical] - stub.x[0])) <= 1e-9


def test_dr_no_roll_expected_but_without_a_physical_part_is_a_failure(monkeypatch):
    # the topology says dr_no_roll must be there (k > k_branch) but its trace has no physical
    # part: a failure, not a note beside ok curves
    real = topology.expected_topology

    def wrong_side(params):
        expected = real(params)
        return {**expected, "dr_no_roll": dataclasses.replace(expected["dr_no_roll"],
                                                              present=True)}

    monkeypatch.setattr("groove_model.tracing.tracer.expected_topology", wrong_side)
    bs = trace_boundaries(1.0)  # below k_branch: T/N_L > k all along dr_no_roll
    assert not bs.ok
    assert any("dr_no_roll" in failure and "expected" in failure for failure in bs.failures)


def test_thresholds_scale_with_the_compliance_ratio():
    params = Parameters(0.6, Compliance(2.0 / 3.0))
    # 0.6 lies between c/sqrt 2 = 0.471 and c sqrt 2 = 0.943: a fold, no junction
    expected = expected_topology(params)
    assert expected["rs_no_roll"].folds_gamma == 1 and expected["dr_limit"].junctions == 0


def test_a_curve_that_stops_short_is_a_failure_with_a_message():
    # too few steps: the engine stops normally (max_steps), but not where the curve must end
    options = dataclasses.replace(DEFAULT_OPTIONS, max_steps=5)
    bs = trace_boundaries(10.0, options=options)
    assert not bs.ok
    dr = bs.curves["dr_limit"]
    assert not dr.ok and "expected gamma_min" in dr.status
    assert "differs from the expected topology for k = 10:" in dr.status
    assert "(the continuation: reached the maximum number of steps (5))" in dr.status


def test_an_inconsistent_junction_is_named_in_coordinates_and_fails_dr_limit_only(monkeypatch):
    # no tolerance at all: the junction located on dr_limit is 1e-13 from dr_no_roll's
    monkeypatch.setattr(tracer_module, "JUNCTION_TOLERANCE", -1.0)
    bs = trace_boundaries(10.0)
    dr, rs = bs.curves["dr_limit"], bs.curves["rs_limit"]
    assert not dr.ok and "the junction is not consistent" in dr.status
    assert "at (gamma, delta, beta_L, upsilon) = (0.8998122762, 0.5713153981" in dr.status
    assert "np.float64" not in dr.status
    # rs_limit is compared with the equations of dr_limit, not with its failed trace
    assert rs.ok and bs.limit_distance <= 1e-10


def test_a_failed_atlas_of_the_thresholds_is_an_error_message_not_a_traceback(
        monkeypatch, tmp_path, capsys):
    # a compliance no other test uses: lru_cache keeps no failure, and no other c is touched
    monkeypatch.setattr(atlas_module, "ATLAS_OPTIONS",
                        dataclasses.replace(atlas_module.ATLAS_OPTIONS, max_steps=3))
    assert main(["trace", "-k", "1", "--poisson", "0.123", "--out", str(tmp_path / "out")]) == 1
    err = capsys.readouterr().err
    assert err.startswith("groove trace: error: the thresholds in k for c = 0.9")
    assert "could not be computed: their atlas failed" in err
    assert "reached the maximum number of steps (3)" in err and "Traceback" not in err
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


def test_every_traced_curve_says_where_it_starts_and_ends():
    bs = trace_boundaries(10.0)
    where = {name: (c.start, c.end) for name, c in bs.curves.items()}
    assert where == {"dr_limit": (Where.SEED, Where.GAMMA_MIN),
                     "rs_limit": (Where.SEED, Where.GAMMA_MIN),
                     "dr_no_roll": (Where.BRANCH_POINT, Where.JUNCTION),
                     "rs_no_roll": (Where.JUNCTION, Where.CORNER)}
    # one junction, shared exactly by the three curves that meet there
    junction = bs.curves["dr_limit"].special("junction")[0].x
    assert np.array_equal(bs.curves["dr_no_roll"].x[-1], junction)
    assert np.array_equal(bs.curves["rs_no_roll"].x[0], junction)
    assert junction[2] == pytest.approx(math.atan(0.1), abs=1e-15)  # T/N_L = cot beta_L = k


@pytest.mark.parametrize("k", [1.4142135623738024, math.sqrt(2.0) * (1.0 + 7e-13),
                               math.sqrt(2.0) * (1.0 + 1e-12), math.sqrt(2.0) * (1.0 + 1e-10)])
def test_just_above_k_branch_the_three_curves_agree_on_the_junction(k):
    # 5e-13 above k_branch the junction lies 4e-13 from the seed, where upsilon = 0 already: no
    # crossing was located on dr_limit, which had no junction while dr_no_roll ended at one and
    # rs_no_roll started there (found by an adversarial helper); the seed is now marked too
    bs = trace_boundaries(k)
    assert bs.ok, bs.failures
    junctions = {name: [p.x for p in curve.special_points if p.kind.value == "junction"]
                 for name, curve in bs.curves.items()}
    if "dr_no_roll" not in bs.curves:
        assert junctions["dr_limit"] == [] and junctions["rs_no_roll"] == []
        return
    assert bs.curves["dr_no_roll"].end is Where.JUNCTION
    assert len(junctions["dr_limit"]) == len(junctions["rs_no_roll"]) == 1
    for x in (junctions["dr_limit"][0], junctions["rs_no_roll"][0]):
        assert np.max(np.abs(x - junctions["dr_no_roll"][-1])) <= 1e-9
