"""Start-up time of the ``groove`` command: wall time of whole processes, min and median.

    python3 benchmarks/startup.py [--repeat 15]

Runs each command as a new process (as a user does), ``--repeat`` times, next to two baselines:
the bare interpreter and ``import numpy``. On a shared machine the minimum is the best estimate
of the cost; the median shows the jitter. ``groove trace`` writes into a temporary directory.
"""

from __future__ import annotations

import argparse
import shutil
import statistics
import subprocess
import sys
import tempfile
import time


def _cases(groove: str, out: str) -> dict:
    solve = [groove, "solve", "--gamma", "0.6", "--delta", "0.2", "-k", "1"]
    return {
        "python -c pass": [sys.executable, "-c", "pass"],
        "python -c 'import numpy'": [sys.executable, "-c", "import numpy"],
        "groove --help": [groove, "--help"],
        "groove --version": [groove, "--version"],
        "groove solve --gamma 0.6 --delta 0.2 -k 1": solve,
        "groove solve ... --json": [*solve, "--json"],
        "groove trace -k 1 --out DIR": [groove, "trace", "-k", "1", "--out", out],
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=15, help="runs per command (default 15)")
    args = parser.parse_args()
    groove = shutil.which("groove")
    if groove is None:
        sys.exit("startup.py: `groove` is not on PATH: install the package first")
    with tempfile.TemporaryDirectory() as out:
        print("| command | min [s] | median [s] | runs |\n|---|---:|---:|---:|")
        for name, argv in _cases(groove, out).items():
            runs = max(3, args.repeat // 5) if "trace" in name else args.repeat
            times = []
            for _ in range(runs):
                start = time.perf_counter()
                subprocess.run(argv, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                               check=True)
                times.append(time.perf_counter() - start)
            print(f"| `{name}` | {min(times):.3f} | {statistics.median(times):.3f} | {runs} |")


if __name__ == "__main__":
    main()
