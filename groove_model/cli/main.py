"""The ``groove`` command line.

Exit codes: 0 success, 1 a computation failed (e.g. a boundary could not be traced),
2 bad input (argument out of range, unreadable file).
"""

from __future__ import annotations

import argparse
import json
import logging
import math
import sys

from ..model.parameters import check_domain, check_friction

__all__ = ["main", "build_parser"]

log = logging.getLogger("groove_model")

EXIT_OK, EXIT_FAILED, EXIT_USAGE = 0, 1, 2


class UsageError(Exception):
    """Bad input from the command line: message printed, exit code 2."""


def _friction(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"friction coefficient k = {text!r} is not a number; k must be finite and > 0"
        ) from None
    try:
        return check_friction(value)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def _real(name: str, allowed: str = "a finite number"):
    def parse(text: str) -> float:
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"{name} = {text!r} is not a number; allowed range: {allowed}") from None
        if not math.isfinite(value):
            raise argparse.ArgumentTypeError(
                f"{name} = {text!r} is outside the allowed range: {allowed}")
        return value

    parse.__name__ = name
    return parse


_SOLVE_EXAMPLES = """examples:
  groove solve --gamma 0.6 --delta 0.2 -k 1
  groove solve --gamma 40 --delta 10 -k 10 --deg --json
  groove solve --gamma 0.6 --delta 0.2 -k 1 --radius 0.01 --young 2e11 --poisson 0.3 --mass 0.033
"""


def _add_solve(sub) -> None:
    p = sub.add_parser(
        "solve", help="equilibrium of the ball at one point (gamma, delta)",
        description="Print the equilibrium the paper predicts at one groove geometry: regime, "
                    "loading direction beta_L, beta_R, rolling upsilon, force ratios, slip, "
                    "rotation sense. Angles in radians unless --deg.",
        epilog=_SOLVE_EXAMPLES, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--gamma", required=True,
                   type=_real("gamma", "0 <= gamma <= pi/2 (90 with --deg)"),
                   help="half-sum of the wall angles, 0 <= gamma <= pi/2")
    p.add_argument("--delta", required=True,
                   type=_real("delta", "0 <= delta <= gamma"),
                   help="half-difference of the wall angles, 0 <= delta <= gamma")
    p.add_argument("-k", required=True, type=_friction, help="friction coefficient, > 0")
    p.add_argument("--deg", action="store_true", help="--gamma and --delta are in degrees")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object (angles in radians)")
    dim = p.add_argument_group("dimensional results (all four needed)")
    dim.add_argument("--radius", type=_real("radius R"), help="ball radius R in m")
    dim.add_argument("--young", type=_real("Young's modulus E"), help="Young's modulus E in Pa")
    dim.add_argument("--poisson", type=_real("Poisson ratio nu"), help="Poisson ratio nu")
    dim.add_argument("--mass", type=_real("mass M"), help="ball mass M in kg")
    dim.add_argument("--g", type=_real("g"), default=9.81, help="gravity in m/s^2 (default 9.81)")
    p.set_defaults(run=_run_solve)


_SOLVE_KEYS = ("regime", "gamma", "delta", "theta_L", "theta_R", "beta_L", "beta_R", "upsilon",
               "T_over_N_L", "T_over_N_R", "d_L", "rotation")


def _json_number(value):
    return value if math.isfinite(value) else None


