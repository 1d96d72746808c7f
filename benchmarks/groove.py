"""The boundary tracer (``ours``) against two baselines a physicist would write without it.

* ``fsolve_natural``: natural-parameter continuation of ``dr_limit`` in ``gamma``, from
  ``arctan k`` down to ``gamma_min``, each point solved by ``scipy.optimize.fsolve`` for
  ``(delta, beta_L, upsilon)`` from the previous one (finite-difference Jacobian, its default
  ``xtol``); it traces one boundary, and stops at a fold in ``gamma`` if there is one.
* ``grid_contour``: the point solver :func:`groove_model.solve_equilibrium` on an ``N x N``
  grid of ``(gamma, delta)``, then marching squares (contourpy, matplotlib's contour
  generator): the regime indicator at 1/2 (``T = kN``) and ``upsilon`` at 0 inside each regime
  (the ``upsilon = 0`` lines).

Accuracy: ``ours`` by its residuals and by its folds against an independent solve of the fold
system; the baselines by the distance of their points to our traced curves in the
``(gamma, delta)`` plane (dense reference: the engine's Hermite arcs, 128 samples per step,
so distances below ~1e-8 are not resolved), and for ``fsolve_natural`` also by the residual of
its points in the boundary equations.
"""

from __future__ import annotations

import math

import numpy as np

from .records import Record, failed, timed

__all__ = ["run_groove"]


def _exact_fold(system, y: np.ndarray) -> np.ndarray:
    """The fold in gamma nearest ``y``: Newton on ``[H(y); det dH/d(delta, w, upsilon)] = 0``.

    The determinant is the gamma component of the (unnormalised) tangent; its gradient is a
    central difference (step 1e-6), which only slows Newton's last digits, not its limit.
    """
    def extended(z):
        H, J = system.residual_and_jacobian(z)
        return np.append(H, np.linalg.det(J[:, 1:]))

    for _ in range(30):
        F = extended(y)
        _, J = system.residual_and_jacobian(y)
        gradient = np.array([(extended(y + 1e-6 * e)[-1] - extended(y - 1e-6 * e)[-1]) / 2e-6
                             for e in np.eye(4)])
        step = np.linalg.solve(np.vstack([J, gradient]), -F)
        y = y + step
        if np.max(np.abs(step)) <= 1e-15 * (1.0 + np.max(np.abs(y))):
            break
    return y


def _ours_fold_error(boundary_set) -> tuple[float | None, int]:
    from groove_model.model.boundaries import BoundarySystem

    worst, count = None, 0
    for name, curve in boundary_set.curves.items():
        system = BoundarySystem(name, boundary_set.params if hasattr(boundary_set, "params")
                                else _params(curve.k), "sqrt_beta_L")
        for point in curve.special_points:
            if point.kind != "fold_gamma":
                continue
            exact = system.to_x(_exact_fold(system, system.from_x(point.x)))
            error = float(np.max(np.abs(exact - point.x)))
            worst = error if worst is None else max(worst, error)
            count += 1
    return worst, count


def _chart_scale(name: str, params) -> float:
    """The tracer's unit of gamma and delta in its chart: ``min(1, arctan(k/c))`` for the
    limit curves, 1 for the others (``groove_model.tracing.tracer``)."""
    return min(1.0, params.gamma_limit) if name.endswith("limit") else 1.0


def _junction_error(boundary_set) -> float | None:
    """Largest distance of a reported junction to an independent Newton solve of
    ``dr_limit`` and ``upsilon = 0`` in the paper's form (``None`` if there is none)."""
    from groove_model.model.boundaries import BoundarySystem

    params = boundary_set.params
    system = BoundarySystem("dr_limit", params, "sqrt_beta_L")
    worst = None
    for name in ("dr_limit", "dr_no_roll", "rs_no_roll"):
        curve = boundary_set.curves.get(name)
        for point in (curve.special("junction") if curve is not None else ()):
            y = system.from_x(point.x)
            for _ in range(30):
                H, J = system.residual_and_jacobian(y)
                step = np.linalg.solve(np.vstack([J, [0.0, 0.0, 0.0, 1.0]]),
                                       np.append(H, y[3]))
                y = y - step
                if np.max(np.abs(step)) <= 1e-15 * (1.0 + np.max(np.abs(y))):
                    break
            error = float(np.max(np.abs(system.to_x(y) - point.x)))
            worst = error if worst is None else max(worst, error)
    return worst


