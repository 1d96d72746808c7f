"""The audit of the paper's claims: quotes, counterexamples re-checked, report files, CLI."""

import dataclasses
import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from groove_model.analysis.audit import run as audit_run
from groove_model.analysis.audit.context import sign_changes
from groove_model.analysis.audit.report import DEFAULT_KS, VERDICTS, Claim, normalise_tex
from groove_model.analysis.audit.run import run_audit
from groove_model.cli.common import EXIT_USAGE, UsageError
from groove_model.cli.main import build_parser, main
from groove_model.model.boundaries import boundary_system
from groove_model.model.equilibrium import (
    double_rolling_state,
    rolling_sliding_state,
    solve_equilibrium,
)
from groove_model.model.lines import dr_limit_delta, rs_limit_delta, rs_no_roll_gamma
from groove_model.model.parameters import Parameters

# shared/ sits beside the repository (here and in CI).
PAPER = Path(__file__).resolve().parents[2] / "shared" / "paper" / "ball_in_a_groove.tex"
SQRT2 = math.sqrt(2.0)


@pytest.fixture(scope="module")
def report():
    return run_audit(DEFAULT_KS, use_tracer=False)


# --------------------------------------------------------------------------------------------
# The report
# --------------------------------------------------------------------------------------------


def test_every_claim_has_a_computed_verdict_and_numbers(report):
    ids = [c.id for c in report.claims]
    assert len(ids) == len(set(ids)) >= 30
    assert {c.section for c in report.claims} == {"Contact mechanics", "Rolling solutions",
                                                  "Rolling-sliding solutions", "Caption of Fig. 2"}
    for c in report.claims:
        assert c.verdict in VERDICTS and c.numbers and c.method and c.summary
        if c.verdict == "fails":
            assert c.counterexample is not None, c.id
    assert sum(report.counts().values()) == len(report.claims)


@pytest.mark.skipif(not PAPER.exists(), reason="the paper's LaTeX source is not available")
def test_quotes_are_verbatim_from_the_paper(report):
    tex = normalise_tex(PAPER.read_text())
    for c in report.claims:
        for piece in c.quote.split(" ... "):
            assert piece in tex, (c.id, piece)


def test_claim_rejects_an_unknown_verdict():
    with pytest.raises(ValueError, match="verdict = 'maybe' is not one of holds, holds with "
                                         "qualification, fails, inconclusive, not applicable"):
        Claim("x", "s", "q", "m", "maybe", "summary")


def test_json_and_markdown(report):
    doc = json.loads(report.to_json())
    assert doc["ks"] == list(DEFAULT_KS)
    assert [c["id"] for c in doc["claims"]] == [c.id for c in report.claims]
    assert doc["counts"] == report.counts()
    text = report.to_markdown()
    for c in report.claims:
        assert f"`{c.id}` — {c.verdict}" in text
    # Every table row has as many cells as its header (no stray '|').
    for block in re.findall(r"((?:^\|.*\|\n)+)", text, flags=re.MULTILINE):
        rows = block.strip().split("\n")
        widths = {len(re.split(r"(?<!\\)\|", row)) for row in rows}
        assert len(widths) == 1, rows[0]


def test_report_is_reproducible():
    first, again = (run_audit((1.0, 10.0), use_tracer=False) for _ in range(2))
    assert again.to_json() == first.to_json()
    assert again.to_markdown() == first.to_markdown()


# --------------------------------------------------------------------------------------------
# Counterexamples, re-checked with the point solver and independent arithmetic
# --------------------------------------------------------------------------------------------


def _counterexamples(report):
    return [c for c in report.claims if c.counterexample is not None]


def test_every_counterexample_is_reproduced_by_the_point_solver(report):
    checked = 0
    for c in _counterexamples(report):
        ce = c.counterexample
        if not ce.solver_fields:
            continue
        eq = solve_equilibrium(ce.gamma, ce.delta, ce.k)
        for name in ce.solver_fields:
            value = getattr(eq, name)
            if isinstance(value, str):
                assert value == ce.values[name], (c.id, name)
            else:
                assert value == pytest.approx(ce.values[name], rel=1e-9, abs=1e-12), (c.id, name)
            checked += 1
    assert checked >= 10


