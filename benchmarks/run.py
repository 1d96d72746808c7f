"""Run every benchmark and print a markdown table: ``python benchmarks/run.py [--quick] --json OUT``.

Problems and tools (``benchmarks/README.md``): the engine on ``cubic`` and ``circle`` against
the Python peers ``bice`` and ``pycont-lite`` (``pip install '.[bench]'``; a peer that is
missing or fails gives a record with ``ok: false`` and the reason), and the tracer on
``groove_k1``, ``groove_k10`` and ``groove_sweep100`` against ``fsolve_natural`` and
``grid_contour``; ``groove_sweep1000`` serially and on 2 processes; the cost of certifying
``k = 1`` and ``k = 10`` (``benchmarks/certify.py``, needs python-flint). Then the targets of issue 14
(:mod:`benchmarks.targets`), each with its ratio and whether it is met: speed against
``fsolve_natural``, microseconds per point of the engine, the 1000-k sweep, the memory of a
streamed sweep and the start-up of the command. Wall times are medians over repeats,
in-process, after a warm-up run, imports excluded. Speed is measured here, never asserted in
tests.
"""

from __future__ import annotations

import argparse
import dataclasses
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
from benchmarks.targets import (
    evaluate,
    markdown_targets,
    measure_memory,
    measure_startup,
    run_sweep1000,
)

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
    #: groove_sweep1000: every ``sweep1000_stride``-th of its 1000 k (0: not run)
    sweep1000_stride: int = 0
    #: sweep sizes whose peak memory is measured (empty: not measured)
    memory_sizes: tuple[int, ...] = ()
    #: repeats of the start-up measurement (0: not measured)
    startup_repeats: int = 0
    #: groove problems whose certification is timed against their trace
    certify_problems: tuple[str, ...] = ()


FULL = Config(repeats=15, sweep1000_stride=1, memory_sizes=(500, 2000), startup_repeats=9,
              certify_problems=("groove_k1", "groove_k10"))
QUICK = Config(repeats=3, grid_sizes=(64, 128, 256, 512), sweep_grid_sizes=(32, 64),
               sweep1000_stride=10, memory_sizes=(100, 400), startup_repeats=5,
               certify_problems=("groove_k1", "groove_k10"))


def build_records(config: Config, facts: dict | None = None) -> list[Record]:
    """Run the configured benchmarks; every (problem, tool) pair gives one record.

    ``facts``, if given, receives what the targets need beyond the records (the sweep's
    output check, memory, start-up times).
    """
    records = run_standard(config.standard_problems, config.standard_tools, config.repeats)
    records += run_groove(config.groove_problems, config.groove_tools, config.repeats,
                          sweep=config.sweep, grid_sizes=config.grid_sizes,
                          sweep_grid_sizes=config.sweep_grid_sizes,
                          fsolve_points=config.fsolve_points)
    records += run_certify(config.certify_problems, config.repeats)
    facts = {} if facts is None else facts
    if config.sweep1000_stride:
        sweep_records, facts["sweep"] = run_sweep1000(config.sweep1000_stride)
        records += sweep_records
    if config.memory_sizes:
        facts["memory"] = measure_memory(config.memory_sizes)
    if config.startup_repeats:
        facts["startup"] = measure_startup(config.startup_repeats)
    return records


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true",
                        help="fewer repeats and smaller grids (under a minute)")
    parser.add_argument("--json", type=Path, help="write the records to this JSON file")
    parser.add_argument("--memory", type=int, metavar="N",
                        help="measure the memory of one streamed sweep of N k instead "
                             "(target 4 itself: N = 100000 took 79 min on 2 shared cores)")
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.ERROR)
    start = time.perf_counter()
    facts: dict = {}
    config = QUICK if args.quick else FULL
    if args.memory:
        config = dataclasses.replace(config, memory_sizes=(args.memory,))
    records = build_records(config, facts)
    targets = evaluate(records, facts.get("sweep"), facts.get("memory"), facts.get("startup"))
    print(markdown_table(records))
    print()
    for record in records:
        if record.note:
            print(f"- {record.problem} / {record.tool}: {record.note}")
    print()
    print(markdown_targets(targets))
    print()
    for target in targets:
        if target.note:
            print(f"- {target.target}: {target.note}")
    print(f"\n{platform.python_implementation()} {platform.python_version()}, "
          f"{platform.machine()}, total {time.perf_counter() - start:.1f} s")
    if args.json is not None:
        payload = [record.to_json() for record in records]
        args.json.write_text(json.dumps(payload, indent=1) + "\n")
        # the targets beside the records: OUT.json -> OUT.targets.json
        args.json.with_suffix(".targets.json").write_text(
            json.dumps([target.to_json() for target in targets], indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
