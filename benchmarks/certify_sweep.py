"""Certify every boundary over the CI sweep of k: ``python benchmarks/certify_sweep.py [--json OUT]``.

The k values are those of ``tests/test_sweep_topology.py`` (367: 300 log-spaced in
[1e-4, 1e6], the neighbours of the thresholds k = 1/sqrt 2, sqrt 2 and k_cross, values that
once failed). For every k
the boundaries are traced and certified (``trace_boundaries(k, certify=True)``); the script
prints how many boundaries were proven, and for each one not proven the k, the boundary and the
reason, then the cost of certifying against tracing (CPU time, each k traced once without and
once with certification). Needs python-flint (``pip install '.[certify]'``).
"""

from __future__ import annotations

import argparse
import collections
import json
import logging
import math
import sys
import time
from pathlib import Path

import numpy as np

if __package__ in (None, ""):
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from groove_model.tracing import trace_boundaries  # noqa: E402

SQRT2 = math.sqrt(2.0)
#: where the junction passes the maximum of delta along dr_limit (the atlas's k_cross)
K_CROSS = 15.19939619365445

#: the k values of tests/test_sweep_topology.py
SWEEP = sorted({
    *np.geomspace(1e-4, 1e6, 300).tolist(),
    *(SQRT2 * (1.0 + sign * 10.0 ** -j) for j in (*range(2, 11), 12) for sign in (1, -1)),
    *(1.0 / SQRT2 * (1.0 + sign * 10.0 ** -j) for j in (*range(2, 11), 12) for sign in (1, -1)),
    *(K_CROSS * (1.0 + sign * 10.0 ** -j) for j in (*range(2, 11), 12) for sign in (1, -1)),
    14.4, 14.5, 32.7274, 32.72740209872818, 0.00013848863713938732, 1.4283556979968262,
    1e4, 1e6, 0.09111627561154892,
})


def certify_k(k: float) -> dict:
    """Trace and certify one k; the record of each boundary and the two CPU times."""
    start = time.process_time()
    trace_boundaries(k)
    traced = time.process_time() - start
    start = time.process_time()
    result = trace_boundaries(k, certify=True)
    both = time.process_time() - start
    curves = {}
    for name, curve in result.curves.items():
        cert = curve.certificate
        curves[name] = dict(ok=curve.ok, proven=bool(cert and cert.proven),
                            message=cert.message if cert else curve.status,
                            check=cert.check.value if cert and cert.check else None,
                            segments=cert.segments if cert else 0,
                            max_radius=cert.max_radius if cert else math.nan,
                            excluded=[e.note for e in cert.excluded] if cert else [])
    return dict(k=k, trace_s=traced, certify_s=both - traced, curves=curves)


def report(records: list[dict]) -> str:
    """The counts, the curves not proven with their reasons, and the cost."""
    counts = collections.Counter()
    lines = []
    for r in records:
        for name, c in r["curves"].items():
            counts["proven" if c["proven"] else "not proven"] += 1
            counts[f"{name} {'proven' if c['proven'] else 'not proven'}"] += 1
            if not c["proven"]:
                lines.append(f"- k = {r['k']!r}: {name}: {c['message']}")
    ratios = np.array([r["certify_s"] / r["trace_s"] for r in records])
    total = sum(counts[key] for key in ("proven", "not proven"))
    out = [f"{len(records)} values of k, {total} boundaries: {counts['proven']} proven, "
           f"{counts['not proven']} not proven"]
    for name in ("dr_limit", "rs_limit", "dr_no_roll", "rs_no_roll"):
        out.append(f"  {name}: {counts[name + ' proven']} proven, "
                   f"{counts[name + ' not proven']} not proven")
    out += lines
    out.append(f"certify / trace (CPU time per k): median {np.median(ratios):.1f}, "
               f"90th percentile {np.percentile(ratios, 90):.1f}, max {ratios.max():.1f}; "
               f"total trace {sum(r['trace_s'] for r in records):.1f} s, certify "
               f"{sum(r['certify_s'] for r in records):.1f} s")
    return "\n".join(out)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", type=Path, help="write the records to this JSON file")
    parser.add_argument("--every", type=int, default=1, help="certify every n-th k only")
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.ERROR)
    records = []
    for k in SWEEP[::args.every]:
        records.append(certify_k(k))
        for name, c in records[-1]["curves"].items():
            if not c["proven"]:
                print(f"k = {k!r}: {name}: {c['message']}", file=sys.stderr, flush=True)
    print(report(records))
    if args.json is not None:
        args.json.write_text(json.dumps(records, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
