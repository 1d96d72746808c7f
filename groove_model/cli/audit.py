"""``groove audit``: every quantitative claim of the paper checked, with numbers."""

from __future__ import annotations

import math
import sys
from pathlib import Path

from ..analysis.audit.defaults import DEFAULT_KS
from .common import (
    EXIT_FAILED,
    EXIT_OK,
    add_command,
    add_friction,
    computation_errors,
    output_directory,
    refuse_blocked,
)

__all__ = ["add_parser", "run"]

_EXAMPLES = """examples:
  groove audit                                  # default k = 0.3 1 1.2 1.4 1.5 2 10 100
  groove audit -k 1 10 --out results/           # write results/claims.md and claims.json
  groove audit -k 2 --json                      # the whole report as JSON on stdout
  groove audit --trace --out results/           # add the tracer's curves as a cross-check

verdicts: 'holds', 'holds with qualification', 'fails' (always with a counterexample, printed
below the list), 'inconclusive' (not confirmed at the check's resolution, but no point found
where it is false), 'not applicable' (the statement is about other k, e.g. k > sqrt 2; the
reason is printed). They are computed by the point solver and bracketed root finding, never
written in. A paper claim that fails is a finding, not an error: the exit code is 0 when the
audit itself ran.
"""


def add_parser(subparsers):
    """Register ``groove audit``; returns its parser."""
    p = add_command(
        subparsers, "audit",
        description="Check each statement of fact in the paper's 'Rolling solutions' and "
                    "'Rolling-sliding solutions' paragraphs (and the caption of its Fig. 2) "
                    "for the given friction coefficients: the statement quoted, how it was "
                    "checked, the computed verdict, the numbers, and for a failure a "
                    "counterexample (k, gamma, delta, values).",
        examples=_EXAMPLES)
    add_friction(p, required=False,
                 help="friction coefficients (1e-4 <= k <= 1e6), e.g. -k 1 10 or -k 1 -k 10 "
                      "(default "
                      + " ".join(f"{k:g}" for k in DEFAULT_KS) + ")")
    p.add_argument("--out", metavar="DIR",
                   help="write claims.md and claims.json into DIR (created if needed)")
    p.add_argument("--json", action="store_true", help="print the report as JSON on stdout")
    p.add_argument("--trace", action="store_true",
                   help="add the tracer's boundaries as a cross-check (several seconds per k; "
                        "exit code 1 where it fails, the claims are still reported)")
    p.set_defaults(run=run, outputs=outputs)
    return p


def outputs(args) -> list[Path]:
    """The files ``groove audit`` would write for ``args`` (none without ``--out``)."""
    return [Path(args.out) / name for name in ("claims.md", "claims.json")] if args.out else []


def run(args) -> int:
    """Audit, print the summary (or JSON) and write the files; 1 if a computation failed."""
    # Imported here, not at the top: the audit loads scipy and the solver, which
    # `groove --help` and the other commands' start-up should not wait for.
    from ..analysis.audit.run import run_audit
    from ..io.atomic import atomic_write_all

    ks = tuple(args.ks) if args.ks else DEFAULT_KS
    out = output_directory(args.out) if args.out else None
    refuse_blocked(outputs(args))
    try:
        report = run_audit(ks, use_tracer=args.trace)
    except computation_errors() as exc:
        print(f"groove audit: error: computation failed: {type(exc).__name__}: {exc}",
              file=sys.stderr)
        return EXIT_FAILED
    paths = []
    if out is not None:
        # written (both or neither) before the report is printed: a failed write is reported
        # alone
        markdown, json_text = report.to_markdown(), report.to_json()
        paths = atomic_write_all([
            (out / "claims.md", lambda tmp: Path(tmp).write_text(markdown, encoding="utf-8")),
            (out / "claims.json", lambda tmp: Path(tmp).write_text(json_text, encoding="utf-8"))])
    print(report.to_json() if args.json else _summary(report))
    for path in paths:
        print(f"wrote {path}", file=sys.stderr if args.json else sys.stdout)
    missing = {k: status for k, status in report.tracer.items() if status != "ok"}
    if args.trace and missing:
        # asked for and not there: the claims stand without it, but the run did not do it all
        for k, status in missing.items():
            print(f"groove audit: error: the tracer's cross-check for {k}: {status}",
                  file=sys.stderr)
        return EXIT_FAILED
    return EXIT_OK


def _summary(report) -> str:
    """One line per claim with its verdict, then each counterexample to a failing claim."""
    # Imported here, not at the top: the model loads numpy (see `run`).
    from ..model.parameters import k_text

    width = max(len(c.id) for c in report.claims)
    lines = [f"audit of the paper's claims for k = {', '.join(map(k_text, report.ks))}: "
             + ", ".join(f"{n} {v}" for v, n in report.counts().items())
             + f" ({report.seconds:.1f} s)"]
    cut = False
    for c in report.claims:
        first = c.summary.split(". ")[0]
        shown = first if len(first) <= 100 else first[:97].rsplit(" ", 1)[0] + " ..."
        cut |= shown != first
        lines.append(f"  {c.verdict:<25}  {c.id:<{width}}  {shown}")
    if cut:
        lines.append("  (a summary cut short ends in '...'; --json, or claims.md with --out, "
                     "has each in full)")
    for c in report.claims:
        if c.counterexample is not None and c.verdict == "fails":
            ce = c.counterexample
            lines.append(f"  counterexample to {c.id}: k = {k_text(ce.k)}, "
                         f"gamma = {ce.gamma!r}, delta = {ce.delta!r}: " + ", ".join(
                             f"{key} = {v:.6g}" if isinstance(v, float) and math.isfinite(v)
                             else f"{key} = {v}" for key, v in ce.values.items()))
            if ce.delta < 0.0:  # a groove written with the shallower wall on the left
                lines.append(f"    (walls theta_L = {ce.gamma + ce.delta!r}, theta_R = "
                             f"{ce.gamma - ce.delta!r}: the shallower wall on the left, "
                             "delta < 0, outside the domain 0 <= delta <= gamma; its mirror "
                             f"image, which groove solve takes, is delta = {-ce.delta!r})")
    return "\n".join(lines)
