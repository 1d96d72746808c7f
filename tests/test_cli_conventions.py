"""What every ``groove`` command shares: ``-k``, ``-v``, ``--version``, ``python -m``."""

import importlib.metadata
import math
import logging
import subprocess
import sys
from pathlib import Path

import pytest

import groove_model
from groove_model.cli.main import build_parser, main


@pytest.mark.parametrize("command, rest", [
    ("solve", ["--gamma", "0.6", "--delta", "0.2"]),
    ("trace", ["--out", "out"]),
    ("map", ["-o", "map.png"]),
    ("audit", []),
])
def test_every_command_reads_k_both_ways(command, rest):
    parser = build_parser()
    spaced = parser.parse_args([command, "-k", "1", "10", *rest])
    repeated = parser.parse_args([command, "-k", "1", "-k", "10", *rest])
    assert spaced.ks == repeated.ks == [1.0, 10.0]


@pytest.mark.parametrize("command, rest", [
    ("map", ["-o", "map.png"]),
    ("solve", ["--gamma", "0.6", "--delta", "0.2"]),
])
def test_one_k_commands_refuse_several(command, rest, tmp_path, capsys):
    rest = [str(tmp_path / r) if r.endswith(".png") else r for r in rest]
    with pytest.raises(SystemExit) as info:
        main([command, "-k", "1", "-k", "10", *rest])
    assert info.value.code == 2
    assert "takes one friction coefficient, got k = 1, 10" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("command, one", [("solve", True), ("map", True), ("trace", False),
                                          ("audit", False)])
def test_usage_shows_how_many_k_a_command_takes(command, one):
    parser = build_parser()
    usage = parser._subparsers._group_actions[0].choices[command].format_usage()
    assert ("-k K [K ...]" in usage) is not one
    assert "-k K" in usage


def test_one_k_commands_accept_a_repeated_value(capsys):
    assert main(["solve", "--gamma", "0.6", "--delta", "0.2", "-k", "1", "-k", "1"]) == 0
    assert capsys.readouterr().out.startswith("k = 1, ")


@pytest.mark.parametrize("argv", [
    ["-v", "solve", "--gamma", "0.6", "--delta", "0.2", "-k", "1"],
    ["solve", "-v", "--gamma", "0.6", "--delta", "0.2", "-k", "1"],
    ["solve", "--gamma", "0.6", "--delta", "0.2", "-k", "1", "--verbose"],
])
def test_verbose_before_or_after_the_command(argv):
    assert build_parser().parse_args(argv).verbose is True


@pytest.mark.parametrize("before", [["--"], ["-v", "--"]])
def test_a_separator_before_the_command_is_no_command(before, capsys):
    assert main([*before, "solve", "--gamma", "0.6", "--delta", "0.2", "-k", "1"]) == 0
    assert "rolling sliding" in capsys.readouterr().out


def test_verbose_is_off_by_default():
    args = build_parser().parse_args(["solve", "--gamma", "0.6", "--delta", "0.2", "-k", "1"])
    assert getattr(args, "verbose", False) is False


def test_verbose_after_the_command_logs(monkeypatch):
    seen = {}
    monkeypatch.setattr(logging, "basicConfig", lambda **kw: seen.update(kw))
    assert main(["solve", "--gamma", "0.6", "--delta", "0.2", "-k", "1", "-v"]) == 0
    assert seen["level"] == logging.INFO


def test_version(capsys):
    with pytest.raises(SystemExit) as info:
        main(["--version"])
    assert info.value.code == 0
    assert capsys.readouterr().out.strip() == f"groove {groove_model.__version__} " \
                                              "(groove-continuation)"
    assert groove_model.__version__ == importlib.metadata.version("groove-continuation")


def test_python_dash_m():
    done = subprocess.run([sys.executable, "-m", "groove_model", "solve", "--gamma", "0.6",
                           "--delta", "0.2", "-k", "1", "--json"],
                          capture_output=True, text=True, check=False)
    assert done.returncode == 0, done.stderr
    assert '"regime": "rolling_sliding"' in done.stdout


def _last_line_printed(code: str) -> str:
    """The last line ``code`` prints, run in a new Python process (nothing imported yet)."""
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          check=True)
    return done.stdout.strip().splitlines()[-1]


