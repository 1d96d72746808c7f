"""Files written atomically: to a temporary file in the target directory, synced, then renamed.

A reader (or a crash) never sees a half-written file. A temporary file is named
``.{stem}.partial-{pid}@{owner}.{token}{suffix}``; one left behind by a writer killed outright
(SIGKILL, power loss) is removed by the next write into that directory once no process with
that pid runs on that host (:func:`remove_stale_temporaries`). This module imports nothing
heavy, so that writing a file does not load pandas.
"""

from __future__ import annotations

import contextlib
import errno
import logging
import os
import re
import secrets
import shutil
import signal
import socket
import stat
import threading
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import Any

__all__ = ["WriteError", "atomic_write", "atomic_write_all", "check_targets", "commit_all",
           "create_temporary", "make_directories", "remove_empty_directories",
           "remove_stale_temporaries"]

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
    removed: list[Path] = []
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
            if not (entry.is_file(follow_symlinks=False) or entry.is_symlink()):
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


def create_temporary(path: Path) -> Path:
    """Create an empty temporary file for ``path`` (mode ``0o666`` less the umask), named so
    that :func:`remove_stale_temporaries` can tell when its writer is gone."""
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


class WriteError(OSError):
    """A file could not be written; the message names the file (not its temporary name)."""


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

    Raises
    ------
    WriteError
        An ``OSError`` naming ``path`` (not the temporary file) and the reason, if the file
        cannot be written (a full disk, no permission, a directory in the way).

    Notes
    -----
    The temporary file is created with the permissions an ordinary ``open()`` would give
    (``0o666`` less the umask), synced to disk before ``os.replace`` and the directory after
    it, so that neither a killed process nor a power loss leaves a truncated ``path``. Any
    exception removes it; a writer killed outright cannot, and the next call in the same
    directory removes it (:func:`remove_stale_temporaries`).
    """
    return atomic_write_all([(path, write)])[0]


def check_targets(paths) -> None:
    """:class:`WriteError` naming the first of ``paths`` that a file cannot be moved onto: a
    directory (or a link to one) in its place.

    The moves of :func:`atomic_write_all` come last, one by one; checking their targets before
    anything is written keeps one that fails from leaving the files before it replaced.
    """
    for path in map(Path, paths):
        try:
            blocked = path.is_dir()
        except OSError as exc:  # e.g. a name too long for the file system
            raise WriteError(exc.errno, f"cannot write {path}: {exc.strerror or exc}") from exc
        if blocked:
            raise WriteError(errno.EISDIR, f"cannot write {path}: a directory is in its place")


def make_directories(directories) -> list[Path]:
    """Create each of ``directories`` and its missing parents; return the ones created, each
    directory's deepest first (for :func:`remove_empty_directories`).

    Raises
    ------
    WriteError
        Naming the directory that cannot be created; those created before it are removed.
    """
    created: list[Path] = []
    for directory in dict.fromkeys(map(Path, directories)):
        missing = [d for d in (directory, *directory.parents) if not d.exists()]
        try:
            directory.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            remove_empty_directories([d for d in missing if d.exists()] + created)
            raise WriteError(exc.errno, f"cannot create {directory}: {exc.strerror or exc}") \
                from exc
        created = missing + created
    return created


def remove_empty_directories(created: Sequence[Path]) -> None:
    """Remove the directories a writer created (deepest first) while they are empty: a write
    that leaves no file leaves no directory either."""
    for directory in created:
        with contextlib.suppress(OSError):  # not empty (another file, or gone): kept
            directory.rmdir()


def atomic_write_all(files: Sequence[tuple[Any, Callable[[Path], object]]]) -> list[Path]:
    """:func:`atomic_write` for files that belong together, e.g. the two CSVs of one ``k``.

    Every file is written to its temporary first; only when all were written are they moved
    into place, so a full disk or a failed writer leaves none of them changed (the moves
    themselves need no space, and their targets are checked first: :func:`check_targets`).
    The targets' directories are created if missing, and removed again if nothing is written.
    Returns the paths, in order.

    Raises
    ------
    WriteError
        Naming the file that could not be written; no temporary is left.
    """
    check_targets(target for target, _ in files)
    created = make_directories(Path(target).parent for target, _ in files)
    temporaries: list[tuple[Path, Path]] = []
    current = None
    try:
        for target, write in files:
            current = Path(target)
            remove_stale_temporaries(current.parent)
            temporaries.append((create_temporary(current), current))
            write(temporaries[-1][0])
        current = None
        commit_all(temporaries)
    except BaseException as exc:
        for tmp, _ in temporaries:
            tmp.unlink(missing_ok=True)
        remove_empty_directories(created)
        if isinstance(exc, OSError) and not isinstance(exc, WriteError):
            raise WriteError(exc.errno, f"cannot write {current}: {exc.strerror or exc}") from exc
        raise
    return [path for _, path in temporaries]


@contextlib.contextmanager
def _signals_deferred() -> Iterator[None]:
    """Hold back SIGINT and SIGTERM until the block ends (main thread only, where Python runs
    its signal handlers): a Ctrl-C between two moves of a group is recorded, and raised again
    once the previous handlers are back, so that each is delivered as it would have been
    (``KeyboardInterrupt``, a handler of the program's, ignored, or the default action)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    received: list[int] = []
    held = [number for number in (signal.SIGINT, getattr(signal, "SIGTERM", None))
            if number is not None and signal.getsignal(number) is not None]
    previous = {number: signal.signal(number, lambda number, frame: received.append(number))
                for number in held}
    try:
        yield
    finally:
        for number, handler in previous.items():
            signal.signal(number, handler)
        _deliver(list(dict.fromkeys(received)))


def _deliver(numbers: list[int]) -> None:
    """Raise each signal of ``numbers`` in this process, every one of them even when a handler
    raises (``KeyboardInterrupt``): the next is raised in a ``finally``."""
    if numbers:
        try:
            signal.raise_signal(numbers[0])
        finally:
            _deliver(numbers[1:])


def _keep_old(path: Path) -> Path | None:
    """The file at ``path`` kept under a temporary's name (removed as stale if its writer dies),
    to put it back if a later move of its group fails: a hard link, or a copy where the file
    system has no hard links; ``None`` if there is nothing at ``path`` or it cannot be kept."""
    if not os.path.lexists(path):
        return None
    prefix = f".{path.stem[:120]}.partial-{os.getpid()}@{_owner()}."
    for _ in range(100):
        backup = path.with_name(f"{prefix}{secrets.token_hex(8)}{path.suffix}")
        try:
            os.link(path, backup, follow_symlinks=False)
        except FileExistsError:
            continue
        except OSError:
            break
        return backup
    try:
        backup = create_temporary(path)
        shutil.copy2(path, backup, follow_symlinks=False)
    except OSError:
        with contextlib.suppress(OSError):
            backup.unlink(missing_ok=True)
        return None
    return backup


def _keep_mode(path: Path, tmp: Path) -> None:
    """Give ``tmp`` the permissions of the file it replaces (a file made read-only stays so),
    where there is one and they can be set."""
    if os.name != "posix":
        return  # on Windows a read-only file can be neither replaced nor removed
    try:
        mode = path.stat().st_mode
        if stat.S_ISREG(mode):
            os.chmod(tmp, stat.S_IMODE(mode))
    except OSError:
        pass


def _undo(done: list[tuple[Path, Path | None, bool]]) -> set[Path]:
    """Undo the moves ``done`` of a failed group, newest first: each old file put back from its
    backup, each new file that had none removed. One that cannot be undone is logged with the
    name of its backup, which is kept; the others are still undone. Returns those targets."""
    lost = set()
    for path, backup, existed in reversed(done):
        try:
            if backup is not None:
                os.replace(backup, path)  # the old file back
            elif not existed:
                path.unlink(missing_ok=True)  # there was none
        except OSError as exc:
            lost.add(path)
            logger.error("cannot put back the old %s after a failed write (%s); it is kept as %s",
                         path, exc, backup)
    return lost


def commit_all(pairs: Sequence[tuple[Path, Path]]) -> None:
    """Move each finished temporary onto its target, all of them or none.

    The temporaries are synced first and given the permissions of the files they replace; the
    old files are kept as hard links (:func:`_keep_old`) while the moves run back to back with
    Ctrl-C held (:func:`_signals_deferred`); if one move fails, those before it are undone (the
    old files put back, new ones removed), so a group of files (the two CSVs of a ``k``, a
    figure's formats) is never left half replaced. Then the directories are synced. Where a
    file system cannot link, the old files are kept as copies; one that cannot be kept at all
    is moved over last, so that only a failure of its own move can leave it replaced.

    Raises
    ------
    WriteError
        Naming the file whose sync or move failed, after the undoing; the temporaries are
        removed.
    """
    path = None
    kept: list[tuple[Path, Path, Path | None]] = []
    done: list[tuple[Path, Path | None, bool]] = []
    lost: set[Path] = set()
    try:
        for tmp, path in pairs:
            _sync_file(tmp)
            _keep_mode(path, tmp)
        with _signals_deferred():
            try:
                for tmp, path in pairs:
                    kept.append((tmp, path, _keep_old(path)))
                # a target whose old file could not be kept goes last
                kept.sort(key=lambda item: os.path.lexists(item[1]) and item[2] is None)
                for tmp, path, backup in kept:
                    existed = backup is not None or os.path.lexists(path)
                    os.replace(tmp, path)
                    done.append((path, backup, existed))
            except BaseException:
                lost = _undo(done)
                for tmp, _ in pairs:
                    tmp.unlink(missing_ok=True)  # (before a deferred SIGTERM ends the process)
                raise
            finally:
                for _, target, backup in kept:
                    if backup is not None and target not in lost:
                        backup.unlink(missing_ok=True)
    except OSError as exc:
        if isinstance(exc, WriteError):
            raise
        raise WriteError(exc.errno, f"cannot write {path}: {exc.strerror or exc}") from exc
    for directory in dict.fromkeys(path.parent for _, path in pairs):
        _sync_directory(directory)

