"""CSV export and import of traced boundaries, written atomically (:mod:`.atomic`)."""

from __future__ import annotations

import errno
from pathlib import Path

import numpy as np
import pandas as pd

from ..model.boundaries import BOUNDARY_NAMES
from ..model.parameters import check_traced_friction, check_traced_ratio, k_text
from ..tracing import CSV_COLUMNS, SPECIAL_POINT_COLUMNS, BoundarySet, PointKind
from .atomic import WriteError, atomic_write, atomic_write_all, remove_stale_temporaries

__all__ = [
    "atomic_write",
    "boundary_file_names",
    "incomplete_boundaries",
    "read_boundaries_csv",
    "remove_stale_temporaries",
    "write_boundary_set",
]


def boundary_file_names(k: float, suffix: str = "") -> tuple[str, str]:
    """``boundaries_k{k}{suffix}.csv`` and ``special_points_k{k}{suffix}.csv`` with ``k``
    written in full (:func:`~groove_model.model.parameters.k_text`): ``boundaries_k1.csv``,
    ``boundaries_k1.0000001.csv``; two different ``k`` never share a file. ``suffix`` names
    another compliance than the paper's (e.g. ``"_nu0.3"``)."""
    return f"boundaries_k{k_text(k)}{suffix}.csv", f"special_points_k{k_text(k)}{suffix}.csv"


def write_boundary_set(boundary_set: BoundarySet, directory,
                       suffix: str = "") -> tuple[Path, Path]:
    """Write the pair of CSV files of one ``k`` into ``directory`` (created if needed).

    Floats are written with 17 significant digits, so a row recomputed from its own columns
    reproduces the traced point exactly. ``suffix`` ends the file names (e.g. ``"_nu0.3"`` for
    another compliance than the paper's).

    Raises
    ------
    TraceError
        If a boundary failed (nothing is written: a failed trace is not a result).
    """
    # the tables first: they raise for a failed trace, before the directory is made (by
    # atomic_write_all, which removes it again if it writes nothing)
    points = boundary_set.to_frame()
    specials = boundary_set.special_points_frame()[list(SPECIAL_POINT_COLUMNS)]
    directory = Path(directory)
    points_name, specials_name = boundary_file_names(boundary_set.k, suffix)
    for name in (points_name, specials_name):
        # checked for both before either is written: a pair is written whole or not at all
        if (directory / name).exists() and not (directory / name).is_file():
            raise WriteError(errno.EISDIR, f"cannot write {directory / name}: it exists and is "
                                           "not a file")
    # both written before either is moved into place: a full disk leaves neither changed
    paths = atomic_write_all([(directory / points_name, _csv_writer(points)),
                              (directory / specials_name, _csv_writer(specials))])
    return paths[0], paths[1]


def _csv_writer(frame: pd.DataFrame):
    """``write(tmp)`` of :func:`atomic_write_all`: ``frame`` as CSV, floats to 17 digits."""
    def write(tmp) -> None:
        frame.to_csv(tmp, index=False, float_format="%.17g")
    return write


