"""CSV export, the committed results, and the trace / plot commands."""

import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from groove_model import tracing as tracer_module
from groove_model.model.boundaries import BoundarySystem
from groove_model.cli.main import main
from groove_model.io.export import atomic_write, read_boundaries_csv, write_boundary_set
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


def test_trace_command_failure_writes_nothing(tmp_path, monkeypatch, capsys):
    real = tracer_module.trace_boundaries

    def failing(k, **kwargs):
        bs = real(k, **kwargs)
        curve = bs.curves["rs_no_roll"]
        broken = type(curve)(**{**curve.__dict__, "ok": False,
                                "status": "the step size fell below its minimum: at step 7"})
        return type(bs)(k=bs.k, curves={**bs.curves, "rs_no_roll": broken})

    monkeypatch.setattr(tracer_module, "trace_boundaries", failing)
    assert main(["trace", "-k", "1", "-k", "3", "--out", str(tmp_path / "out")]) == 1
    err = capsys.readouterr().err
    assert "rs_no_roll: the step size fell below its minimum" in err and "nothing written" in err
    assert not (tmp_path / "out").exists()


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
