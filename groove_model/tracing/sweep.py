"""Many values of ``k`` at once: serial, on a process pool, or on any executor.

Each ``k`` is traced by :func:`~groove_model.tracing.tracer.trace_boundaries`, independently of
the others, and reduced to its two tables (the boundary rows, :data:`CSV_COLUMNS`, and the
special points, :data:`SPECIAL_POINT_COLUMNS` plus ``note``). The tables are computed where the
``k`` is traced (in the worker process when there is one) by the same code in the same order, so
the result does not depend on how the sweep is run: serially, with ``jobs`` processes, or on an
executor the caller passes (a ``concurrent.futures`` process pool, or e.g. Dask's
``Client.get_executor()`` to spread a sweep over machines).

Results come back in the order of the ``k`` values while at most a bounded number of chunks are
in flight, so a sweep can be streamed to disk (:func:`sweep_results`) in constant memory however
many ``k`` it has.
"""

from __future__ import annotations

import collections
import concurrent.futures
import os
import signal
import threading
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from continuation import Options

from ..model.parameters import (
    Compliance,
    Parameters,
    check_flag,
    traced_compliance,
    traced_friction,
)
from .curves import CSV_COLUMNS, TraceError
from .tracer import trace_boundaries

if TYPE_CHECKING:  # pandas is imported where a table is made: `groove atlas` needs none
    import pandas as pd

__all__ = ["SweepError", "SweepResult", "WorkerStopped", "sweep_results", "trace_many"]

#: most ``k`` per task sent to a worker: large enough to amortise the round trip, small enough
#: to balance the load and keep the window of results in flight small
MAX_CHUNK = 16

#: chunks in flight per worker: enough to keep every worker busy while the results are consumed
WINDOW_PER_WORKER = 4


@dataclass(frozen=True)
class SweepResult:
    """The traced boundaries of one ``k`` of a sweep, as tables.

    Attributes
    ----------
    k : float
    ok : bool
        Whether every boundary was traced to its expected end (``BoundarySet.ok``) and, if
        certification was asked for, proven.
    failures : tuple of str
        What failed (``BoundarySet.failures``, then each boundary not proven with its
        certificate's message); empty when ``ok``.
    notes : tuple of str
        ``BoundarySet.notes``.
    boundaries : pandas.DataFrame
        The boundary rows (columns :data:`CSV_COLUMNS`); of a failed ``k``, the rows traced
        before the failure, which are not whole boundaries.
    special_points : pandas.DataFrame
        The special points (columns :data:`SPECIAL_POINT_COLUMNS` and ``note``).
    """

    k: float
    ok: bool
    failures: tuple = ()
    notes: tuple = ()
    boundaries: pd.DataFrame = field(default=None, repr=False)
    special_points: pd.DataFrame = field(default=None, repr=False)


class SweepError(TraceError):
    """A ``k`` of a sweep failed; ``results`` holds every result, the failed ones included."""

    def __init__(self, message: str, results: list) -> None:
        super().__init__(message, None)
        self.results = results


class WorkerStopped(RuntimeError):
    """A worker process of ``jobs`` was stopped by a signal (Ctrl-C, SIGTERM, SIGHUP) before it
    had traced its whole chunk: the sweep has no result for the rest of the chunk."""


#: the signals a worker process of ``jobs`` has received (:func:`_worker_signals`)
_STOP_SIGNALS: list[int] = []


