"""``groove solve``: readable and JSON output, exit code 2 with a pinned message on bad input."""

import json
import math

import pytest

from groove_model.cli.main import main

KEYS = {"regime", "gamma", "delta", "theta_L", "theta_R", "beta_L", "beta_R", "upsilon",
        "T_over_N_L", "T_over_N_R", "d_L", "rotation"}


def test_solve_json(capsys):
    assert main(["solve", "--gamma", "0.6", "--delta", "0.2", "-k", "1", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert set(out) == KEYS
    assert out["regime"] == "rolling_sliding" and out["rotation"] == "clockwise"
    assert out["T_over_N_L"] == pytest.approx(1.0)
    assert out["theta_L"] == pytest.approx(0.8) and out["theta_R"] == pytest.approx(0.4)


def test_solve_degrees_and_dimensional(capsys):
    # --compliance 1 keeps the paper's law while --poisson sets the Hertz contact
    argv = ["solve", "--gamma", "20", "--delta", "0", "-k", "1", "--deg", "--json",
            "--radius", "0.01", "--young", "2e11", "--poisson", "0.3", "--mass", "0.03",
            "--compliance", "1"]
    assert main(argv) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["gamma"] == pytest.approx(math.radians(20))
    assert out["regime"] == "double_rolling" and out["rotation"] == "none"
    assert out["T_over_N_L"] == pytest.approx(math.tan(math.radians(20)))
    assert out["dimensional"]["N_L"] == pytest.approx(out["dimensional"]["N_R"])


def test_solve_readable(capsys):
    assert main(["solve", "--gamma", "0.4", "--delta", "0.1", "-k", "1"]) == 0
    text = capsys.readouterr().out
    assert "regime     double rolling" in text and "T/N_L" in text


@pytest.mark.parametrize(
    "argv, message",
    [
        (["-k", "0"], "argument -k: friction coefficient k = 0.0 is outside the allowed range: k must be finite and > 0"),
        (["-k", "-2"], "friction coefficient k = -2.0 is outside the allowed range"),
        (["-k", "nan"], "friction coefficient k = nan is outside the allowed range"),
        (["-k", "inf"], "friction coefficient k = inf is outside the allowed range"),
        (["-k", "abc"], "friction coefficient k = 'abc' is not a number; k must be finite and > 0"),
    ],
)
def test_solve_bad_friction(argv, message, capsys):
    with pytest.raises(SystemExit) as info:
        main(["solve", "--gamma", "0.6", "--delta", "0.2", *argv])
    assert info.value.code == 2
    assert message in capsys.readouterr().err


@pytest.mark.parametrize(
    "argv, message",
    [
        (["--gamma", "0.6", "--delta", "0.7"],
         "delta = 0.7 rad is outside the allowed range 0 <= delta <= gamma (gamma = 0.6 rad)"),
        (["--gamma", "1.7", "--delta", "0.1"], "gamma = 1.7 rad is outside the allowed range 0 <= gamma <= pi/2"),
        (["--gamma", "0.5", "--delta", "-0.1"], "delta = -0.1 rad is outside the allowed range 0 <= delta <= gamma"),
        (["--gamma", "x", "--delta", "0.1"], "gamma = 'x' is not a number"),
        (["--gamma", "0.5", "--delta", "0.1", "--radius", "0.01"], "dimensional results need all of"),
        (["--gamma", "0.5", "--delta", "0.1", "--radius", "-1", "--young", "1e9", "--poisson", "0.3",
          "--mass", "1"], "radius R = -1.0 m is outside the allowed range"),
    ],
)
def test_solve_bad_angles_and_dimensions(argv, message, capsys):
    with pytest.raises(SystemExit) as info:
        main(["solve", "-k", "1", *argv])
    assert info.value.code == 2
    assert message in capsys.readouterr().err
