"""``groove trace``: every boundary for one or more ``k``, written as CSV and as an overlay."""

from __future__ import annotations

import collections
import logging
import sys
from pathlib import Path

from .common import (
    EXIT_FAILED,
    EXIT_OK,
    UsageError,
    add_command,
    add_compliance_options,
    add_friction,
    compliance_from,
    compliance_label,
    output_directory,
    refuse_blocked,
    require_certify_extra,
    require_plotting,
)

__all__ = ["add_parser", "run"]

log = logging.getLogger("groove_model")

_EXAMPLES = """examples:
  groove trace -k 1 10 --out results/             # the paper's Figure 2: CSVs and overlay
  groove trace -k 1 --poisson 0.5 --out out/      # Mindlin's compliance for nu = 0.5
  groove trace -k 0.5 --out out/ --keep-unphysical  # keep unphysical continuations, flagged
  groove trace -k 2 -k 20 --out out/ --deg --figure my_overlay

writes, for each k, boundaries_k{k}.csv (one row per point) and special_points_k{k}.csv, with
k written in full (k = 1.0000001 gives boundaries_k1.0000001.csv), and the overlay FIGURE.png
and FIGURE.svg (default boundaries_k1_k10 for -k 1 10; for many k a short name with their
count and a hash, e.g. boundaries_200k_0.01-1000_1a2b3c4d). If a boundary of some k fails,
that k is reported and skipped, the other k are written, no overlay is drawn, and the exit
code is 1. Every file is written whole or not at all. With another compliance than the
paper's the names end in _nu{NU} (--poisson) or _c{RATIO}. With --certify each boundary is
proven in ball arithmetic (docs/certification.md): a line per boundary says proven or not
proven and why, the CSV column certified says True or False, and the exit code is 1 if any
boundary is not proven (its files are written all the same).
"""

#: Longest default overlay name (without suffix) built from the list of k.
MAX_FIGURE_NAME = 60


def add_parser(subparsers):
    """Register ``groove trace``; returns its parser."""
    p = add_command(
        subparsers, "trace",
        description="Follow each boundary of the paper (T = kN on the steeper wall, upsilon = 0 "
                    "in double rolling and in rolling sliding) from the seed points the paper "
                    "names, by pseudo-arclength continuation, and write them as CSV and as an "
                    "overlay figure in the style of the paper's Figure 2.",
        examples=_EXAMPLES)
    add_friction(p)
    p.add_argument("--out", required=True, help="output directory (created if needed)")
    p.add_argument("--figure", default=None,
                   help="overlay file name inside --out, without suffix or directory "
                        "(default from the k, see below)")
    p.add_argument("--keep-unphysical", action="store_true",
                   help="keep the parts of each boundary where its regime is not valid")
    p.add_argument("--deg", action="store_true", help="overlay axes in degrees")
    p.add_argument("--no-figure", action="store_true", help="write the CSVs only")
    p.add_argument("--certify", action="store_true",
                   help="prove every boundary in ball arithmetic (needs python-flint: pip "
                        "install 'groove-continuation[certify]')")
    add_compliance_options(p)
    p.set_defaults(run=run, outputs=outputs)
    return p


def overlay_name(ks) -> str:
    """The default overlay name: ``boundaries_k1_k10``, or for many ``k`` (a name longer than
    :data:`MAX_FIGURE_NAME`) ``boundaries_{count}k_{min}-{max}_{hash}``, where the hash of the
    exact values tells different sets of ``k`` apart."""
    # Imported here, not at the top: `groove --help` needs neither hashlib nor the model.
    import hashlib

    from ..model.parameters import k_text  # loads numpy

    texts = [k_text(k) for k in ks]
    name = "boundaries_" + "_".join(f"k{t}" for t in texts)
    if len(name) <= MAX_FIGURE_NAME:
        return name
    digest = hashlib.sha256(" ".join(texts).encode()).hexdigest()[:8]
    return f"boundaries_{len(texts)}k_{k_text(min(ks))}-{k_text(max(ks))}_{digest}"


