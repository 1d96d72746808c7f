"""CSV export, the committed results, and the trace / plot commands."""

import dataclasses
import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from groove_model import tracing as tracer_module
from groove_model.cli.main import main
from groove_model.cli.trace import overlay_name
from groove_model.io.export import (
    atomic_write,
    boundary_file_names,
    incomplete_boundaries,
    read_boundaries_csv,
    write_boundary_set,
)
from groove_model.model.boundaries import BoundarySystem
from groove_model.model.parameters import Parameters
from groove_model.tracing import CSV_COLUMNS, SPECIAL_POINT_COLUMNS, trace_boundaries

RESULTS = Path(__file__).resolve().parents[1] / "results"


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    out = tmp_path_factory.mktemp("trace")
    sets = {k: trace_boundaries(k) for k in (1.0, 10.0)}
    for bs in sets.values():
        write_boundary_set(bs, out)
    return out, sets


def test_csv_columns_and_rows_satisfy_their_equations(written):
    out, _ = written
    for k in (1, 10):
        frame = read_boundaries_csv(out / f"boundaries_k{k}.csv")
        assert tuple(frame.columns) == CSV_COLUMNS
        specials = pd.read_csv(out / f"special_points_k{k}.csv")
        assert tuple(specials.columns) == SPECIAL_POINT_COLUMNS
        params = Parameters(float(k))
        for name, rows in frame.groupby("boundary"):
            system = BoundarySystem(name, params)
            x = rows[["gamma", "delta", "beta_L", "upsilon"]].to_numpy()
            residual = np.array([system.residual(xi) for xi in x])
            assert np.max(np.abs(residual)) <= 1e-10, name
            assert np.allclose(rows["theta_L"], rows["gamma"] + rows["delta"], atol=1e-15)
            assert np.all(np.diff(rows["s"]) > 0)
        assert set(frame["point"]) - {""} <= {"start", "end", "junction", "fold_gamma",
                                             "fold_delta", "branch_point"}


def test_committed_results_are_reproduced(written):
    out, _ = written
    for k in (1, 10):
        for stem in ("boundaries", "special_points"):
            new = pd.read_csv(out / f"{stem}_k{k}.csv", keep_default_na=False)
            old = pd.read_csv(RESULTS / f"{stem}_k{k}.csv", keep_default_na=False)
            assert list(new.columns) == list(old.columns) and len(new) == len(old), stem
            for column in new.columns:
                if new[column].dtype.kind == "f":
                    assert np.allclose(new[column], old[column], rtol=1e-9, atol=1e-11), column
                else:
                    assert list(new[column]) == list(old[column]), column


def test_atomic_write_leaves_nothing_on_failure(tmp_path):
    def broken(tmp):
        Path(tmp).write_text("half")
        raise RuntimeError("disk full")

    with pytest.raises(RuntimeError):
        atomic_write(tmp_path / "x.csv", broken)
    assert list(tmp_path.iterdir()) == []


def test_trace_command_writes_csvs_and_figures(tmp_path, capsys):
    assert main(["trace", "-k", "2", "--out", str(tmp_path)]) == 0
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == ["boundaries_k2.csv", "boundaries_k2.png", "boundaries_k2.svg",
                     "special_points_k2.csv"]
    assert "k = 2" in capsys.readouterr().out


def _failing_for(ks, monkeypatch):
    """Make the tracer fail (rs_no_roll) for the given k."""
    real = tracer_module.trace_boundaries

    def failing(k, **kwargs):
        bs = real(k, **kwargs)
        if getattr(k, "k", k) not in ks:  # k or Parameters(k, compliance)
            return bs
        curve = bs.curves["rs_no_roll"]
        broken = type(curve)(**{**curve.__dict__, "ok": False,
                                "status": "the step size fell below its minimum: at step 7"})
        return type(bs)(k=bs.k, curves={**bs.curves, "rs_no_roll": broken})

    monkeypatch.setattr(tracer_module, "trace_boundaries", failing)


def test_trace_command_failure_writes_nothing(tmp_path, monkeypatch, capsys):
    _failing_for((1.0, 3.0), monkeypatch)
    assert main(["trace", "-k", "1", "-k", "3", "--out", str(tmp_path / "out")]) == 1
    err = capsys.readouterr().err
    assert "k = 1: rs_no_roll: the step size fell below its minimum" in err
    assert "k = 3: nothing written for this k" in err and "no overlay" in err
    assert not (tmp_path / "out").exists()