def test_rs_upsilon_on_the_axis_is_not_zero(report):
    c = report.claim("rs_delta0_upsilon_zero")
    ce = c.counterexample
    k, gamma = ce.k, ce.gamma
    assert gamma > math.atan(k) and ce.delta < 1e-6
    # The paper's formulas on delta = 0: mu = k, beta_L = beta_R = pi/2 - gamma.
    mu = math.sin(gamma) / (math.sin(gamma) / k)
    beta_R = 0.5 * math.pi - gamma
    upsilon_formula = math.cos(beta_R) - mu * math.sin(beta_R)
    assert upsilon_formula == pytest.approx(math.sin(gamma) - k * math.cos(gamma), rel=1e-12)
    assert upsilon_formula > 0.5  # far from 0: counter-clockwise
    eq = solve_equilibrium(gamma, ce.delta, k)
    assert eq.regime == "rolling_sliding" and eq.upsilon == pytest.approx(upsilon_formula, rel=1e-6)
    rs = rolling_sliding_state(gamma, 0.0, Parameters(k))
    assert float(rs["upsilon"]) == pytest.approx(upsilon_formula, rel=1e-12)
    assert ce.values["upsilon of the RS formulas at delta = 0"] == pytest.approx(upsilon_formula)


def test_mu_counterexample_has_no_left_sliding_state(report):
    c = report.claim("rs_mu_above_k_if_shallower_slides")
    ce = c.counterexample
    theta_L, theta_R, k = ce.gamma + ce.delta, ce.gamma - ce.delta, ce.k
    assert 0.0 < theta_L < theta_R < 0.5 * math.pi  # an ordinary groove, right wall steeper
    mu = math.sin(theta_R) / (math.cos(theta_R) - math.cos(theta_L) + math.sin(theta_L) / k)
    assert mu < 0.0 < k and mu == pytest.approx(ce.values["mu"], rel=1e-12)
    # Paper Eqs. 1-2 with T_L = T_R = k N_L, Mg = 1, solved for (N_L, N_R):
    A = np.array([[k * math.sin(theta_L) + math.cos(theta_L) + k * math.sin(theta_R),
                   math.cos(theta_R)],
                  [-k * math.cos(theta_L) + math.sin(theta_L) + k * math.cos(theta_R),
                   -math.sin(theta_R)]])
    N_L, N_R = np.linalg.solve(A, [1.0, 0.0])
    assert N_L * N_R < 0.0  # one normal force would have to pull: no such state
    assert k * N_L / N_R == pytest.approx(mu, rel=1e-10)


def test_double_sliding_limit_has_one_contact_only_at_incipient_sliding(report):
    c = report.claim("rs_delta0_collapses_to_double_sliding")
    ce = c.counterexample
    eq = solve_equilibrium(ce.gamma, ce.delta, ce.k)
    s = math.sin(ce.gamma) - ce.k * math.cos(ce.gamma)
    assert eq.d_R == 0.0 and eq.d_L == pytest.approx(2 * s, rel=1e-6)
    assert eq.T_over_N_R == pytest.approx(ce.k, rel=1e-6)
    axis = solve_equilibrium(ce.gamma, 0.0, ce.k)
    assert axis.regime == "double_sliding" and axis.upsilon == 0.0
    assert axis.d_L == axis.d_R == pytest.approx(s)


def test_the_axis_exception_to_opposite_contact_motion(report):
    ce = report.claim("dr_contacts_opposite").counterexample
    eq = solve_equilibrium(ce.gamma, ce.delta, ce.k)
    assert ce.delta == 0.0 and eq.regime == "double_rolling" and eq.upsilon == 0.0


# --------------------------------------------------------------------------------------------
# The root-finding helpers against the boundary equations
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("k", [0.3, 1.0, 10.0])
def test_limit_curves_solve_the_boundary_equations(k):
    gamma = math.atan(k) * np.array([0.05, 0.3, 0.7, 0.95])
    delta = dr_limit_delta(k, gamma)
    dr = double_rolling_state(gamma, delta, Parameters(1.0))
    system = boundary_system("dr_limit", k)
    for g, d, b, u in zip(gamma, delta, dr["beta_L"], dr["upsilon"]):
        assert np.max(np.abs(system.residual([g, d, b, u]))) <= 1e-12 * (1 + k)
    assert rs_limit_delta(k, gamma) == pytest.approx(delta, abs=1e-12)


