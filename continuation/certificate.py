"""What :func:`continuation.certify` returns, and the tolerances it takes.

A :class:`Certificate` per curve: proven, or the first check that failed (a :class:`Check`)
with its segment or point; the largest tube radius; how far the curve's points are from the
curve of zeros; the zeros of fold components and events proven in boxes
(:class:`ProvenPoint`); the neighbourhoods not covered (:class:`Exclusion`).
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field

import numpy as np

from .result import SpecialKind

__all__ = ["Certificate", "CertifyOptions", "Check", "Exclusion", "ProvenPoint"]


class Check(str, enum.Enum):
    """The test that failed; the values are the names used in messages and files."""

    INPUT = "input"
    TUBE = "tube"
    POINT = "point on the curve"
    CONNECTION = "connection"
    FOLD = "fold"
    EVENT = "event"

    def __str__(self) -> str:
        return self.value


@dataclass(frozen=True)
class CertifyOptions:
    """Tolerances of :func:`certify` (distances in the max-norm of ``x``).

    Parameters
    ----------
    node_tolerance : float
        A point of the curve may be at most ``node_tolerance (1 + |x|)`` from the curve.
    special_tolerance : float
        Largest radius of a special point's box, and largest distance of a zero proven at a
        point of the curve from that point (relative, as above); except for a zero at an end
        of the curve that is not reported there (a curve ending or starting on an event),
        which must lie within ``node_tolerance (1 + |x|)`` of it.
    max_radius : float
        Largest tube radius, as a fraction of the segment's length (at least
        ``node_tolerance (1 + |x|)``); a segment whose tube would be wider is cut in parts.
    extension : float
        Tubes reach this fraction of their length beyond both ends (so consecutive tubes
        overlap).
    max_depth : int
        Most halvings of a segment for its tube.
    leaf_depth : int
        Most halvings of a tube piece to decide the sign or monotonicity of a function (only
        the undecided halves are halved again, so near a zero with a small slope the leaves
        get as short as it needs; at most ``continuation.zeros.LEAF_BUDGET`` per segment).
    refine : int
        Most halvings of a segment whose tube is not proven, each by a point of the arc
        inserted on its middle slice (a curve that bends on a scale below its step; the
        inserted points are proven on the curve like the others).
    """

    node_tolerance: float = 1e-9
    special_tolerance: float = 1e-6
    max_radius: float = 0.2
    extension: float = 1e-3
    max_depth: int = 10
    leaf_depth: int = 40
    refine: int = 4

    def __post_init__(self) -> None:
        for name in ("node_tolerance", "special_tolerance", "max_radius", "extension"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0.0):
                raise ValueError(f"CertifyOptions.{name} = {value!r} must be finite and > 0")
        for name in ("max_depth", "leaf_depth", "refine"):
            value = getattr(self, name)
            if not (isinstance(value, int) and 0 <= value <= 60):
                raise ValueError(f"CertifyOptions.{name} = {value!r} must be an int in [0, 60]")


@dataclass(frozen=True)
class ProvenPoint:
    """A zero of a fold component or event function, proven simple and unique in a box.

    Attributes
    ----------
    kind : SpecialKind
        ``FOLD`` or ``EVENT``.
    index : int
        The point of the curve it belongs to (for a zero at a point the certificate inserted,
        which only a zero crossing against its event's direction can be, the point before).
    centre : ndarray
        Centre of the box ``|x - centre|_inf <= radius`` holding exactly one solution of the
        augmented system.
    radius : float
    distance : float
        Bound of the distance from the curve's point to the solution.
    coordinate, event : int or None
        The fold coordinate, or the event's position.
    reported : bool
        False for a zero at an end of the curve that the run does not report as a crossing.
    """

    kind: SpecialKind
    index: int
    centre: np.ndarray = field(repr=False)
    radius: float
    distance: float
    coordinate: int | None = None
    event: int | None = None
    reported: bool = True


@dataclass(frozen=True)
class Exclusion:
    """A neighbourhood ``|x - centre|_inf <= radius`` the certificate does not cover."""

    centre: np.ndarray = field(repr=False)
    radius: float
    note: str


@dataclass(frozen=True)
class Certificate:
    """The result of :func:`certify` for one curve.

    Attributes
    ----------
    proven : bool
    message : str
        What was proven, or what failed and where.
    check : Check or None
        The test that failed (``None`` if proven).
    segment, point : int or None
        The first failing segment (between points ``segment`` and ``segment + 1``) or point,
        in the curve's own indices (``point`` is ``None`` for an inserted point, whose
        segment is given).
    segments : int
        Segments proven (after inserted points).
    pieces : int
        Tube pieces (segments after halving).
    max_radius : float
        Largest tube radius (max-norm, in the curve's coordinates).
    node_distance : float
        Largest proven distance from a point of the curve to the curve of zeros.
    special_points : tuple of ProvenPoint
    start_sides : tuple of int
        Per event (in the order given): the proven sign of the event at the curve's first
        point, ``+1`` or ``-1``, or for a zero proven there the sign of the side the curve
        leaves it to; ``0`` where not proven (a failed certificate). With the events proven
        to cross zero only where reported (in their direction), a start side of ``+1`` and no
        reported zero of an event with direction ``-1`` keep it positive along the whole
        curve: the curve stays on the side it starts on.
    excluded : tuple of Exclusion
    inserted_points : int
        Points of the arc inserted where a segment's tube was not proven (``refine``).
    seconds : float
    """

    proven: bool
    message: str
    check: Check | None = None
    segment: int | None = None
    point: int | None = None
    segments: int = 0
    pieces: int = 0
    max_radius: float = 0.0
    node_distance: float = 0.0
    special_points: tuple = ()
    excluded: tuple = ()
    start_sides: tuple = ()
    inserted_points: int = 0
    seconds: float = 0.0

    def __str__(self) -> str:
        return self.message