def test_help_and_solve_import_neither_scipy_nor_matplotlib():
    code = ("import sys\n"
            "from groove_model.cli import main\n"
            "try:\n"
            "    main(['--help'])\n"
            "except SystemExit:\n"
            "    pass\n"
            "help_loaded = {m for m in ('numpy', 'scipy', 'pandas', 'matplotlib')"
            " if m in sys.modules}\n"
            "main(['solve', '--gamma', '0.6', '--delta', '0.2', '-k', '1'])\n"
            "solve_loaded = {m for m in ('scipy', 'pandas', 'matplotlib') if m in sys.modules}\n"
            "print(sorted(help_loaded), sorted(solve_loaded))\n")
    assert _last_line_printed(code) == "[] []"


@pytest.mark.parametrize("argv, loaded", [
    (["--help"], []),
    (["-v", "solve", "--help"], ["solve"]),
    (["solve", "--gamma", "0.6", "--delta", "0.2", "-k", "1"], ["solve"]),
    (["map", "--help"], ["map"]),
])
def test_a_command_loads_its_own_module_only(argv, loaded):
    # every command's module was imported to build the parser: start-up is paid on every run
    code = ("import sys\n"
            "from groove_model.cli import main\n"
            "try:\n"
            f"    main({argv!r})\n"
            "except SystemExit:\n"
            "    pass\n"
            "print(sorted(m.rsplit('.', 1)[1] for m in sys.modules if m.startswith("
            "'groove_model.cli.') and m.rsplit('.', 1)[1] not in ('common', 'main')))\n")
    assert _last_line_printed(code) == repr(loaded)


def test_groove_help_is_the_same_whether_the_commands_are_loaded_or_not():
    from groove_model.cli.common import COMMANDS

    lazy, whole = build_parser(()), build_parser()
    for parser in (lazy, whole):
        listed = {action.dest: action.help for action in
                  parser._subparsers._group_actions[0]._choices_actions}
        assert listed == COMMANDS
    assert lazy.format_help() == whole.format_help()


def test_atlas_command_imports_no_pandas(tmp_path):
    # the atlas writes its CSV files with csv: pandas' import would cost a third of a second
    code = ("import sys\n"
            "from groove_model.cli import main\n"
            "main(['atlas', '--k-min', '0.5', '--k-max', '2', '--no-figure',"
            f" '--out', {str(tmp_path)!r}])\n"
            "print('pandas' in sys.modules)\n")
    assert _last_line_printed(code) == "False"


def test_py_typed_marker_is_shipped():
    from importlib import resources

    assert resources.files("groove_model").joinpath("py.typed").is_file()
    assert resources.files("continuation").joinpath("py.typed").is_file()


@pytest.mark.parametrize("argv, message", [
    (["trace", "-k", "1e-5", "--out", "OUT"], "k = 1e-05 is outside the range the boundaries"),
    (["trace", "-k", "1e7", "--out", "OUT"], "k = 1e+07 is outside the range"),
    (["map", "-k", "2e6", "-o", "OUT/m.png"], "k = 2e+06 is outside the range"),
    (["sweep", "--k-min", "5e-5", "--k-max", "1", "-n", "3", "--out", "OUT"],
     "k = 5e-05 is outside the range"),
    (["atlas", "--k-max", "1e7", "--out", "OUT"], "1e-4 <= k <= 1e6"),
    (["audit", "-k", "1e-5", "--out", "OUT"], "1e-4 <= k <= 1e6"),
    (["compliance", "-k", "1e7", "--out", "OUT"], "1e-4 <= k <= 1e6"),
    (["trace", "-k", "1", "--compliance", "0.3", "--out", "OUT"],
     "compliance ratio c = 0.3 is outside the range the boundaries are traced for: 2/3 <= c <= 1"),
    (["trace", "-k", "1", "--compliance", "20", "--out", "OUT"], "2/3 <= c <= 1"),
    (["atlas", "--poisson", "-0.5", "--out", "OUT"],
     "Poisson ratio nu = -0.5 is outside the range the boundaries are traced for: 0 <= nu <= 0.5"),
    (["compliance", "--poissons", "-0.2", "0.3", "--out", "OUT"], "0 <= nu <= 0.5"),
])
def test_traced_commands_refuse_k_and_compliance_outside_the_verified_ranges(
        argv, message, tmp_path, capsys):
    argv = [str(tmp_path / "out") if a == "OUT" else a.replace("OUT", str(tmp_path / "out"))
            for a in argv]
    with pytest.raises(SystemExit) as exit_info:
        main(argv)
    assert exit_info.value.code == 2
    assert message in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def test_the_point_solver_takes_any_k_and_poisson_ratio(capsys):
    # only tracing is limited to the verified ranges; the point solver is exact for any k > 0
    assert main(["solve", "--gamma", "0.5", "--delta", "0.1", "-k", "1e7",
                 "--poisson", "-0.5"]) == 0


