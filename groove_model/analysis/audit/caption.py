"""The claims of the caption of the paper's Fig. 2 about the regions the curves separate."""

from __future__ import annotations

import numpy as np

from ..regimes import CATEGORIES
from .context import Context, k_label
from .registry import Finding, claim, verdict

# The checks are registered with @claim and run by run.run_audit, not imported by name.
__all__: list = []


@claim("caption_dr_below_rs_above")
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
    return Finding(verdict(ok), numbers=per_k)


@claim("caption_rotation_sides")
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
    return Finding(verdict(ok), numbers=per_k)