@pytest.mark.parametrize("k", [0.3, 1.2, 10.0])
def test_rs_no_roll_rows_solve_the_boundary_equations(k):
    delta = np.array([0.01, 0.3, 0.7])
    gamma = rs_no_roll_gamma(k, delta)
    rs = rolling_sliding_state(gamma, delta, Parameters(k))
    system = boundary_system("rs_no_roll", k)
    for g, d, b, u in zip(gamma, delta, rs["beta_L"], rs["upsilon"]):
        assert abs(u) <= 1e-14
        assert np.max(np.abs(system.residual([g, d, b, u]))) <= 1e-12 * (1 + k)


def test_sign_changes_count_through_zeros():
    values = np.array([[-1.0, 0.0, 1.0, 2.0], [-1.0, 0.0, -1.0, -2.0], [0.0, 1.0, -1.0, 1.0]])
    assert sign_changes(values, axis=1).tolist() == [1, 0, 2]


# --------------------------------------------------------------------------------------------
# The tracer cross-check
# --------------------------------------------------------------------------------------------


def test_tracer_cross_check_agrees_with_root_finding():
    result = run_audit((1.0, 10.0), use_tracer=True)
    assert result.tracer == {"k = 1": "ok", "k = 10": "ok"}
    start = result.claim("dr_limit_from_arctan_k").numbers
    assert start["k = 1"]["tracer: |start - (arctan k, 0)|"] <= 1e-12
    large = result.claim("rs_no_roll_large_k_ends").numbers["k = 10"]
    assert large["tracer: |start - junction|"] <= 1e-9
    assert large["tracer: |end - (pi/4, pi/4)|"] <= 1e-9
    small = result.claim("rs_no_roll_small_k_ends").numbers["k = 1"]
    assert small["tracer: |start - (arctan k, 0)|"] <= 1e-12
    for label in ("k = 1", "k = 10"):
        assert result.claim("rs_dL_boundary_is_dr_limit").numbers[label][
            "tracer: limit_distance"] <= 1e-9
    interval = result.claim("dr_no_roll_interval").numbers["k = 10"]
    assert interval["tracer: min gamma"] >= math.pi / 4 - 1e-9
    assert interval["tracer: max gamma"] <= math.atan(SQRT2) + 1e-9
    assert result.claim("dr_no_roll_needs_k_above_sqrt2").numbers["k = 1"][
        "tracer: physical dr_no_roll"] is False


def test_a_failing_tracer_is_reported_not_fatal(monkeypatch):
    from groove_model import tracing as tracer

    def broken(*args, **kwargs):
        raise RuntimeError("engine exploded")

    monkeypatch.setattr(tracer, "trace_boundaries", broken)
    result = run_audit((1.0,), use_tracer=True)
    assert result.tracer["k = 1"] == "unavailable: RuntimeError: engine exploded"
    assert math.isnan(result.claim("dr_limit_from_arctan_k").numbers["k = 1"][
        "tracer: |start - (arctan k, 0)|"])


def test_a_curve_that_stops_short_feeds_no_claim_and_fails_audit_trace(monkeypatch, capsys):
    # the tracer stops after 10 steps: its curves are traced normally but end short of where
    # they must, so the set fails; it once fed "tracer end: gamma = 0.572" to the claims
    # ("holds") and `groove audit --trace` exited 0 with nothing on stderr
    from groove_model.tracing import tracer

    monkeypatch.setattr(tracer, "DEFAULT_OPTIONS",
                        dataclasses.replace(tracer.DEFAULT_OPTIONS, max_steps=10))
    result = run_audit((1.0,), use_tracer=True)
    assert result.tracer["k = 1"].startswith("failed: dr_limit: ")
    assert math.isnan(result.claim("dr_limit_from_arctan_k").numbers["k = 1"][
        "tracer: |start - (arctan k, 0)|"])
    capsys.readouterr()
    assert main(["audit", "-k", "1", "--trace"]) == 1
    err = capsys.readouterr().err
    assert "groove audit: error: the tracer's cross-check for k = 1: failed: dr_limit:" in err
    assert "reached the maximum number of steps (10)" in err


