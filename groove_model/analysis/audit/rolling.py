r"""The claims of the paper's paragraph "Rolling solutions" (double rolling), checked.

Double rolling (DR): both contacts roll without sliding, valid where ``T/N <= k`` on both walls.
The claims are about its unique solution, the symmetric state on ``delta = 0``, the limit
``dr_limit`` (``T/N_L = k`` on the steeper wall) and the ``upsilon = 0`` line ``dr_no_roll``.
"""

from __future__ import annotations

import math

import numpy as np

from ...model.equilibrium import double_rolling_state, solve_equilibrium
from ...model.lines import bracketed_root, dr_limit_delta, dr_margins
from ...model.parameters import Parameters, k_text
from ..regimes import CATEGORIES
from .context import (
    HALF_PI,
    IDENTITY_TOL,
    SQRT2,
    Context,
    distance,
    first_special_point,
    k_label,
    rotation_changes,
    sign_changes,
)
from .registry import Finding, applicable, claim, not_applicable, verdict
from .report import Counterexample

# The checks are registered with @claim and run by run.run_audit, not imported by name.
__all__: list = []


@claim("dr_contacts_opposite")
def check_dr_contacts(ctx: Context) -> Finding:
    dr = ctx.dr_grid()
    per_k, exceptions = {}, []
    for k in ctx.ks:
        valid = (dr["t"] <= k * dr["n_L"]) & (dr["t"] <= k * dr["n_R"])
        ups = dr["upsilon"][valid]
        # Contact motion down each wall (paper): u_c;L = -Z upsilon, u_c;R = +Z upsilon (d = 0).
        opposite = np.count_nonzero(-ups * ups < 0.0)
        row = {"DR grid points (delta > 0)": int(valid.sum()),
               "one up, one down": int(opposite),
               "min |upsilon|": float(np.min(np.abs(ups))) if ups.size else math.nan}
        junction = ctx.junction(k)
        row["upsilon = 0 line in DR"] = junction is not None
        if junction is not None:
            exceptions.append(k)
        per_k[k_label(k)] = row
    all_opposite = all(r["one up, one down"] == r["DR grid points (delta > 0)"]
                       for r in per_k.values())
    gamma0 = 0.5 * math.atan(ctx.ks[0])
    at_axis = solve_equilibrium(gamma0, 0.0, ctx.ks[0])
    ce = Counterexample(
        k=ctx.ks[0], gamma=gamma0, delta=0.0,
        values={"upsilon": at_axis.upsilon, "regime": at_axis.regime},
        solver_fields=("upsilon", "regime"),
        note="on delta = 0 (and on the upsilon = 0 line of double rolling) upsilon = 0: "
             "u_c;L = u_c;R = 0, both contacts are stuck, neither moves up nor down")
    return Finding(
        verdict=verdict(all_opposite, qualified=True),
        summary="At every double-rolling grid point off the axis one contact moves up and the "
                "other down (clockwise: the left contact moves down its wall). Exceptions: "
                "the axis delta = 0 (upsilon = 0 exactly, both contacts stuck, as the paper "
                "itself says two sentences later) and, for k > sqrt 2, the upsilon = 0 line "
                "inside double rolling (present here for k = "
                f"{', '.join(map(k_text, exceptions)) or 'none'}).",
        numbers=per_k,
        counterexample=ce)


@claim("dr_unique")
def check_dr_unique(ctx: Context) -> Finding:
    n = 40
    g = np.linspace(0.0, HALF_PI, n + 1)[1:-1]
    r = np.linspace(0.0, 1.0, n + 1)[1:-1]
    G, R = np.meshgrid(g, r)
    G, D = G.ravel()[:, None], (R * G).ravel()[:, None]
    a = np.linspace(0.0, 1.0, 801)[None, :]
    omega = math.pi - 2.0 * G
    beta_L, beta_R = a * omega, (1.0 - a) * omega
    s_L, s_R, c_L, c_R = np.sin(beta_L), np.sin(beta_R), np.cos(beta_L), np.cos(beta_R)
    q_L, q_R = np.sqrt(s_L), np.sqrt(s_R)
    # Torque (T_L = T_R) solved for upsilon, put into the horizontal balance (paper Eq. 2),
    # multiplied by q_L + q_R > 0: no root is added or lost.
    t = q_L * q_R * (c_L + c_R) / np.where(q_L + q_R > 0.0, q_L + q_R, 1.0)
    horizontal = (s_L * q_L * np.sin(G + D) - s_R * q_R * np.sin(G - D)
                  + t * (np.cos(G - D) - np.cos(G + D)))
    roots = sign_changes(horizontal, axis=1)
    ok = bool(np.all(roots == 1))
    return Finding(
        verdict=verdict(ok),
        summary=f"Exactly one root at every point checked (sign changes: min {int(roots.min())}, "
                f"max {int(roots.max())}).",
        numbers={"points": int(G.size), "min roots": int(roots.min()),
                 "max roots": int(roots.max())},
        method_values=dict(points=G.size))


