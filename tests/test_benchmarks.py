"""The benchmark harness on a tiny configuration: record schema and our accuracy (never speed)."""

import json
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks import standard
from benchmarks.records import KEYS, markdown_table
from benchmarks.run import Config, build_records, main

TINY = Config(repeats=1, standard_tools=("ours",), groove_problems=("groove_k1",),
              groove_tools=("ours", "fsolve_natural", "grid_contour"), grid_sizes=(32, 48),
              fsolve_points=10)


@pytest.fixture(scope="module")
def records():
    return build_records(TINY)


def test_one_record_per_problem_and_tool(records):
    pairs = [(r.problem, r.tool) for r in records]
    assert pairs == [("cubic", "ours"), ("circle", "ours"), ("groove_k1", "ours"),
                     ("groove_k1", "fsolve_natural"), ("groove_k1", "grid_contour")]


def test_json_schema(records):
    for record in records:
        item = json.loads(json.dumps(record.to_json()))
        assert tuple(item)[: len(KEYS)] == KEYS
        assert set(item) <= {*KEYS, "note"}
        assert isinstance(item["problem"], str) and isinstance(item["tool"], str)
        assert item["wall_s"] is None or item["wall_s"] > 0
        for key in ("points", "residual_evals", "jacobian_evals"):
            assert isinstance(item[key], int) and item[key] >= 0
        for key in ("max_residual", "fold_error"):
            assert item[key] is None or isinstance(item[key], float)
        assert isinstance(item["ok"], bool)


def test_ours_is_ok_and_locates_folds_to_1e_10(records):
    for record in records:
        if record.tool == "ours":
            assert record.ok, record.note
            assert record.fold_error is not None and record.fold_error <= 1e-10
            assert record.max_residual <= 1e-10
            assert record.points > 0 and record.residual_evals >= record.points


def test_ours_needs_at_most_five_evaluations_per_point_on_the_standard_problems(records):
    # the target, counting a residual and a Jacobian as two evaluations; the cubic's
    # 5.04 since the screen for steps that jump branches (two steps by its folds checked:
    # 3 Jacobians, the price of catching a jump at a sharp bend); the steps' count: the run's
    # checks of the Jacobian (Options.check_jacobian: 2 residuals at the start, a Jacobian and
    # 2 residuals at each located fold) are not a step's
    folds = {"cubic": len(standard.CUBIC_FOLDS), "circle": len(standard.CIRCLE_FOLDS)}
    for record in records:
        if record.problem in folds:
            checks = 2 + 3 * folds[record.problem]
            steps = record.residual_evals + record.jacobian_evals - checks
            assert steps / record.points <= 5.05


def test_baselines_report_their_accuracy(records):
    by_tool = {r.tool: r for r in records if r.problem == "groove_k1"}
    assert "error against our curve" in by_tool["fsolve_natural"].note
    assert "N=32" in by_tool["grid_contour"].note and "N=48" in by_tool["grid_contour"].note


def test_a_missing_peer_is_a_failed_record(monkeypatch):
    monkeypatch.setitem(sys.modules, "pycont", None)  # import pycont raises ImportError
    (record,) = standard.run_standard(("cubic",), ("pycont-lite",), repeats=1)
    assert record.ok is False and record.wall_s is None
    assert "import failed" in record.note


def test_a_failing_tool_does_not_crash_the_harness(monkeypatch):
    def broken(problem, repeats):
        raise RuntimeError("boom")
    monkeypatch.setitem(standard.TOOLS, "ours", broken)
    (record,) = standard.run_standard(("circle",), ("ours",), repeats=1)
    assert record.ok is False and "boom" in record.note


def test_table_and_json_file(records, tmp_path, monkeypatch, capsys):
    table = markdown_table(records)
    assert table.count("\n") == len(records) + 1
    monkeypatch.setattr("benchmarks.run.QUICK", TINY)
    out = tmp_path / "out.json"
    assert main(["--quick", "--json", str(out)]) == 0
    assert "| cubic | ours |" in capsys.readouterr().out
    assert [item["tool"] for item in json.loads(out.read_text())] == [r.tool for r in records]


def test_instruction_counts_need_valgrind_and_a_checkout(monkeypatch, tmp_path, capsys):
    """benchmarks/instructions.py says what is missing instead of counting nothing."""
    from benchmarks import instructions

    with pytest.raises(SystemExit) as exit_info:
        instructions.main(["--checkout", str(tmp_path)])
    assert exit_info.value.code == 2 and "not a checkout" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        instructions.main(["-n", "0"])
    monkeypatch.setattr(instructions.shutil, "which", lambda name: None)
    assert instructions.main([]) == 2
    assert "valgrind is not installed" in capsys.readouterr().err


def test_the_counted_program_runs(tmp_path):
    """The program callgrind counts traces its k and exits 0 (here without valgrind)."""
    import subprocess

    from benchmarks import instructions

    for what in ("run", "none"):
        done = subprocess.run([sys.executable, "-c", instructions.child_code(1), what],
                              cwd=tmp_path, capture_output=True, text=True)
        assert done.returncode == 0, done.stderr


def test_the_floor_steps_stay_on_the_curve(monkeypatch, capsys):
    """benchmarks/floor.py times steps that land on dr_limit, every lane (it asserts so)."""
    from benchmarks import floor
    monkeypatch.setattr(floor, "REPEATS", 1)
    monkeypatch.setattr(floor, "LANES", 50)
    floor.main()
    rows = capsys.readouterr().out.splitlines()
    assert [row.split(" | ")[0] for row in rows[2:]] == ["| 1", "| 10"]
    assert all("evaluations" in row and "points" in row for row in rows[2:])


def test_the_batching_table_has_every_part_and_leaves_the_engine_as_it_was(capsys):
    """benchmarks/batching.py times each part of a few traces and restores what it wrapped:
    traces after it run the engine's own functions again, and give the same curves."""
    from benchmarks import batching
    from groove_model import trace_boundaries

    before = trace_boundaries(3.0)
    originals = [getattr(owner, name) for owner, name in batching.WRAPPED]
    assert batching.main(["-n", "2"]) == 0
    out = capsys.readouterr().out
    for part in ("plain accepted steps", "other accepted steps", "rejected steps",
                 "locating special points", "assembly of the curves", "limit distance check",
                 "everything but the plain steps", "dot products: one stacked matmul",
                 "norms: sqrt of the sum of squares in order"):
        assert part in out
    assert all(0.0 <= fraction <= 1.0 for _, fraction in batching.primitives(lanes=20))
    assert [getattr(owner, name) for owner, name in batching.WRAPPED] == originals
    after = trace_boundaries(3.0)
    for name, curve in before.curves.items():
        assert np.array_equal(curve.x, after.curves[name].x)