def test_audit_rejects_bad_friction():
    with pytest.raises(ValueError, match="friction coefficient k = 0.0 is outside"):
        run_audit((1.0, 0.0))
    with pytest.raises(ValueError, match="ks is empty"):
        run_audit(())


# --------------------------------------------------------------------------------------------
# Verdicts: "fails" only with a counterexample, "not applicable" with its reason
# --------------------------------------------------------------------------------------------

#: The claims about one side of k = sqrt 2, and that side.
ONE_SIDED = {"rs_no_roll_small_k_ends": lambda k: k < SQRT2,
             "rs_no_roll_large_k_ends": lambda k: k > SQRT2,
             "dr_no_roll_sides": lambda k: k > SQRT2}


@pytest.mark.parametrize("k", [0.1, 1.0, 2.0, 10.0, 100.0])
def test_every_fail_is_a_counterexample_shown_by_the_command(k, capsys):
    assert run_cli(["audit", "-k", str(k)]) == 0
    text = capsys.readouterr().out
    report = run_audit((k,), use_tracer=False)
    fails = [c for c in report.claims if c.verdict == "fails"]
    assert {c.id for c in fails} == {"rs_mu_above_k_if_shallower_slides",
                                     "rs_delta0_upsilon_zero"}
    for c in fails:
        assert c.counterexample is not None and c.counterexample.k == k
        assert f"counterexample to {c.id}: k = " in text
    for claim_id, about in ONE_SIDED.items():
        c = report.claim(claim_id)
        assert (c.verdict == "not applicable") == (not about(k)), (claim_id, c.verdict)
        if c.verdict == "not applicable":
            assert c.summary.startswith("Not applicable: about k ") and c.counterexample is None
            assert re.search(rf"not applicable\s+{claim_id}\s+Not applicable: about k", text)
    assert all(c.verdict != "inconclusive" for c in report.claims)


def test_a_counterexample_outside_the_domain_is_shown_with_its_walls_and_its_mirror(capsys):
    # delta < 0 (the shallower wall on the left) was printed bare; `groove solve` refuses it
    assert run_cli(["audit", "-k", "1"]) == 0
    text = capsys.readouterr().out
    ce = run_audit((1.0,), use_tracer=False).claim("rs_mu_above_k_if_shallower_slides") \
        .counterexample
    assert ce.delta < 0.0
    walls = re.search(r"\(walls theta_L = (\S+), theta_R = (\S+): the shallower wall on the "
                      r"left, delta < 0, outside the domain 0 <= delta <= gamma; its mirror "
                      r"image, which groove solve takes, is delta = (\S+)\)", text)
    assert walls is not None
    theta_l, theta_r, mirror = map(float, walls.groups())
    assert theta_l == ce.gamma + ce.delta and theta_r == ce.gamma - ce.delta  # printed in full
    assert f"gamma = {ce.gamma!r}, delta = {ce.delta!r}: " in text
    assert run_cli(["solve", "-k", "1", "--gamma", repr(ce.gamma), "--delta", repr(mirror)]) == 0


def test_a_summary_cut_short_in_the_table_says_so(capsys):
    assert run_cli(["audit", "-k", "1"]) == 0
    text = capsys.readouterr().out
    report = run_audit((1.0,), use_tracer=False)
    cut = 0
    for c in report.claims:
        first = c.summary.split(". ")[0]
        row = next(line for line in text.splitlines() if f" {c.id} " in line)
        shown = row.split(f" {c.id} ", 1)[1].strip()
        if len(first) <= 100:
            assert shown == first
        else:  # cut at a word (it read "topologi...")
            cut += 1
            assert len(shown) <= 101 and shown.endswith(" ...") and first.startswith(shown[:-4])
            assert first[len(shown) - 4] == " "
    assert cut and "has each in full" in text


