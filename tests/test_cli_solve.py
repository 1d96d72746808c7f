"""``groove solve``: readable and JSON output, exit code 2 with a pinned message on bad input."""

import json
import math
import re

import pytest

from groove_model.cli.main import main
from groove_model.model.equilibrium import solve_equilibrium

KEYS = {"k", "compliance", "regime", "rotation", "gamma", "delta", "theta_L", "theta_R", "beta_L", "beta_R",
        "upsilon", "T_over_N_L", "T_over_N_R", "N_L_over_N_R", "d_L", "d_R"}


def test_solve_json(capsys):
    assert main(["solve", "--gamma", "0.6", "--delta", "0.2", "-k", "1.1", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert set(out) == KEYS
    assert out["k"] == 1.1 and out["compliance"] == 1.0
    assert out["regime"] == "rolling_sliding" and out["rotation"] == "clockwise"
    assert out["T_over_N_L"] == pytest.approx(1.1)
    assert out["theta_L"] == pytest.approx(0.8) and out["theta_R"] == pytest.approx(0.4)
    eq = solve_equilibrium(0.6, 0.2, 1.1)
    assert out["d_R"] == eq.d_R == 0.0 and out["d_L"] == eq.d_L > 0.0


def _printed_angles(text: str) -> tuple[str, str]:
    """``gamma`` and ``delta`` in radians as ``groove solve`` printed them."""
    match = re.search(r"gamma = (\S+) rad .*delta = (\S+) rad", text)
    assert match, text
    return match.group(1), match.group(2)


@pytest.mark.parametrize("argv", [
    ["--gamma", "90", "--delta", "0", "--deg"],          # gamma = pi/2 exactly
    ["--gamma", "90", "--delta", "90", "--deg"],         # the corner (pi/2, pi/2)
    ["--gamma", "0.6", "--delta", "0.2"],
    ["--gamma", "1.2345678901234567", "--delta", "0.333333333333333"],
])
def test_printed_angles_re_enter(argv, capsys):
    assert main(["solve", "-k", "1", *argv]) == 0
    first = capsys.readouterr().out
    gamma, delta = _printed_angles(first)
    assert main(["solve", "-k", "1", "--gamma", gamma, "--delta", delta]) == 0
    assert capsys.readouterr().out == first


def test_json_angles_re_enter(capsys):
    assert main(["solve", "-k", "1", "--gamma", "90", "--delta", "30", "--deg", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["gamma"] == math.pi / 2
    assert main(["solve", "-k", "1", "--gamma", repr(out["gamma"]), "--delta",
                 repr(out["delta"]), "--json"]) == 0
    assert json.loads(capsys.readouterr().out) == out


@pytest.mark.parametrize("argv, message", [
    (["--gamma", "95", "--delta", "10"],
     "gamma = 95.0 deg is outside the allowed range 0 <= gamma <= 90 deg"),
    (["--gamma", "40", "--delta", "50"],
     "delta = 50.0 deg is outside the allowed range 0 <= delta <= gamma (gamma = 40.0 deg)"),
    (["--gamma", "40", "--delta", "-1"],
     "delta = -1.0 deg is outside the allowed range 0 <= delta <= gamma (gamma = 40.0 deg)"),
    (["--gamma", "-5", "--delta", "0"],
     "gamma = -5.0 deg is outside the allowed range 0 <= gamma <= 90 deg"),
])
def test_degree_input_is_checked_in_degrees(argv, message, capsys):
    with pytest.raises(SystemExit) as info:
        main(["solve", "-k", "1", "--deg", *argv])
    assert info.value.code == 2
    err = capsys.readouterr().err
    assert message in err and "rad" not in err


@pytest.mark.parametrize("deg, rad", [
    (["--gamma", "30", "--delta", "30.000000000000004"], ["--gamma", "0.5235987755982988",
                                                          "--delta", "0.5235987755982988"]),
    (["--gamma", "90.00000000000001", "--delta", "10"], ["--gamma", "1.5707963267948966",
                                                         "--delta", "0.17453292519943295"]),
    (["--gamma", "-0", "--delta", "-0"], ["--gamma", "0", "--delta", "0"]),
])
def test_degrees_have_the_edge_slack_of_radians(deg, rad, capsys):
    """An angle in degrees a few rounding units beyond an edge of the domain is taken as on
    the edge, as in radians (4 eps relative); -0 is 0."""
    assert main(["solve", "-k", "1", "--deg", "--json", *deg]) == 0
    in_degrees = json.loads(capsys.readouterr().out)
    assert main(["solve", "-k", "1", "--json", *rad]) == 0
    assert in_degrees == json.loads(capsys.readouterr().out)
    assert math.copysign(1.0, in_degrees["gamma"]) == 1.0


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


def test_solve_names_the_poisson_ratio_of_its_compliance(capsys):
    argv = ["solve", "--gamma", "0.6", "--delta", "0.2", "-k", "1"]
    assert main([*argv, "--poisson", "0.3"]) == 0
    first = capsys.readouterr().out.splitlines()[0]
    assert first.startswith("k = 1, compliance ratio 0.8235294117647058 (Mindlin's for nu = 0.3),")
    # --compliance overrides the ratio from --poisson: no nu is named
    assert main([*argv, "--poisson", "0.3", "--compliance", "0.8"]) == 0
    assert capsys.readouterr().out.startswith("k = 1, compliance ratio 0.8, gamma")


@pytest.mark.parametrize(
    "argv, message",
    [
        (["-k", "0"], "argument -k: friction coefficient k = 0.0 is outside the allowed range: k must be finite and > 0"),
        (["-k", "-2"], "friction coefficient k = -2.0 is outside the allowed range"),
        (["-k", "nan"], "friction coefficient k = nan is outside the allowed range"),
        (["-k", "inf"], "friction coefficient k = inf is outside the allowed range"),
        (["-k", "abc"], "friction coefficient k = 'abc' is not a number; k must be finite and > 0"),
        # Python's float() reads digit separators: "1_0" is 10, a typo a tool should not take
        (["-k", "1_0"], "friction coefficient k = '1_0' is not a number"),
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
        # it read "delta = 'nan' is outside the allowed range"
        (["--gamma", "0.5", "--delta", "nan"],
         "delta = nan is not a finite number; allowed range: 0 <= delta <= gamma"),
        # it read "allowed range: a finite number", where --radius -1 says "> 0"
        (["--gamma", "0.5", "--delta", "0.1", "--radius", "inf", "--young", "1e9", "--poisson",
          "0.3", "--mass", "1"], "radius R = inf is not a finite number; allowed range: finite "
                                 "and > 0"),
        # it read "compliance ratio = 'nan'" (trace: "compliance ratio c = nan")
        (["--gamma", "0.5", "--delta", "0.1", "--compliance", "nan"],
         "compliance ratio c = nan is outside the allowed range: finite and > 0"),
        (["--gamma", "0.5", "--delta", "0.1", "--compliance", "x"],
         "compliance ratio c = 'x' is not a number"),
        (["--gamma", "0.5", "--delta", "0.1", "--radius", "0.01"], "dimensional results need all of"),
        (["--gamma", "0_5", "--delta", "0.1"], "gamma = '0_5' is not a number"),
        # --g alone used to be ignored without a word
        (["--gamma", "0.5", "--delta", "0.1", "--g", "3"],
         "--g 3.0 is used only for the dimensional results"),
        (["--gamma", "0.5", "--delta", "0.1", "--radius", "-1", "--young", "1e9", "--poisson", "0.3",
          "--mass", "1"], "radius R = -1.0 m is outside the allowed range"),
    ],
)
def test_solve_bad_angles_and_dimensions(argv, message, capsys):
    with pytest.raises(SystemExit) as info:
        main(["solve", "-k", "1", *argv])
    assert info.value.code == 2
    assert message in capsys.readouterr().err