def _run_solve(args) -> int:
    from ..model.dimensional import dimensional_state
    from ..model.equilibrium import solve_equilibrium

    gamma, delta = (math.radians(args.gamma), math.radians(args.delta)) if args.deg else (
        args.gamma, args.delta)
    try:
        check_domain(gamma, delta)
    except ValueError as exc:
        raise UsageError(str(exc)) from None
    eq = solve_equilibrium(gamma, delta, args.k)
    dims = [args.radius, args.young, args.poisson, args.mass]
    dimensional = None
    if any(v is not None for v in dims):
        if any(v is None for v in dims):
            raise UsageError("dimensional results need all of --radius, --young, --poisson, --mass")
        try:
            dimensional = dimensional_state(eq, args.radius, args.young, args.poisson, args.mass,
                                            args.g)
        except ValueError as exc:
            raise UsageError(str(exc)) from None
    record = {key: getattr(eq, key) for key in _SOLVE_KEYS}
    if args.json:
        out = {key: (_json_number(v) if isinstance(v, float) else v) for key, v in record.items()}
        if dimensional is not None:
            out["dimensional"] = {key: _json_number(v) for key, v in dimensional.to_dict().items()}
        print(json.dumps(out))
        return EXIT_OK
    print(f"k = {args.k:g}, gamma = {eq.gamma:.10g} rad ({math.degrees(eq.gamma):.6g} deg), "
          f"delta = {eq.delta:.10g} rad ({math.degrees(eq.delta):.6g} deg)")
    print(f"  regime     {eq.regime.replace('_', ' ')}, rotation {eq.rotation}")
    print(f"  theta_L    {eq.theta_L:.10g}   theta_R {eq.theta_R:.10g}")
    print(f"  beta_L     {eq.beta_L:.10g}   beta_R  {eq.beta_R:.10g}")
    print(f"  upsilon    {eq.upsilon:.10g}")
    print(f"  T/N_L      {eq.T_over_N_L:.10g}   T/N_R   {eq.T_over_N_R:.10g}   (k = {args.k:g})")
    print(f"  d_L/Z      {eq.d_L:.10g}   d_R/Z   {eq.d_R:.10g}")
    if dimensional is not None:
        d = dimensional
        print(f"  Z          {d.Z:.6g} m")
        print(f"  N_L, N_R   {d.N_L:.6g} N, {d.N_R:.6g} N;  T {d.T:.6g} N")
        print(f"  a_L, a_R   {d.a_L:.6g} m, {d.a_R:.6g} m (contact radii)")
    return EXIT_OK


_TRACE_EXAMPLES = """examples:
  groove trace -k 1 -k 10 --out results/          # the paper's Figure 2: CSVs and overlay
  groove trace -k 0.5 --out out/ --keep-unphysical  # keep unphysical continuations, flagged
  groove trace -k 2 -k 20 --out out/ --deg --figure my_overlay

writes, for each k, boundaries_k{k}.csv (one row per point) and special_points_k{k}.csv,
and the overlay FIGURE.png and FIGURE.svg; nothing is written if any boundary fails.
"""

_PLOT_EXAMPLES = """examples:
  groove plot results/boundaries_k1.csv results/boundaries_k10.csv -o overlay.png
  groove plot out/boundaries_k2.csv -o k2.svg --deg
"""


