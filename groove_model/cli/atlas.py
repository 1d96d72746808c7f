"""``groove atlas``: every special point followed as a curve in ``k``, and the thresholds."""

from __future__ import annotations

import sys
from pathlib import Path

from .common import (
    EXIT_FAILED,
    EXIT_OK,
    UsageError,
    add_command,
    add_compliance_options,
    compliance_from,
    compliance_label,
    computation_errors,
    output_directory,
    refuse_blocked,
    require_plotting,
    traced_friction,
)

__all__ = ["add_parser", "run"]

_EXAMPLES = """examples:
  groove atlas --out results/                         # k in [1e-4, 1e6], the paper's compliance
  groove atlas --k-min 0.1 --k-max 100 --out out/
  groove atlas --poisson 0.5 --out out/               # Mindlin's compliance for nu = 0.5

writes, with STEM = atlas (atlas_nu0.5, atlas_c0.8 for another compliance):
STEM_<curve>.csv for each curve of special points (junction, dr_limit_fold_delta,
rs_no_roll_fold_gamma; columns k, nu, compliance, gamma, delta, beta_L, upsilon, physical,
threshold), STEM_thresholds.csv, STEM.md (each threshold with its defining equations, the
topology in each range of k) and the figure STEM.png (and STEM.svg with --svg); nothing is
written if a curve fails.
"""


def add_parser(subparsers):
    """Register ``groove atlas``; returns its parser."""
    p = add_command(
        subparsers, "atlas",
        description="Follow the junction (upsilon = 0 on dr_limit), the maximum of delta along "
                    "dr_limit and the fold in gamma of rs_no_roll (and any other fold) as "
                    "curves in k, by two-parameter continuation in log k, and locate the "
                    "thresholds where a special point is born, dies or crosses another, each as "
                    "a codimension-2 point to 1e-12.",
        examples=_EXAMPLES)
    p.add_argument("--k-min", type=traced_friction, default=1e-4,
                   help="smallest k (default 1e-4; 1e-4 <= k <= 1e6)")
    p.add_argument("--k-max", type=traced_friction, default=1e6,
                   help="largest k (default 1e6; 1e-4 <= k <= 1e6)")
    p.add_argument("--out", required=True, help="output directory (created if needed)")
    p.add_argument("--no-figure", action="store_true", help="write the CSVs and report only")
    p.add_argument("--svg", action="store_true", help="also write the figure as SVG")
    add_compliance_options(p)
    p.set_defaults(run=run, outputs=outputs)
    return p


def outputs(args) -> list[Path]:
    """The files ``groove atlas`` would write for ``args`` (a curve that is not one of the
    standard three adds its own CSV, known only once traced)."""
    from ..io.atlas import STANDARD_CURVES  # numpy: not at `groove --help`

    out, stem = Path(args.out), _stem(args)
    return [*(out / f"{stem}_{name}.csv" for name in (*STANDARD_CURVES, "thresholds")),
            out / f"{stem}.md", *(out / f"{stem}.{fmt}" for fmt in _figures(args))]


def _stem(args) -> str:
    return "atlas" + compliance_label(compliance_from(args))


def _figures(args) -> tuple:
    """The figure's formats: none with ``--no-figure``, PNG, and SVG with ``--svg``."""
    return () if args.no_figure else ("png", "svg") if args.svg else ("png",)


def run(args) -> int:
    """Trace the atlas; write nothing and return 1 if a curve failed, else write and 0."""
    # Imported here, not at the top: the atlas loads the engine, scipy and pandas, and the
    # figure matplotlib, which `groove --help` should not wait for.
    from ..io.atlas import STANDARD_CURVES, write_atlas
    from ..model.parameters import k_text
    from ..tracing.atlas import trace_atlas

    if not args.k_min < args.k_max:
        raise UsageError(f"--k-min {k_text(args.k_min)} must be below --k-max "
                         f"{k_text(args.k_max)}")
    out = output_directory(args.out)
    compliance = compliance_from(args)
    stem = _stem(args)
    refuse_blocked(outputs(args))
    if not args.no_figure:
        require_plotting()
    try:
        atlas = trace_atlas((args.k_min, args.k_max), compliance=compliance)
    except computation_errors() as exc:
        print(f"groove atlas: error: computation failed: {type(exc).__name__}: {exc}",
              file=sys.stderr)
        return EXIT_FAILED
    if not atlas.ok:
        for failure in atlas.failures:
            print(f"groove atlas: error: {failure}", file=sys.stderr)
        print("groove atlas: nothing written: a curve failed (see above)", file=sys.stderr)
        return EXIT_FAILED
    figure = []
    if not args.no_figure:
        # Imported here: matplotlib is needed for the figure only.
        from ..plots.atlas import atlas_figure_files

        figure = atlas_figure_files(atlas, out / stem, _figures(args))
    paths = write_atlas(atlas, out, stem, figure)  # the CSVs, the report and the figure: one group
    print(f"atlas for k in [{args.k_min:g}, {args.k_max:g}], c = {compliance.ratio:.6g}: "
          f"{len(atlas.curves)} curves, {sum(len(c.p) for c in atlas.curves.values())} points "
          f"in {atlas.seconds:.2f} s")
    for t in atlas.thresholds:
        print(f"  {t.name:<10} k = {t.value:.15g}  (gamma, delta) = ({t.x[0]:.12g}, "
              f"{t.x[1]:.3g}), residual {t.residual:.1e}: {t.what}")
    if not atlas.thresholds:
        print("  no threshold in this range: the diagram has the same shape for every k in it")
    absent = [name for name in STANDARD_CURVES if name not in atlas.curves]
    if absent:
        print(f"  not in this range (files with no rows): {', '.join(absent)}")
    for path in paths:
        print(f"wrote {path}")
    return EXIT_OK