def test_trace_command_writes_the_k_that_succeeded(tmp_path, monkeypatch, capsys):
    _failing_for((3.0,), monkeypatch)
    assert main(["trace", "-k", "1", "3", "0.5", "--out", str(tmp_path)]) == 1
    captured = capsys.readouterr()
    assert "k = 3: rs_no_roll: the step size fell below its minimum" in captured.err
    assert "no overlay: k = 3 failed or could not be written" in captured.err
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "boundaries_k0.5.csv", "boundaries_k1.csv", "special_points_k0.5.csv",
        "special_points_k1.csv"]
    assert "k = 1: " in captured.out and "k = 0.5: " in captured.out


def test_close_k_get_their_own_files(tmp_path):
    assert main(["trace", "-k", "1.0000001", "1.0000002", "--out", str(tmp_path),
                 "--no-figure"]) == 0
    for k in ("1.0000001", "1.0000002"):
        frame = read_boundaries_csv(tmp_path / f"boundaries_k{k}.csv")
        assert set(frame["k"]) == {float(k)}
        assert (tmp_path / f"special_points_k{k}.csv").exists()


def test_a_k_given_twice_is_traced_once_and_said_so(tmp_path, monkeypatch, capsys):
    traced = []
    real = tracer_module.trace_boundaries

    def counting(k, **kwargs):
        traced.append(getattr(k, "k", k))
        return real(k, **kwargs)

    monkeypatch.setattr(tracer_module, "trace_boundaries", counting)
    assert main(["trace", "-k", "2", "1", "2", "--out", str(tmp_path), "--no-figure"]) == 0
    assert traced == [2.0, 1.0]
    assert "note: k = 2 given more than once: traced once" in capsys.readouterr().err


def test_many_k_get_a_short_distinct_overlay_name():
    ks = list(np.geomspace(1e-2, 1e3, 200))
    name = overlay_name(ks)
    assert len(name) <= 60 and name.startswith("boundaries_200k_0.01-1000_")
    assert overlay_name(ks[:-1] + [ks[-1] * (1 + 1e-15)]) != name
    assert overlay_name([1.0, 10.0]) == "boundaries_k1_k10"
    assert boundary_file_names(1.0000001) == ("boundaries_k1.0000001.csv",
                                              "special_points_k1.0000001.csv")
    assert boundary_file_names(1e-5) == ("boundaries_k1e-05.csv", "special_points_k1e-05.csv")


def test_trace_command_writes_the_short_overlay_name(tmp_path, monkeypatch):
    from groove_model.cli import trace as trace_command

    monkeypatch.setattr(trace_command, "MAX_FIGURE_NAME", 20)
    assert main(["trace", "-k", "0.5", "2", "7", "--out", str(tmp_path)]) == 0
    figures = sorted(p.name for p in tmp_path.glob("*.png"))
    assert figures == [overlay_name([0.5, 2.0, 7.0]) + ".png"]
    assert figures[0].startswith("boundaries_3k_0.5-7_")


@pytest.mark.parametrize("k", ["0", "-1", "nan", "inf", "x"])
def test_trace_command_bad_k(k, tmp_path, capsys):
    with pytest.raises(SystemExit) as info:
        main(["trace", "-k", k, "--out", str(tmp_path)])
    assert info.value.code == 2
    assert "friction coefficient k =" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_plot_command(written, tmp_path):
    out, _ = written
    target = tmp_path / "fig.png"
    assert main(["plot", str(out / "boundaries_k1.csv"), str(out / "boundaries_k10.csv"),
                 "-o", str(target), "--deg"]) == 0
    assert target.stat().st_size > 10_000


@pytest.mark.parametrize("content, message", [
    (None, "No such file"),
    ("a,b\n1,2\n", "missing columns boundary,k,s"),
])
def test_plot_command_bad_files(content, message, tmp_path, capsys):
    path = tmp_path / "in.csv"
    if content is not None:
        path.write_text(content)
    with pytest.raises(SystemExit) as info:
        main(["plot", str(path), "-o", str(tmp_path / "f.png")])
    assert info.value.code == 2
    assert message.replace("boundary,k,s", "boundary, k, s") in capsys.readouterr().err
    assert not (tmp_path / "f.png").exists()


