"""``groove map``: the shaded regime map of the ``(gamma, delta)`` plane for one ``k``."""

from __future__ import annotations

import argparse
import logging
import sys
from pathlib import Path

from .common import (
    EXIT_FAILED,
    EXIT_OK,
    add_command,
    add_compliance_options,
    add_friction,
    compliance_from,
    computation_errors,
    figure_target,
    one_friction,
    refuse_blocked,
    require_plotting,
)

__all__ = ["add_parser", "run"]

log = logging.getLogger(__name__)

#: the cells of a map along each axis (the most: groove_model.plots.regime_map.MAP_RESOLUTION_MAX,
#: which this module does not import at start-up; a test checks the two agree)
_RESOLUTION_RANGE = (2, 5000)

_EXAMPLES = """examples:
  groove map -k 10 -o map_k10.png --svg        # PNG and SVG of the regime map for k = 10
  groove map -k 1 -o map_k1.svg --deg          # SVG only, axes in degrees
  groove map -k 2 -o fine.png --resolution 1200

The map shades double rolling and rolling sliding, each clockwise or counter-clockwise, draws
the axis segments delta = 0 (symmetric no-rotation below arctan(k/c), double sliding above), and
overlays the traced boundaries with their special points and the paper's seed points.
"""


def _resolution(text: str) -> int:
    lo, hi = _RESOLUTION_RANGE
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"grid resolution N = {text!r} is not an integer; allowed range {lo} <= N <= {hi}"
        ) from None
    if not lo <= value <= hi:
        raise argparse.ArgumentTypeError(
            f"grid resolution N = {value} is outside the allowed range {lo} <= N <= {hi}")
    return value


def add_parser(subparsers):
    """Register ``groove map``; returns its parser."""
    p = add_command(
        subparsers, "map",
        description="Classify every point of 0 <= delta <= gamma <= pi/2 with the point solver "
                    "(double rolling or rolling sliding, clockwise or counter-clockwise), shade "
                    "the regions, overlay the traced boundaries, and write the figure. The "
                    "suffix of -o sets the format (.png, .svg, .pdf).",
        examples=_EXAMPLES)
    add_friction(p, help="friction coefficient (1e-4 <= k <= 1e6); one per map", several=False)
    p.add_argument("-o", "--output", required=True, metavar="FIG.png",
                   help="figure file; its suffix (.png, .svg, .pdf) sets the format")
    p.add_argument("--svg", action="store_true",
                   help="also write an SVG beside the figure (same name, suffix .svg)")
    p.add_argument("--resolution", type=_resolution, default=600, metavar="N",
                   help=f"cells along each axis of [0, pi/2], {_RESOLUTION_RANGE[0]} <= N <= "
                        f"{_RESOLUTION_RANGE[1]} (default 600)")
    p.add_argument("--deg", action="store_true", help="axes in degrees")
    p.add_argument("--no-boundaries", action="store_true",
                   help="shade the regions only (no tracing)")
    add_compliance_options(p)
    p.set_defaults(run=run, outputs=outputs)
    return p


def outputs(args) -> list[Path]:
    """The figure files ``groove map`` would write for ``args`` (``-o``, and its SVG with
    ``--svg``)."""
    target = Path(args.output)
    return [target, *([target.with_suffix(".svg")] if args.svg else [])]


def run(args) -> int:
    """Trace (unless ``--no-boundaries``), draw and write; 1 if a computation failed."""
    # Imported here, not at the top: the tracer and the map load the engine, scipy and
    # matplotlib, which `groove --help` and `groove solve` should not wait for.
    from ..model.parameters import Parameters, k_text

    require_plotting()
    # After require_plotting: a bad MPLBACKEND is a usage error, not a traceback.
    from ..plots.regime_map import save_regime_map
    from ..tracing import trace_boundaries

    k = one_friction(args, "map")
    params = Parameters(k, compliance_from(args))
    target, fmt = figure_target(args.output)
    formats = tuple(dict.fromkeys([fmt, "svg"] if args.svg else [fmt]))
    refuse_blocked(outputs(args))
    boundary_set = None
    try:
        if not args.no_boundaries:
            log.info("tracing the boundaries for k = %s", k_text(k))
            boundary_set = trace_boundaries(params)
            if not boundary_set.ok:
                for failure in boundary_set.failures:
                    print(f"groove map: error: k = {k_text(k)}: {failure}", file=sys.stderr)
                print("groove map: nothing written: a boundary failed (see above)",
                      file=sys.stderr)
                return EXIT_FAILED
        paths = save_regime_map(params, target, n=args.resolution, degrees=args.deg,
                                formats=formats, boundary_set=boundary_set,
                                boundaries=not args.no_boundaries)
    except computation_errors() as exc:
        print(f"groove map: error: computation failed for k = {k_text(k)}: "
              f"{type(exc).__name__}: {exc}", file=sys.stderr)
        return EXIT_FAILED
    for path in paths:
        print(f"figure: {path}")
    return EXIT_OK
