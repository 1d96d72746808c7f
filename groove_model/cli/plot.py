"""``groove plot``: an overlay drawn from boundaries CSV files written by ``groove trace``."""

from __future__ import annotations

import sys

from .common import (
    EXIT_OK,
    UsageError,
    add_command,
    figure_target,
    require_plotting,
)

__all__ = ["add_parser", "run"]

_EXAMPLES = """examples:
  groove plot results/boundaries_k1.csv results/boundaries_k10.csv -o overlay.png
  groove plot out/boundaries_k2.csv -o k2.svg --deg
"""


def add_parser(subparsers):
    """Register ``groove plot``; returns its parser."""
    p = add_command(
        subparsers, "plot",
        description="Draw the boundaries stored in boundaries_k*.csv files (one k per file, as "
                    "groove trace writes them) onto one overlay. A file holding several k, a "
                    "k given by two files, or a point outside 0 <= delta <= gamma <= pi/2 is "
                    "refused (exit code 2) and nothing is drawn; a file that lacks part of a "
                    "trace (a boundary, or the marked first or last row of one) is drawn with "
                    "a warning.",
        examples=_EXAMPLES)
    p.add_argument("files", nargs="+", metavar="FILE.csv", help="boundaries CSV files")
    p.add_argument("-o", "--output", required=True, metavar="FIG.png",
                   help="figure file; its suffix (.png, .svg, .pdf) sets the format")
    p.add_argument("--deg", action="store_true", help="axes in degrees")
    p.set_defaults(run=run)
    return p


def run(args) -> int:
    """Read every file, draw, write; :class:`UsageError` for an unreadable file or bad target."""
    # Imported here, not at the top: reading CSV and drawing load pandas and matplotlib, which
    # `groove --help` and `groove solve` should not wait for.
    from ..io.export import incomplete_boundaries, read_boundaries_csv
    from ..model.parameters import k_text

    require_plotting()
    # After require_plotting: a bad MPLBACKEND is a usage error, not a traceback.
    from ..plots.overlay import save_overlay

    frames = []
    sources: dict[tuple[float, float], str] = {}
    for name in args.files:
        try:
            frame = read_boundaries_csv(name)
        except OSError as exc:
            raise UsageError(f"cannot read {name}: {exc.strerror or exc}") from None
        except ValueError as exc:
            raise UsageError(str(exc)) from None
        key = float(frame["k"].iloc[0]), float(frame["compliance"].iloc[0])
        if key in sources:
            raise UsageError(f"{name} and {sources[key]} both hold k = {k_text(key[0])} with "
                             f"compliance ratio {key[1]:g}: give each once")
        sources[key] = name
        frames.append(frame)
        for problem in incomplete_boundaries(frame):
            print(f"groove plot: warning: {name}: {problem}: not the whole trace groove trace "
                  "writes (cut short or edited?); drawn as it is", file=sys.stderr)
    target, fmt = figure_target(args.output)
    for path in save_overlay(frames, target, degrees=args.deg, formats=(fmt,)):
        print(f"figure: {path}")
    return EXIT_OK