def test_trace_boundaries_refuses_k_outside_the_verified_range():
    from groove_model.model.parameters import Compliance, Parameters
    from groove_model.tracing import trace_boundaries, trace_many

    for bad in (1e-5, 2e6, Parameters(1.0, Compliance(0.5)), 0, -1.0, math.nan, math.inf):
        with pytest.raises(ValueError, match="outside the range the boundaries are traced for"):
            trace_boundaries(bad)
    with pytest.raises(ValueError, match=r"k = 0.0 is outside .* 1e-4 <= k <= 1e6"):
        trace_many([1.0, 0.0])
    with pytest.raises(TypeError, match="ks must be friction coefficients .* as compliance="):
        trace_many([Parameters(1.0, Compliance(0.8))])  # its compliance would be dropped


@pytest.mark.parametrize("value", ["-inf", "-1e-3", "-Infinity", "-1E5"])
def test_a_negative_number_written_any_way_is_a_value_not_an_option(value, capsys):
    # argparse alone reads -inf and -1e-3 as options: "expected at least one argument"
    with pytest.raises(SystemExit) as exit_info:
        main(["solve", "--gamma", "0.5", "--delta", "0.1", "-k", value])
    assert exit_info.value.code == 2
    err = capsys.readouterr().err
    assert f"friction coefficient k = {float(value)!r} is outside the allowed range" in err


@pytest.mark.parametrize("argv, message", [
    (["trace", "-k", "1", "--out", "DIR/o", "--figure", "sub/name"], "is not a file name"),
    (["trace", "-k", "1", "--out", "DIR/o", "--figure", "../escape"], "is not a file name"),
    (["trace", "-k", "1", "--out", "DIR/f/sub"], "DIR/f is a file, not a directory"),
    (["reproduce", "--out", "DIR/f"], "--out DIR/f exists and is not a directory"),
    (["map", "-k", "1", "-o", "DIR/f/m.png"], "DIR/f of DIR/f/m.png is a file, not a directory"),
    (["sweep", "--k-min", "1", "--k-max", "10", "-n", "1", "--out", "DIR/o"],
     "-n 1 traces one k"),
])
def test_bad_output_paths_are_refused_before_anything_is_computed(argv, message, tmp_path,
                                                                  capsys):
    (tmp_path / "f").write_text("a file")
    argv = [a.replace("DIR", str(tmp_path)) for a in argv]
    with pytest.raises(SystemExit) as exit_info:
        main(argv)
    assert exit_info.value.code == 2
    assert message.replace("DIR", str(tmp_path)) in capsys.readouterr().err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f"]


def test_ctrl_c_ends_with_a_line_and_exit_code_130_not_a_traceback(monkeypatch, capsys):
    from groove_model.cli import solve

    def interrupted(args):
        raise KeyboardInterrupt

    monkeypatch.setattr(solve, "run", interrupted)
    assert main(["solve", "--gamma", "0.5", "--delta", "0.1", "-k", "1"]) == 130
    assert capsys.readouterr().err == "groove solve: interrupted\n"


_TERMINATED_WHILE_WRITING = """
import os, signal, sys
import pandas as pd
from groove_model.cli.main import main
number = getattr(signal, sys.argv[1])
real = pd.DataFrame.to_csv
def terminated_while_writing(self, path=None, *args, **kwargs):
    real(self, path, *args, **kwargs)  # the temporary file is there, whole
    os.kill(os.getpid(), number)
pd.DataFrame.to_csv = terminated_while_writing
before = signal.getsignal(number)
code = main(["trace", "-k", "1", "--out", sys.argv[2], "--no-figure"])
assert signal.getsignal(number) is before, "the handler is not the caller's again"
sys.exit(code)
"""