def _trace_chunk(ks: list[float], keep_unphysical: bool, options: Options | None,
                 compliance: Compliance, certify: bool = False) -> list:
    """Trace a chunk of checked ``k`` values (in a worker, or in this process); picklable.

    A worker that has received a stopping signal raises :class:`WorkerStopped` before its next
    ``k``: its chunk is then not a result, however short."""
    results = []
    for k in ks:
        if _STOP_SIGNALS:
            raise WorkerStopped(f"a worker process was stopped by signal {_STOP_SIGNALS[0]} "
                                f"({signal.Signals(_STOP_SIGNALS[0]).name}) before k = {k!r}")
        traced = trace_boundaries(Parameters(k, compliance), keep_unphysical=keep_unphysical,
                                  options=options, certify=certify)
        # with certify, a boundary not proven fails its k (as groove trace --certify exits 1)
        unproven = tuple(f"{c.name}: {c.certificate.message}" for c in traced.curves.values()
                         if c.certified is False)
        results.append(SweepResult(traced.k, traced.ok and not unproven,
                                   traced.failures + unproven, traced.notes,
                                   traced.to_frame(partial=True),
                                   traced.special_points_frame(partial=True)))
    return results


def _check_ks(ks, compliance: Compliance | float | None) -> tuple[list[float], Compliance]:
    """Every ``k`` as a float and the compliance, checked before anything is traced.

    The same checks as :func:`trace_boundaries` (a real number, finite, in the traced range,
    with the compliance's ratio in its own), all up front, so that a bad ``k`` at the end of
    a sweep does not throw away the traces before it. Floats, not :class:`Parameters`: a
    sweep of 1e5 ``k`` holds them all.
    """
    if isinstance(ks, (str, bytes)) or not isinstance(ks, Iterable):
        raise TypeError(f"ks must be an iterable of numbers, got {ks!r}")
    compliance = traced_compliance(compliance)   # or a ratio, as for the atlas
    values = []
    for k in ks:
        if isinstance(k, Parameters):
            raise TypeError(f"ks must be friction coefficients (real numbers), got {k!r}: give "
                            "the compliance, the same for every k, as compliance=")
        values.append(traced_friction(k))  # TypeError for str, bool, ...
    return values, compliance


def _workers(jobs, executor) -> int:
    """How many tasks run at once: ``jobs``, the executor's own count, or the CPUs."""
    if executor is not None:
        count = getattr(executor, "_max_workers", None)
        return count if isinstance(count, int) and count > 0 else (os.cpu_count() or 1)
    return jobs


def _worker_signals() -> None:
    """In each worker of ``--jobs``: Ctrl-C, SIGTERM and SIGHUP stop the worker before its next
    ``k`` (:class:`WorkerStopped`), and the end of its parent process, however it ended, ends it.

    Ctrl-C at a terminal, and ``timeout`` or a service manager's SIGTERM, reach the whole
    process group. A worker the signal killed outright (the default action) could die while
    sending its result: the half message left in the pool's pipe, which the parent holds open
    too, blocked the pool's thread in the parent for ever, and the sweep hung. Here the
    handler only records the signal, a result being sent is sent whole, and the worker stops
    between two ``k``: the parent, which handles the signal itself, stops the sweep and writes
    nothing, within one ``k`` of each worker; a signal to a worker alone fails the sweep with
    a message. (Left to Python's own handler, a worker also printed a ``KeyboardInterrupt``
    traceback; a forked worker inherited the parent's SIGTERM handler, which only records the
    signal in the parent, and ran on.) A Ctrl-C the parent ignores (a background job) stays
    ignored in the workers too. A parent killed outright (SIGKILL, the out-of-memory killer)
    handles nothing: its workers, which hold both ends of the pool's pipes themselves, waited
    for their next chunk for ever; :func:`_watch_parent` ends them.
    """
    def stop(signum, frame) -> None:
        _STOP_SIGNALS.append(signum)

    if signal.getsignal(signal.SIGINT) is not signal.SIG_IGN:
        signal.signal(signal.SIGINT, stop)
    for name in ("SIGTERM", "SIGHUP"):  # no SIGHUP on Windows
        if hasattr(signal, name):
            signal.signal(getattr(signal, name), stop)
    threading.Thread(target=_watch_parent, daemon=True, name="groove-watch-parent").start()


