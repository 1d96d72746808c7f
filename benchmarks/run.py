"""Run every benchmark and print a markdown table: ``python benchmarks/run.py [--quick] --json OUT``.

Problems and tools (``benchmarks/README.md``): the engine on ``cubic`` and ``circle`` against
the Python peers ``bice`` and ``pycont-lite`` (``pip install '.[bench]'``; a peer that is
missing or fails gives a record with ``ok: false`` and the reason), and the tracer on
``groove_k1``, ``groove_k10`` and ``groove_sweep100`` against ``fsolve_natural`` and
``grid_contour``, and the cost of certifying ``k = 1`` and ``k = 10`` (``benchmarks/certify.py``,
needs python-flint). Wall times are medians over repeats, in-process, after a warm-up run, imports
excluded. Speed is measured here, never asserted in tests.
"""

from __future__ import annotations

import argparse
import json
import logging
import platform
import sys
import time
from dataclasses import dataclass
from pathlib import Path

if __package__ in (None, ""):
    # run as a script: make the repository root importable
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.certify import run_certify
from benchmarks.groove import run_groove
from benchmarks.records import Record, markdown_table
from benchmarks.standard import run_standard

__all__ = ["FULL", "QUICK", "Config", "build_records", "main"]


@dataclass(frozen=True)
class Config:
    """What to run and how often."""

    repeats: int
    standard_problems: tuple[str, ...] = ("cubic", "circle")
    standard_tools: tuple[str, ...] = ("ours", "bice", "pycont-lite")
    groove_problems: tuple[str, ...] = ("groove_k1", "groove_k10", "groove_sweep100")
    groove_tools: tuple[str, ...] = ("ours", "fsolve_natural", "grid_contour")
    sweep: int = 100
    grid_sizes: tuple[int, ...] = (64, 128, 256, 512, 1024, 2048)
    sweep_grid_sizes: tuple[int, ...] = (64, 128)
    fsolve_points: int = 100
    certify_problems: tuple[str, ...] = ()


FULL = Config(repeats=15, certify_problems=("groove_k1", "groove_k10"))
QUICK = Config(repeats=3, grid_sizes=(64, 128, 256, 512), sweep_grid_sizes=(32, 64),
               certify_problems=("groove_k1", "groove_k10"))


def build_records(config: Config) -> list[Record]:
    """Run the configured benchmarks; every (problem, tool) pair gives one record."""
    records = run_standard(config.standard_problems, config.standard_tools, config.repeats)
    records += run_groove(config.groove_problems, config.groove_tools, config.repeats,
                          sweep=config.sweep, grid_sizes=config.grid_sizes,
                          sweep_grid_sizes=config.sweep_grid_sizes,
                          fsolve_points=config.fsolve_points)
    records += run_certify(config.certify_problems, config.repeats)
    return records


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true",
                        help="fewer repeats and smaller grids (under a minute)")
    parser.add_argument("--json", type=Path, help="write the records to this JSON file")
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.ERROR)
    start = time.perf_counter()
    records = build_records(QUICK if args.quick else FULL)
    print(markdown_table(records))
    print()
    for record in records:
        if record.note:
            print(f"- {record.problem} / {record.tool}: {record.note}")
    print(f"\n{platform.python_implementation()} {platform.python_version()}, "
          f"{platform.machine()}, total {time.perf_counter() - start:.1f} s")
    if args.json is not None:
        payload = [record.to_json() for record in records]
        args.json.write_text(json.dumps(payload, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