@claim("dr_equations")
def check_dr_equations(ctx: Context) -> Finding:
    G, D = ctx.grid()
    dr = ctx.dr_grid()
    keep = (G - D > 1e-3) & (dr["beta_L"] > 1e-3) & (dr["beta_R"] > 1e-3)
    g, d = G[keep], D[keep]
    bL, bR, ups = dr["beta_L"][keep], dr["beta_R"][keep], dr["upsilon"][keep]
    tL, tR = g + d, g - d
    lhs1 = (np.sin(bR) / np.sin(bL)) ** 1.5
    rhs1 = (np.sin(tL) / np.sin(tR)
            + (np.cos(bL) + ups) * (np.cos(tR) - np.cos(tL)) / (np.sin(bL) * np.sin(tR)))
    lhs2 = (np.sin(bR) / np.sin(bL)) ** 0.5
    rhs2 = (np.cos(bL) + ups) / (np.cos(bR) - ups)
    err1 = float(np.max(np.abs(lhs1 - rhs1) / np.maximum(np.abs(lhs1), 1.0)))
    err2 = float(np.max(np.abs(lhs2 - rhs2) / np.maximum(np.abs(lhs2), 1.0)))
    ok = err1 <= IDENTITY_TOL and err2 <= IDENTITY_TOL
    return Finding(
        verdict=verdict(ok),
        summary=f"Both equations are satisfied by the solutions of the balance equations: "
                f"largest relative residuals {err1:.1e} (tran1) and {err2:.1e} (tran2).",
        numbers={"points": int(keep.sum()), "max residual tran1": err1,
                 "max residual tran2": err2},
        method_values=dict(points=keep.sum()))


@claim("delta0_symmetric_state")
def check_delta0_state(ctx: Context) -> Finding:
    g = np.linspace(0.0, HALF_PI, 401)[1:-1]
    # Independently of the solver's special case on delta = 0: bracket the reduced equation
    # (Eq. 2 with upsilon eliminated) over beta_L on (0, pi - 2 gamma), and the limit delta -> 0+.
    a = np.linspace(0.0, 1.0, 2001)[None, :]
    omega = (math.pi - 2.0 * g)[:, None]
    s_L, s_R = np.sin(a * omega), np.sin((1.0 - a) * omega)
    horizontal = (s_L ** 1.5 - s_R ** 1.5) * np.sin(g)[:, None]  # D = 0 on delta = 0
    roots = sign_changes(horizontal, axis=1)

    def reduced(beta, gg):
        return (np.sin(beta) ** 1.5 - np.sin(math.pi - 2.0 * gg - beta) ** 1.5) * np.sin(gg)

    beta_root = bracketed_root(reduced, np.full_like(g, 1e-12), math.pi - 2.0 * g - 1e-12,
                               args=(g,))
    err_beta = float(np.max(np.abs(beta_root - (HALF_PI - g))))
    # The limit delta -> 0+: the deviation must shrink in proportion to delta (it is large
    # only near the closed-groove edge gamma -> pi/2, where it scales like
    # delta / (pi - 2 gamma)^2).
    devs = []
    for small in (1e-9, 1e-12):
        near = double_rolling_state(g, np.full_like(g, small), Parameters(1.0))
        devs.append((float(np.max(np.abs(near["beta_L"] - (HALF_PI - g)))),
                     float(np.max(np.abs(near["upsilon"])))))
    err_limit, ups_limit = devs[1]
    shrink = devs[1][0] / devs[0][0] if devs[0][0] > 0 else 0.0
    ups_axis = (np.sqrt(np.cos(g)) * np.sin(g) - np.sqrt(np.cos(g)) * np.sin(g))
    ok = bool(np.all(roots == 1)) and err_beta <= 1e-12 and shrink <= 1e-2 and ups_limit <= 1e-6
    return Finding(
        verdict=verdict(ok),
        summary=f"Unique root beta_L = pi/2 - gamma (max error {err_beta:.1e}); the solver's "
                f"states converge to it as delta -> 0+ (at delta = 1e-12: |beta_L - (pi/2 - "
                f"gamma)| <= {err_limit:.1e}, |upsilon| <= {ups_limit:.1e}; shrinking "
                f"{1 / shrink if shrink else math.inf:.3g}-fold from delta = 1e-9).",
        numbers={"gammas": int(g.size), "roots per gamma (min, max)": (int(roots.min()),
                                                                       int(roots.max())),
                 "max |beta_L - (pi/2 - gamma)|": err_beta,
                 "delta = 1e-9: max |beta_L - (pi/2 - gamma)|": devs[0][0],
                 "delta = 1e-9: max |upsilon|": devs[0][1],
                 "delta = 1e-12: max |beta_L - (pi/2 - gamma)|": err_limit,
                 "delta = 1e-12: max |upsilon|": ups_limit,
                 "upsilon from torque at beta_L = beta_R": float(np.max(np.abs(ups_axis)))})


