"""The ``groove`` command line: the parser with every command, and the entry point.

Each command is one module of this package with ``add_parser(subparsers)`` and ``run(args)``,
listed in :data:`~groove_model.cli.common.COMMANDS`; exit codes and argument types are in
:mod:`groove_model.cli.common`. ``groove COMMAND ...`` loads that command's module only (the
others are listed, with their line of help, but not loaded): start-up is part of every run.
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import logging
import os
import signal
import sys
import threading
from collections.abc import Collection, Iterator, Sequence

from .. import __version__
from .common import COMMANDS, EXIT_FAILED, EXIT_INTERRUPTED, EXIT_USAGE, UsageError, add_verbose

__all__ = ["build_parser", "main"]

_EXAMPLES = """examples:
  groove solve --gamma 0.6 --delta 0.2 -k 1
  groove trace -k 1 -k 10 --out results/
  groove plot results/boundaries_k1.csv -o k1.png
  groove map -k 10 -o map_k10.png --svg
  groove audit -k 1 10
  groove atlas --out results/          # special points as curves in k, thresholds
  groove compliance --out results/compliance/
  groove reproduce                     # regenerate results/
-k takes one or more values (-k 1 10 or -k 1 -k 10); -v works before or after the command.
run 'groove COMMAND --help' for each command's options and examples"""


def build_parser(commands: Collection[str] | None = None) -> argparse.ArgumentParser:
    """The ``groove`` argument parser.

    Parameters
    ----------
    commands : collection of str, optional
        The commands whose options are loaded (their modules imported); the others are listed
        with their line of help only, and parse no options. ``None``: every command.
    """
    parser = argparse.ArgumentParser(
        prog="groove",
        description="Regime boundaries of an elastic ball in a rigid V-groove "
                    "(Halsey & Ertas, 'A Ball in a Groove').",
        epilog=_EXAMPLES, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--version", action="version",
                        version=f"%(prog)s {__version__} (groove-continuation)")
    add_verbose(parser)
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for name, summary in COMMANDS.items():
        if commands is None or name in commands:
            importlib.import_module(f"{__package__}.{name}").add_parser(sub)
        else:
            sub.add_parser(name, help=summary)
    return parser


def _without_separator_before_command(argv: list[str]) -> list[str]:
    """``argv`` without a ``--`` between ``groove``'s own options and the command
    (``groove -- solve ...``): it ends no options there, and Python 3.11's argparse reads it as
    the command's name."""
    for i, token in enumerate(argv):
        if token == "--":
            return argv[:i] + argv[i + 1:] if i + 1 < len(argv) else argv
        if not token.startswith("-"):
            break
    return argv


def _commands_to_load(argv: Sequence[str]) -> tuple[str, ...] | None:
    """The command ``argv`` runs, as :func:`build_parser`'s ``commands``: none for ``groove``'s
    own options (``--help``, ``--version``), every one where the command is not plain to see."""
    for token in argv:
        if token in ("-h", "--help", "--version"):
            return ()
        if token == "--" or not token.startswith("-"):
            return (token,) if token in COMMANDS else None
    return ()


def main(argv=None) -> int:
    """Entry point of the ``groove`` console script; returns the exit code."""
    argv = _without_separator_before_command(sys.argv[1:] if argv is None else list(argv))
    try:
        parser = build_parser(_commands_to_load(argv))
        args = parser.parse_args(argv)
    except KeyboardInterrupt:  # Ctrl-C while the commands load: nothing was written
        print("groove: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    verbose = getattr(args, "verbose", False)
    logging.basicConfig(level=logging.INFO if verbose else logging.WARNING,
                        format="%(levelname)s %(name)s: %(message)s")
    try:
        with _terminable():
            return args.run(args)
    except _Terminated as exc:
        # as for Ctrl-C: files are written whole or not at all, the temporaries removed
        print(f"groove {args.command}: terminated by {signal.Signals(exc.signum).name}",
              file=sys.stderr)
        return 128 + exc.signum
    except BrokenPipeError:
        # The reader went away (`groove ... | head`): stop quietly, as other tools do, and keep
        # Python from complaining about stdout when it exits.
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return EXIT_FAILED
    except KeyboardInterrupt:
        # Ctrl-C: files are written whole or not at all, so there is nothing to clean up here
        print(f"groove {args.command}: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except UsageError as exc:
        parser.exit(EXIT_USAGE, f"groove {args.command}: error: {exc}\n")
    except OSError as exc:
        # Imported here, not at the top: only a failed write needs it (it is light).
        from ..io.atomic import WriteError

        if isinstance(exc, WriteError):  # the input was fine: the output could not be written
            print(f"groove {args.command}: error: {exc.strerror}", file=sys.stderr)
            return EXIT_FAILED
        parser.exit(EXIT_USAGE, f"groove {args.command}: error: {_os_message(exc)}\n")
    except Exception as exc:
        # A computation that failed where the command does not handle it itself (the
        # thresholds' atlas under `trace`, say): its message, not a traceback (with -v, both).
        # Imported here, not at the top: numpy is what `groove --help` should not wait for.
        from .common import computation_errors

        if not isinstance(exc, computation_errors()):
            raise
        if verbose:
            logging.getLogger(__name__).exception("the computation failed")
        print(f"groove {args.command}: error: {exc}", file=sys.stderr)
        return EXIT_FAILED
    return EXIT_FAILED  # pragma: no cover


class _Terminated(KeyboardInterrupt):
    """SIGTERM or SIGHUP while a command runs: an interrupt from outside, handled as Ctrl-C's
    ``KeyboardInterrupt`` is (what a command does on Ctrl-C, it does here), reported apart."""

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum


@contextlib.contextmanager
def _terminable() -> Iterator[None]:
    """While a command runs, SIGTERM and SIGHUP (a service manager, ``timeout``, a closed
    terminal) raise :class:`_Terminated` in the main thread, as Ctrl-C raises
    ``KeyboardInterrupt``: a file being written is then removed, where the default action
    killed the process outright and left its temporary behind. A signal ignored when the
    command starts (``nohup``'s SIGHUP) stays ignored; ``groove sweep`` sets its own handler
    while its workers run."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def terminate(signum, frame):
        raise _Terminated(signum)

    previous = {}
    for name in ("SIGTERM", "SIGHUP"):  # no SIGHUP on Windows
        number = getattr(signal, name, None)
        if number is not None and signal.getsignal(number) is signal.SIG_DFL:
            previous[number] = signal.signal(number, terminate)
    try:
        yield
    finally:
        for number, handler in previous.items():
            signal.signal(number, handler)


def _os_message(exc: OSError) -> str:
    """``path: reason`` for an error of the system, not Python's ``[Errno 2] reason: 'path'``."""
    if exc.strerror and exc.filename is not None:
        return f"{exc.filename}: {exc.strerror}"
    return exc.strerror or str(exc)
