"""The speed targets of issue 14, each measured in this run, with its ratio and a verdict.

1. One k (all boundaries, every special point, residuals 1e-12) in at most 0.5x the time of
   ``fsolve_natural`` (dr_limit only, 100 gamma values), for k = 1 and k = 10.
2. The engine on the cubic and the circle: at most 30 us per point, folds to 1e-10, and no more
   evaluations per point than before (4.89 and 4.57).
3. ``groove_sweep1000``: 1000 k log-spaced over [1e-4, 1e6] in at most 5 s serially and 3 s on
   2 processes, with the same output for any number of processes.
4. A sweep streamed to disk keeps the resident memory (the command and its workers, their
   proportional set sizes summed) under 300 MB for 1e5 k.
5. ``groove --help`` and ``groove solve ...`` start in under 0.3 s.

Every time is a median over repeats in this run; a ratio is the quotient of two medians of this
run. Nothing here is asserted in the tests: speed is measured, never asserted.
"""

from __future__ import annotations

import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from .records import Record

__all__ = ["Target", "evaluate", "markdown_targets", "measure_memory", "measure_startup",
           "run_sweep1000"]

#: evaluations per point of the engine before issue 14 (residuals + Jacobians over points)
EVALS_BEFORE = {"cubic": (227 + 184) / 84, "circle": (86 + 83) / 37}


@dataclass
class Target:
    """One target: what was measured, its limit, the ratio measured / limit, and the verdict
    (``met`` is ``None`` when only a smaller proxy of the target was measured)."""

    target: str
    measured: str
    limit: str
    ratio: float | None
    met: bool | None
    note: str = ""

    def to_json(self) -> dict:
        return asdict(self)


def _sweep_ks(stride: int) -> list:
    return np.geomspace(1e-4, 1e6, 1000)[::stride].tolist()


def run_sweep1000(stride: int = 1, repeats: int = 1) -> tuple[list[Record], dict]:
    """``groove_sweep1000`` serially and on 2 processes; records and the sweep facts.

    With ``stride > 1`` only every ``stride``-th of the 1000 k is traced and the times are
    scaled by ``1000 / traced`` (said in the note).
    """
    from groove_model.tracing import sweep_results

    ks = _sweep_ks(stride)
    scale = 1000 / len(ks)
    sweep_results([1.0])  # imports and first-call costs outside the timing
    runs = {}
    for tool, jobs in (("ours", None), ("ours_jobs2", 2)):
        times, results = [], None
        for _ in range(repeats):
            start = time.perf_counter()
            results = list(sweep_results(ks, jobs=jobs))
            times.append(time.perf_counter() - start)
        runs[tool] = (statistics.median(times), times, results)
    serial, parallel = runs["ours"][2], runs["ours_jobs2"][2]
    identical = len(serial) == len(parallel) and all(
        a.k == b.k and a.ok == b.ok and a.boundaries.equals(b.boundaries)
        and a.special_points.equals(b.special_points) for a, b in zip(serial, parallel))
    failed = [r.k for r in serial if not r.ok]
    rows = sum(len(r.boundaries) for r in serial)
    records = []
    for tool, (wall, times, _results) in runs.items():
        note = (f"{len(ks)} of the 1000 k log-spaced over [1e-4, 1e6]"
                + (f", times scaled by {scale:g} to 1000 k" if scale != 1 else "")
                + f"; {'serial' if tool == 'ours' else '2 processes'}; {rows} rows; "
                f"{len(failed)} k failed{f' ({failed[:5]})' if failed else ''}; output "
                f"{'identical' if identical else 'DIFFERENT'} serial and on 2 processes; "
                f"runs {', '.join(f'{scale * t:.2f}' for t in times)} s")
        records.append(Record("groove_sweep1000", tool, wall * scale, rows, 0, 0, None, None,
                              not failed and identical, note))
    return records, {"identical": identical, "failed": failed, "scaled": scale != 1,
                     "traced": len(ks)}


