"""Instructions executed by ``trace_boundaries``, counted by callgrind: a cost that does not jitter.

    python3 benchmarks/instructions.py [-n 12] [--checkout DIR] [--vs DIR]

On a shared machine the wall clock of one ``k`` moves by 20-40 % from run to run, more than
most changes to the hot path save. The number of instructions the CPU executes does not:
``valgrind --tool=callgrind`` counts them, the same to about 0.1 % between runs, at about 50
times the wall time. This script counts a process that traces ``-n`` values of ``k``
log-spaced over ``[1e-3, 1e5]`` and one that only imports the package and computes the
expected topology (the atlas, once per process), and prints both and their difference: the
instructions of the traces alone. With ``--vs DIR`` it counts a second checkout the same way
and prints the change (each checkout is imported from its directory through ``PYTHONPATH``).

The counts are made reproducible as far as a process allows: one BLAS thread
(``OPENBLAS_NUM_THREADS=1``), a fixed string hash (``PYTHONHASHSEED=0``) and, where ``setarch``
exists, no address-space randomisation (``setarch -R``). They still depend on the machine's
Python, numpy and libm: compare counts made on one machine.

Needs valgrind (``apt install valgrind``); exits with status 2 and says so without it.
"""

from __future__ import annotations

import argparse
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

K_RANGE = (1e-3, 1e5)
ROOT = Path(__file__).resolve().parent.parent

_CHILD = """
import sys
import numpy as np
from groove_model.model.parameters import Parameters
from groove_model.tracing import trace_boundaries
from groove_model.tracing.topology import expected_topology
expected_topology(Parameters(1.0))  # the atlas, once per process, in both counts
for k in np.logspace({low!r}, {high!r}, {n}) if sys.argv[1] == "run" else ():
    trace_boundaries(float(k))
"""


def child_code(n: int) -> str:
    """The counted program: ``python -c CODE run`` traces ``n`` values of ``k``, ``python -c CODE
    none`` only imports and computes the expected topology."""
    low, high = (math.log10(v) for v in K_RANGE)
    return _CHILD.format(low=low, high=high, n=n)


def _count(checkout: Path, what: str, n: int) -> int:
    """Instructions of one child process (``what``: ``run`` or ``none``)."""
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", PYTHONHASHSEED="0",
               PYTHONPATH=str(checkout))
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "callgrind.out"
        command = ["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}",
                   sys.executable, "-c", child_code(n), what]
        if shutil.which("setarch"):
            command = ["setarch", os.uname().machine, "-R", *command]
        # run from the temporary directory: the current one must not shadow the checkout
        done = subprocess.run(command, cwd=tmp, env=env, capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit(f"instructions.py: the counted process failed ({done.returncode}):\n"
                         + done.stderr[-2000:])
    found = re.search(r"Collected : (\d+)", done.stderr)
    if found is None:
        raise SystemExit("instructions.py: callgrind printed no count:\n" + done.stderr[-2000:])
    return int(found.group(1))


def traces(checkout: Path, n: int) -> tuple[int, int]:
    """``(with the traces, without them)``: instructions of the two processes."""
    return _count(checkout, "run", n), _count(checkout, "none", n)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("-n", type=int, default=12, help="values of k (default 12)")
    parser.add_argument("--checkout", type=Path, default=ROOT,
                        help="the checkout to count (default: this one)")
    parser.add_argument("--vs", type=Path, help="a second checkout to compare with")
    args = parser.parse_args(argv)
    if args.n < 1:
        parser.error(f"-n = {args.n} must be >= 1")
    for checkout in (args.checkout, args.vs):
        if checkout is not None and not (checkout / "groove_model").is_dir():
            parser.error(f"{checkout} is not a checkout of this project (no groove_model/)")
    if shutil.which("valgrind") is None:
        print("instructions.py: valgrind is not installed (e.g. apt install valgrind)",
              file=sys.stderr)
        return 2
    rows = []
    for checkout in (args.checkout, args.vs):
        if checkout is not None:
            run, none = traces(checkout, args.n)
            rows.append((checkout, run, none, run - none))
            print(f"{checkout}: {run / 1e6:.1f} million instructions with the traces of {args.n} "
                  f"k, {none / 1e6:.1f} without: {(run - none) / 1e6:.1f} million for the traces",
                  flush=True)
    if len(rows) == 2:
        change = rows[0][3] / rows[1][3] - 1.0
        print(f"{rows[0][0]} against {rows[1][0]}: {100.0 * change:+.1f} %")
    return 0


if __name__ == "__main__":
    sys.exit(main())
