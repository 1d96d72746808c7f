"""``groove trace``: every boundary for one or more ``k``, written as CSV and as an overlay."""

from __future__ import annotations

import logging
import sys

from .common import EXIT_FAILED, EXIT_OK, UsageError, add_command, friction, output_directory

__all__ = ["add_parser", "certificate_line", "run"]

log = logging.getLogger("groove_model")

_EXAMPLES = """examples:
  groove trace -k 1 -k 10 --out results/          # the paper's Figure 2: CSVs and overlay
  groove trace -k 0.5 --out out/ --keep-unphysical  # keep unphysical continuations, flagged
  groove trace -k 2 -k 20 --out out/ --deg --figure my_overlay
  groove trace -k 1 -k 10 --out results/ --certify   # and prove each boundary (python-flint)

writes, for each k, boundaries_k{k}.csv (one row per point) and special_points_k{k}.csv,
and the overlay FIGURE.png and FIGURE.svg; nothing is written if any boundary fails. With
--certify each boundary is proven in ball arithmetic (docs/certification.md): a line per
boundary says proven or not proven and why, the CSV column certified says True or False, and
the exit code is 1 if any boundary is not proven (the files are written).
"""


def add_parser(subparsers):
    """Register ``groove trace``; returns its parser."""
    p = add_command(
        subparsers, "trace",
        help="trace every regime boundary for one or more k; write CSVs and an overlay",
        description="Follow each boundary of the paper (T = kN on the steeper wall, upsilon = 0 "
                    "in double rolling and in rolling sliding) from the seed points the paper "
                    "names, by pseudo-arclength continuation, and write them as CSV and as an "
                    "overlay figure in the style of the paper's Figure 2.",
        examples=_EXAMPLES)
    p.add_argument("-k", required=True, action="append", type=friction, dest="ks",
                   help="friction coefficient (> 0); repeat for several")
    p.add_argument("--out", required=True, help="output directory (created if needed)")
    p.add_argument("--figure", default=None,
                   help="overlay file name without suffix (default boundaries_k{k1}_k{k2}...)")
    p.add_argument("--keep-unphysical", action="store_true",
                   help="keep the parts of each boundary where its regime is not valid")
    p.add_argument("--deg", action="store_true", help="overlay axes in degrees")
    p.add_argument("--no-figure", action="store_true", help="write the CSVs only")
    p.add_argument("--certify", action="store_true",
                   help="prove every boundary in ball arithmetic (needs python-flint: pip "
                        "install 'groove-continuation[certify]')")
    p.set_defaults(run=run)
    return p


def run(args) -> int:
    """Trace every ``k``; write nothing and return 1 if a boundary failed, else write and 0
    (with ``--certify``: 1 if a boundary is not proven, the files written all the same)."""
    # Imported here, not at the top: the tracer, the CSV files and the figure load the engine,
    # pandas and matplotlib, which `groove --help` and `groove solve` should not wait for.
    from continuation.numbers import require_flint
    from ..io.export import write_boundary_set
    from ..plots.overlay import save_overlay
    from ..tracing import trace_boundaries

    out = output_directory(args.out)
    if args.certify:
        try:
            require_flint()
        except ImportError as exc:
            raise UsageError(str(exc)) from None
    sets = []
    for k in dict.fromkeys(args.ks):
        log.info("tracing k = %g", k)
        result = trace_boundaries(k, keep_unphysical=args.keep_unphysical,
                                  certify=args.certify)
        sets.append(result)
        if not result.ok:
            for failure in result.failures:
                print(f"groove trace: error: k = {k:g}: {failure}", file=sys.stderr)
    if not all(b.ok for b in sets):
        print("groove trace: nothing written: a boundary failed (see above)", file=sys.stderr)
        return EXIT_FAILED
    for result in sets:
        paths = write_boundary_set(result, out)
        print(f"k = {result.k:g}: {', '.join(str(p) for p in paths)}; "
              f"{sum(len(c.x) for c in result.curves.values())} points, "
              f"|rs_limit - dr_limit| <= {result.limit_distance:.1e}")
        for note in result.notes:
            print(f"  note: {note}")
        for curve in result.curves.values():
            if curve.certificate is not None:
                print(f"  {curve.name}: {certificate_line(curve.certificate)}",
                      file=sys.stdout if curve.certified else sys.stderr)
    if not args.no_figure:
        name = args.figure or "boundaries_" + "_".join(f"k{b.k:g}" for b in sets)
        for path in save_overlay(sets, out / name, degrees=args.deg):
            print(f"figure: {path}")
    unproven = [c.name for b in sets for c in b.curves.values() if c.certified is False]
    if unproven:
        print(f"groove trace: error: not proven: {', '.join(unproven)} (see above)",
              file=sys.stderr)
        return EXIT_FAILED
    return EXIT_OK


def certificate_line(certificate) -> str:
    """One line for a boundary's certificate: proven, what is not covered, or what failed."""
    if not certificate.proven:
        return certificate.message
    excluded = "; ".join(f"not covered: {e.note}" if e.radius > 0 else f"excluded: {e.note}"
                         for e in certificate.excluded)
    return (f"proven: {certificate.segments} segments in tubes of radius <= "
            f"{certificate.max_radius:.1e}, points within {certificate.node_distance:.0e}, "
            f"{len(certificate.special_points)} special point(s) in boxes of radius <= "
            f"{max((p.radius for p in certificate.special_points), default=0.0):.0e}"
            + (f"; {excluded}" if excluded else ""))
