"""The atlas against tracing ``k`` one by one: ``python benchmarks/atlas.py [--json OUT]``.

Three timings, on ``1e-4 <= k <= 1e6`` with the paper's compliance:

* ``atlas``: :func:`groove_model.tracing.atlas.trace_atlas`, in-process, median of repeats after
  a warm-up run (imports excluded): every special point as a curve in ``k``, the thresholds as
  codimension-2 points;
* ``groove atlas``: the command (a new interpreter: imports, the atlas, CSV files, the report
  and the PNG figure), median of repeats;
* ``one by one``: :func:`groove_model.tracing.trace_boundaries` at ``N`` log-spaced ``k`` (300 by
  default), in-process, after a warm-up (so that the thresholds of the expected topology, which
  the tracer computes once per compliance, are not counted): the special points at those ``k``
  only, each to the same accuracy as the atlas's (checked: every one agrees with the atlas's
  point at that ``k`` to ``1e-10``), and the thresholds only bracketed between neighbouring ``k``.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

if __package__ in (None, ""):
    # run as a script: make the repository root importable
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import numpy as np

from groove_model.tracing import trace_boundaries
from groove_model.tracing.atlas import trace_atlas

__all__ = ["main", "run_atlas_benchmark"]

K_RANGE = (1e-4, 1e6)
#: atlas curve -> (boundary, kind) of the tracer's special point
_TRACED = {"junction": ("dr_limit", "junction"),
           "dr_limit_fold_delta": ("dr_limit", "fold_delta"),
           "rs_no_roll_fold_gamma": ("rs_no_roll", "fold_gamma")}


def _median_time(function, repeats: int) -> tuple[float, float]:
    """Median wall and CPU times of ``function()``."""
    walls, cpus = [], []
    for _ in range(repeats):
        start, cpu = time.perf_counter(), time.process_time()
        function()
        walls.append(time.perf_counter() - start)
        cpus.append(time.process_time() - cpu)
    return statistics.median(walls), statistics.median(cpus)


def _command_time(repeats: int, *extra: str) -> tuple[float, float]:
    """Median wall time and median CPU time (user + system) of the ``groove atlas`` command.

    The CPU time is what the wall time would be on an idle core; on a shared machine the wall
    time also counts the waits for one.
    """
    groove = Path(sys.executable).with_name("groove")
    argv = [str(groove)] if groove.exists() else [sys.executable, "-m", "groove_model.cli"]
    walls, cpus = [], []
    with tempfile.TemporaryDirectory() as out:
        for _ in range(repeats):
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            start = time.perf_counter()
            subprocess.run([*argv, "atlas", "--k-min", f"{K_RANGE[0]:g}", "--k-max",
                            f"{K_RANGE[1]:g}", "--out", out, *extra], check=True,
                           stdout=subprocess.DEVNULL)
            walls.append(time.perf_counter() - start)
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpus.append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
    return statistics.median(walls), statistics.median(cpus)


def _one_by_one(ks) -> tuple[float, float, list]:
    start, cpu = time.perf_counter(), time.process_time()
    sets = [trace_boundaries(k) for k in ks]
    return time.perf_counter() - start, time.process_time() - cpu, sets


def _agreement(atlas, ks, sets) -> float:
    """Largest difference between a traced special point and the atlas's at the same ``k``
    (gamma and delta in units of ``min(1, arctan k)``)."""
    worst = 0.0
    for k, traced in zip(ks, sets):
        for name, (boundary, kind) in _TRACED.items():
            mine = atlas.curves[name].physical_at(k) if name in atlas.curves else []
            theirs = [p.x for p in traced.curves[boundary].special(kind)] \
                if boundary in traced.curves else []
            if len(mine) != len(theirs):
                return math.inf
            for x, y in zip(mine, theirs):
                difference = np.abs(x - y)
                difference[:2] /= min(1.0, math.atan(k))
                worst = max(worst, float(difference.max()))
    return worst


def _brackets(atlas, ks) -> dict:
    """The relative width of the sweep's bracket of each threshold (neighbouring k)."""
    result = {}
    for t in atlas.thresholds:
        i = int(np.searchsorted(ks, t.value))
        result[t.name] = float(ks[i] / ks[i - 1] - 1.0)
    return result


