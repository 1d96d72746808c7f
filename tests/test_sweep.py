"""Sweeps over many k: the parallel and executor paths give what the serial one gives.

Speed is measured in benchmarks/run.py, never here: these tests check only that every way of
running a sweep returns the same curves (to 1e-12, in fact bit for bit) and the same special
points as tracing each k on its own, that ``groove sweep`` writes the same bytes for any
``--jobs``, and that its progress bar appears on a terminal only.
"""

import concurrent.futures
import contextlib
import multiprocessing
import os
import pty
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from groove_model import Compliance, trace_many
from groove_model.cli.main import main
from groove_model.cli.sweep import Progress, sweep_values
from groove_model.io.sweep import SWEEP_FILES, write_sweep
from groove_model.tracing import (
    CSV_COLUMNS,
    SPECIAL_POINT_COLUMNS,
    SweepError,
    SweepResult,
    sweep_results,
    trace_boundaries,
)

#: both sides of both thresholds (k = 1/sqrt 2, sqrt 2) and the ends of the usual range
KS = [0.05, 0.70, 0.72, 1.41, 1.42, 250.0]
NUMBERS = ["s", "gamma", "delta", "theta_L", "theta_R", "beta_L", "beta_R", "upsilon",
           "T_over_N_L", "T_over_N_R", "d_L"]


@pytest.fixture(scope="module")
def serial():
    """Each k traced on its own, as trace_boundaries returns it."""
    return {k: trace_boundaries(k) for k in KS}


def _same_curves(frame: pd.DataFrame, sets) -> None:
    expected = pd.concat([sets[k].to_frame() for k in KS], ignore_index=True)
    assert list(frame.columns) == list(CSV_COLUMNS)
    assert len(frame) == len(expected)
    for column in ("boundary", "point", "physical"):
        assert list(frame[column]) == list(expected[column]), column
    assert np.array_equal(frame["k"].to_numpy(), expected["k"].to_numpy())
    a, b = frame[NUMBERS].to_numpy(float), expected[NUMBERS].to_numpy(float)
    assert np.array_equal(np.isfinite(a), np.isfinite(b))
    finite = np.isfinite(b)
    assert np.max(np.abs(a[finite] - b[finite])) <= 1e-12
    assert frame.equals(expected)  # in fact bit for bit


def _same_special_points(results, sets) -> None:
    assert [r.k for r in results] == KS
    for result in results:
        expected = sets[result.k].special_points_frame()
        assert result.ok and result.failures == ()
        assert list(result.special_points["kind"]) == list(expected["kind"])
        assert list(result.special_points["boundary"]) == list(expected["boundary"])
        assert result.special_points.equals(expected)


def test_serial_sweep_is_each_k_on_its_own(serial):
    _same_curves(trace_many(KS), serial)
    _same_special_points(list(sweep_results(KS)), serial)


def test_process_pool_gives_the_serial_curves_and_special_points(serial):
    _same_curves(trace_many(KS, jobs=2), serial)
    _same_special_points(list(sweep_results(KS, jobs=2)), serial)


def test_any_executor_gives_the_serial_curves_and_special_points(serial):
    with concurrent.futures.ProcessPoolExecutor(max_workers=2) as executor:
        _same_curves(trace_many(KS, executor=executor), serial)
        _same_special_points(list(sweep_results(KS, executor=executor)), serial)
    with concurrent.futures.ThreadPoolExecutor(max_workers=3) as executor:
        _same_curves(trace_many(KS, executor=executor), serial)


def test_results_come_in_the_order_given_with_a_small_window():
    ks = [3.0, 0.3, 30.0, 0.03, 3.0]
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as executor:
        results = list(sweep_results(ks, executor=executor))
    assert [r.k for r in results] == ks


@pytest.mark.parametrize("bad", [[0.0], [-1.0], [float("nan")], [float("inf")], [1e-5], [2e6],
                                 [10**400], [-10**400]])
def test_bad_k_is_rejected(bad):
    with pytest.raises(ValueError, match=r"friction coefficient k = .* is outside the range the "
                                         r"boundaries are traced for: 1e-4 <= k <= 1e6"):
        trace_many(bad)


