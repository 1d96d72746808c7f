"""``groove sweep``: every boundary for many ``k``, in parallel, streamed to two CSV files."""

from __future__ import annotations

import contextlib
import signal
import sys
import threading
import time

from .common import (
    EXIT_FAILED,
    EXIT_OK,
    UsageError,
    add_command,
    add_compliance_options,
    compliance_from,
    compliance_label,
    output_directory,
    positive_integer,
    refuse_blocked,
    require_certify_extra,
    traced_friction,
)

__all__ = ["Progress", "add_parser", "run", "sweep_values"]

_EXAMPLES = """examples:
  groove sweep --k-min 1e-2 --k-max 1e3 -n 200 --jobs 4 --out sweep/
  groove sweep --k-min 0.5 --k-max 2 -n 11 --out out/ --keep-unphysical

writes sweep_boundaries.csv (the rows of every k, with a k column, as in boundaries_k*.csv)
and sweep_special_points.csv (the special points of every k) into --out; with another
compliance than the paper's, the names end in it (sweep_boundaries_nu0.3.csv for --poisson 0.3,
_c0.8 for --compliance 0.8). The bytes do not depend on --jobs. The k are log-spaced from
--k-min to --k-max. Nothing is written if any k fails (exit code 1, the failures on stderr).
A progress bar is shown on a terminal only.
"""


#: most k of one sweep: about 8 hours of one process at 30 ms per k
MAX_K_VALUES = 1_000_000
#: most worker processes
MAX_JOBS = 256


def add_parser(subparsers):
    """Register ``groove sweep``; returns its parser."""
    p = add_command(
        subparsers, "sweep",
        description="Trace every regime boundary (as groove trace does) for n values of k "
                    "log-spaced from --k-min to --k-max, on --jobs processes, and stream the "
                    "rows into one CSV in long format (a k column) plus one table of the "
                    "special points of every k.",
        examples=_EXAMPLES)
    p.add_argument("--k-min", required=True, type=traced_friction,
                   help="smallest k (1e-4 <= k <= 1e6)")
    p.add_argument("--k-max", required=True, type=traced_friction,
                   help="largest k (>= --k-min, <= 1e6)")
    p.add_argument("-n", required=True, type=positive_integer("-n", MAX_K_VALUES),
                   help=f"number of k values (1 to {MAX_K_VALUES:,})")
    p.add_argument("--jobs", type=positive_integer("--jobs", MAX_JOBS), default=1,
                   help=f"worker processes (default 1: in this process; at most {MAX_JOBS})")
    p.add_argument("--out", required=True, help="output directory (created if needed)")
    p.add_argument("--certify", action="store_true",
                   help="prove every boundary in ball arithmetic (needs python-flint); a k "
                        "with a boundary not proven fails")
    add_compliance_options(p)
    p.add_argument("--keep-unphysical", action="store_true",
                   help="keep the parts of each boundary where its regime is not valid")
    p.set_defaults(run=run, outputs=outputs)
    return p


def sweep_values(k_min: float, k_max: float, n: int) -> list:
    """``n`` values log-spaced from ``k_min`` to ``k_max`` (both included)."""
    # Imported here, not at the top: `groove --help` does not wait for numpy.
    import numpy as np

    return np.geomspace(k_min, k_max, n).tolist()


class Progress:
    """A one-line progress bar on ``stream``, drawn only if it is a terminal."""

    def __init__(self, total: int, stream=None, width: int = 30) -> None:
        self.stream = sys.stderr if stream is None else stream
        self.total = total
        self.width = width
        self.done = 0
        self.start = time.monotonic()
        isatty = getattr(self.stream, "isatty", None)
        self.active = bool(isatty and isatty())

    def __call__(self, result=None) -> None:
        self.done += 1
        if not self.active:
            return
        filled = self.width * self.done // self.total
        elapsed = time.monotonic() - self.start
        self.stream.write(f"\r[{'#' * filled}{'.' * (self.width - filled)}] "
                          f"{self.done}/{self.total} k, {elapsed:.0f} s")
        if self.done == self.total:
            self.stream.write("\n")
        self.stream.flush()


