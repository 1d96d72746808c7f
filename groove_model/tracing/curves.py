"""What the tracer returns: boundaries, their special points, and the CSV tables they make.

A :class:`BoundarySet` holds every boundary of one ``k`` as a :class:`BoundaryCurve` in
``x = (gamma, delta, beta_L, upsilon)``, with its special points
(:class:`BoundarySpecialPoint`, kinds in :class:`PointKind`) and where its physical part starts
and ends (:class:`Where`); ``to_frame`` gives the rows of the CSV files (:data:`CSV_COLUMNS`).
"""

from __future__ import annotations

import dataclasses
import enum
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..model.parameters import Parameters, check_flag

if TYPE_CHECKING:  # pandas is imported where a table is made: `groove atlas` needs none
    import pandas as pd

    from continuation import Certificate

__all__ = [
    "CSV_COLUMNS",
    "SPECIAL_POINT_COLUMNS",
    "BoundaryCurve",
    "BoundarySet",
    "BoundarySpecialPoint",
    "PointKind",
    "TraceError",
    "Where",
    "boundary_quantities",
]


CSV_COLUMNS = ("boundary", "k", "compliance", "s", "gamma", "delta", "theta_L", "theta_R",
               "beta_L", "beta_R", "upsilon", "T_over_N_L", "T_over_N_R", "d_L", "physical",
               "point", "certified")


SPECIAL_POINT_COLUMNS = ("boundary", "k", "compliance", "kind", "gamma", "delta", "beta_L",
                         "upsilon")


class PointKind(str, enum.Enum):
    """Kinds of boundary special points; the values are the names in the CSV files.

    ``START`` and ``END`` bound each physical part of a boundary and the traced curve itself:
    with ``keep_unphysical=True`` a curve can have an ``END`` where its regime stops being
    valid (note ``regime limit: ...``) and another where the traced curve ends.
    """

    START = "start"
    END = "end"
    JUNCTION = "junction"
    FOLD_GAMMA = "fold_gamma"
    FOLD_DELTA = "fold_delta"
    BRANCH_POINT = "branch_point"

    def __str__(self) -> str:
        return self.value


#: legacy tuple of the kind names
SPECIAL_KINDS = tuple(kind.value for kind in PointKind)


#: the order of kinds at one row: the first is the one written in the CSV's point column
POINT_ORDER = {PointKind.BRANCH_POINT: 0, PointKind.JUNCTION: 1, PointKind.FOLD_GAMMA: 2,
             PointKind.FOLD_DELTA: 3, PointKind.START: 4, PointKind.END: 5}


class Where(str, enum.Enum):
    """Where a boundary's physical part starts or ends."""

    SEED = "seed"
    BRANCH_POINT = "branch_point"
    JUNCTION = "junction"
    GAMMA_MIN = "gamma_min"
    CORNER = "corner"
    REGIME_LIMIT = "regime_limit"
    DOMAIN_EDGE = "domain_edge"
    NOWHERE = "nowhere"

    def __str__(self) -> str:
        return self.value


class TraceError(RuntimeError):
    """A boundary could not be traced; ``boundary_set`` holds everything that was traced
    (``None`` on a sweep's ``SweepError``, which holds its ``results`` instead)."""

    def __init__(self, message: str, boundary_set: BoundarySet | None) -> None:
        super().__init__(message)
        self.boundary_set = boundary_set


@dataclass(frozen=True)
class BoundarySpecialPoint:
    """A special point of a boundary.

    Attributes
    ----------
    boundary : str
    kind : PointKind
        ``start``, ``end``, ``junction`` (where boundaries meet), ``fold_gamma`` and
        ``fold_delta`` (turning points in gamma and in delta) or ``branch_point``.
    x : ndarray, shape (4,)
        ``(gamma, delta, beta_L, upsilon)``.
    s : float
        Arclength along the boundary in ``x`` (radians).
    index : int
        Row of the point in ``BoundaryCurve.x``.
    note : str
        What the point is, e.g. "singular corner (pi/4, pi/4): beta_L = 0, N_L = 0".
    """

    boundary: str
    kind: PointKind
    x: np.ndarray = field(repr=False)
    s: float
    index: int
    note: str = ""


