"""Tracing the regime boundaries: the tracer, what it returns, and the topology it checks.

:func:`trace_boundaries` follows every boundary of one ``k`` with the continuation engine and
returns a :class:`BoundarySet`; :func:`~groove_model.tracing.topology.expected_topology` says
what each boundary must look like for that ``k``.
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
from .tracer import DEFAULT_OPTIONS, trace_boundaries

__all__ = [
    "CSV_COLUMNS",
    "DEFAULT_OPTIONS",
    "SPECIAL_POINT_COLUMNS",
    "BoundaryCurve",
    "BoundarySet",
    "BoundarySpecialPoint",
    "PointKind",
    "TraceError",
    "Where",
    "boundary_quantities",
    "trace_boundaries",
]
