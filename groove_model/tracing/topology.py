r"""Which boundaries exist for a friction coefficient ``k``, where they start and end, and why.

The tracer checks every traced curve against :func:`expected_topology`; a curve that disagrees
(a junction or fold missing or extra, a wrong start or end) is reported as a failure, never as a
success. The thresholds in ``k`` where the picture changes are computed here from the boundary
equations (:func:`thresholds`), not written in by hand; for the paper's compliance ``c = 1``:

==========================  ==================  ===============================================
threshold                   value (``c = 1``)   what happens
==========================  ==================  ===============================================
``k_fold``                  0.70710678118654    the turning point in ``gamma`` of ``rs_no_roll``
                                                enters it through its start ``(arctan k, 0)``
``k_branch``                1.41421356237310    ``(arctan k, 0)`` meets the branch point
                                                ``(arctan sqrt 2, 0)``: ``upsilon = 0`` on
                                                ``dr_limit`` (the junction) appears there
==========================  ==================  ===============================================

Both equal ``c / sqrt 2`` and ``c sqrt 2`` to rounding (``k_branch = c tan(arctan sqrt 2)``
since the seed is at ``arctan(k/c)``; ``k_fold``: at the seed ``beta_L = beta_R = beta``, and
a tangent of ``rs_no_roll`` with no ``gamma`` component has ``d beta_L = -d beta_R``, which the
linearised right-rolling equation ``c sqrt(sin beta_R) cos beta_R = k sin(beta_L)^(3/2)`` allows
only where ``tan^2 beta = 2``, i.e. ``k/c = cot beta = 1/sqrt 2``). The tests check the computed
values against these closed forms.

The topology, in each range of ``k`` (``gamma_min`` is where the limit curves stop on their way
into the singular corner ``(0, 0)``; the corner ``(pi/4, pi/4)`` ends both ``upsilon = 0`` lines):

============  ======================  ==========================  ==========================
boundary      ``k < k_fold``          ``k_fold < k < k_branch``   ``k > k_branch``
============  ======================  ==========================  ==========================
dr_limit      seed -> ``gamma_min``;  same                        same, plus one junction
              one fold in ``delta``                               (``upsilon = 0``)
rs_limit      the same curve as ``dr_limit`` (no junction mark)
dr_no_roll    no physical part        no physical part            branch point -> junction
rs_no_roll    seed -> corner          seed -> corner, one fold    junction -> corner, one
                                      in ``gamma``                fold in ``gamma``
============  ======================  ==========================  ==========================

Exactly at ``k_branch`` the junction is the seed and ``dr_no_roll`` is the single point
``(arctan sqrt 2, 0)``. Within a relative distance :data:`THRESHOLD_BAND` of a threshold either
neighbouring topology is accepted: there a junction or fold lies within rounding of a start.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from ..model.boundaries import BoundarySystem, dr_no_roll_branch_point, limit_seed
from ..model.parameters import Compliance, Parameters

__all__ = ["THRESHOLD_BAND", "CurveTopology", "Thresholds", "expected_topology", "thresholds"]

#: relative distance to a threshold within which both neighbouring topologies are accepted
THRESHOLD_BAND = 1e-9


@dataclass(frozen=True)
class Thresholds:
    """The values of ``k`` where the topology changes, for one compliance ratio ``c``."""

    c: float
    k_fold: float
    k_branch: float

    def near(self, k: float) -> bool:
        """Whether ``k`` is within :data:`THRESHOLD_BAND` of a threshold."""
        return any(abs(k / t - 1.0) <= THRESHOLD_BAND for t in (self.k_fold, self.k_branch))


@dataclass(frozen=True)
class CurveTopology:
    """What one boundary must look like; ``None`` means either is accepted (near a threshold).

    Attributes
    ----------
    present : bool or None
        Whether the boundary has a physical part of more than one point.
    start, end : str or None
        ``"seed"``, ``"branch_point"``, ``"junction"`` for a start; ``"gamma_min"``,
        ``"corner"``, ``"junction"`` for an end.
    junctions : int or None
        Junctions strictly inside the curve (not at its ends).
    folds_gamma, folds_delta : int or None
        Turning points in ``gamma`` and in ``delta`` (not at the ends).
    """

    present: bool | None
    start: str | None = None
    end: str | None = None
    junctions: int | None = 0
    folds_gamma: int | None = 0
    folds_delta: int | None = 0


def _seed_fold_function(k: float, c: float) -> float:
    """``det`` of the ``rs_no_roll`` Jacobian without its ``gamma`` column, at the seed.

    It is proportional to the ``gamma`` component of the tangent of ``rs_no_roll`` at
    ``(arctan(k/c), 0)`` and vanishes where a turning point in ``gamma`` passes the seed.
    """
    params = Parameters(k, Compliance(c))
    jacobian = BoundarySystem("rs_no_roll", params).jacobian(limit_seed(params))
    return float(np.linalg.det(jacobian[:, 1:]))


@functools.lru_cache(maxsize=64)
def thresholds(c: float = 1.0) -> Thresholds:
    """The thresholds in ``k`` for compliance ratio ``c``, computed from the equations.

    ``k_branch = c tan(gamma_b)`` with ``gamma_b`` the branch point of ``dr_no_roll`` on the
    symmetric family; ``k_fold`` is the root of :func:`_seed_fold_function` in
    ``(0, k_branch)``, bracketed on a logarithmic grid and refined by Brent's method to
    rounding (the grid also checks that the root is the only one).

    Raises
    ------
    RuntimeError
        If the seed-fold function does not change sign exactly once on ``(0, k_branch)``.
    """
    k_branch = c * math.tan(float(dr_no_roll_branch_point()[0]))
    grid = np.geomspace(1e-4 * k_branch, k_branch * (1.0 - 1e-6), 97)
    values = np.array([_seed_fold_function(k, c) for k in grid])
    changes = np.flatnonzero(np.sign(values[:-1]) != np.sign(values[1:]))
    if len(changes) != 1:
        raise RuntimeError(f"the seed-fold function of rs_no_roll changes sign {len(changes)} "
                           f"times on (0, k_branch) for c = {c!r}; expected once")
    i = int(changes[0])
    k_fold = brentq(_seed_fold_function, grid[i], grid[i + 1], args=(c,), xtol=1e-300,
                    rtol=4.0 * np.finfo(float).eps)
    return Thresholds(c=c, k_fold=float(k_fold), k_branch=float(k_branch))


def expected_topology(params: Parameters) -> dict[str, CurveTopology]:
    """What each boundary must look like for ``params`` (see the module's table)."""
    t = thresholds(params.c)
    k = params.k
    band = THRESHOLD_BAND

    def side(threshold: float) -> bool | None:
        """True above, False below, None within the band."""
        if abs(k / threshold - 1.0) <= band:
            return None
        return k > threshold

    above_branch = side(t.k_branch)
    above_fold = side(t.k_fold)
    junctions = None if above_branch is None else int(above_branch)
    limit = CurveTopology(True, "seed", "gamma_min", junctions=junctions, folds_delta=1)
    return {
        "dr_limit": limit,
        "rs_limit": CurveTopology(True, "seed", "gamma_min", junctions=0, folds_delta=1),
        "dr_no_roll": CurveTopology(above_branch, "branch_point", "junction"),
        "rs_no_roll": CurveTopology(
            True,
            None if above_branch is None else ("junction" if above_branch else "seed"),
            "corner",
            folds_gamma=None if above_fold is None else int(above_fold)),
    }