@claim("delta0_ratio_tan_gamma")
def check_delta0_ratio(ctx: Context) -> Finding:
    g = np.linspace(0.0, HALF_PI, 401)[1:-1]
    dr = double_rolling_state(g, np.zeros_like(g), Parameters(1.0))
    tn_L, tn_R = dr["T_over_N_L"], dr["T_over_N_R"]
    err = float(np.max(np.abs(np.concatenate([tn_L, tn_R]) / np.tan(np.concatenate([g, g])) - 1)))
    per_k = {}
    for k in ctx.ks:
        below = tn_L < k
        per_k[k_label(k)] = {"largest gamma with T/N < k":
                                 float(g[below].max()) if below.any() else math.nan,
                             "arctan k": math.atan(k),
                             "gammas with T/N >= k": int(np.count_nonzero(~below))}
    some_exceed = any(r["gammas with T/N >= k"] > 0 for r in per_k.values())
    k0 = ctx.ks[0]
    g0 = 0.5 * (math.atan(k0) + HALF_PI)
    eq = solve_equilibrium(g0, 0.0, k0)
    ce = Counterexample(
        k=k0, gamma=g0, delta=0.0,
        values={"tan gamma (= T/N of the symmetric state)": math.tan(g0), "k": k0,
                "regime": eq.regime},
        solver_fields=("regime",),
        note="the identity T/N = tan gamma holds, but '< k' only for gamma < arctan k; beyond, "
             "the point solver reports double sliding")
    return Finding(
        verdict=verdict(err <= IDENTITY_TOL, qualified=some_exceed),
        summary=f"T/N_L = T/N_R = cot beta_L = tan gamma to {err:.1e} (relative). The final "
                "'< k' is a condition, not a consequence: it holds only for gamma < arctan k, "
                "as the next sentence of the paper says.",
        numbers={"max relative error of T/N = tan gamma": err, **per_k},
        counterexample=ce)


@claim("delta0_valid_below_arctan_k")
def check_delta0_validity(ctx: Context) -> Finding:
    g = np.linspace(0.0, HALF_PI, 4001)[1:-1]
    per_k, ok = {}, True
    for k in ctx.ks:
        eq = solve_equilibrium(g, np.zeros_like(g), k)
        dr = eq.regime == "double_rolling"
        last = float(g[dr].max()) if np.any(dr) else math.nan
        first_out = float(g[~dr].min()) if np.any(~dr) else math.nan
        # The step where validity is lost brackets arctan k (beyond the last gamma of the
        # grid when arctan k is that close to pi/2).
        brackets = not (last > math.atan(k) or first_out < math.atan(k))
        # Exactly at arctan k the ratio equals k up to round-off: either answer is right.
        decided = np.abs(g - math.atan(k)) > 1e-12
        ok &= brackets and bool(np.all((dr == (g <= math.atan(k)))[decided]))
        per_k[k_label(k)] = {"last double-rolling gamma": last, "arctan k": math.atan(k),
                             "first gamma with T/N > k": first_out}
    return Finding(verdict(ok), numbers=per_k)