def outputs(args) -> list[Path]:
    """The files ``groove trace`` would write for ``args``: the CSVs of every ``k`` and the
    overlay (checked for a directory in their place before anything is traced)."""
    from ..io.export import boundary_file_names  # pandas: not at `groove --help`

    out, suffix, name = Path(args.out), compliance_label(compliance_from(args)), _overlay(args)
    return [*(out / f for k in dict.fromkeys(args.ks) for f in boundary_file_names(k, suffix)),
            *(() if args.no_figure else (out / f"{name}.png", out / f"{name}.svg"))]


def _overlay(args) -> str:
    """The overlay's file name without suffix: ``--figure``, else from the k and compliance."""
    return args.figure or (overlay_name(list(dict.fromkeys(args.ks)))
                           + compliance_label(compliance_from(args)))


def run(args) -> int:
    """Trace every ``k``; write the CSVs of each ``k`` whose boundaries all succeeded, and the
    overlay if every ``k`` did; 1 if any boundary failed (with ``--certify``: or is not
    proven, its files written all the same), else 0."""
    # Imported here, not at the top: the tracer, the CSV files and the figure load the engine,
    # pandas and matplotlib, which `groove --help` and `groove solve` should not wait for.
    from ..model.parameters import k_text

    out = output_directory(args.out)
    if args.figure is not None and (args.figure in ("", ".", "..")
                                    or Path(args.figure).name != args.figure):
        raise UsageError(f"--figure {args.figure!r} is not a file name: give a name without "
                         "directories (the overlay is written inside --out)")
    if args.figure is not None and Path(args.figure).suffix.lower() in (".pdf", ".jpg", ".jpeg",
                                                                       ".eps", ".ps", ".tif"):
        raise UsageError(f"--figure {args.figure!r} asks for a format groove trace does not write:"
                         " it writes NAME.png and NAME.svg; give NAME without a suffix (groove "
                         "plot -o NAME.pdf draws a PDF from the CSVs)")
    if args.certify:
        require_certify_extra()
    if not args.no_figure:
        require_plotting()
    compliance = compliance_from(args)
    suffix = compliance_label(compliance)
    name = _overlay(args)
    refuse_blocked(outputs(args))
    _note_repeated(args.ks)
    sets: list = []
    try:
        failed = _trace_each(args, out, compliance, suffix, sets)
    except KeyboardInterrupt:
        # Ctrl-C: what was written is whole (and stays); say which k it holds
        done = ", ".join(k_text(b.k) for b in sets) or "none"
        print(f"groove trace: CSVs written before the interrupt: k = {done}; no overlay",
              file=sys.stderr)
        raise
    if failed or args.no_figure:
        # an overlay of this name from an earlier run would now sit beside newer CSVs
        _note_earlier((out / f"{name}.{fmt}" for fmt in ("png", "svg")), "not redrawn")
    if failed:
        print(f"groove trace: no overlay: k = {', '.join(map(k_text, failed))} failed or could "
              "not be written (see above)", file=sys.stderr)
        return EXIT_FAILED
    if not args.no_figure:
        # Imported here: matplotlib is needed for the figure only (loaded by require_plotting).
        from ..plots.overlay import save_overlay

        for path in save_overlay(sets, out / name, degrees=args.deg):
            print(f"figure: {path}")
    unproven = [c.name for b in sets for c in b.curves.values() if c.certified is False]
    if unproven:
        print(f"groove trace: error: not proven: {', '.join(unproven)} (see above)",
              file=sys.stderr)
        return EXIT_FAILED
    return EXIT_OK


