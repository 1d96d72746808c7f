"""CSV export and import of traced boundaries, written atomically.

A file is written to a temporary name in its target directory and moved into place with
``os.replace``, so a reader (or a crash) never sees a half-written file.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

from ..model.boundaries import BOUNDARY_NAMES
from ..tracing import CSV_COLUMNS, SPECIAL_POINT_COLUMNS, BoundarySet

__all__ = ["atomic_write", "boundary_file_names", "read_boundaries_csv", "write_boundary_set"]


def atomic_write(path, write) -> Path:
    """Call ``write(tmp_path)`` and move the result to ``path`` atomically.

    Parameters
    ----------
    path : path-like
        Target file; its directory must exist.
    write : callable
        ``write(tmp_path)`` creates the file at ``tmp_path`` (same directory, same suffix).
    """
    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}-", suffix=path.suffix, dir=path.parent)
    os.close(fd)
    try:
        write(tmp)
        # mkstemp creates 0600; give the file the permissions an ordinary open() would.
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path


def boundary_file_names(k: float) -> tuple[str, str]:
    """``boundaries_k{k:g}.csv`` and ``special_points_k{k:g}.csv``."""
    return f"boundaries_k{k:g}.csv", f"special_points_k{k:g}.csv"


def write_boundary_set(boundary_set: BoundarySet, directory) -> tuple[Path, Path]:
    """Write the pair of CSV files of one ``k`` into ``directory`` (created if needed).

    Floats are written with 17 significant digits, so a row recomputed from its own columns
    reproduces the traced point exactly.
    """
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    points_name, specials_name = boundary_file_names(boundary_set.k)
    points = boundary_set.to_frame()
    specials = boundary_set.special_points_frame()[list(SPECIAL_POINT_COLUMNS)]
    paths = []
    for frame, name in ((points, points_name), (specials, specials_name)):
        paths.append(atomic_write(directory / name,
                                  lambda tmp, f=frame: f.to_csv(tmp, index=False,
                                                                float_format="%.17g")))
    return paths[0], paths[1]


def read_boundaries_csv(path) -> pd.DataFrame:
    """Read a ``boundaries_k*.csv`` file and check its columns.

    Raises
    ------
    OSError
        If the file cannot be read.
    ValueError
        If it is not a boundaries CSV: missing columns, no rows, an unknown boundary name, or
        a value that is not a number (the message names the column, value and row).

    Notes
    -----
    ``certified`` is True (proven), False (certification failed) or empty (not asked for,
    or a file written before the column existed), read as True, False or None.
    """
    path = Path(path)
    try:
        frame = pd.read_csv(path, keep_default_na=False, na_values={"": []},
                            dtype={"point": str, "boundary": str, "certified": str})
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as exc:
        raise ValueError(f"{path}: not a boundaries CSV ({exc})") from None
    if "certified" not in frame.columns:
        frame["certified"] = ""  # written before certification existed: not certified
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
            raise ValueError(f"{path}: column {column} = {frame[column].iloc[row]!r} in data row "
                             f"{row + 1} is not a {'finite ' if finite_required else ''}number")
        frame[column] = values.astype(float)
    if not np.all(frame["k"] > 0):
        raise ValueError(f"{path}: column k must be > 0")
    frame["point"] = frame["point"].fillna("")
    physical = frame["physical"].astype(str).str.lower()
    if not physical.isin(["true", "false"]).all():
        raise ValueError(f"{path}: column physical must be True or False")
    frame["physical"] = physical.eq("true")
    certified = frame["certified"].fillna("").astype(str).str.lower()
    if not certified.isin(["true", "false", ""]).all():
        raise ValueError(f"{path}: column certified must be True, False or empty")
    frame["certified"] = certified.map({"true": True, "false": False, "": None})
    return frame