def test_draw_boundaries_on_given_axes(written):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from groove_model.plots.overlay import draw_boundaries

    _, sets = written
    fig, ax = plt.subplots()
    try:
        artists = draw_boundaries(ax, list(sets.values()), degrees=True)
        assert len(artists) >= 6
        assert ax.get_xlim()[1] == pytest.approx(90.0)
        styles = {line.get_linestyle() for line in ax.get_lines()}
        assert {"-", "-.", "--"} <= styles
    finally:
        plt.close(fig)
    assert math.isfinite(sets[10.0].limit_distance)


@pytest.mark.parametrize("body, message", [
    ("0.5,xyz", "column k = 'xyz' in data row 1 is not a finite number"),
    ("abc,1", "column gamma = 'abc' in data row 1 is not a finite number"),
    ("nan,1", "column gamma = 'nan' in data row 1 is not a finite number"),
])
def test_plot_command_bad_values(body, message, written, tmp_path, capsys):
    out, _ = written
    frame = pd.read_csv(out / "boundaries_k1.csv", keep_default_na=False, dtype=str).head(3)
    gamma_or_k = body.split(",")
    if "k =" in message:
        frame.loc[0, "k"] = gamma_or_k[1]
    else:
        frame.loc[0, "gamma"] = gamma_or_k[0]
    path = tmp_path / "bad.csv"
    frame.to_csv(path, index=False)
    with pytest.raises(SystemExit) as info:
        main(["plot", str(path), "-o", str(tmp_path / "f.png")])
    assert info.value.code == 2
    assert message in capsys.readouterr().err


def test_overlay_name_keeps_dots(tmp_path):
    assert main(["trace", "-k", "0.5", "-k", "2.5", "--out", str(tmp_path)]) == 0
    assert (tmp_path / "boundaries_k0.5_k2.5.png").exists()
    assert (tmp_path / "boundaries_k0.5_k2.5.svg").exists()


def _csv_text(written, k=1):
    out, _ = written
    return pd.read_csv(out / f"boundaries_k{k}.csv", keep_default_na=False, dtype=str)


def _plot_refused(paths, tmp_path, capsys) -> str:
    target = tmp_path / "f.png"
    with pytest.raises(SystemExit) as info:
        main(["plot", *map(str, paths), "-o", str(target)])
    assert info.value.code == 2
    assert not target.exists()
    return capsys.readouterr().err


def test_plot_refuses_a_csv_with_several_k(written, tmp_path, capsys):
    both = pd.concat([_csv_text(written, 1), _csv_text(written, 10)])
    path = tmp_path / "both.csv"
    both.to_csv(path, index=False)
    err = _plot_refused([path], tmp_path, capsys)
    assert "column k holds 2 values (1, 10); a boundaries CSV holds one k" in err


def test_plot_refuses_the_same_k_twice(written, tmp_path, capsys):
    out, _ = written
    copy = tmp_path / "copy.csv"
    copy.write_text((out / "boundaries_k1.csv").read_text())
    err = _plot_refused([out / "boundaries_k1.csv", copy], tmp_path, capsys)
    assert "both hold k = 1" in err


@pytest.mark.parametrize("column, value, message", [
    ("k", 1e9, "data row 1: friction coefficient k = 1e+09 is outside the range the boundaries "
               "are traced for: 1e-4 <= k <= 1e6"),
    # k <= 0 was "outside the allowed range: friction coefficient k > 0", in another form
    ("k", 0.0, "data row 1: friction coefficient k = 0.0 is outside the range the boundaries "
               "are traced for: 1e-4 <= k <= 1e6"),
    ("k", -2.0, "friction coefficient k = -2.0 is outside the range"),
    ("compliance", 5.0, "compliance ratio c = 5.0 is outside the range the boundaries are traced"),
    ("compliance", 0.0, "data row 1: compliance ratio c = 0.0 is outside the range the "
                        "boundaries are traced for: 2/3 <= c <= 1"),
])
def test_plot_refuses_a_k_or_compliance_outside_the_traced_ranges(column, value, message,
                                                                   written, tmp_path, capsys):
    frame = _csv_text(written)
    frame[column] = value
    path = tmp_path / "bad.csv"
    frame.to_csv(path, index=False)
    assert message in _plot_refused([path], tmp_path, capsys)