@pytest.mark.parametrize("ratio", [-1.0, 0.0, float("inf"), float("nan"), 0.5, 2.0])
def test_a_compliance_ratio_out_of_range_names_the_traced_range(ratio):
    """A ratio <= 0 or not finite gets the traced range's message too, not only "finite and
    > 0" (the range the sweep would have refused next)."""
    for call in (lambda: trace_many([1.0], compliance=ratio),
                 lambda: trace_boundaries(1.0, compliance=ratio)):
        with pytest.raises(ValueError, match=r"compliance ratio c = .* is outside the range the "
                                             r"boundaries are traced for: 2/3 <= c <= 1"):
            call()


@pytest.mark.parametrize("bad", ["12", b"12", 1.0, ["x"], [True], [1.0, None]])
def test_what_is_not_an_iterable_of_numbers_is_rejected(bad):
    # a string is not read one character at a time ("12" is not k = 1 and k = 2)
    with pytest.raises(TypeError):
        trace_many(bad)


@pytest.mark.parametrize("call", [
    lambda: trace_many([1.0], certify="no"),
    lambda: trace_many([1.0], keep_unphysical=1),
    lambda: trace_boundaries(1.0, certify="no"),
    lambda: trace_boundaries(1.0, keep_unphysical="yes"),
    lambda: trace_boundaries(1.0, raise_on_failure=None),
    lambda: trace_boundaries(0.5).to_frame(partial="no"),
    lambda: trace_boundaries(0.5).curves["dr_limit"].to_frame(partial=1),
])
def test_a_flag_that_is_not_a_bool_is_refused(call, monkeypatch):
    # certify="no" used to read as true (and certified): a flag must be True or False
    import groove_model.tracing.sweep as sweep

    monkeypatch.setattr(sweep, "_trace_chunk", lambda *args: pytest.fail("traced"))
    with pytest.raises(TypeError, match="must be True or False, got"):
        call()


def test_every_k_is_checked_before_any_is_traced(monkeypatch):
    import groove_model.tracing.sweep as sweep

    traced = []
    monkeypatch.setattr(sweep, "_trace_chunk", lambda chunk, *args: traced.extend(chunk) or [])
    with pytest.raises(ValueError, match=r"k = 1e\+07"):
        trace_many([1.0, 1e7])
    with pytest.raises(ValueError, match="compliance ratio"):
        sweep_results([1.0], compliance=0.5)  # raised when called, not when consumed
    assert traced == []


def test_a_compliance_ratio_is_read_as_trace_atlas_reads_it():
    ratio = next(sweep_results([1.0], compliance=0.8))
    compliance = next(sweep_results([1.0], compliance=Compliance(0.8)))
    pd.testing.assert_frame_equal(ratio.boundaries, compliance.boundaries)
    assert set(ratio.boundaries["compliance"]) == {0.8}


@pytest.mark.parametrize("jobs", [0, -2, 1.5, True])
def test_bad_jobs_is_rejected(jobs):
    with pytest.raises(ValueError, match="jobs"):
        sweep_results([1.0], jobs=jobs)  # when called, before anything is traced


def test_jobs_and_executor_together_are_rejected():
    with concurrent.futures.ThreadPoolExecutor(1) as executor:
        with pytest.raises(ValueError, match="not both"):
            list(sweep_results([1.0], jobs=2, executor=executor))


def _failed(k):
    empty = pd.DataFrame(columns=list(CSV_COLUMNS))
    specials = pd.DataFrame(columns=[*SPECIAL_POINT_COLUMNS, "note"])
    return SweepResult(k, False, ("rs_no_roll: it stops short",), (), empty, specials)


def test_a_failed_k_raises_with_every_result(monkeypatch):
    import groove_model.tracing.sweep as sweep

    original = sweep._trace_chunk

    def failing(ks, *args):
        return [_failed(k) if k == 2.0 else r for k, r in zip(ks, original(ks, *args))]

    monkeypatch.setattr(sweep, "_trace_chunk", failing)
    with pytest.raises(SweepError, match="k = 2.0: rs_no_roll") as error:
        trace_many([1.0, 2.0])
    assert [r.ok for r in error.value.results] == [True, False]