def _params(k):
    from groove_model.model.parameters import Parameters

    return Parameters(k)


def _ours(problem: str, ks, repeats: int) -> Record:
    from groove_model import trace_boundaries

    def run():
        return [trace_boundaries(k) for k in ks]

    wall, sets = timed(run, repeats)
    points = residual_evals = jacobian_evals = kept = 0
    residual = 0.0
    ok = True
    worst, folds = None, 0
    junction = None
    for boundary_set in sets:
        error = _junction_error(boundary_set)
        if error is not None:
            junction = error if junction is None else max(junction, error)
        ok &= boundary_set.ok
        for curve in boundary_set.curves.values():
            engine = curve.engine[0]
            points += len(engine)
            kept += len(curve.x)
            residual_evals += engine.residual_evals
            jacobian_evals += engine.jacobian_evals
            residual = max(residual, curve.residual)
        error, count = _ours_fold_error(boundary_set)
        folds += count
        if error is not None:
            worst = error if worst is None else max(worst, error)
    ok &= worst is None or worst <= 1e-10
    ok &= junction is None or junction <= 1e-10
    failed = [b.k for b in sets if not b.ok]
    return Record(problem, "ours", wall, points, residual_evals, jacobian_evals, residual, worst,
                  bool(ok),
                  f"all boundaries and special points of {len(ks)} k; {folds} folds in gamma "
                  f"checked against an independent solve of the fold system; junction error "
                  f"{'-' if junction is None else f'{junction:.2e}'} (against an independent "
                  f"solve of dr_limit and upsilon = 0); {kept} physical points kept; "
                  f"{len(failed)} k failed{f' ({failed[:5]})' if failed else ''}; counts are "
                  "the engine's (the tracer's own checks not counted)")


# --------------------------------------------------------------------------- reference

def _reference(ks, samples: int = 128):
    """Dense points of every traced boundary, per k, in (gamma, delta).

    Each engine step is sampled at ``samples`` points of its cubic Hermite arc (the engine's
    own dense-output predictor, error ``O(h^4)`` ~ 1e-8 for its steps <= 0.05), so the
    polyline resolves distances down to ~1e-8.
    """
    from groove_model import trace_boundaries

    u = np.linspace(0.0, 1.0, samples, endpoint=False)[:, None, None]
    basis = (2 * u**3 - 3 * u**2 + 1, u**3 - 2 * u**2 + u, -2 * u**3 + 3 * u**2, u**3 - u**2)
    references = []
    for k in ks:
        boundary_set = trace_boundaries(k)
        pieces = []
        for curve in boundary_set.curves.values():
            engine = curve.engine[0]
            # the engine's chart has gamma and delta in units of _chart_scale
            scale = _chart_scale(curve.name, boundary_set.params)
            x, t = scale * engine.x[:, :2], scale * engine.tangents[:, :2]
            h = np.diff(engine.s)[None, :, None]
            arcs = (basis[0] * x[:-1] + basis[1] * h * t[:-1] + basis[2] * x[1:]
                    + basis[3] * h * t[1:])
            dense = np.concatenate([arcs.transpose(1, 0, 2).reshape(-1, 2), x[-1:]])
            pieces.append(dense)
        references.append((boundary_set, pieces))
    return references


def _distance(points: np.ndarray, pieces) -> np.ndarray:
    """Distance of each point to the nearest polyline of ``pieces`` (point-to-segment)."""
    from scipy.spatial import cKDTree

    best = np.full(len(points), np.inf)
    for piece in pieces:
        if len(piece) < 2:
            continue
        _, nearest = cKDTree(piece).query(points)
        for offset in (-1, 0):
            i = np.clip(nearest + offset, 0, len(piece) - 2)
            a, b = piece[i], piece[i + 1]
            ab = b - a
            u = np.clip(np.einsum("ij,ij->i", points - a, ab)
                        / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300), 0.0, 1.0)
            best = np.minimum(best, np.linalg.norm(a + u[:, None] * ab - points, axis=1))
    return best