def _trace_each(args, out, compliance, suffix: str, sets: list) -> list:
    """Trace and write each ``k`` of ``args`` in turn; append the written sets to ``sets``
    (so that an interrupted run can say which) and return the ``k`` that failed."""
    # Imported here, not at the top: see run().
    from ..io.atomic import WriteError
    from ..io.export import boundary_file_names, write_boundary_set
    from ..model.parameters import Parameters, k_text
    from ..tracing import trace_boundaries

    failed = []
    for k in dict.fromkeys(args.ks):
        log.info("tracing k = %s", k_text(k))
        result = trace_boundaries(Parameters(k, compliance),
                                  keep_unphysical=args.keep_unphysical, certify=args.certify)
        if not result.ok:
            failed.append(k)
            for failure in result.failures:
                print(f"groove trace: error: k = {k_text(k)}: {failure}", file=sys.stderr)
            print(f"groove trace: k = {k_text(k)}: nothing written for this k", file=sys.stderr)
            _note_earlier(out / f for f in boundary_file_names(k, suffix))
            continue
        try:
            paths = write_boundary_set(result, out, suffix)
        except WriteError as exc:  # e.g. a full disk: the other k are still traced and written
            failed.append(k)
            print(f"groove trace: error: k = {k_text(k)}: {exc.strerror}; nothing written for "
                  "this k", file=sys.stderr)
            _note_earlier(out / f for f in boundary_file_names(k, suffix))
            continue
        sets.append(result)
        print(f"k = {k_text(result.k)}, c = {compliance.ratio!r}: "
              f"{', '.join(str(p) for p in paths)}; "
              f"{sum(len(c.x) for c in result.curves.values())} points, "
              f"|rs_limit - dr_limit| <= {result.limit_distance:.1e}")
        for note in result.notes:
            print(f"  note: {note}")
        for curve in result.curves.values():
            if curve.certificate is not None:
                print(f"  {curve.name}: {certificate_line(curve.certificate)}",
                      file=sys.stdout if curve.certified else sys.stderr)
    return failed


def _note_earlier(paths, what: str = "not rewritten") -> None:
    """Say which of ``paths`` exist from an earlier run: they sit beside this run's files and
    look as current."""
    for path in paths:
        if path.is_file():
            print(f"groove trace: note: {path} is from an earlier run ({what})", file=sys.stderr)


def _note_repeated(ks: list) -> None:
    """Say which ``k`` were given more than once: the files of a ``k`` are named by it, so it
    is traced and written once."""
    from ..model.parameters import k_text  # loads numpy, as every tracing command does

    repeated = sorted(k for k, n in collections.Counter(ks).items() if n > 1)
    if repeated:
        print(f"groove trace: note: k = {', '.join(map(k_text, repeated))} given more than "
              "once: traced once", file=sys.stderr)


def certificate_line(certificate) -> str:
    """One line for a boundary's certificate: proven, what is not covered, or what failed."""
    if not certificate.proven:
        return certificate.message
    excluded = "; ".join(f"not covered: {e.note}" if e.radius > 0 else f"covered: {e.note}"
                         for e in certificate.excluded)
    inserted = certificate.inserted_points
    segments = f"{certificate.segments} segments" + (
        f" ({inserted} more than traced: points of the arc inserted where no tube was proven)"
        if inserted else "")
    return (f"proven: {segments} in tubes of radius <= "
            f"{certificate.max_radius:.1e}, points within {certificate.node_distance:.0e}, "
            f"{_zeros(certificate.special_points)}, in boxes of radius <= "
            f"{max((p.radius for p in certificate.special_points), default=0.0):.0e}"
            + (f"; {excluded}" if excluded else ""))


def _zeros(points) -> str:
    """What the proven points of a certificate are, by kind: ``"1 fold, 1 event zero of the
    special points, and 5 more zeros of folds and events"``. Only the first are rows of the
    special-points file; the others (where several events vanish at a curve's start, where
    ``gamma`` and ``delta`` turn at the corner it ends in) mark none."""
    def kinds(chosen) -> str:
        counts = collections.Counter("fold" if p.kind == "fold" else "branch point"
                                     if p.kind == "branch_point" else "event zero"
                                     for p in chosen)
        return ", ".join(f"{n} {kind}{'s' if n != 1 else ''}"
                         for kind, n in sorted(counts.items()))

    listed = [p for p in points if p.reported]
    others = len(points) - len(listed)
    text = f"{kinds(listed)} of the special points" if listed else "no special point"
    if others:
        text += f", and {others} more zero{'s' if others != 1 else ''} of folds and events"
    return text