def test_write_sweep_leaves_nothing_when_a_k_failed(tmp_path):
    good = next(sweep_results([1.0]))
    paths, failed = write_sweep([good, _failed(2.0)], tmp_path)
    assert paths == () and [r.k for r in failed] == [2.0]
    assert list(tmp_path.iterdir()) == []


def test_sweep_values_are_log_spaced_with_exact_ends():
    values = sweep_values(1e-2, 1e3, 6)
    assert values[0] == 1e-2 and values[-1] == 1e3
    assert np.allclose(np.diff(np.log10(values)), 1.0)
    assert sweep_values(2.0, 2.0, 1) == [2.0]


def _sweep(out: Path, jobs: int, n: int = 8):
    return main(["sweep", "--k-min", "0.05", "--k-max", "50", "-n", str(n), "--jobs", str(jobs),
                 "--out", str(out)])


def test_sweep_command_writes_the_same_bytes_for_any_jobs(tmp_path, capsys):
    assert _sweep(tmp_path / "one", 1) == 0
    assert _sweep(tmp_path / "two", 2) == 0
    for name in SWEEP_FILES:
        one, two = (tmp_path / "one" / name).read_bytes(), (tmp_path / "two" / name).read_bytes()
        assert one == two and len(one) > 1000, name
    frame = pd.read_csv(tmp_path / "one" / SWEEP_FILES[0])
    assert tuple(frame.columns) == CSV_COLUMNS
    assert np.allclose(sorted(set(frame["k"])), sweep_values(0.05, 50.0, 8), rtol=1e-15)
    assert "8 k from 0.05 to 50" in capsys.readouterr().out


@pytest.mark.slow
def test_sweep_command_of_200_k_writes_the_same_bytes_for_jobs_1_and_4(tmp_path):
    args = ["sweep", "--k-min", "1e-2", "--k-max", "1e3", "-n", "200", "--out"]
    assert main([*args, str(tmp_path / "one"), "--jobs", "1"]) == 0
    assert main([*args, str(tmp_path / "four"), "--jobs", "4"]) == 0
    for name in SWEEP_FILES:
        assert (tmp_path / "one" / name).read_bytes() == (tmp_path / "four" / name).read_bytes()


@pytest.mark.parametrize("argv, message", [
    (["--k-min", "10", "--k-max", "1", "-n", "3"], "--k-min"),
    (["--k-min", "0", "--k-max", "1", "-n", "3"], "k"),
    (["--k-min", "1", "--k-max", "2", "-n", "0"], "-n"),
    (["--k-min", "1", "--k-max", "2", "-n", "3", "--jobs", "0"], "--jobs"),
    (["--k-min", "1", "--k-max", "1", "-n", "3"], "would all be that one k"),
    # geomspace gives 1 three times and 1.0000000000000002 twice: blocks of one k, not told apart
    (["--k-min", "1", "--k-max", "1.0000000000000002", "-n", "5"],
     "-n 5 values of k log-spaced from --k-min = 1 to --k-max = 1.0000000000000002 are only 2 "
     "distinct numbers"),
    (["--k-min", "1", "--k-max", "2", "-n", "1000001"], "from 1 to 1000000"),
    (["--k-min", "1", "--k-max", "2", "-n", "\uff13"], "is not an integer in ASCII digits"),
    (["--k-min", "1", "--k-max", "2", "-n", "1_000"], "is not an integer in ASCII digits"),
    (["--k-min", "1", "--k-max", "2", "-n", "3", "--jobs", "257"], "--jobs"),
])
def test_sweep_command_rejects_bad_input(tmp_path, capsys, argv, message):
    with pytest.raises(SystemExit) as exit_:
        main(["sweep", *argv, "--out", str(tmp_path / "out")])
    assert exit_.value.code == 2
    assert message in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


class _Terminal:
    def __init__(self):
        self.text = ""

    def isatty(self):
        return True

    def write(self, text):
        self.text += text

    def flush(self):
        pass


