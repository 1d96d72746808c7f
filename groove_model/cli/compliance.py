"""``groove compliance``: the atlas for several Poisson ratios, and in ``nu`` at fixed ``k``."""

from __future__ import annotations

import sys
from pathlib import Path

from .common import (
    EXIT_FAILED,
    EXIT_OK,
    add_command,
    computation_errors,
    output_directory,
    refuse_blocked,
    require_plotting,
    traced_friction,
    traced_poisson,
)

__all__ = ["add_parser", "run"]

_EXAMPLES = """examples:
  groove compliance --out results/compliance/       # nu = 0, 0.3, 0.5; k = 1 and 10
  groove compliance --poissons 0 0.25 0.5 -k 2 --out out/

writes atlas_nu<NU>_*.csv for each Poisson ratio (the atlas in k, as groove atlas writes it),
atlas_k<K>_in_nu_*.csv for each k (the atlas in nu over [0, 0.5]), compliance.md (thresholds,
topologies and shifts compared) and the figure compliance.png/.svg.
"""


def add_parser(subparsers):
    """Register ``groove compliance``; returns its parser."""
    p = add_command(
        subparsers, "compliance",
        description="Trace the atlas of special points in k for Mindlin's compliance "
                    "c = 2 (1 - nu)/(2 - nu) at several Poisson ratios, and in nu over "
                    "[0, 0.5] at fixed k; report which thresholds and special points move, "
                    "by how much, and whether the topology changes.",
        examples=_EXAMPLES)
    p.add_argument("--poissons", type=traced_poisson, nargs="+", default=[0.0, 0.3, 0.5],
                   metavar="NU", help="Poisson ratios, the first the reference (default 0 0.3 "
                                      "0.5)")
    p.add_argument("-k", type=traced_friction, action="extend", nargs="+", dest="ks", metavar="K",
                   help="friction coefficients of the atlases in nu (default 1 10)")
    p.add_argument("--out", required=True, help="output directory (created if needed)")
    p.add_argument("--no-figure", action="store_true", help="write the CSVs and report only")
    p.set_defaults(run=run, outputs=outputs)
    return p


def outputs(args) -> list[Path]:
    """The files ``groove compliance`` would write for ``args``."""
    # Imported here, not at the top: numpy, which `groove --help` does not need.
    from ..io.atlas import STANDARD_CURVES
    from ..model.parameters import k_text

    out = Path(args.out)
    stems = [*(f"atlas_nu{k_text(nu)}" for nu in dict.fromkeys(args.poissons)),
             *(f"atlas_k{k_text(k)}_in_nu" for k in dict.fromkeys(args.ks or (1.0, 10.0)))]
    return [*(out / f"{stem}_{name}.csv" for stem in stems
              for name in (*STANDARD_CURVES, "thresholds")),
            *(out / f"{stem}.md" for stem in stems), out / "compliance.md",
            *(() if args.no_figure else (out / "compliance.png", out / "compliance.svg"))]


def run(args) -> int:
    """Compute, write and print the comparison; 1 if a computation failed."""
    # Imported here, not at the top: the atlases load the engine, scipy and pandas.
    from ..analysis.compliance import compliance_study
    from ..io.atlas import atlas_files
    from ..io.atomic import atomic_write_all
    from ..model.parameters import k_text

    out = output_directory(args.out)
    ks = tuple(dict.fromkeys(args.ks or (1.0, 10.0)))
    refuse_blocked(outputs(args))
    if not args.no_figure:
        require_plotting()
    try:
        study = compliance_study(tuple(dict.fromkeys(args.poissons)), ks)
    except computation_errors() as exc:
        print(f"groove compliance: error: computation failed: {type(exc).__name__}: {exc}",
              file=sys.stderr)
        return EXIT_FAILED
    if not study.ok:
        for atlas in (*study.in_k.values(), *study.in_nu.values()):
            for failure in atlas.failures:
                print(f"groove compliance: error: {failure}", file=sys.stderr)
        print("groove compliance: nothing written: a curve failed", file=sys.stderr)
        return EXIT_FAILED
    files = []
    for nu, atlas in study.in_k.items():
        files += atlas_files(atlas, out, f"atlas_nu{k_text(nu)}")
    for k, atlas in study.in_nu.items():
        files += atlas_files(atlas, out, f"atlas_k{k_text(k)}_in_nu")
    report = study.to_markdown()
    files.append((out / "compliance.md",
                  lambda tmp: Path(tmp).write_text(report, encoding="utf-8")))
    if not args.no_figure:
        # Imported here: matplotlib is needed for the figure only.
        from ..plots.atlas import compliance_figure_files

        files += compliance_figure_files(study.in_k, study.in_nu, out / "compliance")
    paths = atomic_write_all(files)  # every file of the comparison, or none
    print(report)
    print(f"computed in {study.seconds:.1f} s")
    for path in paths:
        print(f"wrote {path}")
    return EXIT_OK
