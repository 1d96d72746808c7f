"""Where a sweep's time goes, and what a tracer batched over ``k`` could take off it.

    python3 benchmarks/batching.py [-n 100]

Issue 14's third target (1000 ``k`` in 5 s serially) leaves 5 ms per ``k``; the serial tracer
takes 40 to 55 on the 2-core machine of ``benchmarks/README.md``, by its load.
``benchmarks/floor.py`` shows that stepping many ``k`` at once through the model's array form
costs a few microseconds per lane and step. This script measures, over
``-n`` values of ``k`` log-spaced over ``[1e-4, 1e6]`` (``trace_boundaries`` with its
defaults), how much of the time such batching could reach:

* the time per ``k`` by part: the engine's steps (``continuation.tracker``), split into
  *plain* accepted steps (every event and fold coordinate cleared by the tests on the step's
  end points, nothing bracketed or located), the other accepted steps (a bracket scan, a
  located special point), and rejected steps; the special points' location inside them
  (``locate_zero``); the rest of the engine (start, end checks); the tracer's assembly of each
  curve (``assemble``), the limit curve's distance check and the topology check;
* the steps per ``k`` of each kind;
* which of the serial engine's small operations (dot products, bordered solves, the
  predictor's product, norms) one numpy call over all lanes repeats to the last bit
  (:func:`primitives`): a batched engine that repeats the serial one's decisions exactly
  needs them.

Plain steps are the ones a batched engine can take for all lanes at once with the same tests
as the serial one; everything else is per lane: in serial Python unless it is batched too.
The timers wrap the engine's functions in this process (``time.perf_counter``, a few
microseconds per call on top), so the parts add up to slightly more than an untimed run.
Times are one run on a shared machine: compare parts within a run, not runs.
"""

from __future__ import annotations

import argparse
import contextlib
import functools
import math
import time
from collections import Counter

import numpy as np

import continuation.special as special
import continuation.tracker as tracker
import groove_model.tracing.tracer as tracer
from continuation.scan import StepScan
from groove_model import trace_boundaries

K_RANGE = (1e-4, 1e6)

#: what the timers wrap, ``(owner, attribute)``, in the order of the wrappers
WRAPPED = [(tracker._Stepper, "step"), (tracker._Stepper, "_reject"), (tracker, "scan_step"),
           (StepScan, "_brackets"), (special, "locate_zero"), (tracer, "trace_curve"),
           (tracer, "assemble"), (tracer, "_limit_distance"), (tracer, "_check")]


class _Tally:
    """Seconds and counts per part, and the kind of the step being taken."""

    def __init__(self) -> None:
        self.seconds: Counter = Counter()
        self.counts: Counter = Counter()
        self.scanned = False   # the current step called the bracket scan
        self.found = False     # the current step located a special point
        self.rejected = False  # the current step was rejected


def _timed(tally: _Tally, part: str, function):
    @functools.wraps(function)
    def wrapper(*args, **kwargs):
        start = time.perf_counter()
        try:
            return function(*args, **kwargs)
        finally:
            tally.seconds[part] += time.perf_counter() - start
            tally.counts[part] += 1
    return wrapper


@contextlib.contextmanager
def _instrumented(tally: _Tally):
    """The engine's and the tracer's functions wrapped by timers, restored on exit."""
    originals = [(owner, name, getattr(owner, name)) for owner, name in WRAPPED]
    step, reject, scan, brackets = (original for _, _, original in originals[:4])

    def stepped(self):
        tally.scanned = tally.found = tally.rejected = False
        start = time.perf_counter()
        step(self)
        seconds = time.perf_counter() - start
        kind = ("rejected" if tally.rejected else
                "scanned" if tally.scanned or tally.found else "plain")
        tally.seconds[f"step {kind}"] += seconds
        tally.counts[f"step {kind}"] += 1

    def rejected(self, *args, **kwargs):
        tally.rejected = True
        return reject(self, *args, **kwargs)

    def scanned(*args, **kwargs):
        found = scan(*args, **kwargs)
        tally.found = tally.found or bool(found)
        return found

    def bracketed(self, *args, **kwargs):
        tally.scanned = True
        return brackets(self, *args, **kwargs)

    patches = [stepped, rejected, scanned, bracketed,
               _timed(tally, "locate", special.locate_zero),
               _timed(tally, "engine", tracer.trace_curve),
               _timed(tally, "assemble", tracer.assemble),
               _timed(tally, "limit distance", tracer._limit_distance),
               _timed(tally, "topology check", tracer._check)]
    try:
        for (owner, name, _), patch in zip(originals, patches, strict=True):
            setattr(owner, name, patch)
        yield
    finally:
        for owner, name, original in originals:
            setattr(owner, name, original)


