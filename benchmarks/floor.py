"""The floor of a serial pure-Python tracer: a pseudo-arclength step with no checks at all.

Issue 14 asks for 1000 ``k`` in 5 s serial: 5 ms per ``k`` for four boundaries, which the
tracer draws with about 100 accepted steps at the default ``ds_max = 0.05``, so about 50 us per
step, everything included. This script measures what the simplest possible step costs on the
same model, to say whether any serial pure-Python engine can get there:

* ``dr_limit`` from its seed, 20 steps of fixed arclength ``ds = 0.05`` (Keller's
  pseudo-arclength condition ``t . (y - x) = ds``), tangent predictor, full Newton to
  ``|dy| < 1e-10`` with the model's residual and analytic Jacobian at every iterate, the new
  tangent from the last bordered matrix; no step control, no events, no folds, no branch points,
  no domain, no residual check beyond an assertion at the end;
* ``numpy``: the bordered 4 x 4 system by ``numpy.linalg.solve``;
* ``floats``: the same with Python lists and Gaussian elimination with partial pivoting;
* ``batched``: the ``numpy`` step on ``LANES`` curves at once, as a sweep batched over ``k``
  would step them: the residuals and Jacobians of all lanes in one evaluation over arrays
  (``BoundarySystem.residuals_and_jacobians``), the bordered systems by one stacked
  ``numpy.linalg.solve``; a fixed 3 Newton iterations, no convergence test. The lanes here are
  one ``k`` with ``LANES`` arclength steps from ``ds/2`` to ``ds`` (the model's formulas are
  elementwise, so ``k`` as an array costs the same); the time is per lane and step;
* ``ours``: ``trace_boundaries(k)`` (all four boundaries with every check and special point)
  per point of the engine's curves.

Run: ``python3 benchmarks/floor.py`` (a few seconds). Times are minima of 7 runs.
"""

from __future__ import annotations

import math
import time

import numpy as np

from groove_model import trace_boundaries
from groove_model.model.boundaries import BoundarySystem, limit_seed
from groove_model.model.parameters import Parameters

STEPS, DS, REPEATS, LANES = 20, 0.05, 7, 1000


def _solve_lists(A: list, b: list) -> list:
    """``A x = b`` for a small dense ``A`` by Gaussian elimination with partial pivoting."""
    n = len(b)
    M = [row[:] + [bi] for row, bi in zip(A, b, strict=True)]
    for c in range(n):
        p = c
        for r in range(c + 1, n):
            if abs(M[r][c]) > abs(M[p][c]):
                p = r
        M[c], M[p] = M[p], M[c]
        for r in range(c + 1, n):
            f = M[r][c] / M[c][c]
            if f:
                for j in range(c, n + 1):
                    M[r][j] -= f * M[c][j]
    x = [0.0] * n
    for r in range(n - 1, -1, -1):
        x[r] = (M[r][n] - sum(M[r][j] * x[j] for j in range(r + 1, n))) / M[r][r]
    return x


def steps_numpy(system, x, t):
    evaluations = 0
    for _ in range(STEPS):
        y = x + DS * t
        for _ in range(8):
            H, J = system.residual_and_jacobian(y)
            evaluations += 1
            A = np.vstack([J, t])
            dy = np.linalg.solve(A, -np.append(H, t @ (y - x) - DS))
            y = y + dy
            if np.max(np.abs(dy)) < 1e-10:
                break
        t = np.linalg.solve(A, np.array([0.0, 0.0, 0.0, 1.0]))
        x, t = y, t / np.linalg.norm(t)
    return x, evaluations


def steps_floats(system, x, t):
    evaluations = 0
    x, t = x.tolist(), t.tolist()
    for _ in range(STEPS):
        y = [xi + DS * ti for xi, ti in zip(x, t, strict=True)]
        for _ in range(8):
            H, J = system.residual_and_jacobian(np.array(y))
            evaluations += 1
            A = J.tolist() + [t]
            arc = sum(ti * (yi - xi) for ti, yi, xi in zip(t, y, x, strict=True)) - DS
            dy = _solve_lists(A, [-v for v in H.tolist()] + [-arc])
            y = [a + b for a, b in zip(y, dy, strict=True)]
            if max(map(abs, dy)) < 1e-10:
                break
        t = _solve_lists(A, [0.0, 0.0, 0.0, 1.0])
        norm = math.sqrt(sum(v * v for v in t))
        x, t = y, [v / norm for v in t]
    return np.array(x), evaluations


def steps_batched(system, x, t):
    ds = np.linspace(0.5 * DS, DS, LANES)
    X, T = np.tile(x, (LANES, 1)), np.tile(t, (LANES, 1))
    last = np.broadcast_to(np.array([0.0, 0.0, 0.0, 1.0])[:, None], (LANES, 4, 1))
    for _ in range(STEPS):
        Y = X + ds[:, None] * T
        for _ in range(3):
            H, J = system.residuals_and_jacobians(Y)
            A = np.concatenate([J, T[:, None, :]], axis=1)
            arc = np.einsum("ij,ij->i", T, Y - X) - ds
            Y = Y - np.linalg.solve(A, np.concatenate([H, arc[:, None]], axis=1)[:, :, None])[
                :, :, 0]
        T = np.linalg.solve(A, last)[:, :, 0]
        X, T = Y, T / np.linalg.norm(T, axis=1)[:, None]
    return X, 3 * LANES * STEPS


def _best(f) -> float:
    times = []
    for _ in range(REPEATS):
        start = time.perf_counter()
        f()
        times.append(time.perf_counter() - start)
    return min(times)


def main() -> None:
    print(f"| k | numpy step | floats step | batched step ({LANES} lanes) "
          "| ours per point (all checks) | ours per k |")
    print("|---:|---:|---:|---:|---:|---:|")
    for k in (1.0, 10.0):
        params = Parameters(k)
        system = BoundarySystem("dr_limit", params)
        x0 = limit_seed(params).astype(float)
        t0 = np.linalg.svd(system.residual_and_jacobian(x0)[1])[2][-1]
        t0 = -t0 if t0[0] > 0 else t0          # into the domain: gamma decreasing
        row = [f"{k:g}"]
        for steps, lanes in ((steps_numpy, 1), (steps_floats, 1), (steps_batched, LANES)):
            x, evaluations = steps(system, x0, t0)
            xs = np.reshape(x, (-1, 4))
            assert np.max(np.abs(system.residuals(xs))) < 1e-10, steps
            assert np.all((0.0 <= xs[:, 1]) & (xs[:, 1] <= xs[:, 0])), steps
            seconds = _best(lambda f=steps, s=system, x=x0, t=t0: f(s, x, t)) / (STEPS * lanes)
            row.append(f"{seconds * 1e6:.{0 if lanes == 1 else 1}f} us "
                       f"({evaluations / (STEPS * lanes):.1f} evaluations)")
        result = trace_boundaries(k)
        points = sum(len(c.x) - 1 for curve in result.curves.values() for c in curve.engine)
        seconds = _best(lambda k=k: trace_boundaries(k))
        row += [f"{seconds / points * 1e6:.0f} us ({points} points)", f"{seconds * 1e3:.1f} ms"]
        print("| " + " | ".join(row) + " |")


if __name__ == "__main__":
    main()
