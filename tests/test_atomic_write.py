"""Crash safety of ``atomic_write``: writers killed with SIGKILL leave no stale or truncated files.

The writers are real processes: a launcher imports the package once and forks a writer per
request (a fresh interpreter per kill would spend a second on imports); the test kills them
with SIGKILL at random moments and reads their exit status back through the launcher.
"""

import os
import random
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd
import pytest

from groove_model.io.export import atomic_write, remove_stale_temporaries

ROWS = 20_000
#: the documented temporary name ``.{stem}.partial-{pid}@{owner}.{token}{suffix}``
TEMPORARY = re.compile(r"\.(?P<stem>.*)\.partial-(?P<pid>[0-9]+)@(?P<owner>[A-Za-z0-9-]+)"
                       r"\.(?P<token>[0-9a-f]{16})(?P<suffix>\.[^./]*)?")

LAUNCHER = r'''
import os, sys, time, traceback
from pathlib import Path
from groove_model.io.export import atomic_write

rows = int(sys.argv[1])
body = "i,square\n" + "".join(f"{i},{i * i}\n" for i in range(rows))


def write_in_pieces(tmp):
    # slow, like a figure being drawn: most of a writer's time is spent inside a write
    with open(tmp, "w") as f:
        for start in range(0, len(body), 4096):
            f.write(body[start:start + 4096])
            f.flush()
            time.sleep(0.0002)


def write_forever(out):
    for n in range(os.getpid(), 10**9):
        atomic_write(out / f"data_{n % 3}.csv", write_in_pieces)


def write_held(out, release):
    def held(tmp):
        Path(tmp).write_text(body[: len(body) // 2])
        while not release.exists():
            time.sleep(0.001)
        Path(tmp).write_text(body)
    atomic_write(out / "held.csv", held)


def fork(target, *args):
    pid = os.fork()
    if pid == 0:
        code = 0
        try:
            target(*args)
        except BaseException:
            traceback.print_exc()
            code = 1
        os._exit(code)
    return pid


print("ready", flush=True)
for line in sys.stdin:
    command, *args = line.split()
    if command == "write":
        print(fork(write_forever, Path(args[0])), flush=True)
    elif command == "hold":
        print(fork(write_held, Path(args[0]), Path(args[1])), flush=True)
    elif command == "reap":
        print(os.waitstatus_to_exitcode(os.waitpid(int(args[0]), 0)[1]), flush=True)
'''

posix_only = pytest.mark.skipif(os.name != "posix", reason="needs fork and SIGKILL")


class Launcher:
    """Drives the launcher process: start writers, reap them and read their exit codes."""

    def __init__(self, directory: Path) -> None:
        self.log = directory / "launcher-stderr.txt"
        env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1",
                   MKL_NUM_THREADS="1", PYTHONWARNINGS="ignore")
        with open(self.log, "w") as stderr:
            self.process = subprocess.Popen(
                [sys.executable, "-c", LAUNCHER, str(ROWS)], stdin=subprocess.PIPE,
                stdout=subprocess.PIPE, stderr=stderr, text=True, env=env)
        self.children: set[int] = set()
        assert self._read() == "ready"

    def _read(self) -> str:
        line = self.process.stdout.readline()
        if not line:
            pytest.fail(f"the launcher ended: {self.log.read_text()}")
        return line.strip()

    def _ask(self, *words) -> str:
        self.process.stdin.write(" ".join(str(w) for w in words) + "\n")
        self.process.stdin.flush()
        return self._read()

    def start(self, *words) -> int:
        pid = int(self._ask(*words))
        self.children.add(pid)
        return pid

    def reap(self, pid: int) -> int:
        """Exit code of writer ``pid`` (``-9`` if SIGKILL ended it); waits for it."""
        self.children.discard(pid)
        return int(self._ask("reap", pid))

    def kill(self, pid: int) -> int:
        os.kill(pid, signal.SIGKILL)
        return self.reap(pid)

    def close(self) -> None:
        for pid in sorted(self.children):
            self.kill(pid)
        self.process.stdin.close()
        self.process.wait(timeout=30)
        self.process.stdout.close()