def run_atlas_benchmark(sweep: int = 300, repeats: int = 5) -> dict:
    """Time the atlas, the command and ``sweep`` traces one by one; check their agreement."""
    trace_atlas(K_RANGE)  # warm-up
    atlas_s, atlas_cpu = _median_time(lambda: trace_atlas(K_RANGE), repeats)
    atlas = trace_atlas(K_RANGE)
    command_s, command_cpu = _command_time(repeats)
    bare_s, bare_cpu = _command_time(repeats, "--no-figure")
    ks = np.geomspace(*K_RANGE, sweep)
    trace_boundaries(1.0)  # warm-up: the tracer's thresholds, computed once per compliance
    one_by_one_s, one_by_one_cpu, sets = _one_by_one(ks)
    return {
        "k_range": list(K_RANGE), "sweep": sweep, "repeats": repeats,
        "atlas_s": atlas_s, "atlas_cpu_s": atlas_cpu,
        "groove_atlas_s": command_s, "groove_atlas_cpu_s": command_cpu,
        "groove_atlas_no_figure_s": bare_s, "groove_atlas_no_figure_cpu_s": bare_cpu,
        "one_by_one_s": one_by_one_s, "one_by_one_cpu_s": one_by_one_cpu,
        "ratio_one_by_one_over_atlas": one_by_one_s / atlas_s,
        "ratio_one_by_one_over_atlas_cpu": one_by_one_cpu / atlas_cpu,
        "ratio_one_by_one_over_groove_atlas": one_by_one_s / command_s,
        "ratio_one_by_one_over_groove_atlas_cpu": one_by_one_cpu / command_cpu,
        "ratio_one_by_one_over_groove_atlas_no_figure": one_by_one_s / bare_s,
        "ratio_one_by_one_over_groove_atlas_no_figure_cpu": one_by_one_cpu / bare_cpu,
        "atlas_points": sum(len(c.p) for c in atlas.curves.values()),
        "traced_all_ok": all(s.ok for s in sets),
        "max_difference_atlas_vs_traced": _agreement(atlas, ks, sets),
        "threshold_residuals": {t.name: t.residual for t in atlas.thresholds},
        "thresholds": {t.name: t.value for t in atlas.thresholds},
        "sweep_bracket_relative_width": _brackets(atlas, ks),
        "load_average_at_end": os.getloadavg()[0], "cpus": os.cpu_count(),
        "python": platform.python_version(),
    }


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sweep", type=int, default=300, help="values of k traced one by one")
    parser.add_argument("--repeats", type=int, default=5, help="repeats of the atlas timings")
    parser.add_argument("--json", type=Path, help="write the results to this JSON file")
    args = parser.parse_args(argv)
    result = run_atlas_benchmark(args.sweep, args.repeats)
    print("| what | wall [s] | CPU [s] | one by one / it (wall) | (CPU) |\n"
          "|---|---:|---:|---:|---:|")
    rows = (("atlas, k in [1e-4, 1e6] (in-process)", "atlas", "ratio_one_by_one_over_atlas"),
            ("groove atlas (command: interpreter, imports, files, PNG)", "groove_atlas",
             "ratio_one_by_one_over_groove_atlas"),
            ("groove atlas --no-figure", "groove_atlas_no_figure",
             "ratio_one_by_one_over_groove_atlas_no_figure"))
    for label, key, ratio in rows:
        print(f"| {label} | {result[key + '_s']:.3f} | {result[key + '_cpu_s']:.3f} | "
              f"{result[ratio]:.1f} | {result[ratio + '_cpu']:.1f} |")
    print(f"| trace_boundaries at {args.sweep} k one by one (in-process) | "
          f"{result['one_by_one_s']:.3f} | {result['one_by_one_cpu_s']:.3f} | 1 | 1 |")
    print(f"\nevery traced special point within {result['max_difference_atlas_vs_traced']:.1e} "
          f"of the atlas's; the sweep brackets the thresholds to relative widths "
          + ", ".join(f"{name} {width:.2g}"
                      for name, width in result["sweep_bracket_relative_width"].items())
          + f"; the atlas locates them to 1e-12; load average {result['load_average_at_end']:.1f}"
          f" on {result['cpus']} cores")
    if args.json is not None:
        args.json.write_text(json.dumps(result, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
