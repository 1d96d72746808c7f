"""The atlas as files: one CSV per curve of special points, the thresholds, and a report.

Files of an atlas with stem ``S`` (``atlas`` by default) in a directory:

* ``S_<curve>.csv``: the rows of one curve (:data:`~groove_model.tracing.atlas.ATLAS_COLUMNS`:
  ``curve, k, nu, compliance, gamma, delta, beta_L, upsilon, physical, threshold``);
* ``S_thresholds.csv``: the thresholds with their points, equations and residuals;
* ``S.md``: the same in words, with the topology of each range of ``k``.

Floats are written with 17 significant digits.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path
from typing import TYPE_CHECKING

from ..model.parameters import k_text
from ..tracing.atlas import ATLAS_COLUMNS, THRESHOLD_COLUMNS, Atlas
from ..tracing.topology import format_table, thresholds_from_atlas
from .atomic import atomic_write_all

if TYPE_CHECKING:  # reading back is the only use of pandas here
    import pandas as pd

__all__ = ["STANDARD_CURVES", "atlas_files", "atlas_report", "read_atlas_csv", "write_atlas"]


def _cell(value) -> str:
    """A CSV cell as pandas writes it with ``float_format="%.17g"`` (NaN empty)."""
    if isinstance(value, bool):
        return str(value)
    if isinstance(value, float):
        return "" if math.isnan(value) else f"{value:.17g}"
    return str(value)


def _csv(columns, rows, path: Path):
    """``(path, write)`` for :func:`atomic_write_all`: a CSV of ``columns`` and ``rows``."""
    def write(tmp):
        with open(tmp, "w", newline="", encoding="utf-8") as handle:
            writer = csv.writer(handle, lineterminator="\n")
            writer.writerow(columns)
            writer.writerows([_cell(v) for v in row] for row in rows)
    return path, write


#: the curves of the paper's special points: each gets its file, with no rows where the curve
#: does not exist in the range (so a file of an earlier run never stands for this one)
STANDARD_CURVES = ("junction", "dr_limit_fold_delta", "rs_no_roll_fold_gamma")


def write_atlas(atlas: Atlas, directory, stem: str = "atlas", extra=()) -> list[Path]:
    """Write the CSV files and the report of ``atlas`` into ``directory`` (created if needed).

    One CSV per curve; a curve of :data:`STANDARD_CURVES` that does not exist in the range gets
    a file with the header only. ``extra``: more ``(path, write)`` of the same result (its
    figure). All are written before any is moved into place, so a failed write (a full disk)
    leaves the files of an earlier run as they were.
    """
    return atomic_write_all([*atlas_files(atlas, directory, stem), *extra])


def atlas_files(atlas: Atlas, directory, stem: str = "atlas") -> list:
    """The files of :func:`write_atlas` as ``(path, write)``, to be written with others as one
    group (:func:`~groove_model.io.atomic.atomic_write_all`)."""
    directory = Path(directory)
    names = [*atlas.curves, *(n for n in STANDARD_CURVES if n not in atlas.curves)]
    files = [_csv(ATLAS_COLUMNS, atlas.curve_table(name) if name in atlas.curves else [],
                  directory / f"{stem}_{name}.csv") for name in names]
    files.append(_csv(THRESHOLD_COLUMNS, atlas.thresholds_table(),
                      directory / f"{stem}_thresholds.csv"))
    report = atlas_report(atlas)
    files.append((directory / f"{stem}.md",
                  lambda tmp: Path(tmp).write_text(report, encoding="utf-8")))
    return files


def _range_text(atlas: Atlas) -> str:
    low, high = atlas.range
    if atlas.axis.name == "k":
        return f"k in [{low:g}, {high:g}], compliance ratio c = {atlas.axis.fixed:.10g}"
    return f"nu in [{low:g}, {high:g}] (c = 2 (1 - nu)/(2 - nu)), k = {k_text(atlas.axis.fixed)}"


def atlas_report(atlas: Atlas) -> str:
    """The atlas in words: its curves, each threshold with its defining equations, and (in
    ``k``) the topology of each range."""
    symbol = "k" if atlas.axis.name == "k" else "nu"
    lines = [f"# Atlas of the special points: {_range_text(atlas)}", "",
             "Status: " + ("ok" if atlas.ok else "FAILED: " + "; ".join(atlas.failures))
             + ".", "",
             "| curve | rows | boundary | from | to |", "|---|---:|---|---:|---:|"]
    for name, curve in atlas.curves.items():
        values = curve.values
        lines.append(f"| `{name}` | {len(values)} | `{curve.boundary}` | "
                     f"{values.min():.12g} | {values.max():.12g} |")
    lines += ["", "## Thresholds", "",
              f"Each is a codimension-2 point: five equations in the five unknowns "
              f"(gamma, delta, w, upsilon, {'log k' if symbol == 'k' else 'nu'}), "
              "w = sqrt(beta_L), located on its curve to 1e-12 in arclength and polished by "
              "Newton; the residual is the largest of the five at the point.", "",
              f"| threshold | {symbol} | gamma | delta | beta_L | upsilon | residual | what |",
              "|---|---:|---:|---:|---:|---:|---:|---|"]
    for t in atlas.thresholds:
        lines.append(f"| `{t.name}` | {t.value:.15g} | {t.x[0]:.15g} | {t.x[1]:.15g} | "
                     f"{t.x[2]:.15g} | {t.x[3]:.15g} | {t.residual:.1e} | {t.what} |")
    for t in atlas.thresholds:
        lines += ["", f"**`{t.name}`** on `{t.curve}`, defining equations "
                      "(n = sin(beta)^(3/2), q = sqrt(sin beta), D = 2 sin(gamma) sin(delta), "
                      "beta_R = pi - 2 gamma - beta_L, theta_L,R = gamma +- delta):", ""]
        lines += [f"{i}. {equation}" for i, equation in enumerate(t.equations, 1)]
        if t.also:
            lines += ["", "Also zero there: " + "; ".join(t.also) + "."]
    if atlas.axis.name == "k" and atlas.ok:
        lines += ["", "## Topology in each range of k", "",
                  "Read from the curves above at one k inside each range (special points on "
                  "the physical part of their boundary; the inner points of each boundary in "
                  "order from its start); `groove trace` checks every traced curve against "
                  "it.", "", "```", format_table(thresholds_from_atlas(atlas)), "```"]
    return "\n".join(lines) + "\n"


def read_atlas_csv(path) -> pd.DataFrame:
    """Read one curve's CSV back (columns checked).

    Raises
    ------
    ValueError
        If a column of :data:`~groove_model.tracing.atlas.ATLAS_COLUMNS` is missing.
    """
    import pandas as pd  # reading a table back is the only use of pandas here

    frame = pd.read_csv(path, keep_default_na=False, na_values={"": []},
                        dtype={"threshold": str, "curve": str})
    missing = [c for c in ATLAS_COLUMNS if c not in frame.columns]
    if missing:
        raise ValueError(f"{path}: not an atlas CSV; missing columns {', '.join(missing)}")
    return frame