@pytest.fixture(scope="module")
def launcher(tmp_path_factory):
    launcher = Launcher(tmp_path_factory.mktemp("launcher"))
    yield launcher
    launcher.close()


def temporaries(directory: Path) -> list[str]:
    return sorted(name for name in os.listdir(directory) if TEMPORARY.fullmatch(name))


def write_rows(tmp) -> None:
    Path(tmp).write_text("i,square\n" + "".join(f"{i},{i * i}\n" for i in range(ROWS)))


def assert_complete(path: Path) -> None:
    frame = pd.read_csv(path)
    assert list(frame.columns) == ["i", "square"], path
    assert len(frame) == ROWS, path
    assert frame["i"].tolist() == list(range(ROWS)) and (frame["square"] == frame["i"] ** 2).all(), path


def size_or_none(path: Path):
    try:
        return path.stat().st_size
    except FileNotFoundError:
        return None


def wait_for_temporary_of(pid: int, directory: Path, min_size: int = 0) -> None:
    """Wait until writer ``pid`` has a temporary file of ``min_size`` bytes or more."""
    deadline = time.monotonic() + 30.0
    while not any(int(TEMPORARY.fullmatch(name)["pid"]) == pid
                  and (size_or_none(directory / name) or 0) >= min_size
                  for name in temporaries(directory)):
        assert time.monotonic() < deadline, f"writer {pid} never wrote a temporary file"
        time.sleep(0.0005)


def dead_pid() -> int:
    """The pid of a process that has ended (unless the system has reused it since)."""
    process = subprocess.Popen([sys.executable, "-c", "pass"])
    process.wait()
    return process.pid


@posix_only
def test_writers_killed_at_random_moments_leave_no_stale_or_truncated_file(launcher, tmp_path):
    rng = random.Random(80)
    live = [launcher.start("write", tmp_path) for _ in range(2)]
    for _ in range(8):
        time.sleep(rng.uniform(0.0, 0.03))
        # the oldest writer dies; the other keeps writing (and cleaning) beside a new one.
        # A writer whose temporary file a cleaner removed would have failed: exit code 1
        assert launcher.kill(live.pop(0)) == -signal.SIGKILL
        live.append(launcher.start("write", tmp_path))
    time.sleep(rng.uniform(0.0, 0.03))
    for pid in live:
        # the last ones die inside a write, so that the final write has files to clean
        wait_for_temporary_of(pid, tmp_path)
        assert launcher.kill(pid) == -signal.SIGKILL
    left = temporaries(tmp_path)
    assert left
    assert {TEMPORARY.fullmatch(name)["suffix"] for name in left} == {".csv"}

    atomic_write(tmp_path / "data_0.csv", write_rows)

    assert temporaries(tmp_path) == []
    finals = set(os.listdir(tmp_path))
    assert "data_0.csv" in finals and finals <= {"data_0.csv", "data_1.csv", "data_2.csv"}
    for name in finals:
        assert_complete(tmp_path / name)


@posix_only
def test_a_live_writers_temporary_file_is_kept(launcher, tmp_path):
    out, release = tmp_path / "out", tmp_path / "release"
    out.mkdir()
    pid = launcher.start("hold", out, release)
    # inside its write callback: a file removed now would not be created again
    wait_for_temporary_of(pid, out, min_size=1)
    held = temporaries(out)

    atomic_write(out / "other.csv", write_rows)  # cleans the directory meanwhile

    assert temporaries(out) == held
    release.touch()
    assert launcher.reap(pid) == 0
    assert sorted(os.listdir(out)) == ["held.csv", "other.csv"]
    assert_complete(out / "held.csv")