def _watch_parent() -> None:
    """End this worker process once the process that started it has ended.

    It waits on the pipe that :mod:`multiprocessing` gives every child for this
    (``parent_process().join()``): the pipe is closed when the sweep's process ends, however its
    workers were started (forked, spawned, or by a fork server, whose workers' parent process
    outlives the sweep).
    """
    import multiprocessing  # in a worker only, where the pool has loaded it: 13 ms otherwise

    parent = multiprocessing.parent_process()
    if parent is None:  # not started by multiprocessing: nothing to watch
        return
    parent.join()
    os._exit(1)  # nobody reads the results: no clean-up to do, no message to give


def _in_order(executor, function, chunks: list, window: int, args: tuple,
              cancel: bool = True) -> Iterator[list]:
    """``function(chunk, *args)`` for each chunk on ``executor``, in order, ``window`` at a time;
    the chunks not yet started are cancelled when the caller stops early, if ``cancel``."""
    pending: collections.deque = collections.deque()
    remaining = iter(chunks)
    try:
        for chunk in remaining:
            pending.append(executor.submit(function, chunk, *args))
            if len(pending) >= window:
                break
        while pending:
            done = pending.popleft().result()
            chunk = next(remaining, None)
            if chunk is not None:
                pending.append(executor.submit(function, chunk, *args))
            yield done
    finally:
        for future in pending if cancel else ():
            future.cancel()


def sweep_results(ks: Iterable[float], *, jobs: int | None = None,
                  executor: concurrent.futures.Executor | None = None,
                  keep_unphysical: bool = False,
                  options: Options | None = None,
                  compliance: Compliance | float | None = None,
                  certify: bool = False) -> Iterator[SweepResult]:
    """Trace every ``k`` and yield one :class:`SweepResult` per ``k``, in the order given.

    Parameters
    ----------
    ks : iterable of float
        Friction coefficients, each in the traced range 1e-4 <= k <= 1e6 (duplicates are
        traced again).
    jobs : int or None
        ``None`` or 1: trace in this process; ``N >= 2``: on a pool of ``N`` processes.
    executor : concurrent.futures.Executor, optional
        Run the traces there instead (``jobs`` must then be ``None``); the executor is not
        shut down. Its workers must be able to import ``groove_model``.
    keep_unphysical, options, certify
        As for :func:`~groove_model.tracing.tracer.trace_boundaries`; with ``certify``, a ``k``
        with a boundary not proven is a failure.
    compliance : Compliance or float, optional
        The contact's compliance or its ratio ``c`` (default the paper's law, ``c = 1``), the
        same for every ``k``; ``2/3 <= c <= 1``.

    Yields
    ------
    SweepResult
        Failures are yielded like any result (``ok = False``), never skipped. A worker of
        ``jobs`` stopped by a signal (Ctrl-C, SIGTERM, SIGHUP) raises :class:`WorkerStopped`
        where its results would come.

    Raises
    ------
    ValueError
        When called, before anything is traced: if a ``k`` is outside the traced range
        (or not finite), the compliance ratio outside ``[2/3, 1]``, ``jobs`` is not ``None``
        or an integer >= 1, or both ``jobs`` and ``executor`` are given.
    TypeError
        When called: if ``ks`` is a string or not iterable, a ``k`` or the compliance is not
        a real number, a flag not a bool, or ``executor`` is not an Executor.

    Notes
    -----
    At most ``4 x workers`` chunks of at most :data:`MAX_CHUNK` ``k`` are in flight, so memory
    does not grow with the number of ``k`` when the results are consumed as they come.
    """
    values, checked = _check_ks(ks, compliance)
    keep_unphysical = check_flag("keep_unphysical", keep_unphysical)
    certify = check_flag("certify", certify)
    if jobs is not None and (isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1):
        raise ValueError(f"jobs = {jobs!r} is outside the allowed range: None or an integer "
                         ">= 1")
    if jobs is not None and executor is not None:
        raise ValueError("give jobs or executor, not both")
    if executor is not None and not isinstance(executor, concurrent.futures.Executor):
        raise TypeError(f"executor must be a concurrent.futures.Executor, got "
                        f"{type(executor).__name__}")
    # checked here, when called; the traces run as the results are consumed
    return _results(values, jobs, executor, (keep_unphysical, options, checked, certify))