def _add_trace(sub) -> None:
    p = sub.add_parser(
        "trace", help="trace every regime boundary for one or more k; write CSVs and an overlay",
        description="Follow each boundary of the paper (T = kN on the steeper wall, upsilon = 0 "
                    "in double rolling and in rolling sliding) from the seed points the paper "
                    "names, by pseudo-arclength continuation, and write them as CSV and as an "
                    "overlay figure in the style of the paper's Figure 2.",
        epilog=_TRACE_EXAMPLES, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("-k", required=True, action="append", type=_friction, dest="ks",
                   help="friction coefficient (> 0); repeat for several")
    p.add_argument("--out", required=True, help="output directory (created if needed)")
    p.add_argument("--figure", default=None,
                   help="overlay file name without suffix (default boundaries_k{k1}_k{k2}...)")
    p.add_argument("--keep-unphysical", action="store_true",
                   help="keep the parts of each boundary where its regime is not valid")
    p.add_argument("--deg", action="store_true", help="overlay axes in degrees")
    p.add_argument("--no-figure", action="store_true", help="write the CSVs only")
    p.set_defaults(run=_run_trace)


def _add_plot(sub) -> None:
    p = sub.add_parser(
        "plot", help="draw an overlay from existing boundaries CSV files",
        description="Draw the boundaries stored in boundaries_k*.csv files onto one overlay.",
        epilog=_PLOT_EXAMPLES, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("files", nargs="+", metavar="FILE.csv", help="boundaries CSV files")
    p.add_argument("-o", "--output", required=True, metavar="FIG.png",
                   help="figure file; its suffix (.png, .svg, .pdf) sets the format")
    p.add_argument("--deg", action="store_true", help="axes in degrees")
    p.set_defaults(run=_run_plot)


def _run_trace(args) -> int:
    from pathlib import Path

    from ..io.export import write_boundary_set
    from ..plots.overlay import save_overlay
    from ..tracer import trace_boundaries

    out = Path(args.out)
    if out.exists() and not out.is_dir():
        raise UsageError(f"--out {out} exists and is not a directory")
    sets = []
    for k in dict.fromkeys(args.ks):
        log.info("tracing k = %g", k)
        result = trace_boundaries(k, keep_unphysical=args.keep_unphysical)
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
    if not args.no_figure:
        name = args.figure or "boundaries_" + "_".join(f"k{b.k:g}" for b in sets)
        for path in save_overlay(sets, out / name, degrees=args.deg):
            print(f"figure: {path}")
    return EXIT_OK


def _run_plot(args) -> int:
    from pathlib import Path

    from ..io.export import read_boundaries_csv
    from ..plots.overlay import save_overlay

    frames = []
    for name in args.files:
        try:
            frames.append(read_boundaries_csv(name))
        except OSError as exc:
            raise UsageError(f"cannot read {name}: {exc.strerror or exc}") from None
        except ValueError as exc:
            raise UsageError(str(exc)) from None
    target = Path(args.output)
    fmt = target.suffix.lstrip(".").lower()
    if fmt not in ("png", "svg", "pdf"):
        raise UsageError(f"output format {target.suffix!r} of {target} is not one of .png, .svg, .pdf")
    if not target.parent.is_dir():
        raise UsageError(f"directory {target.parent} of {target} does not exist")
    for path in save_overlay(frames, target, degrees=args.deg, formats=(fmt,)):
        print(f"figure: {path}")
    return EXIT_OK


_REPRODUCE_EXAMPLES = """examples:
  groove reproduce                  # regenerate results/ (the README's main command)
  groove reproduce --out elsewhere/

runs, in order: groove trace -k 1 -k 10 --out OUT; groove map -k 1 -o OUT/map_k1.png --svg;
groove map -k 10 -o OUT/map_k10.png --svg; groove audit --trace --out OUT
"""


def _add_reproduce(sub) -> None:
    p = sub.add_parser(
        "reproduce", help="regenerate every committed result: Figure 2, regime maps, claims audit",
        description="Regenerate the paper's Figure 2 (boundaries for k = 1 and 10, CSV and "
                    "figure), the regime maps for k = 1 and 10, and the audit of the paper's "
                    "claims, into one directory.",
        epilog=_REPRODUCE_EXAMPLES, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", default="results", help="output directory (default results/)")
    p.set_defaults(run=_run_reproduce)


def _run_reproduce(args) -> int:
    from pathlib import Path

    out = Path(args.out)
    steps = (
        ["trace", "-k", "1", "-k", "10", "--out", str(out)],
        ["map", "-k", "1", "-o", str(out / "map_k1.png"), "--svg"],
        ["map", "-k", "10", "-o", str(out / "map_k10.png"), "--svg"],
        ["audit", "--trace", "--out", str(out)],
    )
    parser = build_parser()
    out.mkdir(parents=True, exist_ok=True)
    for argv in steps:
        log.info("groove %s", " ".join(argv))
        step = parser.parse_args(argv)
        code = step.run(step)
        if code != EXIT_OK:
            return code
    return EXIT_OK


def build_parser() -> argparse.ArgumentParser:
    """The ``groove`` argument parser with every subcommand."""
    parser = argparse.ArgumentParser(
        prog="groove",
        description="Regime boundaries of an elastic ball in a rigid V-groove "
                    "(Halsey & Ertas, 'A Ball in a Groove').",
        epilog="examples:\n  groove solve --gamma 0.6 --delta 0.2 -k 1\n"
               "  groove trace -k 1 -k 10 --out results/\n"
               "  groove plot results/boundaries_k1.csv -o k1.png\n"
               "  groove map -k 10 -o map_k10.png --svg\n"
               "  groove audit -k 1 10\n"
               "  groove reproduce                     # regenerate results/\n"
               "run 'groove COMMAND --help' for each command's options and examples",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("-v", "--verbose", action="store_true", help="log progress")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    from .analysis import add_audit_command, add_map_command

    _add_solve(sub)
    _add_trace(sub)
    _add_plot(sub)
    add_map_command(sub)
    add_audit_command(sub)
    _add_reproduce(sub)
    return parser


def main(argv=None) -> int:
    """Entry point of the ``groove`` console script; returns the exit code."""
    parser = build_parser()
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.INFO if args.verbose else logging.WARNING,
                        format="%(levelname)s %(name)s: %(message)s")
    try:
        return args.run(args)
    except UsageError as exc:
        parser.exit(EXIT_USAGE, f"groove {args.command}: error: {exc}\n")
    except OSError as exc:
        parser.exit(EXIT_USAGE, f"groove {args.command}: error: {exc}\n")
    return EXIT_FAILED  # pragma: no cover


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