def test_only_files_of_gone_writers_of_this_host_are_removed(tmp_path):
    names = []
    atomic_write(tmp_path / "probe.csv", lambda tmp: names.append(Path(tmp).name))
    ours = TEMPORARY.fullmatch(names[0])
    assert ours is not None and int(ours["pid"]) == os.getpid(), names
    owner, gone, token = ours["owner"], dead_pid(), "0123456789abcdef"
    stale = f".data.partial-{gone}@{owner}.{token}.csv"
    kept_files = [
        f".data.partial-{gone}@other-host.{token}.csv",  # another host: its pid means nothing here
        f".data.partial-{os.getpid()}@{owner}.{token}.csv",  # a live writer (this process)
        ".data-k3j2h1g0.csv",  # what tempfile.mkstemp used to leave
        ".data.csv",
        f"data.partial-{gone}@{owner}.{token}.csv",  # not hidden: a user's file
        f".data.partial-{gone}@{owner}.{token}.csv.bak",
        "notes.txt",
    ]
    for name in [stale, *kept_files]:
        (tmp_path / name).write_text("x")
    (tmp_path / f".dir.partial-{gone}@{owner}.{token}").mkdir()

    removed = remove_stale_temporaries(tmp_path)

    assert removed == [tmp_path / stale]
    assert sorted(os.listdir(tmp_path)) == sorted(
        [*kept_files, f".dir.partial-{gone}@{owner}.{token}", "probe.csv"])


@posix_only
def test_temporary_file_has_the_permissions_of_an_ordinary_open(tmp_path):
    umask = os.umask(0o027)
    try:
        atomic_write(tmp_path / "x.csv", write_rows)
    finally:
        os.umask(umask)
    assert (tmp_path / "x.csv").stat().st_mode & 0o777 == 0o640


def _writer(text):
    return lambda tmp: Path(tmp).write_text(text)


@pytest.mark.parametrize("failing", [2, 3])
def test_a_group_whose_later_move_fails_is_put_back_as_it_was(failing, tmp_path, monkeypatch):
    # the moves come one by one: a failure after the first (a target owned by someone else in
    # a sticky directory, an immutable file) left the group half replaced
    from groove_model.io.atomic import WriteError, atomic_write_all

    (tmp_path / "a.csv").write_text("old a")
    (tmp_path / "c.csv").write_text("old c")  # b.csv is new
    real, calls = os.replace, []

    def replace(src, dst):
        calls.append(Path(dst).name)
        if len(calls) == failing:
            raise PermissionError(1, "Operation not permitted")
        return real(src, dst)

    monkeypatch.setattr(os, "replace", replace)
    with pytest.raises(WriteError):
        atomic_write_all([(tmp_path / name, _writer(f"new {name}"))
                          for name in ("a.csv", "b.csv", "c.csv")])
    monkeypatch.setattr(os, "replace", real)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.csv", "c.csv"]  # no temporaries
    assert (tmp_path / "a.csv").read_text() == "old a"
    assert (tmp_path / "c.csv").read_text() == "old c"


@pytest.mark.parametrize("handler", [signal.default_int_handler, signal.SIG_IGN])
def test_ctrl_c_during_the_moves_comes_after_the_whole_group(handler, tmp_path, monkeypatch):
    # the handler is set here: a process started in the background of a shell without job
    # control inherits SIGINT ignored, and Ctrl-C must then stay ignored after the group
    from groove_model.io.atomic import atomic_write_all

    real, calls = os.replace, []

    def replace(src, dst):
        calls.append(Path(dst).name)
        if len(calls) == 1:
            os.kill(os.getpid(), signal.SIGINT)  # held until the group is in place
        return real(src, dst)

    previous = signal.signal(signal.SIGINT, handler)
    try:
        monkeypatch.setattr(os, "replace", replace)
        files = [(tmp_path / name, _writer(name)) for name in ("a.csv", "b.csv")]
        if handler is signal.SIG_IGN:
            atomic_write_all(files)
        else:
            with pytest.raises(KeyboardInterrupt):
                atomic_write_all(files)
    finally:
        signal.signal(signal.SIGINT, previous)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.csv", "b.csv"]