# --------------------------------------------------------------------------- fsolve_natural

def _fsolve_dr_limit(k: float, n_points: int):
    from scipy.optimize import fsolve

    from groove_model.model.boundaries import BoundarySystem, limit_seed
    from groove_model.model.parameters import Parameters

    params = Parameters(k)
    system = BoundarySystem("dr_limit", params)
    seed = limit_seed(params)
    gamma_min = min(1e-3, 0.01 * params.gamma_limit)
    gammas = np.linspace(seed[0], gamma_min, n_points)
    z = seed[1:].copy()
    points, calls, failures = [seed.copy()], 0, 0
    for gamma in gammas[1:]:
        def equations(z, gamma=gamma):
            return system.residual(np.concatenate([[gamma], z]))
        # a nudge off delta = 0, where the family delta = 0 also solves two of the equations
        guess = z + np.array([1e-3, 0.0, 0.0]) if z[0] == 0.0 else z
        z_new, info, ier, _ = fsolve(equations, guess, full_output=True)
        calls += info["nfev"]
        if ier != 1:
            failures += 1
            break
        z = z_new
        points.append(np.concatenate([[gamma], z]))
    return np.array(points), calls, failures, system


def _error_at_gamma(xs: np.ndarray, boundary) -> float:
    """Largest error in ``(delta, beta_L, upsilon)`` of points against our curve at their gamma.

    Our point at each gamma is corrected onto the curve by Newton (``Curve.point_where``),
    not interpolated; the seed itself is skipped (it is the common start).
    """
    from groove_model.model.boundaries import BoundarySystem

    engine = boundary.engine[0]
    params = _params(boundary.k)
    scale = _chart_scale(boundary.name, params)
    system = BoundarySystem(boundary.name, params, "sqrt_beta_L", scale)
    worst = 0.0
    for x in xs[1:]:
        try:
            found = engine.point_where(0, float(x[0]) / scale)
        except ValueError:
            continue
        candidates = found if isinstance(found, list) else [found]
        worst = max(worst, min(float(np.max(np.abs(system.to_x(y) - x))) for y in candidates))
    return worst


def _fsolve(problem: str, ks, repeats: int, references, n_points: int) -> Record:
    def run():
        return [_fsolve_dr_limit(k, n_points) for k in ks]

    try:
        wall, results = timed(run, repeats)
    except Exception as error:  # noqa: BLE001
        return failed(problem, "fsolve_natural", f"run failed: {error!r}")
    points = calls = failures = 0
    residual = distance = 0.0
    for (xs, count, failed_points, system), (boundary_set, _) in zip(results, references):
        points += len(xs)
        calls += count
        failures += failed_points
        residual = max(residual, max(float(np.max(np.abs(system.residual(x)))) for x in xs))
        distance = max(distance, _error_at_gamma(xs, boundary_set.curves["dr_limit"]))
    return Record(problem, "fsolve_natural", wall, points, calls, 0, residual, None,
                  failures == 0,
                  f"dr_limit only, {n_points} gamma values per k; error against our curve at "
                  f"the same gamma {distance:.2e}; {failures} fsolve failures; no special "
                  "points located; Jacobian by finite differences inside fsolve (counted as "
                  "residuals)")


# --------------------------------------------------------------------------- grid_contour

def _grid_contour(k: float, n: int):
    import contourpy

    from groove_model import solve_equilibrium

    gamma = np.linspace(0.0, 0.5 * math.pi, n)
    G, D = np.meshgrid(gamma, gamma)
    inside = (D <= G) & (G > 0.0)
    regime = np.full(G.shape, np.nan)
    upsilon = np.full(G.shape, np.nan)
    eq = solve_equilibrium(G[inside], D[inside], k)
    double_rolling = np.asarray(eq.regime) == "double_rolling"
    regime[inside] = double_rolling
    upsilon[inside] = eq.upsilon
    lines = []
    for field, level in ((regime, 0.5),
                         (np.where(regime == 1.0, upsilon, np.nan), 0.0),
                         (np.where(regime == 0.0, upsilon, np.nan), 0.0)):
        generator = contourpy.contour_generator(gamma, gamma, np.ma.masked_invalid(field))
        lines.extend(generator.lines(level))
    points = np.vstack(lines) if lines else np.zeros((0, 2))
    # delta = 0 is the symmetric family (upsilon = 0 all along it), not a regime boundary
    points = points[points[:, 1] > 0.5 * gamma[1]]
    return points, int(inside.sum())