@dataclass(frozen=True)
class BoundaryCurve:
    """One traced boundary in ``x = (gamma, delta, beta_L, upsilon)``.

    Attributes
    ----------
    name : str
    k : float
    x : ndarray, shape (m, 4)
    s : ndarray, shape (m,)
        Arclength in ``x`` from the first traced point.
    physical : ndarray of bool, shape (m,)
        Whether the boundary's regime is valid at each point.
    special_points : tuple of BoundarySpecialPoint
    status : str
        The engine's status message of the run behind the curve, or what failed.
    ok : bool
        False if the engine failed or the curve differs from the expected topology; the
        points traced are kept.
    residual : float
        Largest ``|H_i| / scale_i`` over the points, in the ``x`` form of the paper's
        equations (:meth:`groove_model.model.boundaries.BoundarySystem.scaled_residual`: each
        equation divided by the largest size of its terms, which grows with ``k``:
        :attr:`~groove_model.model.boundaries.BoundarySystem.row_scales`).
    start, end : Where
        Where the physical part starts and ends (``NOWHERE`` if it has none or the engine
        failed before its end).
    engine_rows : ndarray of int
        The rows of the engine curve (``engine[0]``) kept, in order.
    certificate : continuation.Certificate or None
        The proof in ball arithmetic (``trace_boundaries(k, certify=True)``); ``None`` if
        certification was not asked for.
    params : Parameters or None
        The parameters of the trace (``k`` and the compliance); ``None``: ``k`` with the
        paper's compliance.
    """

    name: str
    k: float
    x: np.ndarray = field(repr=False)
    s: np.ndarray = field(repr=False)
    physical: np.ndarray = field(repr=False)
    special_points: tuple = ()
    status: str = ""
    ok: bool = True
    residual: float = 0.0
    engine: tuple = field(default=(), repr=False, compare=False)
    start: Where = Where.NOWHERE
    end: Where = Where.NOWHERE
    engine_rows: np.ndarray = field(default_factory=lambda: np.zeros(0, int), repr=False,
                                    compare=False)
    certificate: Certificate | None = field(default=None, repr=False, compare=False)
    params: Parameters | None = field(default=None, repr=False, compare=False)

    @property
    def certified(self) -> bool | None:
        """``True`` if proven, ``False`` if certification failed, ``None`` if not asked for."""
        return None if self.certificate is None else bool(self.certificate.proven)

    def failed(self, message: str) -> BoundaryCurve:
        """This curve marked as failed, with ``message`` as its status."""
        return dataclasses.replace(self, status=message, ok=False)

    def special(self, kind: PointKind | str) -> tuple:
        """The special points of one kind."""
        kind = PointKind(kind)
        return tuple(p for p in self.special_points if p.kind is kind)

    def to_frame(self, partial: bool = False) -> pd.DataFrame:
        """The CSV table of this boundary (columns :data:`CSV_COLUMNS`), with the compliance
        of its trace.

        Raises
        ------
        TraceError
            If the boundary failed (``ok`` is False): its rows are not a whole boundary. With
            ``partial=True`` they are returned all the same, for inspection.
        """
        import pandas as pd  # only the tables need it, not the tracer

        if not check_flag("partial", partial) and not self.ok:
            raise TraceError(f"{self.name} for k = {self.k!r} failed ({self.status}): its rows "
                             "are not a whole boundary; to_frame(partial=True) gives them "
                             "for inspection", None)
        return pd.DataFrame(self._columns(self.params or Parameters(self.k)),
                            columns=list(CSV_COLUMNS))

    def _columns(self, params: Parameters) -> dict:
        """The columns of :meth:`to_frame` as arrays, ``{name: array}``."""
        m = len(self.x)
        q = boundary_quantities(self.name, self.x, params)
        point = np.full(m, "", dtype=object)
        for p in sorted(self.special_points, key=lambda p: -POINT_ORDER[p.kind]):
            point[p.index] = p.kind.value
        return {"boundary": np.full(m, self.name, dtype=object),
                "k": np.full(m, self.k, dtype=float),
                "compliance": np.full(m, params.c, dtype=float), "s": self.s, **q,
                "physical": self.physical, "point": point,
                "certified": np.full(m, self.certified, dtype=object)}