def test_claims_about_one_side_of_sqrt2_name_the_k_they_skip():
    report = run_audit((1.0, 10.0), use_tracer=False)
    large = report.claim("rs_no_roll_large_k_ends")
    assert large.verdict == "holds"
    assert large.numbers["not applicable (the statement is about k > sqrt 2)"] == "k = 1"
    assert set(large.numbers) - {"not applicable (the statement is about k > sqrt 2)"} \
        == {"k = 10"}


def test_a_fail_without_counterexample_is_inconclusive():
    from groove_model.analysis.audit.registry import CLAIM_TEXTS, Finding
    from groove_model.analysis.audit.report import Verdict

    text = next(t for t in CLAIM_TEXTS if t.id == "dr_contacts_opposite")
    c = text.state(Finding(Verdict.FAILS, numbers={"k = 1": {"rows violating": 3}}))
    assert c.verdict == "inconclusive" and c.summary.startswith("Inconclusive")
    assert c.numbers == {"k = 1": {"rows violating": 3}}


# --------------------------------------------------------------------------------------------
# Command line
# --------------------------------------------------------------------------------------------


def run_cli(argv):
    """Parse and run like ``groove_model.cli.main`` (exit code 2 for bad input)."""
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.run(args)
    except UsageError as exc:
        print(f"groove {args.command}: error: {exc}")
        return EXIT_USAGE