def test_progress_bar_draws_on_a_terminal_only():
    terminal = _Terminal()
    bar = Progress(4, terminal)
    for _ in range(4):
        bar()
    assert terminal.text.count("\r") == 4 and "4/4 k" in terminal.text
    assert terminal.text.endswith("\n")
    piped = _Terminal()
    piped.isatty = lambda: False
    bar = Progress(4, piped)
    bar()
    assert piped.text == ""


def _run_groove(args, stderr):
    code = "import sys; from groove_model.cli.main import main; sys.exit(main(sys.argv[1:]))"
    return subprocess.run([sys.executable, "-c", code, *args], stdout=subprocess.PIPE,
                          stderr=stderr, timeout=300)


def test_sweep_command_shows_a_bar_on_a_terminal_and_none_when_piped(tmp_path):
    args = ["sweep", "--k-min", "1", "--k-max", "2", "-n", "2"]
    piped = _run_groove([*args, "--out", str(tmp_path / "piped")], subprocess.PIPE)
    assert piped.returncode == 0 and b"\r" not in piped.stderr and b"2/2 k" not in piped.stderr
    controller, terminal = pty.openpty()
    try:
        shown = _run_groove([*args, "--out", str(tmp_path / "tty")], terminal)
        os.close(terminal)
        terminal = None
        screen = b""
        while True:
            try:
                chunk = os.read(controller, 4096)
            except OSError:
                break
            if not chunk:
                break
            screen += chunk
    finally:
        if terminal is not None:
            os.close(terminal)
        os.close(controller)
    assert shown.returncode == 0
    assert b"\r[" in screen and b"2/2 k" in screen