def test_rows_in_any_order_read_back_along_each_boundary(written, tmp_path):
    # a shuffled (or re-sorted) file was drawn as a zig-zag: the rows are put back in the
    # order of the boundaries and of s, the arclength along each
    out, _ = written
    path = tmp_path / "shuffled.csv"
    _csv_text(written).sample(frac=1.0, random_state=3).to_csv(path, index=False)
    pd.testing.assert_frame_equal(read_boundaries_csv(path),
                                  read_boundaries_csv(out / "boundaries_k1.csv"))


@pytest.mark.parametrize("column, value, message", [
    ("gamma", "1.6", "column gamma = '1.6' in data row 2 is outside the allowed range "
                     "0 <= gamma <= pi/2"),
    ("gamma", "-0.1", "column gamma = '-0.1' in data row 2 is outside the allowed range"),
    ("delta", "-0.001", "column delta = '-0.001' in data row 2 is outside the allowed range "
                        "0 <= delta <= gamma"),
    ("delta", "1.5", "column delta = '1.5' in data row 2 is outside the allowed range "
                     "0 <= delta <= gamma"),
])
def test_plot_refuses_points_outside_the_domain(column, value, message, written, tmp_path,
                                                capsys):
    frame = _csv_text(written)
    frame.loc[1, column] = value
    path = tmp_path / "bad.csv"
    frame.to_csv(path, index=False)
    assert message.replace("'", "") in _plot_refused([path], tmp_path, capsys).replace("'", "")


def test_the_compliance_travels_with_the_csv_and_tells_two_traces_apart(tmp_path, capsys):
    # a trace for nu = 0.5 wrote no compliance column, so `groove plot` refused it next to the
    # paper's trace of the same k ("both hold k = 1") and titled it "k = 1"
    assert main(["trace", "-k", "1", "--out", str(tmp_path), "--no-figure"]) == 0
    assert main(["trace", "-k", "1", "--poisson", "0.5", "--out", str(tmp_path),
                 "--no-figure"]) == 0
    mindlin = read_boundaries_csv(tmp_path / "boundaries_k1_nu0.5.csv")
    assert mindlin["compliance"].unique().tolist() == [pytest.approx(2.0 / 3.0, rel=1e-15)]
    specials = pd.read_csv(tmp_path / "special_points_k1_nu0.5.csv")
    assert specials["compliance"].unique().tolist() == [pytest.approx(2.0 / 3.0, rel=1e-15)]
    assert main(["plot", str(tmp_path / "boundaries_k1.csv"),
                 str(tmp_path / "boundaries_k1_nu0.5.csv"), "-o", str(tmp_path / "both.png")]) == 0
    # a file written before the column existed reads as the paper's compliance
    old = pd.read_csv(tmp_path / "boundaries_k1.csv").drop(columns="compliance")
    old.to_csv(tmp_path / "old.csv", index=False)
    assert read_boundaries_csv(tmp_path / "old.csv")["compliance"].eq(1.0).all()


def test_a_boundary_curve_table_has_the_compliance_of_its_trace():
    # BoundaryCurve.to_frame() wrote c = 1 and recomputed T/N for a trace with c = 2/3
    from groove_model.model.parameters import Compliance, Parameters

    boundaries = trace_boundaries(Parameters(1.0, Compliance.from_poisson(0.5)))
    mine = boundaries.curves["dr_limit"].to_frame()
    theirs = boundaries.to_frame().query("boundary == 'dr_limit'").reset_index(drop=True)
    assert mine["compliance"].eq(2.0 / 3.0).all()
    assert np.allclose(mine["T_over_N_L"], 1.0, rtol=1e-9)  # T = kN on the limit, k = 1
    pd.testing.assert_frame_equal(mine, theirs)