@claim("dr_limit_from_arctan_k")
def check_dr_limit_start(ctx: Context) -> Finding:
    per_k, ok = {}, True
    G, _ = ctx.grid()
    dr = ctx.dr_grid()
    for k in ctx.ks:
        gk = math.atan(k)
        # One transition per column below arctan k.
        col_g = gk * np.linspace(0.0, 1.0, 41)[1:-1]
        r = np.linspace(0.0, 1.0, 801)[1:][None, :]
        margin = dr_margins(col_g[:, None], r * col_g[:, None], k)[0]
        transitions = sign_changes(margin, axis=1)
        # Approach to the seed along the limit.
        near_g = gk - np.array([1e-2, 1e-3, 1e-4, 1e-5]) * gk
        near_d = dr_limit_delta(k, near_g)
        # No double rolling beyond arctan k (off the axis).
        beyond = (G > gk)
        valid = (dr["t"] <= k * dr["n_L"]) & (dr["t"] <= k * dr["n_R"])
        n_beyond = int(np.count_nonzero(beyond & valid))
        bs = ctx.traced(k)
        start = first_special_point(bs, "dr_limit", "start")
        row = {"transitions per column (min, max)": (int(transitions.min()),
                                                       int(transitions.max())),
               "delta_b at gamma = arctan k (1 - 1e-5)": float(near_d[-1]),
               "slope delta_b / (arctan k - gamma)": float(near_d[-1] / (gk - near_g[-1])),
               "DR grid points with gamma > arctan k": n_beyond,
               "tracer: |start - (arctan k, 0)|": distance(start, (gk, 0.0))}
        ok &= (bool(np.all(transitions == 1)) and n_beyond == 0 and near_d[-1] < 1e-4)
        per_k[k_label(k)] = row
    return Finding(verdict(ok), numbers=per_k)


@claim("dr_limit_steeper_wall_first")
def check_dr_limit_steeper(ctx: Context) -> Finding:
    dr = ctx.dr_grid()
    per_k, ok = {}, True
    for k in ctx.ks:
        g, d = ctx.dr_limit(k)
        st = double_rolling_state(g, d, Parameters(1.0))
        worst_R = float(np.max(st["T_over_N_R"] / k))
        right_first = int(np.count_nonzero((dr["t"] > k * dr["n_R"]) & (dr["t"] <= k * dr["n_L"])))
        # on the grid's columns of the limit: at the seed (delta = 0) the walls are alike and
        # T/N_R = k, the supremum; the claim is that the steeper wall reaches k first off it
        per_k[k_label(k)] = {"max T/N_R / k on the limit's grid columns (1 at the seed)":
                             worst_R,
                             "grid points with T/N_R > k >= T/N_L": right_first}
        ok &= worst_R < 1.0 and right_first == 0
    steeper_larger = int(np.count_nonzero(dr["T_over_N_L"] < dr["T_over_N_R"]))
    return Finding(
        verdict=verdict(ok and steeper_larger == 0),
        summary="On the limit T/N_R stays below k for every k, and nowhere does the less steep "
                f"wall reach k first; in fact T/N_L >= T/N_R everywhere (points with T/N_L < "
                f"T/N_R: {steeper_larger}).",
        numbers={"grid points with T/N_L < T/N_R": steeper_larger, **per_k})


@claim("dr_limit_to_origin_along_diagonal")
def check_dr_limit_end(ctx: Context) -> Finding:
    per_k, ok = {}, True
    gammas = np.array([1e-1, 1e-2, 1e-3, 1e-4])
    for k in ctx.ks:
        # the limit lives below gamma = arctan k: for small k the columns shrink with it
        g = gammas * min(1.0, 5.0 * math.atan(k))
        g = g[g < 0.5 * math.atan(k)]
        d = dr_limit_delta(k, g)
        gap = (g - d) / g
        st = double_rolling_state(g, d, Parameters(1.0))
        slope = float(np.polyfit(np.log(g[-3:]), np.log(g[-3:] - d[-3:]), 1)[0])
        bs = ctx.traced(k)
        end = first_special_point(bs, "dr_limit", "end")
        row = {f"(gamma - delta)/gamma at gamma = {g[-1]:.3g}": float(gap[-1]),
               "log-log slope of gamma - delta": slope,
               f"beta_L k / (2 gamma^2) at {g[-1]:.3g}": float(
                   st["beta_L"][-1] * k / (2 * g[-1] ** 2)),
               "tracer end: delta/gamma": (end[1] / end[0]) if end else math.nan,
               "tracer end: gamma": end[0] if end else math.nan}
        ok &= bool(np.all(np.diff(gap) < 0)) and gap[-1] < 1e-3 and slope > 1.5
        per_k[k_label(k)] = row
    return Finding(verdict(ok), numbers=per_k)