def _long_sweep(out: Path, start: str | None = None, **popen) -> subprocess.Popen:
    """``groove sweep`` of 4000 k on 2 processes into ``out``, started, with its pipes; its
    workers started by the ``multiprocessing`` method ``start`` if given."""
    code = "import sys; from groove_model.cli.main import main; sys.exit(main(sys.argv[1:]))"
    if start is not None:
        code = f"import multiprocessing; multiprocessing.set_start_method({start!r}); {code}"
    return subprocess.Popen([sys.executable, "-c", code, "sweep", "--k-min", "1e-3", "--k-max",
                             "1e3", "-n", "4000", "--jobs", "2", "--out", str(out)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, **popen)


def _children(pid: int) -> list[int]:
    """The child processes of ``pid``, from Linux's /proc (field 4 of ``stat`` is the parent)."""
    children = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except (OSError, IndexError):
            continue  # ended meanwhile
        if int(fields[1]) == pid:
            children.append(int(stat.parent.name))
    return children


@pytest.mark.skipif(not Path("/proc/self/task").exists(), reason="needs Linux's /proc")
@pytest.mark.parametrize("signum, message", [
    (signal.SIGTERM, b"a worker process was stopped by signal 15 (SIGTERM) before k = "),
    (signal.SIGINT, b"a worker process was stopped by signal 2 (SIGINT) before k = "),
    (signal.SIGKILL, b"a worker process ended abruptly")])
def test_a_killed_worker_fails_the_sweep_with_a_message(signum, message, tmp_path):
    # a forked worker inherited the parent's SIGTERM handler, which only records the signal, and
    # ran on (the sweep ended 0); a worker killed outright gave the pool's traceback. A worker
    # stops at its next k on a signal it can handle (it does not die while sending a result)
    out = tmp_path / "out"
    process = _long_sweep(out, start_new_session=True)
    try:
        deadline = time.monotonic() + 120
        while not _children(process.pid) and time.monotonic() < deadline:
            time.sleep(0.05)  # until the pool has started its workers
        workers = _children(process.pid)
        assert workers, "no worker process found"
        time.sleep(0.5)  # into their first chunks
        os.kill(workers[0], signum)
        _, stderr = process.communicate(timeout=120)
    finally:  # no process of the sweep left running (they hold the pipes open)
        with contextlib.suppress(ProcessLookupError):
            os.killpg(process.pid, signal.SIGKILL)
        process.communicate()
    assert process.returncode == 1, stderr
    assert message in stderr and b"nothing written" in stderr and b"Traceback" not in stderr
    assert not out.exists()  # the directory it created is removed, empty


@pytest.mark.skipif(not Path("/proc/self/task").exists(), reason="needs Linux's /proc")
@pytest.mark.parametrize("signum, code, message", [
    (signal.SIGINT, 130, b"groove sweep: interrupted"),
    (signal.SIGTERM, 143, b"groove sweep: terminated by SIGTERM; nothing written")])
@pytest.mark.parametrize("delay", [0.3, 1.1])
def test_a_signal_to_the_whole_group_ends_the_sweep_and_its_workers(signum, code, message, delay,
                                                                  tmp_path):
    # Ctrl-C at a terminal, and `timeout`, signal the whole group: a worker the signal killed
    # while it sent a result left half a message in the pool's pipe, and the sweep hung for ever
    # (3 runs in 37 with Ctrl-C) with its temporary files
    out = tmp_path / "out"
    process = _long_sweep(out, start_new_session=True)
    try:
        workers = _started_workers(process)
        time.sleep(delay)  # into their chunks
        os.killpg(process.pid, signum)
        _, stderr = process.communicate(timeout=60)
        _assert_ended(workers)
    finally:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(process.pid, signal.SIGKILL)
        process.communicate()
    assert process.returncode == code, stderr
    assert message in stderr and b"Traceback" not in stderr
    assert not out.exists()  # no temporary file, and not the directory it created


def _pool_workers(pid: int) -> list[int]:
    """The pool's workers of the sweep ``pid``: its children, but for the resource tracker, and
    the children of its fork server."""
    workers = []
    for child in _children(pid):
        try:
            command = Path(f"/proc/{child}/cmdline").read_bytes()
        except OSError:
            continue  # ended meanwhile
        if b"multiprocessing.forkserver" in command:
            workers += _children(child)
        elif b"multiprocessing.resource_tracker" not in command:
            workers.append(child)
    return workers


def _started_workers(process: subprocess.Popen) -> list[int]:
    """The two pool workers of the sweep ``process``, once it has started them."""
    workers: list[int] = []
    deadline = time.monotonic() + 120
    while len(workers) < 2 and time.monotonic() < deadline:
        time.sleep(0.05)
        workers = _pool_workers(process.pid)
    assert len(workers) == 2, f"no worker processes found: {workers}"
    return workers


def _assert_ended(workers: list[int]) -> None:
    """Within 30 s, no worker of the sweep runs on after it ended."""
    deadline = time.monotonic() + 30
    while any(map(_running, workers)) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not any(map(_running, workers)), "a worker ran on after its sweep ended"


def _running(pid: int) -> bool:
    """Whether ``pid`` still runs (a zombie nobody reaped has ended)."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except (OSError, IndexError):
        return False


@pytest.mark.skipif(not Path("/proc/self/task").exists(), reason="needs Linux's /proc")
@pytest.mark.parametrize("start", ["fork", "spawn", "forkserver"])
def test_the_workers_end_when_the_sweep_is_killed_outright(start, tmp_path):
    # SIGKILL gives the parent no chance to stop its pool: the workers waited for their next
    # chunk for ever, orphans (a fork server's workers are its children, not the sweep's)
    if start not in multiprocessing.get_all_start_methods():
        pytest.skip(f"no {start!r} start method here")
    process = _long_sweep(tmp_path / "out", start, start_new_session=True)
    try:
        workers = _started_workers(process)
        time.sleep(0.5)  # into their first chunks
        process.kill()
        process.communicate(timeout=60)
        _assert_ended(workers)
    finally:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(process.pid, signal.SIGKILL)
        process.communicate()


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGHUP])
def test_a_terminated_sweep_leaves_no_file(signum, tmp_path):
    # SIGHUP: the terminal closed; it left the temporary files behind
    out = tmp_path / "out"
    process = _long_sweep(out)
    deadline = time.monotonic() + 120
    while not (out.exists() and any(out.iterdir())) and time.monotonic() < deadline:
        time.sleep(0.05)  # until the temporary files exist
    process.send_signal(signum)
    process.communicate(timeout=120)
    assert process.returncode == 128 + signum
    assert not out.exists()  # no temporary file, and not the directory it created