@pytest.mark.parametrize("signame", ["SIGTERM", "SIGHUP"])
def test_a_terminated_command_removes_what_it_was_writing(signame, tmp_path):
    """SIGTERM (a service manager, timeout) or SIGHUP (the terminal closed) while a file is
    being written: its temporary is removed and the command says so, exit 128 + the signal (the
    default action killed it outright and left `.name.partial-...` behind)."""
    import signal

    out = tmp_path / "out"
    done = subprocess.run([sys.executable, "-c", _TERMINATED_WHILE_WRITING, signame, str(out)],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 128 + getattr(signal, signame), done.stderr
    assert done.stderr.endswith("groove trace: CSVs written before the interrupt: k = none; no "
                                f"overlay\ngroove trace: terminated by {signame}\n")
    assert not out.exists()  # no temporary, no half of the pair, not the directory it made


@pytest.mark.parametrize("argv", [
    ["trace", "-k", "1", "--out", "DIR/o"],
    ["map", "-k", "1", "-o", "DIR/o/m.png", "--no-boundaries", "--resolution", "20"],
    ["plot", "RESULTS/boundaries_k1.csv", "-o", "DIR/o/p.png"],
    ["atlas", "--k-min", "1", "--k-max", "2", "--out", "DIR/o"],
])
def test_an_unknown_mplbackend_is_a_usage_error_before_anything_is_written(argv, tmp_path,
                                                                           monkeypatch, capsys):
    for name in [m for m in sys.modules if m == "matplotlib" or m.startswith("matplotlib.")]:
        monkeypatch.delitem(sys.modules, name)  # so that matplotlib reads MPLBACKEND again
    monkeypatch.setenv("MPLBACKEND", "no-such-backend")
    results = Path(__file__).resolve().parents[1] / "results"
    argv = [a.replace("DIR", str(tmp_path)).replace("RESULTS", str(results)) for a in argv]
    with pytest.raises(SystemExit) as exit_info:
        main(argv)
    assert exit_info.value.code == 2
    assert "MPLBACKEND = 'no-such-backend' is not a backend matplotlib knows" in \
        capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_an_unwritable_out_directory_is_refused_before_anything_is_computed(tmp_path,
                                                                            monkeypatch, capsys):
    import os

    from groove_model.analysis.audit import run as audit_run

    # root may write anywhere, so the directory's permission is stood in for by os.access
    monkeypatch.setattr(os, "access", lambda path, mode: Path(path) != tmp_path)
    monkeypatch.setattr(audit_run, "run_audit", lambda *a, **k: pytest.fail("audit ran"))
    with pytest.raises(SystemExit) as exit_info:
        main(["audit", "-k", "1", "--out", str(tmp_path / "new")])
    assert exit_info.value.code == 2
    captured = capsys.readouterr()
    assert f"--out {tmp_path / 'new'} cannot be written: {tmp_path} is not writable" in \
        captured.err
    assert captured.out == ""


@pytest.mark.parametrize(("argv", "blocked", "untouched"), [
    # the second file of a group is blocked by a directory: the first must not be replaced
    (["sweep", "--k-min", "1", "--k-max", "2", "-n", "2", "--out", "DIR"],
     "sweep_special_points.csv", "sweep_boundaries.csv"),
    (["audit", "-k", "1", "--out", "DIR"], "claims.json", "claims.md"),
    (["atlas", "--k-min", "1", "--k-max", "2", "--out", "DIR"], "atlas_thresholds.csv",
     "atlas_junction.csv"),
])
def test_a_directory_in_a_files_place_leaves_every_file_of_the_group_as_it_was(
        argv, blocked, untouched, tmp_path, monkeypatch, capsys):
    (tmp_path / blocked).mkdir()
    (tmp_path / untouched).write_text("old")
    argv = [a.replace("DIR", str(tmp_path)) for a in argv]
    monkeypatch.setattr("groove_model.tracing.sweep.trace_boundaries",
                        lambda *a, **k: pytest.fail("traced before the files were checked"))
    with pytest.raises(SystemExit) as exit_info:  # seen at the start: bad input
        main(argv)
    assert exit_info.value.code == 2
    err = capsys.readouterr().err
    assert f"cannot write {tmp_path / blocked}: a directory is in its place" in err
    assert (tmp_path / untouched).read_text() == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([blocked, untouched])


@pytest.mark.parametrize("argv, blocked", [
    (["trace", "-k", "1", "10", "--out", "DIR"], "boundaries_k1_k10.svg"),
    (["map", "-k", "1", "-o", "DIR/m.png", "--svg", "--no-boundaries"], "m.svg"),
    (["atlas", "--k-min", "1", "--k-max", "2", "--out", "DIR"], "atlas.png"),
])
def test_a_directory_in_the_place_of_a_later_file_is_refused_before_computing(
        argv, blocked, tmp_path, monkeypatch, capsys):
    # the figure is written after the CSVs: a directory in its place was found only then,
    # with the CSVs (or the PNG) already replaced
    (tmp_path / blocked).mkdir()
    monkeypatch.setattr("groove_model.tracing.trace_boundaries",
                        lambda *a, **k: pytest.fail("traced before the files were checked"))
    with pytest.raises(SystemExit) as exit_info:
        main([a.replace("DIR", str(tmp_path)) for a in argv])
    assert exit_info.value.code == 2
    assert f"cannot write {tmp_path / blocked}: a directory is in its place" in \
        capsys.readouterr().err
    assert [p.name for p in tmp_path.iterdir()] == [blocked]


def test_a_figure_goes_into_a_new_directory_as_out_does(tmp_path, capsys):
    target = tmp_path / "new" / "sub" / "m.png"
    assert main(["map", "-k", "1", "-o", str(target), "--no-boundaries",
                 "--resolution", "12"]) == 0
    assert target.is_file()


@pytest.mark.parametrize("argv", [
    ["map", "-k", "1", "-o", "DIR/new/m.png", "--no-boundaries", "--resolution", "12"],
    ["plot", "RESULTS/boundaries_k1.csv", "-o", "DIR/p.png"],
])
def test_an_unwritable_figure_directory_is_refused_before_anything_is_computed(
        argv, tmp_path, monkeypatch, capsys):
    import os

    # root may write anywhere, so the directory's permission is stood in for by os.access
    monkeypatch.setattr(os, "access", lambda path, mode: Path(path) != tmp_path)
    results = Path(__file__).resolve().parents[1] / "results"
    argv = [a.replace("DIR", str(tmp_path)).replace("RESULTS", str(results)) for a in argv]
    with pytest.raises(SystemExit) as exit_info:
        main(argv)
    assert exit_info.value.code == 2
    assert f"cannot be written: {tmp_path} is not writable" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_a_directory_given_as_the_figure_is_refused(tmp_path, capsys):
    (tmp_path / "d.png").mkdir()
    with pytest.raises(SystemExit) as exit_info:
        main(["map", "-k", "1", "-o", str(tmp_path / "d.png"), "--no-boundaries"])
    assert exit_info.value.code == 2
    assert "is a directory; give a file name" in capsys.readouterr().err
    # one with no suffix is named as a directory too, not as a file of format '(none)'
    with pytest.raises(SystemExit):
        main(["plot", str(Path(__file__).resolve().parents[1] / "results" / "boundaries_k1.csv"),
              "-o", str(tmp_path)])
    assert (f"-o {tmp_path} is a directory; give a file name such as {tmp_path / 'figure.png'}"
            in capsys.readouterr().err)


@pytest.mark.parametrize("argv", [
    ["trace", "-k", "1", "--out", "DIR/link"],
    ["trace", "-k", "1", "--out", "DIR/link/sub"],
    ["map", "-k", "1", "-o", "DIR/link/m.png", "--no-boundaries"],
])
def test_a_link_to_nothing_as_the_output_directory_is_named(argv, tmp_path, capsys):
    # it read "[Errno 17] File exists", after tracing
    (tmp_path / "link").symlink_to(tmp_path / "nowhere")
    with pytest.raises(SystemExit) as exit_info:
        main([a.replace("DIR", str(tmp_path)) for a in argv])
    assert exit_info.value.code == 2
    assert f"{tmp_path / 'link'} is a link to {tmp_path / 'nowhere'}, which does not exist" in \
        capsys.readouterr().err


@pytest.mark.skipif(not Path("/proc/self").is_dir(), reason="needs a /proc file system")
@pytest.mark.parametrize("argv", [
    ["trace", "-k", "1", "--out", "/proc/groove-out"],
    ["map", "-k", "1", "-o", "/proc/groove-map.png", "--no-boundaries"],
])
def test_a_directory_where_no_file_can_be_created_is_refused_before_computing(
        argv, monkeypatch, capsys):
    # root passes the permission check on /proc, so it was found only when writing: the map
    # was computed first, and trace printed Python's "[Errno 2] ...: '/proc/groove-out'"
    monkeypatch.setattr("groove_model.tracing.trace_boundaries",
                        lambda *a, **k: pytest.fail("traced before the directory was checked"))
    monkeypatch.setattr("groove_model.plots.regime_map.save_regime_map",
                        lambda *a, **k: pytest.fail("mapped before the file was checked"))
    with pytest.raises(SystemExit) as exit_info:
        main(argv)
    assert exit_info.value.code == 2
    err = capsys.readouterr().err
    given = argv[argv.index("--out" if "--out" in argv else "-o") + 1]
    assert f"{given} cannot be written: " in err and "Errno" not in err
    assert "creating a file in /proc failed: " in err or "/proc is not writable" in err


def test_an_error_of_the_system_reads_path_then_reason(monkeypatch, capsys):
    from groove_model.cli import solve

    def failed(args):
        raise FileNotFoundError(2, "No such file or directory", "/no/such/place")

    monkeypatch.setattr(solve, "run", failed)
    with pytest.raises(SystemExit) as exit_info:
        main(["solve", "--gamma", "0.5", "--delta", "0.1", "-k", "1"])
    assert exit_info.value.code == 2
    assert capsys.readouterr().err == \
        "groove solve: error: /no/such/place: No such file or directory\n"


def test_an_out_directory_that_cannot_be_made_after_all_is_a_failed_write(tmp_path, monkeypatch,
                                                                         capsys):
    def refused(self, *args, **kwargs):
        raise PermissionError(13, "Permission denied", str(self))

    monkeypatch.setattr(Path, "mkdir", refused)  # a directory that could not be made after all
    assert main(["trace", "-k", "1", "--out", str(tmp_path / "new"), "--no-figure"]) == 1
    assert capsys.readouterr().err.startswith(
        f"groove trace: error: k = 1: cannot create {tmp_path / 'new'}: Permission denied; "
        "nothing written for this k\n")


def test_ctrl_c_while_the_commands_load_is_a_line_not_a_traceback(monkeypatch, capsys):
    main_module = sys.modules[main.__module__]  # the module (its package exports main itself)

    def interrupted(commands=None):
        raise KeyboardInterrupt

    monkeypatch.setattr(main_module, "build_parser", interrupted)
    assert main(["solve", "--gamma", "0.5", "--delta", "0.1", "-k", "1"]) == 130
    assert capsys.readouterr().err == "groove: interrupted\n"


def test_a_k_whose_files_cannot_be_written_does_not_stop_the_others(tmp_path, monkeypatch,
                                                                      capsys):
    from groove_model.io import export
    from groove_model.io.atomic import WriteError

    real = export.write_boundary_set

    def full_for_k1(boundary_set, directory, suffix=""):
        if boundary_set.k == 1.0:
            raise WriteError(28, "cannot write boundaries_k1.csv: No space left on device")
        return real(boundary_set, directory, suffix)

    monkeypatch.setattr(export, "write_boundary_set", full_for_k1)
    assert main(["trace", "-k", "1", "10", "--out", str(tmp_path), "--no-figure"]) == 1
    err = capsys.readouterr().err
    assert "k = 1: cannot write boundaries_k1.csv: No space left on device" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["boundaries_k10.csv",
                                                          "special_points_k10.csv"]


def test_reproduce_refuses_a_file_where_its_compliance_directory_goes_before_any_step(
        tmp_path, monkeypatch, capsys):
    # it ran trace, map and atlas (rewriting their files) before compliance refused
    (tmp_path / "compliance").write_text("a file")
    monkeypatch.setattr("groove_model.tracing.trace_boundaries",
                        lambda *a, **k: pytest.fail("a step ran before the check"))
    with pytest.raises(SystemExit) as exit_info:
        main(["reproduce", "--out", str(tmp_path)])
    assert exit_info.value.code == 2
    assert "compliance exists and is not a directory" in capsys.readouterr().err
    assert [p.name for p in tmp_path.iterdir()] == ["compliance"]


def test_compliance_refuses_a_directory_in_the_place_of_its_report(tmp_path, capsys):
    (tmp_path / "compliance.md").mkdir()
    with pytest.raises(SystemExit) as exit_info:
        main(["compliance", "--poissons", "0", "-k", "1", "--out", str(tmp_path)])
    assert exit_info.value.code == 2
    assert f"cannot write {tmp_path / 'compliance.md'}: a directory is in its place" in \
        capsys.readouterr().err
    assert [p.name for p in tmp_path.iterdir()] == ["compliance.md"]


@pytest.mark.parametrize("blocked", ["map_k1.svg", "claims.json", "compliance/compliance.md"])
def test_reproduce_checks_every_steps_files_before_the_first_step(blocked, tmp_path,
                                                                   monkeypatch, capsys):
    # a directory in the place of a later step's file was found by that step, after trace (and
    # the maps) had rewritten their files
    (tmp_path / blocked).mkdir(parents=True)
    monkeypatch.setattr("groove_model.tracing.trace_boundaries",
                        lambda *a, **k: pytest.fail("a step ran before the check"))
    with pytest.raises(SystemExit) as exit_info:
        main(["reproduce", "--out", str(tmp_path)])
    assert exit_info.value.code == 2
    assert f"cannot write {tmp_path / blocked}: a directory is in its place" in \
        capsys.readouterr().err


def test_an_empty_out_is_refused_not_taken_as_the_current_directory(tmp_path, capsys,
                                                                     monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(SystemExit) as info:
        main(["trace", "-k", "1", "--out", ""])
    assert info.value.code == 2
    assert "--out '' is empty: give a directory ('.' for this one)" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_an_empty_csv_is_named_as_empty(tmp_path, capsys):
    empty = tmp_path / "boundaries_k1.csv"
    empty.write_text("")
    with pytest.raises(SystemExit) as info:
        main(["plot", str(empty), "-o", str(tmp_path / "x.png")])
    assert info.value.code == 2
    assert f"{empty}: not a boundaries CSV (the file is empty)" in capsys.readouterr().err


@pytest.mark.parametrize("failure", ["code", "exception"])
def test_reproduce_names_the_step_that_failed_and_those_not_run(failure, tmp_path, monkeypatch,
                                                                capsys):
    def broken(args):
        if failure == "code":
            return 1
        raise ArithmeticError("the computation failed")

    monkeypatch.setattr("groove_model.cli.trace.run", broken)
    assert main(["reproduce", "--out", str(tmp_path)]) == 1
    err = capsys.readouterr().err
    assert (f"groove reproduce: stopped at step 1 of 6 (groove trace -k 1 -k 10 --out "
            f"{tmp_path}); not run: groove map -k 1 -o {tmp_path / 'map_k1.png'} --svg; ") in err
    last = f"groove audit --trace --out {tmp_path}"
    if failure == "code":
        assert err.rstrip().endswith(last)
    else:  # the step's own error follows, from groove's entry point
        assert err.rstrip().endswith(f"{last}\ngroove reproduce: error: the computation failed")


def test_ctrl_c_in_a_trace_of_several_k_says_which_were_written(tmp_path, monkeypatch, capsys):
    from groove_model import tracing

    real = tracing.trace_boundaries

    def until_three(k, **kwargs):
        if k.k == 3.0:
            raise KeyboardInterrupt
        return real(k, **kwargs)

    monkeypatch.setattr(tracing, "trace_boundaries", until_three)
    out = tmp_path / "out"
    assert main(["trace", "-k", "1", "2", "3", "4", "--out", str(out)]) == 130
    err = capsys.readouterr().err
    assert err.endswith("groove trace: CSVs written before the interrupt: k = 1, 2; no overlay\n"
                        "groove trace: interrupted\n")
    assert sorted(p.name for p in out.iterdir()) == [
        "boundaries_k1.csv", "boundaries_k2.csv", "special_points_k1.csv",
        "special_points_k2.csv"]
