"""``groove atlas``, ``groove compliance`` and the compliance options of the other commands."""

import argparse
import json
import math

import pandas as pd
import pytest

from groove_model.cli.common import add_compliance_options, compliance_from, compliance_label
from groove_model.cli.main import main
from groove_model.io.atlas import read_atlas_csv
from groove_model.model.parameters import Compliance


def test_atlas_command_writes_curves_thresholds_report_and_figure(tmp_path, capsys):
    assert main(["atlas", "--k-min", "0.1", "--k-max", "100", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "k_cross" in out and "k = 15.199396193654" in out
    for name in ("junction", "dr_limit_fold_delta", "rs_no_roll_fold_gamma"):
        frame = read_atlas_csv(tmp_path / f"atlas_{name}.csv")
        assert frame["k"].min() >= 0.1 * (1 - 1e-12) and frame["k"].max() <= 100 * (1 + 1e-12)
    table = pd.read_csv(tmp_path / "atlas_thresholds.csv")
    assert list(table["threshold"]) == ["k_fold", "k_branch", "k_cross"]
    assert table["value"][1] == pytest.approx(math.sqrt(2.0), rel=1e-14)
    report = (tmp_path / "atlas.md").read_text()
    assert "T/N_L = k: c (cos beta_L + upsilon) - k sin beta_L = 0" in report
    assert "k_branch < k < k_cross" in report
    assert (tmp_path / "atlas.png").stat().st_size > 0 and not (tmp_path / "atlas.svg").exists()


def test_atlas_command_with_a_poisson_ratio_names_its_files(tmp_path, capsys):
    assert main(["atlas", "--k-min", "0.1", "--k-max", "10", "--poisson", "0.5", "--out",
                 str(tmp_path), "--no-figure"]) == 0
    table = pd.read_csv(tmp_path / "atlas_nu0.5_thresholds.csv")
    assert table["value"][0] == pytest.approx(2.0 / 3.0 / math.sqrt(2.0), rel=1e-14)
    frame = read_atlas_csv(tmp_path / "atlas_nu0.5_junction.csv")
    assert (frame["nu"] == 0.5).all() and frame["compliance"].iloc[0] == pytest.approx(2 / 3)


@pytest.mark.parametrize("argv, message", [
    (["--k-min", "10", "--k-max", "1"], "--k-min 10 must be below --k-max 1"),
    (["--k-min", "0"], "friction coefficient k = 0.0 is outside the range the boundaries are "
                       "traced for: 1e-4 <= k <= 1e6"),
    (["--poisson", "0.6"], "Poisson ratio nu = 0.6 is outside the range the boundaries are "
                           "traced for: 0 <= nu <= 0.5"),
    (["--compliance", "-1"], "compliance ratio c = -1.0 is outside the range the boundaries are "
                             "traced for: 2/3 <= c <= 1"),
    (["--compliance", "inf"], "compliance ratio c = inf is outside the range the boundaries are "
                              "traced for: 2/3 <= c <= 1"),
])
def test_atlas_command_bad_input(argv, message, tmp_path, capsys):
    with pytest.raises(SystemExit) as info:
        main(["atlas", "--out", str(tmp_path), *argv])
    assert info.value.code == 2
    assert message in capsys.readouterr().err


def test_compliance_command(tmp_path, capsys):
    assert main(["compliance", "--out", str(tmp_path), "--no-figure"]) == 0
    report = (tmp_path / "compliance.md").read_text()
    assert "The same topologies, in the same order, for every nu" in report
    assert "nu_branch = 0.45308183932" in report
    for stem in ("atlas_nu0", "atlas_nu0.3", "atlas_nu0.5", "atlas_k1_in_nu", "atlas_k10_in_nu"):
        assert (tmp_path / f"{stem}_thresholds.csv").exists()
    frame = read_atlas_csv(tmp_path / "atlas_k1_in_nu_junction.csv")
    assert (frame["k"] == 1.0).all() and frame["nu"].min() == pytest.approx(0.4530818393, 1e-9)


def test_compliance_files_of_close_values_do_not_overwrite_each_other(tmp_path):
    # with f"{k:g}" names, k = 1.0000001 was written over k = 1 (and nu = 0.30000001 over
    # nu = 0.3), exit 0, the report saying k = 1 twice
    assert main(["compliance", "--poissons", "0.3", "0.30000001", "-k", "1", "1.0000001",
                 "--out", str(tmp_path), "--no-figure"]) == 0
    for stem in ("atlas_nu0.3", "atlas_nu0.30000001", "atlas_k1_in_nu", "atlas_k1.0000001_in_nu"):
        assert (tmp_path / f"{stem}_thresholds.csv").exists()
    report = (tmp_path / "compliance.md").read_text()
    assert "k = 1.0000001" in report and "nu = 0.30000001" in report


def test_compliance_options_helper():
    parser = argparse.ArgumentParser()
    add_compliance_options(parser)
    assert compliance_from(parser.parse_args([])) == Compliance()
    nu = compliance_from(parser.parse_args(["--poisson", "0.5"]))
    assert nu.ratio == pytest.approx(2.0 / 3.0) and nu.poisson == 0.5
    assert compliance_label(nu) == "_nu0.5"
    both = compliance_from(parser.parse_args(["--poisson", "0.5", "--compliance", "0.9"]))
    assert both.ratio == 0.9 and compliance_label(both) == "_c0.9"
    assert compliance_label(Compliance.from_poisson(0.0)) == ""


def test_trace_and_map_take_the_compliance(tmp_path, capsys):
    assert main(["trace", "-k", "1", "--poisson", "0.5", "--out", str(tmp_path),
                 "--no-figure"]) == 0
    frame = pd.read_csv(tmp_path / "boundaries_k1_nu0.5.csv")
    # k = 1 > c sqrt 2 = 0.943 for nu = 1/2: dr_no_roll has a physical part
    assert "dr_no_roll" in set(frame["boundary"])
    target = tmp_path / "map.png"
    assert main(["map", "-k", "1", "--compliance", "0.8", "-o", str(target),
                 "--resolution", "40"]) == 0
    assert target.stat().st_size > 0


def test_solve_with_a_poisson_ratio_uses_mindlins_compliance(capsys):
    assert main(["solve", "--gamma", "0.3", "--delta", "0", "-k", "1", "--poisson", "0.5",
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    # on delta = 0 the symmetric state has T/N = c tan gamma
    assert out["T_over_N_L"] == pytest.approx(2.0 / 3.0 * math.tan(0.3), rel=1e-12)


def test_reproduce_runs_the_atlas_and_the_compliance_study(tmp_path):
    from groove_model.cli.main import build_parser
    from groove_model.cli.reproduce import steps

    commands = [argv[0] for argv in steps(tmp_path)]
    assert commands == ["trace", "map", "map", "atlas", "compliance", "audit"]
    parser = build_parser()
    for argv in steps(tmp_path):
        assert callable(parser.parse_args(argv).run)


def test_a_range_without_thresholds_says_so_and_leaves_no_file_of_an_earlier_run(tmp_path,
                                                                                   capsys):
    assert main(["atlas", "--k-min", "0.1", "--k-max", "10", "--no-figure", "--out",
                 str(tmp_path)]) == 0
    assert len((tmp_path / "atlas_junction.csv").read_text().splitlines()) > 1
    capsys.readouterr()
    assert main(["atlas", "--k-min", "1", "--k-max", "1.1", "--no-figure", "--out",
                 str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "no threshold in this range" in out
    assert "not in this range (files with no rows): junction" in out
    # the junction (born at k = sqrt 2) does not exist here: its file is rewritten empty
    assert (tmp_path / "atlas_junction.csv").read_text().splitlines()[1:] == []
