"""``groove map`` and ``groove audit``: the regime map and the audit of the paper's claims.

:func:`add_map_command` and :func:`add_audit_command` register the two subcommands on the
``groove`` parser (:func:`groove_model.cli.build_parser`). Exit codes as for every ``groove``
command: 0 success, 1 a computation failed, 2 bad input (the message names the quantity, its
value and the allowed range).
"""

from __future__ import annotations

import argparse
import logging
import math
import sys
from pathlib import Path

import numpy as np

from .main import EXIT_FAILED, EXIT_OK, UsageError, _friction

__all__ = ["add_audit_command", "add_map_command"]

log = logging.getLogger(__name__)

#: Errors of a computation (root finding, continuation, linear algebra): exit code 1.
_COMPUTATION_ERRORS = (ArithmeticError, RuntimeError, np.linalg.LinAlgError)
_FORMATS = ("png", "svg", "pdf")
_RESOLUTION_RANGE = (2, 20000)

_MAP_EXAMPLES = """examples:
  groove map -k 10 -o map_k10.png --svg        # PNG and SVG of the regime map for k = 10
  groove map -k 1 -o map_k1.svg --deg          # SVG only, axes in degrees
  groove map -k 2 -o fine.png --resolution 1200

The map shades double rolling and rolling sliding, each clockwise or counter-clockwise, draws
the axis segments delta = 0 (symmetric no-rotation below arctan k, double sliding above), and
overlays the traced boundaries with their special points and the paper's seed points.
"""