@claim("dr_no_roll_interval")
def check_dr_no_roll_interval(ctx: Context) -> Finding:
    gs = np.linspace(0.0, HALF_PI, 801)[1:-1]
    # Ratios delta/gamma, dense towards both ends where the line meets delta = 0 and delta = gamma.
    r = np.unique(np.concatenate([np.linspace(0.0, 1.0, 201)[1:-1], np.geomspace(1e-7, 1e-2, 15),
                                  1.0 - np.geomspace(1e-9, 1e-2, 15)]))
    G, R = np.meshgrid(gs, r, indexing="ij")
    ups = double_rolling_state(G, R * G, Parameters(1.0))["upsilon"]
    roots = sign_changes(ups, axis=1)
    with_root = gs[roots > 0]
    h = gs[1] - gs[0]
    lo, hi = 0.25 * math.pi, math.atan(SQRT2)
    inside = (gs > lo + h) & (gs < hi - h)
    g, d, st = ctx.dr_no_roll()
    beta_gap = float(np.min(np.abs(st["beta_L"] - st["beta_R"])))
    traced = {}
    for k in ctx.ks:
        bs = ctx.traced(k)
        if bs is not None and "dr_no_roll" in bs.curves and len(bs.curves["dr_no_roll"].x):
            x = bs.curves["dr_no_roll"].x
            traced[k_label(k)] = {"tracer: min gamma": float(x[:, 0].min()),
                                   "tracer: max gamma": float(x[:, 0].max())}
    ok = (with_root.size > 0 and with_root.min() >= lo - h and with_root.max() <= hi + h
          and bool(np.all(roots[inside] == 1)) and beta_gap > 0.0
          and g.min() >= lo - 1e-9 and g.max() <= hi + 1e-9)
    return Finding(
        verdict=verdict(ok),
        summary=f"upsilon = 0 off the axis only in columns {with_root.min():.5f} <= gamma <= "
                f"{with_root.max():.5f} (grid step {h:.1e}; pi/4 = {lo:.5f}, arctan sqrt 2 = "
                f"{hi:.5f}), exactly once per column inside; on the rows the line spans "
                f"{g.min():.9f} <= gamma <= {g.max():.9f}, from (arctan sqrt 2, 0) to "
                f"(pi/4, pi/4), with beta_L != beta_R (min |beta_L - beta_R| = {beta_gap:.1e}, "
                "at the branch-point end).",
        numbers={"columns with a root: min gamma": float(with_root.min()),
                 "columns with a root: max gamma": float(with_root.max()), "pi/4": lo,
                 "arctan sqrt 2": hi, "grid step": float(h),
                 "roots per column inside (min, max)": (int(roots[inside].min()),
                                                        int(roots[inside].max())),
                 "line on rows: min gamma": float(g.min()),
                 "line on rows: max gamma": float(g.max()),
                 "line: gamma at delta = 1e-6": float(g[0]),
                 "line: (gamma, delta) nearest the corner": (float(g[-1]), float(d[-1])),
                 "min |beta_L - beta_R| on the line": beta_gap, **traced},
        method_values=dict(columns=gs.size, ratios=r.size, rows=d.size))


@claim("dr_no_roll_ratio_sqrt2")
def check_dr_no_roll_ratio(ctx: Context) -> Finding:
    g, d, st = ctx.dr_no_roll()
    worst = np.maximum(st["T_over_N_L"], st["T_over_N_R"])
    i = int(np.argmin(worst))
    monotone = bool(np.all(np.diff(st["T_over_N_L"]) > 0))
    ok = float(worst.min()) >= SQRT2 * (1.0 - 1e-12)
    return Finding(
        verdict=verdict(ok),
        summary=f"The larger ratio is T/N_L = cot beta_L; it falls monotonically from infinity "
                f"at (pi/4, pi/4) to sqrt 2 at the branch point (arctan sqrt 2, 0): minimum on "
                f"the line {worst.min():.9f} at gamma = {g[i]:.6f} (sqrt 2 = {SQRT2:.9f}).",
        numbers={"min max(T/N) on the line": float(worst.min()), "at gamma": float(g[i]),
                 "at delta": float(d[i]), "sqrt 2": SQRT2,
                 "T/N_L increasing with delta": monotone,
                 "max T/N_R on the line": float(st["T_over_N_R"].max())},
        method_values=dict(rows=g.size))


