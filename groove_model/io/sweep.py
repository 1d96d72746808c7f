"""A sweep over many ``k`` streamed to two CSV files, written atomically.

The rows of each ``k`` are appended as its result arrives, so memory does not grow with the
number of ``k``; the files appear under their names only once every ``k`` has been written.
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterable
from pathlib import Path

from ..tracing import SPECIAL_POINT_COLUMNS, SweepResult
from .atomic import (
    WriteError,
    check_targets,
    commit_all,
    create_temporary,
    make_directories,
    remove_empty_directories,
    remove_stale_temporaries,
)

__all__ = ["SWEEP_FILES", "sweep_files", "write_sweep"]

#: the boundary rows of every k (long format) and the special points of every k
SWEEP_FILES = ("sweep_boundaries.csv", "sweep_special_points.csv")


def sweep_files(directory, prefix: str = "sweep", suffix: str = "") -> list[Path]:
    """The two files of :func:`write_sweep`: ``{prefix}_boundaries{suffix}.csv`` and
    ``{prefix}_special_points{suffix}.csv`` in ``directory``."""
    return [Path(directory) / f"{prefix}_{table}{suffix}.csv"
            for table in ("boundaries", "special_points")]


def _temporary(path: Path):
    name = create_temporary(path)
    try:
        return open(name, "w", newline=""), name  # closed by write_sweep
    except BaseException:
        name.unlink(missing_ok=True)  # e.g. too many open files: not left behind
        raise


def write_sweep(results: Iterable[SweepResult], directory, prefix: str = "sweep",
                suffix: str = "", progress: Callable[[SweepResult], None] | None = None):
    """Stream every result into ``directory`` (created if needed); keep them only if all are ok.

    Parameters
    ----------
    results : iterable of SweepResult
        In the order the rows are to be written (e.g. :func:`groove_model.tracing.sweep_results`).
    directory : path-like
    prefix, suffix : str
        The files are ``{prefix}_boundaries{suffix}.csv`` and
        ``{prefix}_special_points{suffix}.csv`` (:data:`SWEEP_FILES` by default); ``suffix``
        names another compliance than the paper's (e.g. ``"_nu0.3"``).
    progress : callable, optional
        Called with each result after its rows are written.

    Returns
    -------
    paths : tuple of Path
        The two files (:data:`SWEEP_FILES`), or ``()`` if a ``k`` failed (nothing is left,
        nor the directories it created).
    failed : list of SweepResult
        The results that were not ok.

    Raises
    ------
    WriteError
        Naming a file that cannot be written (checked before the first ``k`` where it can be:
        a directory in the place of a file); nothing is left.

    Notes
    -----
    Floats are written with 17 significant digits, as by :func:`write_boundary_set`, so the
    bytes depend only on the traced values, not on how the sweep was run.
    """
    directory = Path(directory)
    created = make_directories([directory])
    remove_stale_temporaries(directory)
    targets = sweep_files(directory, prefix, suffix)
    check_targets(targets)
    opened: list = []
    failed: list[SweepResult] = []
    current = targets[0]  # the file being written, for the message of a failed write
    try:
        for current in targets:
            opened.append(_temporary(current))
        first = True
        for result in results:
            tables = (result.boundaries, result.special_points[list(SPECIAL_POINT_COLUMNS)])
            for (handle, _), table, target in zip(opened, tables, targets, strict=True):
                current = target
                table.to_csv(handle, header=first, index=False, float_format="%.17g")
            first = False
            if not result.ok:
                failed.append(result)
            if progress is not None:
                progress(result)
        for (handle, _), target in zip(opened, targets, strict=True):
            current = target
            handle.close()
        if failed or first:
            for _, name in opened:
                name.unlink(missing_ok=True)
            remove_empty_directories(created)
            return (), failed
        commit_all([(name, path) for (_, name), path in zip(opened, targets, strict=True)])
        return tuple(targets), failed
    except BaseException as exc:
        for handle, name in opened:
            with contextlib.suppress(OSError):
                handle.close()  # (flushing a full disk's buffer fails again)
            name.unlink(missing_ok=True)
        remove_empty_directories(created)
        if isinstance(exc, OSError) and not isinstance(exc, WriteError):
            raise WriteError(exc.errno, f"cannot write {current}: {exc.strerror or exc}") from exc
        raise
