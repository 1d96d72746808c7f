"""A sweep over many ``k`` streamed to two CSV files, written atomically.

The rows of each ``k`` are appended as its result arrives, so memory does not grow with the
number of ``k``; the files appear under their names only once every ``k`` has been written.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable, Iterable
from pathlib import Path

from ..tracing import SPECIAL_POINT_COLUMNS, SweepResult

__all__ = ["SWEEP_FILES", "write_sweep"]

#: the boundary rows of every k (long format) and the special points of every k
SWEEP_FILES = ("sweep_boundaries.csv", "sweep_special_points.csv")


def _temporary(path: Path):
    fd, name = tempfile.mkstemp(prefix=f".{path.stem}-", suffix=path.suffix, dir=path.parent)
    return os.fdopen(fd, "w", newline=""), Path(name)


def write_sweep(results: Iterable[SweepResult], directory,
                progress: Callable[[SweepResult], None] | None = None):
    """Stream every result into ``directory`` (created if needed); keep them only if all are ok.

    Parameters
    ----------
    results : iterable of SweepResult
        In the order the rows are to be written (e.g. :func:`groove_model.tracing.sweep_results`).
    directory : path-like
    progress : callable, optional
        Called with each result after its rows are written.

    Returns
    -------
    paths : tuple of Path
        The two files (:data:`SWEEP_FILES`), or ``()`` if a ``k`` failed (nothing is left).
    failed : list of SweepResult
        The results that were not ok.

    Notes
    -----
    Floats are written with 17 significant digits, as by :func:`write_boundary_set`, so the
    bytes depend only on the traced values, not on how the sweep was run.
    """
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    targets = [directory / name for name in SWEEP_FILES]
    opened = [_temporary(path) for path in targets]
    failed = []
    try:
        first = True
        for result in results:
            tables = (result.boundaries, result.special_points[list(SPECIAL_POINT_COLUMNS)])
            for (handle, _), table in zip(opened, tables):
                table.to_csv(handle, header=first, index=False, float_format="%.17g")
            first = False
            if not result.ok:
                failed.append(result)
            if progress is not None:
                progress(result)
        for handle, _ in opened:
            handle.close()
        if failed or first:
            for _, name in opened:
                name.unlink(missing_ok=True)
            return (), failed
        umask = os.umask(0)
        os.umask(umask)
        for (_, name), path in zip(opened, targets):
            # mkstemp creates 0600; give the file the permissions an ordinary open() would.
            os.chmod(name, 0o666 & ~umask)
            os.replace(name, path)
        return tuple(targets), failed
    except BaseException:
        for handle, name in opened:
            handle.close()
            name.unlink(missing_ok=True)
        raise