def _grid(problem: str, ks, repeats: int, references, sizes, ours_wall) -> Record:
    trend = []
    for n in sizes:
        def run(n=n):
            return [_grid_contour(k, n) for k in ks]
        try:
            wall, results = timed(run, repeats if n <= 512 else 1)
        except Exception as error:  # noqa: BLE001
            return failed(problem, "grid_contour", f"run failed at N={n}: {error!r}")
        distance = 0.0
        count = solves = 0
        for (points, evals), (_, pieces) in zip(results, references):
            count += len(points)
            solves += evals
            if len(points):
                distance = max(distance, float(np.max(_distance(points, pieces))))
        trend.append((n, wall, distance, count, solves))
    n, wall, distance, count, solves = trend[-1]
    note = "; ".join(f"N={n}: {1e3 * t:.3g} ms, error {e:.2e}" for n, t, e, _, _ in trend)
    if len(trend) >= 2 and all(e > 0 for _, _, e, _, _ in trend):
        h = np.array([1.0 / t[0] for t in trend])
        errors = np.array([t[2] for t in trend])
        times = np.array([t[1] for t in trend])
        order = float(np.polyfit(np.log(h), np.log(errors), 1)[0])
        time_power = float(np.polyfit(np.log(1.0 / h), np.log(times), 1)[0])
        target = 1e-10
        log_n = math.log(sizes[-1]) + math.log(errors[-1] / target) / max(order, 1e-3)
        n_needed = math.exp(min(log_n, 700.0))
        # the grid's work grows as N^2 however the small grids happen to time
        t_needed = times[-1] * math.exp(min(2.0 * (log_n - math.log(sizes[-1])), 700.0))
        note += (f". Fit: error ~ N^-{order:.2f}, time ~ N^{time_power:.2f} (N^2 "
                 f"asymptotically); error 1e-10 (ours) would need N ~ {n_needed:.1e}, "
                 f"time ~ {t_needed:.1e} s (extrapolated, "
                 f"memory aside). Its finest grid takes {wall / ours_wall:.3g}x our time "
                 f"for error {distance:.1e}" if ours_wall else "")
    note += ("; points are contour vertices, residual_evals counts point-solver solves "
             "(each a bracketed scalar root), error = max distance to our curves")
    return Record(problem, "grid_contour", wall, count, solves, 0, None, None, True, note)


def run_groove(problems=("groove_k1", "groove_k10", "groove_sweep100"),
               tools=("ours", "fsolve_natural", "grid_contour"), repeats: int = 5,
               sweep=100, grid_sizes=(64, 128, 256, 512, 1024), sweep_grid_sizes=(64, 128),
               fsolve_points=100) -> list[Record]:
    """Records of every tool on every tracer problem."""
    records = []
    for problem in problems:
        ks = {"groove_k1": [1.0], "groove_k10": [10.0]}.get(
            problem, list(np.logspace(-2.0, 3.0, sweep)))
        ours_wall = None
        references = None
        for tool in tools:
            try:
                if tool == "ours":
                    record = _ours(problem, ks, repeats)
                    ours_wall = record.wall_s
                else:
                    if references is None:
                        references = _reference(ks)
                    if tool == "fsolve_natural":
                        record = _fsolve(problem, ks, repeats if len(ks) == 1 else 1,
                                         references, fsolve_points)
                    else:
                        sizes = grid_sizes if len(ks) == 1 else sweep_grid_sizes
                        record = _grid(problem, ks, repeats if len(ks) == 1 else 1,
                                       references, sizes, ours_wall)
            except Exception as error:  # noqa: BLE001 - the harness never crashes
                record = failed(problem, tool, f"harness error: {error!r}")
            records.append(record)
    return records
