"""CSV export and import of traced boundaries, written atomically.

A file is written to a temporary name in its target directory, flushed to disk and moved into
place with ``os.replace``, so a reader (or a crash) never sees a half-written file. A writer
killed outright (SIGKILL, power loss) cannot remove its temporary file; the name records
the owning process, and the next write into that directory removes the temporary files of
owners that no longer run.
"""

from __future__ import annotations

import logging
import os
import re
import secrets
import socket
from pathlib import Path

import numpy as np
import pandas as pd

from ..model.boundaries import BOUNDARY_NAMES
from ..tracing import CSV_COLUMNS, SPECIAL_POINT_COLUMNS, BoundarySet

__all__ = [
    "atomic_write",
    "boundary_file_names",
    "read_boundaries_csv",
    "remove_stale_temporaries",
    "write_boundary_set",
]

logger = logging.getLogger(__name__)

#: ``.{stem}.partial-{pid}@{owner}.{token}{suffix}``; ``owner`` is the host name (letters,
#: digits and ``-`` only) and, where the system has them, the inode of the pid namespace, so
#: that a pid is only ever compared with pids of the same host and namespace
_TEMPORARY_NAME = re.compile(
    r"\.(?P<stem>.*)\.partial-(?P<pid>[0-9]{1,10})@(?P<owner>[A-Za-z0-9-]{1,80})"
    r"\.(?P<token>[0-9a-f]{16})(?P<suffix>\.[^./]*)?")


def _owner() -> str:
    """This process's host (and pid namespace): where its pid means something."""
    host = re.sub(r"[^A-Za-z0-9-]", "-", socket.gethostname())[:63] or "localhost"
    try:
        namespace = os.readlink("/proc/self/ns/pid")
    except OSError:
        return host
    digits = re.sub(r"[^0-9]", "", namespace)
    return f"{host}-ns{digits}"[:80] if digits else host


def _process_exists(pid: int) -> bool:
    """Whether ``pid`` names a process of this host; ``True`` whenever that is not certain."""
    if os.name != "posix":
        # os.kill(pid, 0) terminates the process on Windows; never treat an owner as gone there
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (OSError, OverflowError):
        # PermissionError: it exists and belongs to someone else
        return True
    return True


def remove_stale_temporaries(directory) -> list[Path]:
    """Remove the temporary files left in ``directory`` by writers that no longer run.

    A temporary file of :func:`atomic_write` is named
    ``.{stem}.partial-{pid}@{owner}.{token}{suffix}``. It is removed only if its ``owner`` is
    this host (and pid namespace) and no process ``pid`` exists there. Files of live writers,
    of other hosts, and every file not named like that are left alone; so is a file whose pid
    has since been reused by another process (it goes once that process ends).

    Parameters
    ----------
    directory : path-like
        Directory to clean; if it cannot be listed nothing is removed.

    Returns
    -------
    list of Path
        The files removed.
    """
    directory = Path(directory)
    owner, me = _owner(), os.getpid()
    removed = []
    try:
        entries = list(os.scandir(directory))
    except OSError as exc:
        logger.debug("cannot list %s for stale temporary files: %s", directory, exc)
        return removed
    for entry in entries:
        match = _TEMPORARY_NAME.fullmatch(entry.name)
        if match is None or match["owner"] != owner:
            continue
        pid = int(match["pid"])
        if pid == me or _process_exists(pid):
            continue
        try:
            if not entry.is_file(follow_symlinks=False):
                continue
            os.unlink(entry.path)
        except FileNotFoundError:
            continue  # another writer removed it first
        except OSError as exc:
            logger.warning("cannot remove stale temporary file %s: %s", entry.path, exc)
            continue
        logger.info("removed %s, left by process %d that no longer runs", entry.path, pid)
        removed.append(Path(entry.path))
    return removed


def _create_temporary(path: Path) -> Path:
    """Create an empty temporary file for ``path`` (mode ``0o666`` less the umask)."""
    # a long stem is cut so that the name stays within the usual 255-byte limit
    prefix = f".{path.stem[:120]}.partial-{os.getpid()}@{_owner()}."
    while True:
        tmp = path.with_name(f"{prefix}{secrets.token_hex(8)}{path.suffix}")
        try:
            fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
        except FileExistsError:
            continue
        os.close(fd)
        return tmp


def _sync_file(path: Path) -> None:
    # Windows' fsync (_commit) needs a descriptor open for writing
    fd = os.open(path, os.O_RDONLY if os.name == "posix" else os.O_RDWR)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def _sync_directory(directory: Path) -> None:
    """Make a rename in ``directory`` durable, where the system can (not on Windows)."""
    try:
        fd = os.open(directory, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def atomic_write(path, write) -> Path:
    """Call ``write(tmp_path)`` and move the result to ``path`` atomically.

    Parameters
    ----------
    path : path-like
        Target file; its directory must exist.
    write : callable
        ``write(tmp_path)`` creates the file at ``tmp_path`` (same directory, same suffix).

    Returns
    -------
    Path
        ``path``.

    Notes
    -----
    The temporary file is created with the permissions an ordinary ``open()`` would give
    (``0o666`` less the umask), synced to disk before ``os.replace`` and the directory after
    it, so that neither a killed process nor a power loss leaves a truncated ``path``. Any
    exception removes it; a writer killed outright cannot, and the next call in the same
    directory removes it (:func:`remove_stale_temporaries`).
    """
    path = Path(path)
    remove_stale_temporaries(path.parent)
    tmp = _create_temporary(path)
    try:
        write(tmp)
        _sync_file(tmp)
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    _sync_directory(path.parent)
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
    """
    path = Path(path)
    try:
        frame = pd.read_csv(path, keep_default_na=False, na_values={"": []},
                            dtype={"point": str, "boundary": str})
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as exc:
        raise ValueError(f"{path}: not a boundaries CSV ({exc})") from None
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
        if column in ("boundary", "point", "physical"):
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
    return frame