def _memory(pid: int, page: int) -> int:
    """Proportional set size of a process in bytes (shared pages split between their users,
    so forked workers are not counted twice), or its resident size where PSS is not readable."""
    try:
        with open(f"/proc/{pid}/smaps_rollup") as handle:
            for line in handle:
                if line.startswith("Pss:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    try:
        with open(f"/proc/{pid}/statm") as handle:
            return int(handle.read().split()[1]) * page
    except OSError:
        return 0


def _tree_memory(pid: int) -> int:
    """Memory in bytes of a process and all its descendants (Linux ``/proc``, PSS summed)."""
    children: dict[int, list[int]] = {}
    page = os.sysconf("SC_PAGE_SIZE")
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat") as handle:
                fields = handle.read().rsplit(")", 1)[1].split()
        except OSError:
            continue
        children.setdefault(int(fields[1]), []).append(int(entry))
    total, stack = 0, [pid]
    while stack:
        current = stack.pop()
        total += _memory(current, page)
        stack.extend(children.get(current, []))
    return total


def _groove_command() -> list[str]:
    script = Path(sys.executable).with_name("groove")
    if script.exists():
        return [str(script)]
    found = shutil.which("groove")
    if found:
        return [found]
    return [sys.executable, "-c", "import sys; from groove_model.cli import main; "
            "sys.exit(main())"]


def measure_memory(sizes=(200, 800), jobs: int = 2) -> dict:
    """Peak memory of ``groove sweep`` (command and workers, proportional set sizes summed).

    Sampled every 20 ms from ``/proc``; the k are log-spaced over [1e-4, 1e6]. Returns
    ``{n: (peak bytes, seconds, output bytes, exit code)}``.
    """
    peaks = {}
    for n in sizes:
        with tempfile.TemporaryDirectory() as out:
            command = [*_groove_command(), "sweep", "--k-min", "1e-4", "--k-max", "1e6",
                       "-n", str(n), "--jobs", str(jobs), "--out", out]
            start = time.perf_counter()
            process = subprocess.Popen(command, stdout=subprocess.DEVNULL,
                                       stderr=subprocess.DEVNULL)
            peak = 0
            while process.poll() is None:
                peak = max(peak, _tree_memory(process.pid))
                time.sleep(0.02)
            seconds = time.perf_counter() - start
            written = sum(p.stat().st_size for p in Path(out).iterdir())
            peaks[n] = (peak, seconds, written, process.returncode)
    return peaks


def measure_startup(repeats: int = 7) -> dict:
    """Median and spread of the wall time of ``groove --help`` and ``groove solve ...``."""
    commands = {"groove --help": ["--help"],
                "groove solve --gamma 0.6 --delta 0.2 -k 1": ["solve", "--gamma", "0.6",
                                                              "--delta", "0.2", "-k", "1"]}
    times = {}
    for name, args in commands.items():
        samples = []
        for _ in range(repeats):
            start = time.perf_counter()
            subprocess.run([*_groove_command(), *args], stdout=subprocess.DEVNULL,
                           stderr=subprocess.DEVNULL, check=True)
            samples.append(time.perf_counter() - start)
        times[name] = samples
    return times


def _by(records, problem, tool):
    return next((r for r in records if r.problem == problem and r.tool == tool), None)


def _speed_targets(records) -> list[Target]:
    targets = []
    for problem in ("groove_k1", "groove_k10"):
        ours, fsolve = _by(records, problem, "ours"), _by(records, problem, "fsolve_natural")
        if ours and fsolve and ours.wall_s and fsolve.wall_s:
            ratio = ours.wall_s / fsolve.wall_s
            targets.append(Target(
                f"1. {problem}: ours / fsolve_natural", f"{ratio:.2f}x "
                f"({1e3 * ours.wall_s:.3g} / {1e3 * fsolve.wall_s:.3g} ms)", "<= 0.5x",
                ratio / 0.5, ratio <= 0.5 and ours.ok,
                f"residual {ours.max_residual:.2e}, fold error {ours.fold_error:.2e}"))
    for problem in ("cubic", "circle"):
        ours = _by(records, problem, "ours")
        if ours and ours.wall_s and ours.points:
            per_point = 1e6 * ours.wall_s / ours.points
            evals = (ours.residual_evals + ours.jacobian_evals) / ours.points
            folds = ours.fold_error is not None and ours.fold_error <= 1e-10
            targets.append(Target(
                f"2. {problem}: us per point", f"{per_point:.1f} us", "<= 30 us",
                per_point / 30.0, per_point <= 30.0 and folds
                and evals <= EVALS_BEFORE[problem] + 1e-9,
                f"folds to {ours.fold_error:.1e}; {evals:.2f} evaluations per point "
                f"(before {EVALS_BEFORE[problem]:.2f})"))
    return targets


def evaluate(records, sweep: dict | None, memory: dict | None,
             startup: dict | None) -> list[Target]:
    """Every target measured in this run, with its verdict."""
    targets = _speed_targets(records)
    if sweep is not None:
        how = " (extrapolated)" if sweep["scaled"] else ""
        for tool, limit in (("ours", 5.0), ("ours_jobs2", 3.0)):
            record = _by(records, "groove_sweep1000", tool)
            if record and record.wall_s:
                targets.append(Target(
                    f"3. groove_sweep1000 {'serial' if tool == 'ours' else 'on 2 processes'}",
                    f"{record.wall_s:.1f} s{how}", f"<= {limit:g} s", record.wall_s / limit,
                    record.wall_s <= limit and sweep["identical"] and not sweep["failed"],
                    f"output identical serial and on 2 processes: {sweep['identical']}; "
                    f"{len(sweep['failed'])} k failed"))
    if memory:
        sizes = sorted(memory)
        largest = sizes[-1]
        peak = memory[largest][0]
        targets.append(Target(
            f"4. sweep streamed to disk: peak memory at {largest:g} k (limit for 1e5 k)",
            f"{peak / 2**20:.0f} MB", "< 300 MB", peak / (300 * 2**20),
            (peak < 300 * 2**20 and all(memory[n][3] == 0 for n in sizes))
            if largest >= 1e5 else None,
            "; ".join(f"{n:g} k on 2 processes: peak PSS {memory[n][0] / 2**20:.0f} MB, "
                      f"{memory[n][1]:.1f} s, {memory[n][2] / 2**20:.1f} MB written"
                      for n in sizes)
            + ("" if largest >= 1e5 else
               "; a sweep keeps at most 4 chunks per worker in flight, so its memory is "
               "bounded by the window, not by the number of k, but it grows in steps as the "
               "allocators reach new high-water marks: only a sweep of 1e5 k shows the "
               "figure of the target (benchmarks/run.py --memory 100000: 200 MB on "
               "2026-11-23, in 79 min)")))
    if startup:
        for name, samples in startup.items():
            median = statistics.median(samples)
            targets.append(Target(
                f"5. `{name}` start-up", f"{median:.3f} s", "< 0.3 s", median / 0.3,
                median < 0.3, f"median of {len(samples)}, range {min(samples):.3f}-"
                f"{max(samples):.3f} s"))
    return targets


def markdown_targets(targets: list[Target]) -> str:
    lines = ["| target | measured | limit | measured / limit | met |", "|---|---|---|---:|:-:|"]
    for t in targets:
        ratio = f"{t.ratio:.2f}" if t.ratio is not None else "-"
        verdict = "proxy only" if t.met is None else "met" if t.met else "not met"
        lines.append(f"| {t.target} | {t.measured} | {t.limit} | {ratio} | {verdict} |")
    return "\n".join(lines)