def _results(values: list[float], jobs: int | None,
             executor: concurrent.futures.Executor | None, args: tuple) -> Iterator[SweepResult]:
    """The results of :func:`sweep_results`, traced as they are consumed."""
    if executor is None and (jobs is None or jobs == 1):
        for k in values:
            yield from _trace_chunk([k], *args)
        return
    workers = _workers(jobs, executor)
    size = max(1, min(MAX_CHUNK, len(values) // (WINDOW_PER_WORKER * workers)))
    chunks = [values[i:i + size] for i in range(0, len(values), size)]
    window = WINDOW_PER_WORKER * workers
    if executor is not None:
        for results in _in_order(executor, _trace_chunk, chunks, window, args):
            yield from results
        return
    pool = concurrent.futures.ProcessPoolExecutor(max_workers=jobs, initializer=_worker_signals)
    try:
        for results in _in_order(pool, _trace_chunk, chunks, window, args, cancel=False):
            yield from results
    finally:
        # the pool cancels what it has not started itself: a future cancelled from here
        # while a worker ended by Ctrl-C breaks the pool made Python 3.11's pool thread
        # fail with a traceback (InvalidStateError in terminate_broken)
        pool.shutdown(wait=True, cancel_futures=True)


def trace_many(ks: Iterable[float], jobs: int | None = None, *,
               executor: concurrent.futures.Executor | None = None,
               keep_unphysical: bool = False, options: Options | None = None,
               compliance: Compliance | float | None = None,
               certify: bool = False) -> pd.DataFrame:
    """Every boundary for many ``k``, as one table (long format, a ``k`` column).

    Parameters
    ----------
    ks : iterable of float
        Friction coefficients, each in the traced range 1e-4 <= k <= 1e6.
    jobs : int or None
        ``None`` or 1: in this process; ``N >= 2``: on a pool of ``N`` processes.
    executor : concurrent.futures.Executor, optional
        Run the traces on this executor instead (any ``concurrent.futures.Executor``: a
        process pool, or e.g. Dask's ``Client.get_executor()``).
    keep_unphysical, options, compliance, certify
        As for :func:`sweep_results`.

    Returns
    -------
    pandas.DataFrame
        The rows of every ``k`` in the order given (columns :data:`CSV_COLUMNS`), identical
        whatever ``jobs`` or ``executor``. The special points of each ``k`` are in the
        results of :func:`sweep_results`.

    Raises
    ------
    SweepError
        If a ``k`` failed; it carries every result (``.results``), the failed ones included.
    WorkerStopped
        If a worker of ``jobs`` was stopped by a signal (Ctrl-C, SIGTERM, SIGHUP).
    ValueError, TypeError
        As for :func:`sweep_results`, before anything is traced.

    Notes
    -----
    As with any process pool, a script that calls this with ``jobs >= 2`` must run its top
    level under ``if __name__ == "__main__":`` where processes are started by spawning
    (Windows, macOS, and Linux from Python 3.14).
    """
    results = list(sweep_results(ks, jobs=jobs, executor=executor,
                                 keep_unphysical=keep_unphysical, options=options,
                                 compliance=compliance, certify=certify))
    import pandas as pd  # only the joined table needs it, not the traces

    failed = [r for r in results if not r.ok]
    if failed:
        raise SweepError("; ".join(f"k = {r.k!r}: {', '.join(r.failures)}" for r in failed),
                         results)
    if not results:
        return pd.DataFrame(columns=list(CSV_COLUMNS))
    return pd.concat([r.boundaries for r in results], ignore_index=True)