def test_a_sweep_on_a_full_disk_leaves_no_temporary(tmp_path, monkeypatch):
    # closing a temporary flushes its buffer, which failed again on the full disk and skipped
    # the removal of the temporaries and the message naming the file
    import errno

    from groove_model.io import sweep as sweep_io
    from groove_model.io.atomic import WriteError

    class Full:
        def __init__(self, handle):
            self.handle = handle

        def write(self, text):
            raise OSError(errno.ENOSPC, "No space left on device")

        def close(self):
            self.handle.close()
            raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(sweep_io, "open", lambda *a, **k: Full(open(*a, **k)), raising=False)
    from groove_model.tracing import sweep_results

    with pytest.raises(WriteError, match=r"cannot write .*sweep_boundaries\.csv: No space"):
        sweep_io.write_sweep(sweep_results([1.0]), tmp_path)
    assert list(tmp_path.iterdir()) == []


def test_a_file_made_read_only_stays_read_only_when_replaced(tmp_path):
    from groove_model.io.atomic import atomic_write_all

    target = tmp_path / "a.csv"
    target.write_text("old")
    target.chmod(0o444)
    atomic_write_all([(target, _writer("new"))])
    assert target.read_text() == "new"
    assert target.stat().st_mode & 0o777 == 0o444


def _failing(name, at, error=PermissionError(1, "Operation not permitted")):
    """``name`` (an ``os`` function) that raises ``error`` at its ``at``-th call (1-based)."""
    real, calls = getattr(os, name), []

    def function(*args, **kwargs):
        calls.append(args)
        if len(calls) in at:
            raise error
        return real(*args, **kwargs)
    return function


def test_a_failed_move_names_its_file(tmp_path, monkeypatch):
    from groove_model.io.atomic import WriteError, atomic_write_all

    monkeypatch.setattr(os, "replace", _failing("replace", {2}))
    with pytest.raises(WriteError, match=r"cannot write .*b\.csv: Operation not permitted"):
        atomic_write_all([(tmp_path / n, _writer(n)) for n in ("a.csv", "b.csv")])


def test_an_undo_that_fails_keeps_that_old_file_and_puts_back_the_others(tmp_path, monkeypatch,
                                                                           caplog):
    # the move of c fails, then putting b back fails: a was not put back and every backup was
    # removed, so the old a and b were lost
    from groove_model.io.atomic import WriteError, atomic_write_all

    for name in ("a.csv", "b.csv", "c.csv"):
        (tmp_path / name).write_text(f"old {name}")
    monkeypatch.setattr(os, "replace", _failing("replace", {3, 4}))  # c, then b back
    with pytest.raises(WriteError):
        atomic_write_all([(tmp_path / n, _writer(f"new {n}")) for n in ("a.csv", "b.csv", "c.csv")])
    assert (tmp_path / "a.csv").read_text() == "old a.csv"
    assert (tmp_path / "c.csv").read_text() == "old c.csv"
    assert (tmp_path / "b.csv").read_text() == "new b.csv"
    kept = [p for p in tmp_path.iterdir() if p.name.startswith(".b.partial-")]
    assert len(kept) == 1 and kept[0].read_text() == "old b.csv"
    assert str(kept[0]) in caplog.text


def test_without_hard_links_a_group_is_still_all_or_none(tmp_path, monkeypatch):
    # (vfat, exFAT, some network file systems) the old files are kept as copies
    from groove_model.io.atomic import WriteError, atomic_write_all

    for name in ("a.csv", "b.csv"):
        (tmp_path / name).write_text(f"old {name}")
    monkeypatch.setattr(os, "link", _failing("link", set(range(1, 1000))))
    monkeypatch.setattr(os, "replace", _failing("replace", {2}))
    with pytest.raises(WriteError):
        atomic_write_all([(tmp_path / n, _writer(f"new {n}")) for n in ("a.csv", "b.csv")])
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.csv", "b.csv"]
    assert [(tmp_path / n).read_text() for n in ("a.csv", "b.csv")] == ["old a.csv", "old b.csv"]