def test_a_failed_trace_gives_no_table_and_no_file_unless_asked_for_partial(tmp_path):
    # gamma_min above the fold of dr_limit: the limit curve stops short of its end
    failed = trace_boundaries(1.0, gamma_min=0.5)
    assert not failed.ok
    for table in (failed.to_frame, failed.special_points_frame):
        with pytest.raises(tracer_module.TraceError, match="partial=True") as error:
            table()
        assert error.value.boundary_set is failed
    with pytest.raises(tracer_module.TraceError, match="failed"):
        failed.curves["dr_limit"].to_frame()
    with pytest.raises(tracer_module.TraceError):
        write_boundary_set(failed, tmp_path / "out")
    assert list(tmp_path.iterdir()) == []
    # asked for, the rows traced so far, for inspection
    partial = failed.to_frame(partial=True)
    assert set(partial["boundary"]) == set(failed.curves)
    assert len(failed.special_points_frame(partial=True))
    assert len(failed.curves["dr_limit"].to_frame(partial=True))


def test_an_upper_case_suffix_names_the_file_written(written, tmp_path):
    # -o x.PNG wrote x.png, another file (that may exist already)
    out, _ = written
    assert main(["plot", str(out / "boundaries_k1.csv"), "-o", str(tmp_path / "x.PNG")]) == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["x.PNG"]


def test_trace_refuses_a_figure_name_in_a_format_it_does_not_write(tmp_path, capsys):
    # --figure x.pdf wrote x.png and x.svg
    with pytest.raises(SystemExit) as info:
        main(["trace", "-k", "1", "--out", str(tmp_path / "out"), "--figure", "x.pdf"])
    assert info.value.code == 2
    assert "writes NAME.png and NAME.svg" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def test_a_file_that_cannot_be_written_is_named_and_its_pair_is_not_written(tmp_path, capsys):
    # a directory in the way of special_points_k1.csv: boundaries_k1.csv was written alone,
    # and the message named the hidden temporary file with exit code 2 (a usage error)
    # (now seen before anything is traced: bad input, exit code 2)
    out = tmp_path / "out"
    (out / "special_points_k1.csv").mkdir(parents=True)
    with pytest.raises(SystemExit) as exit_info:
        main(["trace", "-k", "1", "--out", str(out), "--no-figure"])
    assert exit_info.value.code == 2
    err = capsys.readouterr().err
    assert f"cannot write {out / 'special_points_k1.csv'}: a directory is in its place" in err
    assert sorted(p.name for p in out.iterdir()) == ["special_points_k1.csv"]


def test_a_failed_write_names_the_target_not_its_temporary_file(tmp_path):
    from groove_model.io.atomic import WriteError

    def write(tmp):
        raise OSError(28, "No space left on device")

    with pytest.raises(WriteError, match=r"cannot write .*x\.csv: No space left on device"):
        atomic_write(tmp_path / "x.csv", write)
    assert list(tmp_path.iterdir()) == []


def test_an_overlay_left_from_an_earlier_run_is_pointed_out(tmp_path, capsys):
    # new CSVs beside an old overlay of the same name looked like one current result
    out = tmp_path / "out"
    assert main(["trace", "-k", "1", "--out", str(out)]) == 0
    capsys.readouterr()
    assert main(["trace", "-k", "1", "--out", str(out), "--no-figure"]) == 0
    err = capsys.readouterr().err
    assert f"{out / 'boundaries_k1.png'} is from an earlier run (not redrawn)" in err
    assert main(["trace", "-k", "2", "--out", str(out), "--no-figure"]) == 0
    assert "earlier run" not in capsys.readouterr().err  # another name: nothing to point out


def test_a_disk_that_fills_between_the_two_csvs_of_a_k_leaves_both_as_they_were(written,
                                                                                 tmp_path,
                                                                                 monkeypatch):
    # the first CSV used to be moved into place before the second was written: a full disk
    # then left a new boundaries file beside the special points of an earlier run
    from groove_model.io.atomic import WriteError

    out, sets = written
    for name in boundary_file_names(1.0):
        (tmp_path / name).write_text("earlier run")
    to_csv = pd.DataFrame.to_csv

    def fills_on_the_second(frame, path, *args, **kwargs):
        if "special_points" in str(path):
            raise OSError(28, "No space left on device")
        return to_csv(frame, path, *args, **kwargs)

    monkeypatch.setattr(pd.DataFrame, "to_csv", fills_on_the_second)
    with pytest.raises(WriteError, match=r"cannot write .*special_points_k1\.csv: No space"):
        write_boundary_set(sets[1.0], tmp_path)
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(boundary_file_names(1.0))
    assert all((tmp_path / n).read_text() == "earlier run" for n in boundary_file_names(1.0))


