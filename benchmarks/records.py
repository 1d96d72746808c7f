"""The benchmark record, the timing helper and the markdown table."""

from __future__ import annotations

import math
import statistics
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass

__all__ = ["KEYS", "Record", "failed", "markdown_table", "timed"]

#: keys of every JSON record, in order (``note`` is optional and always written)
KEYS = ("problem", "tool", "wall_s", "points", "residual_evals", "jacobian_evals",
        "max_residual", "fold_error", "ok")


@dataclass
class Record:
    """One benchmark result.

    Attributes
    ----------
    problem, tool : str
    wall_s : float or None
        Median wall time of the repeats, in seconds, in-process, imports and a warm-up run
        excluded; ``None`` if the tool did not run.
    points : int
        Points the tool returned (all branches).
    residual_evals, jacobian_evals : int
        Residual and Jacobian evaluations of one run (a combined call counts as one of each;
        Jacobian-free tools count their finite-difference residuals as residual evaluations).
    max_residual : float or None
        Largest ``max |H|`` over the returned points.
    fold_error : float or None
        Largest error of the located folds in any coordinate; ``None`` if the tool located none.
    ok : bool
        Whether the tool ran, covered the problem and located what it was asked for.
    note : str
        Reasons, accuracy and settings.
    """

    problem: str
    tool: str
    wall_s: float | None
    points: int
    residual_evals: int
    jacobian_evals: int
    max_residual: float | None
    fold_error: float | None
    ok: bool
    note: str = ""

    def to_json(self) -> dict:
        record = asdict(self)
        for key in ("wall_s", "max_residual", "fold_error"):
            value = record[key]
            if value is not None and not math.isfinite(value):
                record[key] = None
        return record


def failed(problem: str, tool: str, reason: str) -> Record:
    """The record of a tool that could not be installed, imported or run."""
    return Record(problem, tool, None, 0, 0, 0, None, None, False, reason)


def timed(run: Callable[[], object], repeats: int):
    """Run once to warm up, then ``repeats`` times; return ``(median seconds, last result)``."""
    result = run()
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        result = run()
        times.append(time.perf_counter() - start)
    return statistics.median(times), result


def _number(value, digits: int = 2) -> str:
    if value is None:
        return "-"
    if isinstance(value, float):
        return f"{value:.{digits}e}" if value != 0 else "0"
    return str(value)


def markdown_table(records: list[Record]) -> str:
    """The records as a markdown table, with the speed-up of ``ours`` over each tool."""
    ours = {r.problem: r.wall_s for r in records if r.tool == "ours" and r.wall_s}
    lines = [("| problem | tool | wall [ms] | x ours | points | res evals | jac evals | "
              "evals/point | max residual | fold error | ok |"),
             "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|:-:|"]
    for r in records:
        wall = f"{1e3 * r.wall_s:.3g}" if r.wall_s is not None else "-"
        ratio = (f"{r.wall_s / ours[r.problem]:.3g}" if r.wall_s is not None
                 and r.problem in ours else "-")
        counted = r.residual_evals + r.jacobian_evals
        per_point = f"{counted / r.points:.2f}" if r.points and counted else "-"
        lines.append(f"| {r.problem} | {r.tool} | {wall} | {ratio} | {r.points} | "
                     f"{r.residual_evals} | {r.jacobian_evals} | {per_point} | "
                     f"{_number(r.max_residual)} | {_number(r.fold_error)} | "
                     f"{'yes' if r.ok else 'no'} |")
    return "\n".join(lines)
