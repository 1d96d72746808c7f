r"""The claims of the paper's paragraph "Rolling-sliding solutions", checked.

Rolling sliding (RS): beyond ``dr_limit`` the steeper (left) wall slides, ``T = k N_L``, while
the right contact rolls; ``T/N_R = mu``, and the slip ``d_L`` of the left contact must be
``>= 0``. The claims are about ``mu``, the continuation of double rolling, the axis
``delta = 0`` and the ``upsilon = 0`` line ``rs_no_roll``.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import optimize

from ...model.equilibrium import double_rolling_state, rolling_sliding_state, solve_equilibrium
from ...model.lines import rs_limit_delta, rs_no_roll_gamma
from ...model.parameters import Parameters
from .context import (
    CORNER,
    HALF_PI,
    IDENTITY_TOL,
    POINT_TOL,
    SQRT2,
    VIOLATION,
    Context,
    distance,
    k_label,
    rotation_changes,
    sign_changes,
)
from .registry import Finding, applicable, claim, not_applicable, verdict
from .report import Counterexample

# The checks are registered with @claim and run by run.run_audit, not imported by name.
__all__: list = []


@claim("rs_only_solution_beyond_limit")
def check_rs_only(ctx: Context) -> Finding:
    G, D = ctx.grid()
    dr = ctx.dr_grid()
    tL, tR = G + D, G - D
    per_k, ok = {}, True
    for k in ctx.ks:
        rs = ctx.rs_grid(k)
        dr_valid = (dr["t"] <= k * dr["n_L"]) & (dr["t"] <= k * dr["n_R"])
        rs_valid = (rs["d_L"] >= 0.0) & (rs["mu"] <= k)
        # The shallower (right) wall sliding instead: T/N_L = mu' from the mirrored formula.
        den_mirror = np.cos(tL) - np.cos(tR) + np.sin(tR) / k
        mirror_ok = (den_mirror > 0.0) & (np.sin(tL) <= k * den_mirror)
        # Both walls sliding: horizontal balance with N_L = N_R, T = kN leaves
        # 2 sin(delta) (cos gamma + k sin gamma) N, zero only on delta = 0.
        ds_residual = 2.0 * np.sin(D) * (np.cos(G) + k * np.sin(G))
        row = {"DR-invalid points": int(np.count_nonzero(~dr_valid)),
               "of which without an RS state": int(np.count_nonzero(~dr_valid & ~rs_valid)),
               "points where RS and DR both valid": int(np.count_nonzero(dr_valid & rs_valid)),
               "admissible right-wall sliding": int(np.count_nonzero(mirror_ok)),
               "min double-sliding residual": float(ds_residual.min())}
        per_k[k_label(k)] = row
        ok &= (row["of which without an RS state"] == 0
               and row["admissible right-wall sliding"] == 0
               and row["min double-sliding residual"] > 0.0)
    return Finding(verdict(ok), numbers=per_k)


def _force_balance_mu(gamma, delta, k):
    """``T/N_R`` with ``T = k N_L`` from the vertical and horizontal balances as a 2x2 solve."""
    tL, tR = gamma + delta, gamma - delta
    # Unknowns (N_L, N_R), Mg = 1, T_L = T_R = k N_L (paper Eqs. 1-3).
    A = np.array([[k * math.sin(tL) + math.cos(tL) + k * math.sin(tR), math.cos(tR)],
                  [-k * math.cos(tL) + math.sin(tL) + k * math.cos(tR), -math.sin(tR)]])
    N_L, N_R = np.linalg.solve(A, [1.0, 0.0])
    return k * N_L / N_R, N_L, N_R


def _mu(theta_L, theta_R, k):
    return np.sin(theta_R) / (np.cos(theta_R) - np.cos(theta_L) + np.sin(theta_L) / k)


@claim("rs_mu_formula")
def check_rs_mu_formula(ctx: Context) -> Finding:
    rng = np.random.default_rng(20260101)
    per_k, ok = {}, True
    for k in ctx.ks:
        g = rng.uniform(0.02, HALF_PI - 0.02, 300)
        d = rng.uniform(0.0, 0.98, 300) * g
        errs = []
        for gi, di in zip(g, d, strict=True):
            mu_fb, _, _ = _force_balance_mu(gi, di, k)
            errs.append(abs(mu_fb / _mu(gi + di, gi - di, k) - 1.0))
        per_k[k_label(k)] = {"max relative difference": float(max(errs))}
        ok &= max(errs) <= IDENTITY_TOL
    return Finding(verdict(ok), numbers=per_k)


def _theta_grid(n=400, shallower_left=False):
    """Wall angles with ``theta_R < theta_L`` (or ``>`` if ``shallower_left``) and
    ``theta_L + theta_R <= pi``."""
    t = np.linspace(0.0, math.pi, n + 1)
    TL, TR = np.meshgrid(t, t)
    keep = (TL + TR <= math.pi) & ((TR > TL) if shallower_left else (TR < TL))
    return TL[keep], TR[keep]


@claim("rs_mu_below_k")
def check_rs_mu_below(ctx: Context) -> Finding:
    tL, tR = _theta_grid()
    per_k, ok = {}, True
    for k in ctx.ks:
        mu = _mu(tL, tR, k)
        # a grid maximum: mu/k tends to 1 as theta_R -> theta_L (the walls alike)
        per_k[k_label(k)] = {"max mu / k over the grid's wall pairs": float(np.max(mu / k)),
                             "min denominator": float(np.min(np.cos(tR) - np.cos(tL)
                                                              + np.sin(tL) / k))}
        ok &= per_k[k_label(k)]["max mu / k over the grid's wall pairs"] < 1.0
    return Finding(verdict(ok), numbers=per_k, method_values=dict(pairs=tL.size))


@claim("rs_mu_above_k_if_shallower_slides")
def check_rs_mu_above(ctx: Context) -> Finding:
    tL, tR = _theta_grid(shallower_left=True)
    ordinary = (tL >= 0.05) & (tR <= HALF_PI - 0.05)  # both walls between 0.05 and pi/2 - 0.05
    per_k, ok = {}, True
    first_bad = {}
    for k in ctx.ks:
        den = np.cos(tR) - np.cos(tL) + np.sin(tL) / k
        mu = np.full_like(den, -np.inf)
        np.divide(np.sin(tR), den, out=mu, where=den != 0.0)
        below = mu <= k
        per_k[k_label(k)] = {"pairs": int(tL.size), "pairs with mu <= k": int(below.sum()),
                             "of which denominator > 0": int(np.count_nonzero(below & (den > 0))),
                             "ordinary grooves with mu <= k":
                                 int(np.count_nonzero(below & ordinary))}
        ok &= not np.any(below)
        if np.any(below):
            # A representative violation: the groove with the most negative denominator,
            # an ordinary one (both walls away from 0 and pi/2) where there is one.
            where = below & ordinary if np.any(below & ordinary) else below
            first_bad[k] = int(np.argmin(np.where(where, den, np.inf)))
    ce = None
    if first_bad:
        k = 1.0 if 1.0 in first_bad else next(iter(first_bad))
        i = first_bad[k]
        g, d = 0.5 * (tL[i] + tR[i]), 0.5 * (tL[i] - tR[i])
        mu_fb, N_L, N_R = _force_balance_mu(g, d, k)
        ce = Counterexample(
            k=float(k), gamma=float(g), delta=float(d),
            values={"mu": float(_mu(tL[i], tR[i], k)),
                    "denominator": float(np.cos(tR[i]) - np.cos(tL[i]) + np.sin(tL[i]) / k),
                    "k N_L / N_R from the balances": float(mu_fb),
                    "N_R / N_L": float(N_R / N_L)},
            note="theta_R > theta_L (the mirror image of the groove (gamma, -delta) with the "
                 "shallower wall on the left): the formula's denominator is negative, so "
                 "mu < 0 < k; the balances with the left wall sliding then need N_R < 0, i.e. "
                 "no such state exists at all. The conclusion 'sliding always occurs on the "
                 "steeper wall' survives; the inequality mu > k does not")
    strict = all(r["of which denominator > 0"] == 0 for r in per_k.values())
    if ok:
        summary = "mu > k at every pair checked."
    else:
        summary = ("False as written: wherever the denominator cos theta_R - cos theta_L + "
                   "sin(theta_L)/k is negative (a steep right wall, a shallow left one; for "
                   "large k almost every pair) the formula gives mu < 0 < k. "
                   + ("Where the denominator is positive, mu > k does hold." if strict else
                      "Even with a positive denominator mu <= k occurs."))
    return Finding(
        verdict=verdict(ok),
        summary=summary,
        numbers=per_k,
        counterexample=ce,
        method_values=dict(pairs=tL.size))


@claim("rs_sliding_on_steeper_wall")
def check_rs_sliding_steeper(ctx: Context) -> Finding:
    G, D = ctx.grid()
    tL, tR = G + D, G - D
    per_k, ok = {}, True
    for k in ctx.ks:
        den = np.cos(tL) - np.cos(tR) + np.sin(tR) / k  # right wall slides: T = k N_R
        admissible = (den > 0.0) & (np.sin(tL) <= k * den)
        # The left-sliding state where double rolling fails: is it admissible (d_L >= 0)?
        dr, rs = ctx.dr_grid(), ctx.rs_grid(k)
        beyond = (dr["t"] > k * dr["n_L"]) | (dr["t"] > k * dr["n_R"])
        left_ok = int(np.count_nonzero(beyond & (rs["d_L"] >= 0.0) & (rs["mu"] <= k)))
        per_k[k_label(k)] = {"admissible right-wall sliding": int(admissible.sum()),
                             "DR-invalid points": int(beyond.sum()),
                             "of which left-wall sliding admissible": left_ok}
        ok &= admissible.sum() == 0 and left_ok == beyond.sum()
    return Finding(verdict(ok), numbers=per_k)


@claim("rs_continues_dr")
def check_rs_continuation(ctx: Context) -> Finding:
    per_k, ok = {}, True
    for k in ctx.ks:
        g, d = ctx.dr_limit(k)
        dr = double_rolling_state(g, d, Parameters(1.0))
        rs = rolling_sliding_state(g, d, Parameters(k))
        row = {"max |beta_L(DR) - beta_L(RS)|": float(np.max(np.abs(dr["beta_L"] - rs["beta_L"]))),
               "max |upsilon(DR) - upsilon(RS)|":
                   float(np.max(np.abs(dr["upsilon"] - rs["upsilon"]))),
               "max |d_L(RS)|": float(np.max(np.abs(rs["d_L"])))}
        per_k[k_label(k)] = row
        ok &= max(row.values()) <= 1e-8
    return Finding(verdict(ok), numbers=per_k)


@claim("rs_beta_unique")
def check_rs_beta_unique(ctx: Context) -> Finding:
    per_k, ok = {}, True
    # f(beta_L) = sin beta_L / sin(omega - beta_L) has derivative sin omega / sin^2 > 0.
    g = np.linspace(0.0, HALF_PI, 201)[1:-1][:, None]
    a = np.linspace(0.0, 1.0, 2001)[1:-1][None, :]
    omega = math.pi - 2.0 * g
    f = np.sin(a * omega) / np.sin((1.0 - a) * omega)
    increasing = bool(np.all(np.diff(f, axis=1) > 0.0))
    for k in ctx.ks:
        rs = ctx.rs_grid(k)
        ratio = rs["n_L"] / rs["n_R"]
        err = float(np.max(np.abs(ratio - rs["mu"] / k) / np.maximum(rs["mu"] / k, 1e-300)))
        per_k[k_label(k)] = {"max relative error of N_L/N_R = mu/k": err}
        ok &= err <= IDENTITY_TOL
    return Finding(
        verdict=verdict(ok and increasing),
        numbers={"monotonic on every column": increasing, **per_k})


@claim("rs_upsilon_from_right_wall")
def check_rs_upsilon(ctx: Context) -> Finding:
    per_k, ok = {}, True
    for k in ctx.ks:
        rs = ctx.rs_grid(k)
        keep = np.sin(rs["beta_R"]) > 1e-6
        lhs = (np.cos(rs["beta_R"][keep]) - rs["upsilon"][keep]) / np.sin(rs["beta_R"][keep])
        err = float(np.max(np.abs(lhs - rs["mu"][keep]) / np.maximum(rs["mu"][keep], 1.0)))
        per_k[k_label(k)] = {"max error of mu = (cos beta_R - upsilon)/sin beta_R": err}
        ok &= err <= IDENTITY_TOL
    return Finding(verdict(ok), numbers=per_k)


@claim("rs_dL_boundary_is_dr_limit")
def check_rs_dL_boundary(ctx: Context) -> Finding:
    G, _ = ctx.grid()
    per_k, ok = {}, True
    for k in ctx.ks:
        g, d_dr = ctx.dr_limit(k)
        d_rs = rs_limit_delta(k, g)
        rs = ctx.rs_grid(k)
        beyond = G > math.atan(k)
        bs = ctx.traced(k)
        smallest = "min d_L on the grid for gamma > arctan k (0 at the seed)"
        row = {"max |delta(d_L = 0) - delta(T/N_L = k)|": float(np.max(np.abs(d_rs - d_dr))),
               smallest: float(np.min(rs["d_L"][beyond])) if np.any(beyond) else math.nan,
               "tracer: limit_distance": bs.limit_distance if bs is not None else math.nan}
        per_k[k_label(k)] = row
        ok &= row["max |delta(d_L = 0) - delta(T/N_L = k)|"] <= POINT_TOL and (
            not np.any(beyond) or row[smallest] > 0.0)
    return Finding(verdict(ok), numbers=per_k)


def _axis_limit_points(ctx: Context, k: float, n: int = 200):
    g = np.linspace(math.atan(k), HALF_PI, n + 1)[1:-1]
    return g


@claim("rs_delta0_upsilon_zero")
def check_rs_delta0_upsilon(ctx: Context) -> Finding:
    per_k, ok, ce = {}, True, None
    for k in ctx.ks:
        g = _axis_limit_points(ctx, k)
        at0 = rolling_sliding_state(g, np.zeros_like(g), Parameters(k))
        near = solve_equilibrium(g, np.full_like(g, 1e-9), k)
        predicted = np.sin(g) - k * np.cos(g)
        worst = float(np.max(np.abs(near.upsilon)))
        err = float(np.max(np.abs(near.upsilon - predicted)))
        per_k[k_label(k)] = {"max |upsilon| at delta = 1e-9": worst,
                             "max |upsilon - (sin gamma - k cos gamma)|": err,
                             "max |upsilon| of the RS formulas at delta = 0":
                                  float(np.max(np.abs(at0["upsilon"])))}
        ok &= worst <= VIOLATION
    k0 = 1.0 if 1.0 in ctx.ks else ctx.ks[0]
    g0 = 0.5 * (math.atan(k0) + HALF_PI)
    if not ok:
        eq = solve_equilibrium(g0, 1e-9, k0)
        rs0 = rolling_sliding_state(g0, 0.0, Parameters(k0))
        ce = Counterexample(
            k=k0, gamma=g0, delta=1e-9,
            values={"regime": eq.regime, "upsilon": eq.upsilon, "T_over_N_R": eq.T_over_N_R,
                    "d_L": eq.d_L, "d_R": eq.d_R,
                    "sin gamma - k cos gamma": math.sin(g0) - k0 * math.cos(g0),
                    "upsilon of the RS formulas at delta = 0": float(rs0["upsilon"])},
            solver_fields=("regime", "upsilon", "T_over_N_R", "d_L", "d_R"),
            note="the rolling-sliding state next to the axis (and its formulas on it) has "
                 "upsilon = sin gamma - k cos gamma > 0 for gamma > arctan k, not 0; "
                 "upsilon = 0 only at gamma = arctan k, where the rolling-sliding upsilon = 0 "
                 "line starts")
    return Finding(verdict(ok), numbers=per_k, counterexample=ce)


@claim("rs_delta0_ratio_k")
def check_rs_delta0_ratio(ctx: Context) -> Finding:
    per_k, ok = {}, True
    for k in ctx.ks:
        g = _axis_limit_points(ctx, k)
        at0 = rolling_sliding_state(g, np.zeros_like(g), Parameters(k))
        near = rolling_sliding_state(g, np.full_like(g, 1e-9), Parameters(k))
        per_k[k_label(k)] = {"max |mu/k - 1| at delta = 0":
                                 float(np.max(np.abs(at0["mu"] / k - 1))),
                             "max |mu/k - 1| at delta = 1e-9":
                                  float(np.max(np.abs(near["mu"] / k - 1)))}
        ok &= per_k[k_label(k)]["max |mu/k - 1| at delta = 0"] <= IDENTITY_TOL
    return Finding(verdict(ok), numbers=per_k)


def _next_to_axis(k: float) -> float:
    """The ``delta`` of a point "next to the axis": 1e-9, smaller for k > 100 (the forces leave
    double sliding as ``~2 k delta``, so the probe keeps that below 1e-6)."""
    return 1e-9 * min(1.0, 100.0 / k)


@claim("rs_delta0_collapses_to_double_sliding")
def check_rs_delta0_double_sliding(ctx: Context) -> Finding:
    per_k, forces_ok, kinematics_same = {}, True, True
    for k in ctx.ks:
        g = _axis_limit_points(ctx, k)
        near = solve_equilibrium(g, np.full_like(g, _next_to_axis(k)), k)
        axis = solve_equilibrium(g, np.zeros_like(g), k)
        row = {"max |N_L/N_R - 1|": float(np.max(np.abs(near.N_L_over_N_R - 1))),
               "max |T/N_R - k| / k": float(np.max(np.abs(near.T_over_N_R - k)) / k),
               "max |upsilon(0+) - upsilon(DS)|":
                   float(np.max(np.abs(near.upsilon - axis.upsilon))),
               "max d_R(0+)": float(np.max(near.d_R)),
               "max |d_L(0+) - 2 (sin gamma - k cos gamma)|":
                   float(np.max(np.abs(near.d_L - 2 * (np.sin(g) - k * np.cos(g)))))}
        per_k[k_label(k)] = row
        forces_ok &= row["max |N_L/N_R - 1|"] <= 1e-6 and row["max |T/N_R - k| / k"] <= 1e-6
        kinematics_same &= row["max |upsilon(0+) - upsilon(DS)|"] <= VIOLATION
    k0 = 1.0 if 1.0 in ctx.ks else ctx.ks[0]
    g0 = 0.5 * (math.atan(k0) + HALF_PI)
    ce = None
    if not kinematics_same:
        eq = solve_equilibrium(g0, _next_to_axis(k0), k0)
        ds = solve_equilibrium(g0, 0.0, k0)
        ce = Counterexample(
            k=k0, gamma=g0, delta=_next_to_axis(k0),
            values={"upsilon": eq.upsilon, "d_L": eq.d_L, "d_R": eq.d_R,
                    "N_L_over_N_R": eq.N_L_over_N_R, "T_over_N_R": eq.T_over_N_R,
                    "double sliding on the axis: upsilon": ds.upsilon,
                    "double sliding on the axis: d_L = d_R": ds.d_L},
            solver_fields=("upsilon", "d_L", "d_R", "N_L_over_N_R", "T_over_N_R"),
            note="next to the axis the forces are those of double sliding (T = kN on both "
                 "walls, N_L = N_R) but the right contact only reaches T = kN without slipping "
                 "(d_R = 0) and the ball turns counter-clockwise, whereas the symmetric "
                 "double-sliding state has upsilon = 0 and d_L = d_R; on the axis the "
                 "kinematics is indeterminate (any |upsilon| <= sin gamma - k cos gamma)")
    # The counterexample is about the kinematics: it qualifies a "holds", it does not show
    # that the forces fail to collapse.
    return Finding(verdict(forces_ok, qualified=not kinematics_same), numbers=per_k,
                   counterexample=ce if forces_ok else None)


@claim("rs_no_roll_line_stuck")
def check_rs_no_roll_stuck(ctx: Context) -> Finding:
    per_k, ok = {}, True
    for k in ctx.ks:
        _, _, st = ctx.rs_no_roll(k)
        physical = st["d_L"] >= 0.0
        # Contact motions (paper): u_c;L = -Z upsilon + d_L, u_c;R = Z upsilon + d_R, d_R = 0.
        u_cR = st["upsilon"][physical]
        u_cL = -st["upsilon"][physical] + st["d_L"][physical]
        row = {"physical points": int(physical.sum()),
               "max |u_c;R| / Z (stuck)":
                   float(np.max(np.abs(u_cR))) if physical.any() else math.nan,
               "min u_c;L / Z (sliding)": float(np.min(u_cL)) if physical.any() else math.nan}
        per_k[k_label(k)] = row
        ok &= physical.sum() > 0 and row["max |u_c;R| / Z (stuck)"] <= 1e-12
    return Finding(verdict(ok), numbers=per_k)


def _min_max(values: np.ndarray) -> tuple:
    return int(values.min()), int(values.max())


def _rs_no_roll_ends(ctx: Context, k: float) -> dict:
    """Numbers on the physical part of the rolling-sliding upsilon = 0 line for one k."""
    g, d, st = ctx.rs_no_roll(k)
    # One crossing per row, from the left edge (upsilon = -cos 2 delta < 0) to gamma = pi/2.
    rows = 0.25 * math.pi * np.linspace(0.0, 1.0, 101)[1:-1]
    cols = np.linspace(0.0, 1.0, 2001)[None, :]
    G = rows[:, None] + (HALF_PI - rows[:, None]) * cols
    D = np.broadcast_to(rows[:, None], G.shape)
    ups = rolling_sliding_state(G, D, Parameters(k))["upsilon"]
    crossings = sign_changes(ups, axis=1)
    physical = st["d_L"] >= 0.0
    first = int(np.argmax(physical)) if physical.any() else None
    low_end = math.nan if first is None else float(d[first])
    unphysical_runs = int(np.count_nonzero(np.diff(physical.astype(int)) != 0))
    # The line leaves the axis linearly in delta, with a slope ~ 1/k^2 for small k: its start is
    # (arctan k, 0) if the distance shrinks a hundredfold from delta = d to d/100, with
    # d = 1e-8, smaller for k < 0.1 (d ~ k^3) to stay in the linear part (delta/k^2 << k).
    near_deltas = 1e-8 * min(1.0, 1e3 * k ** 3) * np.array([1.0, 1e-2])
    near_axis = rs_no_roll_gamma(k, near_deltas)
    end_near_corner = float(rs_no_roll_gamma(k, np.array([0.25 * math.pi - 1e-7]))[0])
    bs = ctx.traced(k)
    curve = bs.curves.get("rs_no_roll") if bs is not None else None
    tr_start = tr_end = None
    if curve is not None and np.any(curve.physical):
        xs = curve.x[curve.physical]
        tr_start, tr_end = (float(xs[0, 0]), float(xs[0, 1])), (float(xs[-1, 0]), float(xs[-1, 1]))
    return dict(g=g, d=d, st=st, physical=physical, crossings=crossings, first=first,
                low_end=low_end, switches=unphysical_runs, near_axis=near_axis,
                near_deltas=near_deltas,
                end_near_corner=end_near_corner, tracer_start=tr_start, tracer_end=tr_end)


def _starts_at(gammas: np.ndarray, gamma0: float) -> bool:
    """Whether ``gamma`` at ``delta = d, d/100`` approaches ``gamma0`` linearly in delta."""
    far, near = np.abs(gammas - gamma0)
    return bool(near <= 0.02 * far + 1e-13)


@claim("rs_no_roll_small_k_ends")
def check_rs_no_roll_small_k(ctx: Context) -> Finding:
    ks, skipped = applicable(ctx.ks, lambda k: k < SQRT2, "k < sqrt 2")
    if not ks:
        return not_applicable(ctx.ks, "k < sqrt 2")
    per_k, ok = {}, True
    for k in ks:
        e = _rs_no_roll_ends(ctx, k)
        row = {"crossings per row (min, max)": _min_max(e["crossings"]),
               "all physical": bool(np.all(e["physical"])),
               f"gamma at delta = {e['near_deltas'][0]:.3g}": float(e["near_axis"][0]),
               f"gamma at delta = {e['near_deltas'][1]:.3g}": float(e["near_axis"][1]),
               "arctan k": math.atan(k),
               "gamma at delta = pi/4 - 1e-7": e["end_near_corner"],
               "tracer: |start - (arctan k, 0)|": distance(e["tracer_start"], (math.atan(k), 0.0)),
               "tracer: |end - (pi/4, pi/4)|": distance(e["tracer_end"], CORNER),
               "turns back in gamma":
                   bool(np.any(np.diff(e["g"]) > 0) and np.any(np.diff(e["g"]) < 0))}
        per_k[k_label(k)] = row
        ok &= (bool(np.all(e["crossings"] == 1)) and row["all physical"]
               and _starts_at(e["near_axis"], math.atan(k))
               and abs(e["end_near_corner"] - 0.25 * math.pi) < 1e-5)
    return Finding(verdict(ok), numbers={**skipped, **per_k})


@claim("rs_no_roll_large_k_ends")
def check_rs_no_roll_large_k(ctx: Context) -> Finding:
    ks, skipped = applicable(ctx.ks, lambda k: k > SQRT2, "k > sqrt 2")
    if not ks:
        return not_applicable(ctx.ks, "k > sqrt 2")
    per_k, ok = {}, True
    for k in ks:
        e = _rs_no_roll_ends(ctx, k)
        junction = ctx.junction(k)
        # Where d_L = 0 on the line: the lower end of its physical part, located exactly.
        first = e["first"]
        if first is not None and first > 0:
            d_lo, d_hi = float(e["d"][first - 1]), float(e["d"][first])

            def slip(dd, k=k):
                gg = rs_no_roll_gamma(k, np.array([dd]))
                return float(rolling_sliding_state(gg, np.array([dd]), Parameters(k))["d_L"][0])

            d_end = optimize.brentq(slip, d_lo, d_hi, xtol=1e-15)
            g_end = float(rs_no_roll_gamma(k, np.array([d_end]))[0])
        else:
            d_end = g_end = math.nan
        row = {"crossings per row (min, max)": _min_max(e["crossings"]),
               "unphysical/physical switches on the line": e["switches"],
               "physical part from (gamma, delta)": (g_end, d_end),
               "DR-limit upsilon = 0 point": (float(junction[0]), float(junction[1])),
               "distance": distance((g_end, d_end), junction[:2]),
               "gamma at delta = pi/4 - 1e-7": e["end_near_corner"],
               "tracer: |start - junction|": distance(e["tracer_start"], junction[:2]),
               "tracer: |end - (pi/4, pi/4)|": distance(e["tracer_end"], CORNER)}
        per_k[k_label(k)] = row
        ok &= (bool(np.all(e["crossings"] == 1)) and e["switches"] == 1
               and row["distance"] <= POINT_TOL
               and abs(e["end_near_corner"] - 0.25 * math.pi) < 1e-5)
    return Finding(verdict(ok), numbers={**skipped, **per_k})


@claim("rs_no_roll_sides")
def check_rs_no_roll_sides(ctx: Context) -> Finding:
    per_k, ok = {}, True
    for k in ctx.ks:
        rg = ctx.regime_grid(k)
        changes, bad = rotation_changes(rg, "rolling_sliding")
        per_k[k_label(k)] = {"rows with a change in RS": int(np.count_nonzero(changes)),
                             "rows violating": bad}
        ok &= bad == 0
    return Finding(verdict(ok), numbers=per_k)