def test_audit_cli_writes_markdown_and_json(tmp_path, capsys):
    out = tmp_path / "res"
    assert run_cli(["audit", "-k", "1", "-k", "10", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "audit of the paper's claims for k = 1, 10" in text and "counterexample to" in text
    assert sorted(p.name for p in out.iterdir()) == ["claims.json", "claims.md"]
    doc = json.loads((out / "claims.json").read_text())
    assert doc["ks"] == [1.0, 10.0]
    assert (out / "claims.md").read_text().startswith("# Audit of the claims")


def test_audit_cli_json_on_stdout(capsys):
    assert run_cli(["audit", "-k", "2", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["ks"] == [2.0] and len(doc["claims"]) >= 30


def test_default_audit_runs_in_seconds(capsys):
    # A loose bound against pathological slow-downs; speed itself is a benchmark matter.
    assert run_cli(["audit"]) == 0
    first = capsys.readouterr().out.splitlines()[0]
    seconds = float(re.search(r"\(([\d.]+) s\)$", first).group(1))
    assert seconds < 30.0


@pytest.mark.parametrize("argv, message", [
    (["audit", "-k", "0"], "friction coefficient k = 0.0 is outside the range the boundaries "
                           "are traced for: 1e-4 <= k <= 1e6"),
    (["audit", "-k", "abc"], "friction coefficient k = 'abc' is not a number"),
    (["map", "-k", "-2", "-o", "m.png"], "friction coefficient k = -2.0 is outside"),
    (["map", "-k", "1", "-o", "m.png", "--resolution", "1"],
     "grid resolution N = 1 is outside the allowed range 2 <= N <= 5000"),
    (["map", "-k", "1", "-o", "m.png", "--resolution", "x"],
     "grid resolution N = 'x' is not an integer"),
    # a number that is no double is named as typed too (it read "k = 0.0" alone)
    (["solve", "--gamma", "0.5", "--delta", "0.1", "-k", "1e-400"],
     "k = 0.0 is outside the allowed range: k must be finite and > 0 (1e-400 is below the "
     "smallest double and reads as 0)"),
    (["map", "-k", "1e400", "-o", "m.png"], "(1e400 is beyond the largest double and reads as inf)"),
    (["solve", "--gamma", "0.5", "--delta", "0.1", "-k", "1", "--poisson", "-7e400"],
     "(-7e400 is beyond the largest double and reads as -inf)"),
])
def test_bad_arguments_exit_2_naming_the_quantity(argv, message, capsys):
    with pytest.raises(SystemExit) as exc:
        run_cli(argv)
    assert exc.value.code == 2
    assert message in capsys.readouterr().err


def test_bad_paths_exit_2(tmp_path, capsys):
    assert run_cli(["map", "-k", "1", "-o", str(tmp_path / "m.gif")]) == EXIT_USAGE
    assert "output format '.gif'" in capsys.readouterr().out
    afile = tmp_path / "file"
    afile.write_text("x")
    assert run_cli(["map", "-k", "1", "-o", str(afile / "no" / "m.png")]) == EXIT_USAGE
    assert "is a file, not a directory" in capsys.readouterr().out
    assert run_cli(["audit", "-k", "1", "--out", str(afile)]) == EXIT_USAGE
    assert "is not a directory" in capsys.readouterr().out


def test_map_cli_writes_png_and_svg(tmp_path, capsys):
    target = tmp_path / "map_k10.png"
    assert run_cli(["map", "-k", "10", "-o", str(target), "--svg", "--resolution", "60"]) == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["map_k10.png", "map_k10.svg"]
    assert "figure:" in capsys.readouterr().out


def test_computation_failures_exit_1(tmp_path, monkeypatch, capsys):
    from groove_model import tracing as tracer

    def broken(*args, **kwargs):
        raise ArithmeticError("root finding failed for 3 brackets")

    monkeypatch.setattr(audit_run, "run_audit", broken)
    assert run_cli(["audit", "-k", "1"]) == 1
    assert "computation failed" in capsys.readouterr().err
    monkeypatch.setattr(tracer, "trace_boundaries", broken)
    assert run_cli(["map", "-k", "1", "-o", str(tmp_path / "m.png")]) == 1
    assert "computation failed for k = 1" in capsys.readouterr().err
    assert not list(tmp_path.iterdir())


def test_help_has_examples(capsys):
    for command in ("map", "audit"):
        with pytest.raises(SystemExit) as exc:
            run_cli([command, "--help"])
        assert exc.value.code == 0
        text = capsys.readouterr().out
        assert "examples:" in text and f"groove {command} -k" in text


def test_the_compliance_claim_holds_with_qualification_with_its_numbers(report):
    claim = report.claim("compliance_qualitative")
    assert claim.verdict == "holds with qualification"
    numbers = claim.numbers
    assert numbers["same topologies in k, in the same order"] is True
    # Mindlin's ratio at nu = 1/2 is 2/3; k_fold and k_branch scale exactly with it
    assert numbers["c(nu = 0.5)"] == pytest.approx(2.0 / 3.0, rel=1e-15)
    for name in ("k_fold", "k_branch"):
        assert numbers[f"{name}(nu = 0.5) / {name}(nu = 0)"] == pytest.approx(2.0 / 3.0,
                                                                               rel=1e-12)
    assert numbers["k_cross(nu = 0.5) / k_cross(nu = 0)"] < 0.5
    # at the paper's k = 1 the junction is born at c sqrt 2 = 1
    c = 1.0 / SQRT2
    assert numbers["k = 1"]["thresholds in nu"] == f"nu_branch = {2 * (1 - c) / (2 - c):.10g}"
    assert claim.counterexample.k == 1.0 and claim.counterexample.values["nu"] == 0.5


def test_the_smallest_supported_k_is_audited_without_error_or_doubt():
    # k = 1e-4 crashed (no gamma below arctan(k)/2 among fixed columns 1e-1 ... 1e-4), and the
    # start of rs_no_roll was probed at deltas outside its linear part (inconclusive)
    report = run_audit([1e-4])
    verdicts = {c.id: c.verdict for c in report.claims}
    assert "inconclusive" not in verdicts.values(), verdicts
    assert verdicts["dr_limit_to_origin_along_diagonal"] == "holds"
    assert verdicts["rs_no_roll_small_k_ends"] == "holds"


def test_the_largest_supported_k_is_audited_without_doubt():
    # at k >= 1e3 the probe next to the axis (delta = 1e-9) moved the forces by 2 k delta, and at
    # k >= 1e5 the physical part of rs_no_roll (5e-4 below pi/4 in delta at k = 1e6) fell
    # between two rows: three claims were inconclusive
    report = run_audit([1e3, 1e6])
    verdicts = {c.id: c.verdict for c in report.claims}
    assert "inconclusive" not in verdicts.values(), verdicts
    for claim in ("rs_no_roll_line_stuck", "rs_no_roll_large_k_ends"):
        assert verdicts[claim] == "holds", claim