def test_a_link_to_nothing_in_a_failed_group_is_put_back(tmp_path, monkeypatch):
    from groove_model.io.atomic import WriteError, atomic_write_all

    (tmp_path / "a.csv").symlink_to(tmp_path / "nowhere")
    monkeypatch.setattr(os, "replace", _failing("replace", {2}))
    with pytest.raises(WriteError):
        atomic_write_all([(tmp_path / n, _writer(n)) for n in ("a.csv", "b.csv")])
    assert (tmp_path / "a.csv").is_symlink()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.csv"]


def test_ctrl_c_and_sigterm_during_the_moves_both_reach_their_handlers(tmp_path, monkeypatch):
    from groove_model.io.atomic import atomic_write_all

    seen = []
    real = os.replace

    def replace(src, dst):
        if not seen:
            seen.append("moving")
            os.kill(os.getpid(), signal.SIGINT)
            os.kill(os.getpid(), signal.SIGTERM)
        return real(src, dst)

    # the SIGINT handler raising KeyboardInterrupt kept the SIGTERM handler from being called
    previous = {signal.SIGINT: signal.signal(signal.SIGINT, signal.default_int_handler),
                signal.SIGTERM: signal.signal(signal.SIGTERM, lambda n, f: seen.append(n))}
    try:
        monkeypatch.setattr(os, "replace", replace)
        with pytest.raises(KeyboardInterrupt):
            atomic_write_all([(tmp_path / n, _writer(n)) for n in ("a.csv", "b.csv")])
    finally:
        for number, handler in previous.items():
            signal.signal(number, handler)
    assert seen == ["moving", signal.SIGTERM]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.csv", "b.csv"]


def test_a_stale_backup_of_a_link_is_removed_and_only_the_link(tmp_path):
    # a writer killed while it kept an old symbolic link (its backup is a link too) left a
    # backup that the clean-up, which took regular files only, never removed
    names = []
    atomic_write(tmp_path / "probe.csv", lambda tmp: names.append(Path(tmp).name))
    owner, gone = TEMPORARY.fullmatch(names[0])["owner"], dead_pid()
    (tmp_path / "elsewhere.csv").write_text("the user's file")
    stale = tmp_path / f".data.partial-{gone}@{owner}.0123456789abcdef.csv"
    stale.symlink_to(tmp_path / "elsewhere.csv")
    assert remove_stale_temporaries(tmp_path) == [stale]
    assert (tmp_path / "elsewhere.csv").read_text() == "the user's file"


def test_a_group_that_writes_nothing_leaves_no_directory_it_created(tmp_path):
    """The targets' missing directories are created, and removed again when the group fails
    (a full disk): a command that writes nothing leaves nothing, not an empty --out."""
    import errno

    from groove_model.io.atomic import WriteError, atomic_write_all

    def full(tmp):
        Path(tmp).write_text("half")
        raise OSError(errno.ENOSPC, "No space left on device")

    (tmp_path / "kept").mkdir()
    files = [(tmp_path / "new" / "deeper" / "a.csv", lambda tmp: Path(tmp).write_text("a")),
             (tmp_path / "kept" / "b.csv", full)]
    with pytest.raises(WriteError, match=r"cannot write .*b\.csv: No space left on device"):
        atomic_write_all(files)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["kept"]  # new/deeper removed
    assert list((tmp_path / "kept").iterdir()) == []  # an existing directory stays
    files[1] = (tmp_path / "kept" / "b.csv", lambda tmp: Path(tmp).write_text("b"))
    assert atomic_write_all(files) == [path for path, _ in files]
    assert (tmp_path / "new" / "deeper" / "a.csv").read_text() == "a"


def test_the_atlas_command_on_a_full_disk_leaves_no_directory(tmp_path, monkeypatch, capsys):
    import errno

    from groove_model.cli.main import main

    def full(self, *args, **kwargs):  # the report, the last file of the group
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(Path, "write_text", full)
    out = tmp_path / "new" / "atlas"
    assert main(["atlas", "--k-min", "1", "--k-max", "10", "--out", str(out), "--no-figure"]) == 1
    assert "No space left on device" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []
