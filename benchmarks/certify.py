"""Certification's cost: ``trace_boundaries(k, certify=True)`` against the trace alone, and Arb
(python-flint) against mpmath's interval type on the boundary equations.

* ``groove_k1_certify``, ``groove_k10_certify``: ``wall_s`` is the time certification adds to
  the trace (median over repeats of the traced-and-certified run minus that of the trace);
  the note gives the ratio to the trace, which issue 16 wants at most 10, in CPU time of
  this process over runs of the two taken in turn (on a shared machine the wall clock of
  either moves by 2x with the neighbours' load, CPU time much less), and whether every
  boundary was proven.
* ``ball_jacobian``: one evaluation of the conditioned limit curve's Jacobian over a box of
  balls, in python-flint's ``arb`` (the ``[certify]`` extra) and in ``mpmath.iv`` (pure
  Python), through the same formulas (:mod:`continuation.numbers`).
"""

from __future__ import annotations

import math
import statistics
import time

from .records import Record, failed, timed

__all__ = ["run_certify"]

_K = {"groove_k1": 1.0, "groove_k10": 10.0}


def _certify_record(problem: str, repeats: int) -> Record:
    from groove_model.tracing import trace_boundaries

    k = _K[problem]
    trace_s, _ = timed(lambda: trace_boundaries(k), repeats)
    both_s, result = timed(lambda: trace_boundaries(k, certify=True), repeats)
    certs = {name: c.certificate for name, c in result.curves.items()}
    proven = all(c.proven for c in certs.values())
    radius = max(c.max_radius for c in certs.values())
    added = max(both_s - trace_s, 1e-9)
    cpu_trace, cpu_added = _cpu_in_turn(k, max(repeats, 5))
    note = (f"certifying costs {cpu_added / cpu_trace:.1f} x the trace in CPU time "
            f"({cpu_trace * 1e3:.1f} ms; {added / trace_s:.1f} x in wall time); "
            f"{sum(c.proven for c in certs.values())}/{len(certs)} boundaries proven, "
            f"tube radius <= {radius:.1e}, points within "
            f"{max(c.node_distance for c in certs.values()):.0e} of the curves")
    points = sum(len(c.x) for c in result.curves.values())
    return Record(f"{problem}_certify", "ours", added, points, 0, 0, None, None, proven, note)


def _cpu_in_turn(k: float, repeats: int) -> tuple[float, float]:
    """Median CPU seconds of ``trace_boundaries(k)`` and median of what ``certify=True`` adds,
    the two run in turn ``repeats`` times (after one of each to warm up)."""
    from groove_model.tracing import trace_boundaries

    trace_boundaries(k, certify=True)
    traces, added = [], []
    for _ in range(repeats):
        start = time.process_time()
        trace_boundaries(k)
        traces.append(time.process_time() - start)
        start = time.process_time()
        trace_boundaries(k, certify=True)
        added.append(time.process_time() - start - traces[-1])
    return statistics.median(traces), max(statistics.median(added), 1e-9)


class _MpmathIntervals:
    """``mpmath.iv`` as a numbers namespace (enough for the limit curve's equations)."""

    name = "mpmath.iv"
    rigorous = True

    def __init__(self, iv) -> None:
        self.iv = iv
        self.pi = iv.pi

    def number(self, x):
        return x if isinstance(x, self.iv.mpf) else self.iv.mpf(x)

    def sin(self, a):
        return self.iv.sin(self.number(a))

    def cos(self, a):
        return self.iv.cos(self.number(a))

    def sqrt(self, a):
        return self.iv.sqrt(self.number(a))

    def sinc(self, a):
        a = self.number(a)
        return self.iv.sin(a) / a  # the box below keeps w^2 away from 0


def _arithmetic_records(repeats: int) -> list[Record]:
    from groove_model.model.boundaries import BoundarySystem
    from groove_model.model.parameters import Parameters

    system = BoundarySystem("dr_limit", Parameters(10.0), "sqrt_beta_L", 1.0, conditioned=True)
    centre = [0.9, 0.3, 0.6, 0.1]
    records = []
    try:
        from continuation.numbers import balls

        B = balls()
        box = [B.arb(v, 1e-6) for v in centre]
        wall, _ = timed(lambda: system.jacobian(box, B), 50 * repeats)
        records.append(Record("ball_jacobian", "python-flint", wall, 1, 0, 1, None, None, True,
                              "Arb balls, 53 bits, the [certify] extra"))
    except ImportError as exc:
        records.append(failed("ball_jacobian", "python-flint", str(exc)))
    try:
        from mpmath import iv

        iv.prec = 53
        M = _MpmathIntervals(iv)
        box = [iv.mpf([v - 1e-6, v + 1e-6]) for v in centre]
        wall, _ = timed(lambda: system.jacobian(box, M), 5 * repeats)
        flint = records[0].wall_s
        ratio = f"; {wall / flint:.0f} x python-flint" if flint and math.isfinite(flint) else ""
        records.append(Record("ball_jacobian", "mpmath.iv", wall, 1, 0, 1, None, None, True,
                              f"mpmath intervals, 53 bits, pure Python{ratio}"))
    except ImportError as exc:
        records.append(failed("ball_jacobian", "mpmath.iv", str(exc)))
    return records


def run_certify(problems, repeats: int) -> list[Record]:
    """A record per certified problem, then the two ball arithmetics (if any problem)."""
    records = []
    for problem in problems:
        try:
            records.append(_certify_record(problem, repeats))
        except ImportError as exc:
            records.append(failed(f"{problem}_certify", "ours", str(exc)))
    return records + (_arithmetic_records(repeats) if problems else [])