def read_boundaries_csv(path) -> pd.DataFrame:
    """Read a ``boundaries_k*.csv`` file and check its columns.

    Raises
    ------
    OSError
        If the file cannot be read.
    ValueError
        If it is not a boundaries CSV: missing columns, no rows, an unknown boundary name or
        point kind, a value that is not a number, a point outside the domain, or a ``k`` or
        compliance ratio outside the ranges the boundaries are traced for (the message names
        the column, value and row). The rows come back in the order along each boundary
        (increasing ``s``), whatever their order in the file.

    Notes
    -----
    ``certified`` is True (proven), False (certification failed) or empty (not asked for,
    or a file written before the column existed), read as True, False or None.
    """
    path = Path(path)
    try:
        frame = pd.read_csv(path, keep_default_na=False, na_values={"": []},
                            dtype={"point": str, "boundary": str, "certified": str})
    except pd.errors.EmptyDataError:
        raise ValueError(f"{path}: not a boundaries CSV (the file is empty)") from None
    except (pd.errors.ParserError, UnicodeDecodeError) as exc:
        raise ValueError(f"{path}: not a boundaries CSV ({exc})") from None
    if "certified" not in frame.columns:
        frame["certified"] = ""  # written before certification existed: not certified
    if "compliance" not in frame.columns:
        frame["compliance"] = 1.0  # written before the column existed: the paper's law
    missing = [c for c in CSV_COLUMNS if c not in frame.columns]
    if missing:
        raise ValueError(f"{path}: not a boundaries CSV; missing columns {', '.join(missing)} "
                         f"(expected {','.join(CSV_COLUMNS)})")
    if not len(frame):
        raise ValueError(f"{path}: no rows")
    unknown = sorted(set(frame["boundary"]) - set(BOUNDARY_NAMES))
    if unknown:
        raise ValueError(f"{path}: unknown boundary {unknown[0]!r}; allowed "
                         f"{', '.join(BOUNDARY_NAMES)}")
    for column in CSV_COLUMNS:
        if column in ("boundary", "point", "physical", "certified"):
            continue
        values = pd.to_numeric(frame[column], errors="coerce")
        finite_required = column not in ("T_over_N_L", "T_over_N_R")
        bad = values.isna() | (~np.isfinite(values) if finite_required else False)
        if bad.any():
            row = int(np.flatnonzero(bad.to_numpy())[0])
            shown = frame[column].iloc[row]
            shown = float(shown) if isinstance(shown, (float, np.floating)) else shown
            raise ValueError(f"{path}: column {column} = {shown!r} in data row "
                             f"{row + 1} is not a {'finite ' if finite_required else ''}number")
        frame[column] = values.astype(float)
    for column, traced in (("k", check_traced_friction), ("compliance", check_traced_ratio)):
        values = list(dict.fromkeys(frame[column]))
        for value in values:  # in the range the boundaries are traced for (0 and 1e9 alike)
            try:
                traced(float(value))
            except ValueError as exc:
                row = int(np.flatnonzero((frame[column] == value).to_numpy())[0])
                raise ValueError(f"{path}: data row {row + 1}: {exc}") from None
        if len(values) > 1:
            raise ValueError(
                f"{path}: column {column} holds {len(values)} values ("
                f"{', '.join(map(k_text, values[:3]))}{', ...' if len(values) > 3 else ''}); "
                f"a boundaries CSV holds one {column}, as groove trace writes it")
    _check_domain_rows(path, frame)
    physical = frame["physical"].astype(str).str.lower()
    certified = frame["certified"].fillna("").astype(str).str.lower()
    for column, values, allowed in (("physical", physical, "True or False"),
                                    ("certified", certified, "True, False or empty")):
        bad = ~values.isin(["true", "false"] + ([""] if column == "certified" else []))
        if bad.any():
            row = int(np.flatnonzero(bad.to_numpy())[0])
            raise ValueError(f"{path}: column {column} = {frame[column].iloc[row]!r} in data row "
                             f"{row + 1} is not {allowed}")
    frame["physical"] = physical.eq("true")
    frame["certified"] = certified.map({"true": True, "false": False, "": None})
    frame["point"] = frame["point"].fillna("")
    kinds = [kind.value for kind in PointKind]
    bad = ~frame["point"].isin(["", *kinds])
    if bad.any():
        row = int(np.flatnonzero(bad.to_numpy())[0])
        raise ValueError(f"{path}: column point = {frame['point'].iloc[row]!r} in data row "
                         f"{row + 1} is not empty or one of {', '.join(kinds)}")
    # the boundaries in their order, each along its arclength s, whatever the file's order
    order = frame["boundary"].map({name: i for i, name in enumerate(BOUNDARY_NAMES)})
    return frame.assign(_order=order).sort_values(["_order", "s"], kind="stable") \
        .drop(columns="_order").reset_index(drop=True)


#: the boundaries ``groove trace`` writes for every ``k`` (``dr_no_roll`` only for some)
_ALWAYS = ("dr_limit", "rs_limit", "rs_no_roll")


def incomplete_boundaries(frame: pd.DataFrame) -> list[str]:
    """What a boundaries table (:func:`read_boundaries_csv`) lacks of a whole trace, in words.

    ``groove trace`` writes ``dr_limit``, ``rs_limit`` and ``rs_no_roll`` for every ``k``, and
    marks the first and the last row of each boundary (``start``, ``branch_point`` or
    ``junction``; ``end`` or ``junction``). A boundary missing, or one whose first or last row
    is unmarked, shows a file cut short or edited (or the rows of a failed trace); an empty
    list, none of that.
    """
    problems = [f"no {name} rows" for name in _ALWAYS if name not in set(frame["boundary"])]
    for name, rows in frame.groupby("boundary", sort=False):
        for where, row in (("first", rows.iloc[0]), ("last", rows.iloc[-1])):
            if not row["point"]:
                problems.append(f"the {where} row of {name} (s = {float(row['s']):.6g}) is not "
                                f"marked as its {'start' if where == 'first' else 'end'}")
    return problems


def _check_domain_rows(path: Path, frame: pd.DataFrame) -> None:
    """Raise ``ValueError`` naming the first row outside ``0 <= delta <= gamma <= pi/2``.

    The slack is that of :func:`~groove_model.model.parameters.check_domain` (the tracer keeps
    its rows inside the domain exactly, and 17 digits read back exactly).
    """
    slack = 4.0 * np.finfo(float).eps
    gamma, delta = frame["gamma"].to_numpy(), frame["delta"].to_numpy()
    for bad, name, allowed in (
            ((gamma < 0.0) | (gamma > 0.5 * np.pi * (1.0 + slack)), "gamma",
             "0 <= gamma <= pi/2"),
            ((delta < 0.0) | (delta > gamma * (1.0 + slack)), "delta", "0 <= delta <= gamma")):
        if np.any(bad):
            row = int(np.flatnonzero(bad)[0])
            raise ValueError(f"{path}: column {name} = {float(frame[name].iloc[row])!r} in data "
                             f"row {row + 1} is outside the allowed range {allowed} (gamma = "
                             f"{float(gamma[row])!r}, delta = {float(delta[row])!r}, radians)")