_AUDIT_EXAMPLES = """examples:
  groove audit                                  # default k = 0.3 1 1.2 1.4 1.5 2 10 100
  groove audit -k 1 10 --out results/           # write results/claims.md and claims.json
  groove audit -k 2 --json                      # the whole report as JSON on stdout
  groove audit --trace --out results/           # add the tracer's curves as a cross-check

verdicts: 'holds', 'holds with qualification', 'fails' (with a counterexample); they are
computed by the point solver and bracketed root finding, never written in. A paper claim
that fails is a finding, not an error: the exit code is 0 when the audit itself ran.
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


def add_map_command(subparsers) -> argparse.ArgumentParser:
    """Register ``groove map`` on an ``argparse`` subparsers object; returns its parser."""
    p = subparsers.add_parser(
        "map", help="shade the regime map of the (gamma, delta) plane for one k",
        description="Classify every point of 0 <= delta <= gamma <= pi/2 with the point solver "
                    "(double rolling or rolling sliding, clockwise or counter-clockwise), shade "
                    "the regions, overlay the traced boundaries, and write the figure. The "
                    "suffix of -o sets the format (.png, .svg, .pdf).",
        epilog=_MAP_EXAMPLES, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("-k", required=True, type=_friction, help="friction coefficient, > 0")
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
    p.set_defaults(run=_run_map)
    return p


def add_audit_command(subparsers) -> argparse.ArgumentParser:
    """Register ``groove audit`` on an ``argparse`` subparsers object; returns its parser."""
    from ..analysis.audit.checks import DEFAULT_KS

    p = subparsers.add_parser(
        "audit", help="check every quantitative claim of the paper, with numbers",
        description="Check each statement of fact in the paper's 'Rolling solutions' and "
                    "'Rolling-sliding solutions' paragraphs (and the caption of its Fig. 2) "
                    "for the given friction coefficients: the statement quoted, how it was "
                    "checked, the computed verdict, the numbers, and for a failure a "
                    "counterexample (k, gamma, delta, values).",
        epilog=_AUDIT_EXAMPLES, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("-k", action="extend", nargs="+", type=_friction, dest="ks", metavar="K",
                   help="friction coefficients (> 0), e.g. -k 1 10 or -k 1 -k 10 (default "
                        + " ".join(f"{k:g}" for k in DEFAULT_KS) + ")")
    p.add_argument("--out", metavar="DIR",
                   help="write claims.md and claims.json into DIR (created if needed)")
    p.add_argument("--json", action="store_true", help="print the report as JSON on stdout")
    p.add_argument("--trace", action="store_true",
                   help="add the tracer's boundaries as a cross-check (several seconds per k)")
    p.set_defaults(run=_run_audit)
    return p


def _formats(target: Path, svg: bool) -> tuple:
    fmt = target.suffix.lstrip(".").lower()
    if fmt not in _FORMATS:
        raise UsageError(f"output format {target.suffix or '(none)'!r} of {target} is not one "
                         "of .png, .svg, .pdf")
    return tuple(dict.fromkeys([fmt, "svg"] if svg else [fmt]))


def _run_map(args) -> int:
    from ..plots.regime_map import save_regime_map

    target = Path(args.output)
    formats = _formats(target, args.svg)
    if not target.parent.is_dir():
        raise UsageError(f"directory {target.parent} of {target} does not exist")
    boundary_set = None
    try:
        if not args.no_boundaries:
            from ..tracer import trace_boundaries

            log.info("tracing the boundaries for k = %g", args.k)
            boundary_set = trace_boundaries(args.k)
            if not boundary_set.ok:
                for failure in boundary_set.failures:
                    print(f"groove map: error: k = {args.k:g}: {failure}", file=sys.stderr)
                print("groove map: nothing written: a boundary failed (see above)",
                      file=sys.stderr)
                return EXIT_FAILED
        paths = save_regime_map(args.k, target, n=args.resolution, degrees=args.deg,
                                formats=formats, boundary_set=boundary_set,
                                boundaries=not args.no_boundaries)
    except _COMPUTATION_ERRORS as exc:
        print(f"groove map: error: computation failed for k = {args.k:g}: "
              f"{type(exc).__name__}: {exc}", file=sys.stderr)
        return EXIT_FAILED
    for path in paths:
        print(f"figure: {path}")
    return EXIT_OK


def _summary(report) -> str:
    width = max(len(c.id) for c in report.claims)
    lines = [f"audit of the paper's claims for k = {', '.join(f'{k:g}' for k in report.ks)}: "
             + ", ".join(f"{n} {v}" for v, n in report.counts().items())
             + f" ({report.seconds:.1f} s)"]
    for c in report.claims:
        lines.append(f"  {c.verdict:<25}  {c.id:<{width}}  {c.summary.split('. ')[0][:100]}")
    for c in report.claims:
        if c.counterexample is not None and c.verdict == "fails":
            ce = c.counterexample
            lines.append(f"  counterexample to {c.id}: k = {ce.k:g}, gamma = {ce.gamma:.10g}, "
                         f"delta = {ce.delta:.10g}: " + ", ".join(
                             f"{key} = {v:.6g}" if isinstance(v, float) and math.isfinite(v)
                             else f"{key} = {v}" for key, v in ce.values.items()))
    return "\n".join(lines)


def _run_audit(args) -> int:
    from ..analysis.audit.checks import DEFAULT_KS, run_audit
    from ..io.export import atomic_write

    ks = tuple(args.ks) if args.ks else DEFAULT_KS
    out = Path(args.out) if args.out else None
    if out is not None and out.exists() and not out.is_dir():
        raise UsageError(f"--out {out} exists and is not a directory")
    try:
        report = run_audit(ks, use_tracer=args.trace)
    except _COMPUTATION_ERRORS as exc:
        print(f"groove audit: error: computation failed: {type(exc).__name__}: {exc}",
              file=sys.stderr)
        return EXIT_FAILED
    if args.json:
        print(report.to_json())
    else:
        print(_summary(report))
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)
        for name, text in (("claims.md", report.to_markdown()), ("claims.json", report.to_json())):
            path = atomic_write(out / name, lambda tmp, t=text: Path(tmp).write_text(t, encoding="utf-8"))
            print(f"wrote {path}", file=sys.stderr if args.json else sys.stdout)
    return EXIT_OK