class _Termination:
    """Turns SIGTERM (and SIGHUP) into ``SystemExit(128 + signal)`` raised between two results
    of the sweep, so a killed sweep removes its temporary files and stops its workers like an
    interrupted one.

    The handler only records the signal: an exception raised inside the process pool's own
    bookkeeping (starting its threads and processes) could leave it unable to shut down.
    """

    def __init__(self, progress: Progress) -> None:
        self.progress = progress
        self.signum: int | None = None

    def __call__(self, result) -> None:
        self.progress(result)
        if self.signum is not None:
            self.exit()

    def exit(self) -> None:
        """Say so and end with ``128 + signal``, as a shell reports a process a signal ended."""
        signum = int(self.signum or signal.SIGTERM)
        print(f"groove sweep: terminated by {signal.Signals(signum).name}; nothing written",
              file=sys.stderr)
        raise SystemExit(128 + signum)

    @contextlib.contextmanager
    def installed(self):
        if threading.current_thread() is not threading.main_thread():
            yield self  # signal handlers can only be set in the main thread
            return

        def record(signum, frame):
            self.signum = signum

        # SIGHUP (the terminal closed) as SIGTERM; it does not exist on Windows
        signums = [signal.SIGTERM, *([signal.SIGHUP] if hasattr(signal, "SIGHUP") else [])]
        previous = {signum: signal.signal(signum, record) for signum in signums}
        try:
            yield self
        finally:
            for signum, handler in previous.items():
                signal.signal(signum, handler)
        if self.signum is not None:
            self.exit()


def outputs(args) -> list:
    """The two files ``groove sweep`` would write for ``args``."""
    from ..io.sweep import sweep_files  # pandas: not at `groove --help`

    return sweep_files(args.out, suffix=compliance_label(compliance_from(args)))


def run(args) -> int:
    """Trace every ``k``; write the two files and return 0, or write nothing and return 1."""
    # Imported here, not at the top: the tracer and the CSV files load the engine and pandas,
    # and the pool multiprocessing, which `groove --help` and `groove solve` should not wait for.
    from concurrent.futures.process import BrokenProcessPool

    from ..io.sweep import write_sweep  # pandas (see above)
    from ..model.parameters import k_text  # numpy (see above)
    from ..tracing import WorkerStopped, sweep_results  # the engine (see above)

    if not args.k_min <= args.k_max:
        raise UsageError(f"--k-min = {k_text(args.k_min)} must be <= --k-max = "
                         f"{k_text(args.k_max)}")
    if args.n == 1 and args.k_min != args.k_max:
        raise UsageError(f"-n 1 traces one k, but --k-min = {args.k_min!r} and --k-max = "
                         f"{args.k_max!r} differ: give -n >= 2, or the same k twice")
    if args.n > 1 and args.k_min == args.k_max:
        raise UsageError(f"-n {args.n} values of k from --k-min = {args.k_min!r} to --k-max = "
                         f"{args.k_max!r} would all be that one k: give -n 1, or a wider range")
    ks = sweep_values(args.k_min, args.k_max, args.n)
    distinct = len(set(ks))
    if distinct < len(ks):
        # rows are told apart by their k alone: two blocks of one k would read as one
        raise UsageError(f"-n {args.n} values of k log-spaced from --k-min = {k_text(args.k_min)} "
                         f"to --k-max = {k_text(args.k_max)} are only {distinct} distinct "
                         "numbers: give a smaller -n or a wider range")
    out = output_directory(args.out)
    compliance = compliance_from(args)
    refuse_blocked(outputs(args))
    if args.certify:
        require_certify_extra()
    results = sweep_results(ks, jobs=args.jobs, keep_unphysical=args.keep_unphysical,
                            compliance=compliance, certify=args.certify)
    termination = _Termination(Progress(len(ks)))
    try:
        with termination.installed() as progress:
            paths, failed = write_sweep(results, out, suffix=compliance_label(compliance),
                                        progress=progress)
    except (BrokenProcessPool, WorkerStopped) as exc:
        if termination.signum is not None:  # the signal reached this process too
            termination.exit()
        # a worker was killed (out of memory, a signal to it alone, or a Ctrl-C that reached the
        # workers while the parent was starting them, where Python can drop the parent's), or
        # stopped by a signal to it alone
        what = str(exc) if isinstance(exc, WorkerStopped) else (
            "a worker process ended abruptly (killed, interrupted or out of memory)")
        print(f"groove sweep: error: {what}; nothing written", file=sys.stderr)
        return EXIT_FAILED
    for result in failed:
        for failure in result.failures:
            print(f"groove sweep: error: k = {k_text(result.k)}: {failure}", file=sys.stderr)
    if failed:
        print(f"groove sweep: nothing written: {len(failed)} of {len(ks)} k failed (see above)",
              file=sys.stderr)
        return EXIT_FAILED
    print(f"{len(ks)} k from {k_text(args.k_min)} to {k_text(args.k_max)}: "
          f"{', '.join(str(p) for p in paths)}")
    return EXIT_OK
