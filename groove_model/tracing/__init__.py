"""Tracing the regime boundaries: the tracer, what it returns, and the topology it checks.

:func:`trace_boundaries` follows every boundary of one ``k`` with the continuation engine and
returns a :class:`BoundarySet`; :func:`trace_many` does it for many ``k`` (in parallel with
``jobs`` or on any ``concurrent.futures`` executor) and returns one table;
:func:`~groove_model.tracing.topology.expected_topology` says what each boundary must look like
for that ``k``.
"""

from .curves import (
    CSV_COLUMNS,
    SPECIAL_POINT_COLUMNS,
    BoundaryCurve,
    BoundarySet,
    BoundarySpecialPoint,
    PointKind,
    TraceError,
    Where,
    boundary_quantities,
)
from .sweep import SweepError, SweepResult, WorkerStopped, sweep_results, trace_many
from .tracer import DEFAULT_OPTIONS, trace_boundaries

__all__ = [
    "CSV_COLUMNS",
    "DEFAULT_OPTIONS",
    "SPECIAL_POINT_COLUMNS",
    "BoundaryCurve",
    "BoundarySet",
    "BoundarySpecialPoint",
    "PointKind",
    "SweepError",
    "SweepResult",
    "TraceError",
    "Where",
    "WorkerStopped",
    "boundary_quantities",
    "sweep_results",
    "trace_boundaries",
    "trace_many",
]