@claim("dr_no_roll_needs_k_above_sqrt2")
def check_dr_no_roll_k(ctx: Context) -> Finding:
    _, _, st = ctx.dr_no_roll()
    per_k, ok = {}, True
    for k in ctx.ks:
        physical = (st["T_over_N_L"] <= k) & (st["T_over_N_R"] <= k)
        rg = ctx.regime_grid(k)
        codes = rg.category[1:]  # rows delta > 0
        dr_cw = CATEGORIES.index("double_rolling_clockwise")
        dr_ccw = CATEGORIES.index("double_rolling_counterclockwise")
        n_ccw = int(np.count_nonzero(codes == dr_ccw))
        bs = ctx.traced(k)
        traced = (bs is not None and "dr_no_roll" in bs.curves
                  and bool(np.any(bs.curves["dr_no_roll"].physical)))
        per_k[k_label(k)] = {"physical points of the line": int(physical.sum()),
                             "DR counter-clockwise grid nodes": n_ccw,
                             "DR clockwise grid nodes": int(np.count_nonzero(codes == dr_cw)),
                             "tracer: physical dr_no_roll": traced if bs is not None else "n/a"}
        ok &= (physical.sum() > 0) == (k > SQRT2) and (n_ccw > 0) == (k > SQRT2)
    return Finding(verdict(ok), numbers=per_k)


@claim("dr_no_roll_sides")
def check_dr_no_roll_sides(ctx: Context) -> Finding:
    # The line is a boundary inside double rolling only where it is physical: for k > sqrt 2.
    ks, skipped = applicable(ctx.ks, lambda k: k > SQRT2, "k > sqrt 2")
    if not ks:
        return not_applicable(ctx.ks, "k > sqrt 2")
    per_k, ok = {}, True
    g_line, d_line, _ = ctx.dr_no_roll()
    for k in ks:
        rg = ctx.regime_grid(k)
        changes, bad = rotation_changes(rg, "double_rolling")
        # Where the change happens on each row against the line.
        offsets = []
        cw = CATEGORIES.index("double_rolling_clockwise")
        ccw = CATEGORIES.index("double_rolling_counterclockwise")
        for j, row in enumerate(rg.category[1:], start=1):
            idx = np.flatnonzero((row == cw) | (row == ccw))
            if idx.size < 2:
                continue
            jumps = idx[:-1][np.diff(row[idx]) != 0]
            if jumps.size == 1:
                i = jumps[0]
                g_cross = float(np.interp(rg.delta[j], d_line, g_line))
                offsets.append(abs(g_cross - 0.5 * (rg.gamma[i] + rg.gamma[i + 1])))
        worst = max(offsets) if offsets else math.nan
        per_k[k_label(k)] = {"rows with a change": int(np.count_nonzero(changes)),
                             "rows cw -> ccw only": int(np.count_nonzero(changes == 1)) - bad,
                             "rows violating": bad,
                             "max |change - line| / step": worst / rg.step}
        ok &= bad == 0 and worst <= rg.step
    return Finding(verdict(ok), numbers={**skipped, **per_k})


@claim("amontons_one_sided")
def check_amontons_sign(ctx: Context) -> Finding:
    dr = ctx.dr_grid()
    min_t = float(np.min(dr["t"]))
    per_k, ok = {}, min_t >= 0.0
    for k in ctx.ks:
        rs = ctx.rs_grid(k)
        valid_rs = rs["d_L"] >= 0.0
        per_k[k_label(k)] = {"min mu = T/N_R in RS": float(np.min(rs["mu"][valid_rs]))}
        ok &= per_k[k_label(k)]["min mu = T/N_R in RS"] >= 0.0
    return Finding(
        verdict=verdict(ok),
        summary=f"T >= 0 everywhere (min scaled T in double rolling {min_t:.2e}, zero only on "
                "the edges), so -k N <= T holds automatically and the one-sided form suffices.",
        numbers={"min scaled T in double rolling": min_t, **per_k})