@dataclass(frozen=True)
class BoundarySet:
    """Every boundary traced for one ``k``.

    Attributes
    ----------
    k : float
    curves : dict of str to BoundaryCurve
        By name, in the order of ``BOUNDARY_NAMES``; a boundary with no physical part is
        absent unless the unphysical parts were kept.
    limit_distance : float
        Largest distance in ``x`` from a point of ``rs_limit`` to the curve ``dr_limit``
        (they are the same curve, paper "Rolling-sliding solutions"), each point projected
        onto the equations of ``dr_limit``; NaN where ``rs_limit`` failed or a projection did
        not converge (``rs_limit`` then fails).
    notes : tuple of str
        What was found, e.g. that ``dr_no_roll`` has no physical part for ``k < sqrt 2``.
    params : Parameters
        The parameters of the trace.
    """

    k: float
    curves: dict = field(repr=False)
    limit_distance: float = math.nan
    notes: tuple = ()
    params: Parameters | None = field(default=None, repr=False, compare=False)

    @property
    def ok(self) -> bool:
        return all(c.ok for c in self.curves.values())

    @property
    def failures(self) -> tuple:
        return tuple(f"{c.name}: {c.status}" for c in self.curves.values() if not c.ok)

    def _require_ok(self, partial: bool, what: str) -> None:
        if not check_flag("partial", partial) and not self.ok:
            raise TraceError(f"k = {self.k!r}: {'; '.join(self.failures)}: the {what} of a "
                             "failed trace are not whole boundaries; pass partial=True to "
                             "get them for inspection", self)

    def to_frame(self, partial: bool = False) -> pd.DataFrame:
        """All boundaries as one table (columns :data:`CSV_COLUMNS`).

        Raises
        ------
        TraceError
            If a boundary failed (``ok`` is False; ``failures`` says which and why): its rows
            are not a whole boundary. With ``partial=True`` every row traced is returned all
            the same, for inspection.
        """
        import pandas as pd  # only the tables need it, not the tracer
        self._require_ok(partial, "rows")
        params = self.params or Parameters(self.k)
        if not self.curves:
            return pd.DataFrame(columns=list(CSV_COLUMNS))
        # one frame from the joined columns: the table pd.concat of the boundaries' frames
        # gives, at a fraction of its cost (this runs once per k of a sweep)
        parts = [c._columns(params) for c in self.curves.values()]
        return pd.DataFrame({name: np.concatenate([np.asarray(p[name]) for p in parts])
                             for name in CSV_COLUMNS}, columns=list(CSV_COLUMNS))

    def special_points_frame(self, partial: bool = False) -> pd.DataFrame:
        """All special points (columns :data:`SPECIAL_POINT_COLUMNS`, plus ``note``).

        Raises
        ------
        TraceError
            If a boundary failed, unless ``partial=True`` (as for :meth:`to_frame`).
        """
        import pandas as pd  # only the tables need it, not the tracer
        self._require_ok(partial, "special points")
        ratio = (self.params or Parameters(self.k)).c
        rows = [dict(boundary=p.boundary, k=self.k, compliance=ratio, kind=p.kind.value,
                     gamma=p.x[0], delta=p.x[1], beta_L=p.x[2], upsilon=p.x[3], note=p.note)
                for c in self.curves.values() for p in c.special_points]
        return pd.DataFrame(rows, columns=[*SPECIAL_POINT_COLUMNS, "note"])


def boundary_quantities(name: str, x, params: Parameters) -> dict:
    """Angles, force ratios and slip along a boundary from its points ``x`` (m, 4).

    Double-rolling boundaries: ``T/N_L = c (cos beta_L + upsilon) / sin beta_L``,
    ``T/N_R = c (cos beta_R - upsilon) / sin beta_R``, ``d_L = 0``. Rolling-sliding ones:
    ``T/N_L = k``, ``T/N_R = mu`` from the rolling right wall, ``d_L / Z = cos beta_L + upsilon -
    (k/c) sin beta_L``. ``T/N_L`` is ``inf`` where ``beta_L = 0`` (``N_L = 0``).
    """
    x = np.atleast_2d(np.asarray(x, dtype=float))
    gamma, delta, beta_L, upsilon = x.T
    beta_R = math.pi - 2.0 * gamma - beta_L
    k, c = params.k, params.c
    s_L, s_R = np.sin(beta_L), np.sin(beta_R)
    A, B = np.cos(beta_L) + upsilon, np.cos(beta_R) - upsilon
    T_over_N_R = np.full_like(gamma, np.inf)
    np.divide(c * B, s_R, out=T_over_N_R, where=s_R != 0.0)
    if name.startswith("dr"):
        T_over_N_L = np.full_like(gamma, np.inf)
        np.divide(c * A, s_L, out=T_over_N_L, where=s_L != 0.0)
        d_L = np.zeros_like(gamma)
    else:
        T_over_N_L = np.full_like(gamma, k)
        d_L = A - (k / c) * s_L
    return dict(gamma=gamma, delta=delta, theta_L=gamma + delta, theta_R=gamma - delta,
                beta_L=beta_L, beta_R=beta_R, upsilon=upsilon, T_over_N_L=T_over_N_L,
                T_over_N_R=T_over_N_R, d_L=d_L)