def test_atomic_write_all_moves_the_files_only_when_every_one_was_written(tmp_path):
    from groove_model.io.atomic import atomic_write_all

    (tmp_path / "a.txt").write_text("old a")

    def broken(tmp):
        Path(tmp).write_text("half")
        raise RuntimeError("writer failed")

    with pytest.raises(RuntimeError, match="writer failed"):
        atomic_write_all([(tmp_path / "a.txt", lambda tmp: Path(tmp).write_text("new a")),
                          (tmp_path / "b.txt", broken)])
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.txt"]
    assert (tmp_path / "a.txt").read_text() == "old a"
    paths = atomic_write_all([(tmp_path / "a.txt", lambda tmp: Path(tmp).write_text("new a")),
                              (tmp_path / "b.txt", lambda tmp: Path(tmp).write_text("new b"))])
    assert paths == [tmp_path / "a.txt", tmp_path / "b.txt"]
    assert [p.read_text() for p in paths] == ["new a", "new b"]


@pytest.mark.parametrize("column, value, message", [
    ("physical", "maybe", "column physical = 'maybe' in data row 3 is not True or False"),
    ("certified", "yes", "column certified = 'yes' in data row 3 is not True, False or empty"),
    ("point", "bogus", "column point = 'bogus' in data row 3 is not empty or one of start, end, "
                       "junction, fold_gamma, fold_delta, branch_point"),
])
def test_plot_names_the_row_and_value_of_a_bad_flag(column, value, message, written, tmp_path,
                                                    capsys):
    frame = _csv_text(written).astype({column: object})
    frame.loc[2, column] = value
    path = tmp_path / "bad.csv"
    frame.to_csv(path, index=False)
    assert message in _plot_refused([path], tmp_path, capsys)


@pytest.mark.parametrize(("k", "keep_unphysical"), [
    (0.5, False), (0.5, True), (10.0, True), (1e5, False), (math.sqrt(2.0) * (1 - 1e-12), False),
    (math.sqrt(2.0) * (1 + 1e-12), False), (1e-4, True)])
def test_every_file_groove_trace_writes_is_whole(k, keep_unphysical, tmp_path):
    paths = write_boundary_set(trace_boundaries(k, keep_unphysical=keep_unphysical), tmp_path)
    assert incomplete_boundaries(read_boundaries_csv(paths[0])) == []


def test_plot_warns_of_a_file_cut_short_and_draws_it(written, tmp_path, capsys):
    out, _ = written
    cut = tmp_path / "cut.csv"
    cut.write_text("".join((out / "boundaries_k10.csv").read_text().splitlines(True)[:5]))
    target = tmp_path / "cut.png"
    assert main(["plot", str(cut), "-o", str(target)]) == 0
    assert target.is_file()
    err = capsys.readouterr().err
    assert f"groove plot: warning: {cut}: no rs_limit rows" in err
    assert "the last row of dr_limit (s = " in err and "is not marked as its end" in err
    assert main(["plot", str(out / "boundaries_k10.csv"), "-o", str(target)]) == 0
    assert "warning" not in capsys.readouterr().err


def test_the_files_of_a_k_that_failed_left_from_an_earlier_run_are_pointed_out(
        tmp_path, capsys, monkeypatch):
    # the old CSVs of a k that fails now sat beside the new ones with no word: they looked current
    out = tmp_path / "out"
    assert main(["trace", "-k", "2", "--out", str(out), "--no-figure"]) == 0
    capsys.readouterr()
    short = dataclasses.replace(tracer_module.DEFAULT_OPTIONS, max_steps=10)
    real = tracer_module.trace_boundaries
    monkeypatch.setattr(tracer_module, "trace_boundaries",
                        lambda k, **kw: real(k, **kw, options=short))
    assert main(["trace", "-k", "2", "--out", str(out), "--no-figure"]) == 1
    err = capsys.readouterr().err
    for name in ("boundaries_k2.csv", "special_points_k2.csv"):
        assert f"{out / name} is from an earlier run (not rewritten)" in err
