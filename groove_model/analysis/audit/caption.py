"""The claims of the caption of the paper's Fig. 2 about the regions the curves separate, checked."""

from __future__ import annotations

import numpy as np

from ..regimes import CATEGORIES
from .context import MAP_N, Context, k_label
from .registry import Finding, Section, verdict

__all__ = ["CAPTION"]

CAPTION = Section("Caption of Fig. 2")


@CAPTION.claim(
    id="caption_dr_below_rs_above",
    quote="Solid lines mark the boundary between the elastic double-rolling regime below "
          "and the plastic rolling-sliding regime above.",
    method=f"Every column gamma = const of the {MAP_N}-step map grid (delta > 0): the "
           "double-rolling nodes must form one run starting at the bottom.",
)
def check_caption_dr_below(ctx: Context) -> Finding:
    per_k, ok = {}, True
    for k in ctx.ks:
        rg = ctx.regime_grid(k)
        names = rg.names()
        bad_cols = 0
        for i in range(1, rg.gamma.size):
            col = names[1: i + 1, i]
            is_dr = np.array([n.startswith("double_rolling") for n in col])
            # Double rolling must be a (possibly empty) run starting at the bottom.
            if is_dr.any() and not np.all(is_dr[: np.flatnonzero(is_dr)[-1] + 1]):
                bad_cols += 1
        per_k[k_label(k)] = {"columns checked": int(rg.gamma.size - 1),
                             "columns with RS below DR": bad_cols}
        ok &= bad_cols == 0
    return Finding(
        verdict=verdict(ok),
        summary="In every column double rolling lies below the limit and rolling sliding above.",
        numbers=per_k)


@CAPTION.claim(
    id="caption_rotation_sides",
    quote="The dashed and dot-dashed lines mark the boundaries between clockwise "
          "(low-$\\gamma$) and counter-clockwise (high-$\\gamma$) rolling.",
    method=f"Every row delta = const > 0 of the {MAP_N}-step map grid, across both regimes: "
           "the rotation sense may change at most once, and then from clockwise (low gamma) "
           "to counter-clockwise (high gamma).",
)
def check_caption_rotation(ctx: Context) -> Finding:
    per_k, ok = {}, True
    for k in ctx.ks:
        rg = ctx.regime_grid(k)
        cw = np.isin(rg.category, [CATEGORIES.index("double_rolling_clockwise"),
                                   CATEGORIES.index("rolling_sliding_clockwise")])
        ccw = np.isin(rg.category, [CATEGORIES.index("double_rolling_counterclockwise"),
                                    CATEGORIES.index("rolling_sliding_counterclockwise")])
        bad, changes = 0, []
        for j in range(1, rg.delta.size):
            seq = np.where(cw[j], -1, np.where(ccw[j], 1, 0))
            seq = seq[seq != 0]
            n = int(np.count_nonzero(np.diff(seq)))
            changes.append(n)
            if n > 1 or (n == 1 and seq[0] != -1):
                bad += 1
        per_k[k_label(k)] = {"rows with one cw -> ccw change": int(np.sum(np.array(changes) == 1)),
                             "rows all one sense": int(np.sum(np.array(changes) == 0)),
                             "rows violating": bad}
        ok &= bad == 0
    return Finding(
        verdict=verdict(ok),
        summary="On every row the rotation changes at most once, always from clockwise at low "
                "gamma to counter-clockwise at high gamma (rows above delta = pi/4 are all "
                "counter-clockwise).",
        numbers=per_k)
