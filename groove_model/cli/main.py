"""The ``groove`` command line: the parser with every command, and the entry point.

Each command is one module of this package with ``add_parser(subparsers)`` and ``run(args)``;
exit codes and argument types are in :mod:`groove_model.cli.common`.
"""

from __future__ import annotations

import argparse
import logging
import os
import sys

from .. import __version__
from . import atlas, audit, compliance, plot, reproduce, solve, sweep, trace
from . import map as regime_map
from .common import EXIT_FAILED, EXIT_INTERRUPTED, EXIT_USAGE, UsageError, add_verbose

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


def build_parser() -> argparse.ArgumentParser:
    """The ``groove`` argument parser with every subcommand."""
    parser = argparse.ArgumentParser(
        prog="groove",
        description="Regime boundaries of an elastic ball in a rigid V-groove "
                    "(Halsey & Ertas, 'A Ball in a Groove').",
        epilog=_EXAMPLES, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--version", action="version",
                        version=f"%(prog)s {__version__} (groove-continuation)")
    add_verbose(parser)
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for command in (solve, trace, plot, regime_map, audit, sweep, atlas, compliance):
        command.add_parser(sub)
    reproduce.add_parser(sub, parser)
    return parser


def main(argv=None) -> int:
    """Entry point of the ``groove`` console script; returns the exit code."""
    try:
        parser = build_parser()
        args = parser.parse_args(argv)
    except KeyboardInterrupt:  # Ctrl-C while the commands load: nothing was written
        print("groove: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    verbose = getattr(args, "verbose", False)
    logging.basicConfig(level=logging.INFO if verbose else logging.WARNING,
                        format="%(levelname)s %(name)s: %(message)s")
    try:
        return args.run(args)
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
    return EXIT_FAILED  # pragma: no cover


def _os_message(exc: OSError) -> str:
    """``path: reason`` for an error of the system, not Python's ``[Errno 2] reason: 'path'``."""
    if exc.strerror and exc.filename is not None:
        return f"{exc.filename}: {exc.strerror}"
    return exc.strerror or str(exc)