def measure(n: int) -> tuple[_Tally, float]:
    """The tally of ``n`` traces and their total seconds (after one untimed warm-up trace)."""
    ks = np.logspace(*np.log10(K_RANGE), n)
    trace_boundaries(float(ks[0]))
    tally = _Tally()
    with _instrumented(tally):
        start = time.perf_counter()
        for k in ks:
            result = trace_boundaries(float(k))
            if not result.ok:
                raise SystemExit(f"batching.py: k = {k!r} failed: {result.failures}")
        total = time.perf_counter() - start
    return tally, total


def report(tally: _Tally, total: float, n: int) -> str:
    """The table of parts, per ``k``."""
    seconds, counts = tally.seconds, tally.counts
    steps = sum(seconds[f"step {kind}"] for kind in ("plain", "scanned", "rejected"))
    rows = [("all of trace_boundaries", total, None),
            ("engine (trace_curve)", seconds["engine"], None),
            ("- plain accepted steps", seconds["step plain"], counts["step plain"]),
            ("- other accepted steps", seconds["step scanned"], counts["step scanned"]),
            ("- rejected steps", seconds["step rejected"], counts["step rejected"]),
            ("  (locating special points, in the steps above)", seconds["locate"],
             counts["locate"]),
            ("- start and end of each curve", seconds["engine"] - steps, None),
            ("assembly of the curves", seconds["assemble"], counts["assemble"]),
            ("limit distance check", seconds["limit distance"], None),
            ("topology check", seconds["topology check"], None)]
    lines = [f"{n} k log-spaced over [{K_RANGE[0]:g}, {K_RANGE[1]:g}], per k:", "",
             "| part | ms per k | calls or steps per k |", "|---|---:|---:|"]
    for name, value, count in rows:
        calls = "" if count is None else f"{count / n:.1f}"
        lines.append(f"| {name} | {value / n * 1e3:.2f} | {calls} |")
    plain = seconds["step plain"]
    taken = sum(counts[f"step {kind}"] for kind in ("plain", "scanned", "rejected"))
    lines += ["", f"everything but the plain steps: {(total - plain) / n * 1e3:.1f} ms per k "
              f"({(total - plain) / total:.0%} of the time); the plain steps are "
              f"{counts['step plain'] / max(1, taken):.0%} of all steps"]
    return "\n".join(lines)


def primitives(lanes: int = 2000, seed: int = 1) -> list[tuple[str, float]]:
    """Which of the serial engine's small operations a batched engine gets to the last bit
    from one numpy call over all lanes: the fraction of ``lanes`` random cases that agree.

    The serial engine takes dot products of 4-vectors with ``@``, bordered 4 x 4 systems with
    LAPACK's ``dgetrf`` and ``dgetrs`` (``scipy.linalg.lapack``), Hermite weights times node
    vectors as a ``(2, 6) @ (6, 4)`` product, and norms with ``math.hypot``. An operation that
    agrees on every case here can be batched; one that does not stays per lane.
    """
    from scipy.linalg.lapack import dgetrf, dgetrs  # only this check uses LAPACK directly

    rng = np.random.default_rng(seed)
    a, b = rng.standard_normal((lanes, 4)), rng.standard_normal((lanes, 4))
    dots = np.array([u @ v for u, v in zip(a, b, strict=True)])
    matrices, rhs = rng.standard_normal((lanes, 4, 4)), rng.standard_normal((lanes, 4))
    solves = np.array([dgetrs(*dgetrf(m)[:2], r)[0] for m, r in zip(matrices, rhs, strict=True)])
    weights, vectors = rng.standard_normal((lanes, 2, 6)), rng.standard_normal((lanes, 6, 4))
    products = np.array([w @ v for w, v in zip(weights, vectors, strict=True)])
    norms = np.array([math.hypot(*v) for v in a.tolist()])
    return [
        ("dot products: one stacked matmul", float(np.mean(
            np.matmul(a[:, None, :], b[:, :, None])[:, 0, 0] == dots))),
        ("bordered solves: one stacked numpy.linalg.solve", float(np.mean(np.all(
            np.linalg.solve(matrices, rhs[:, :, None])[:, :, 0] == solves, axis=1)))),
        ("Hermite weights times nodes: one stacked matmul", float(np.mean(np.all(
            np.matmul(weights, vectors) == products, axis=(1, 2))))),
        ("norms: sqrt of the sum of squares in order", float(np.mean(np.sqrt(
            ((a[:, 0] ** 2 + a[:, 1] ** 2) + a[:, 2] ** 2) + a[:, 3] ** 2) == norms))),
    ]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("-n", type=int, default=100, help="values of k (default 100)")
    args = parser.parse_args(argv)
    if args.n < 1:
        parser.error(f"-n must be at least 1, got {args.n}")
    tally, total = measure(args.n)
    print(report(tally, total, args.n))
    print("\n| operation over 2000 random lanes | the serial engine's bits |\n|---|---:|")
    for name, fraction in primitives():
        print(f"| {name} | {fraction:.1%} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
