r"""Every point of the ``(gamma, delta)`` plane classified by regime and sense of rotation.

Each point of the domain ``0 <= delta <= gamma <= pi/2`` is classified with the vectorised point
solver :func:`groove_model.model.equilibrium.solve_equilibrium` into one of

=====================================  =====================================================
category                               where
=====================================  =====================================================
``double_rolling_clockwise``           ``T/N <= k`` on both walls, ``upsilon < 0``
``double_rolling_counterclockwise``    ``T/N <= k`` on both walls, ``upsilon > 0``
``rolling_sliding_clockwise``          steeper (left) wall slides, ``upsilon < 0``
``rolling_sliding_counterclockwise``   steeper (left) wall slides, ``upsilon > 0``
``double_sliding``                     the segment ``delta = 0``, ``gamma > arctan k``
``symmetric_no_rotation``              the segment ``delta = 0``, ``gamma <= arctan k``
``no_rotation``                        ``upsilon = 0`` exactly off the axis (measure zero)
=====================================  =====================================================

(``upsilon = R phi / Z``, negative clockwise, i.e. rolling down the steeper wall; paper,
"Rolling solutions"). :mod:`groove_model.plots.regime_map` shades these categories.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..model.equilibrium import solve_equilibrium
from ..model.parameters import Parameters

__all__ = [
    "CATEGORIES",
    "CATEGORY_CODE",
    "OUTSIDE",
    "RegimeGrid",
    "check_resolution",
    "classify_cells",
    "classify_grid",
    "classify_points",
]

CATEGORIES = (
    "double_rolling_clockwise",
    "double_rolling_counterclockwise",
    "rolling_sliding_clockwise",
    "rolling_sliding_counterclockwise",
    "double_sliding",
    "symmetric_no_rotation",
    "no_rotation",
)
#: The code of each category: its index into :data:`CATEGORIES`.
CATEGORY_CODE = {name: i for i, name in enumerate(CATEGORIES)}
#: Code of a grid node outside the domain ``0 <= delta <= gamma <= pi/2``.
OUTSIDE = -1

_HALF_PI = 0.5 * math.pi
_RESOLUTION_RANGE = (2, 20000)


def _readonly(array: np.ndarray) -> np.ndarray:
    array.setflags(write=False)
    return array


@dataclass(frozen=True)
class RegimeGrid:
    """Classification of the nodes of a regular grid over ``[0, pi/2]^2``.

    Attributes
    ----------
    k : float
        Friction coefficient.
    gamma : ndarray, shape (n + 1,)
        Node abscissae ``gamma_i = i h``, ``h = (pi/2)/n`` (radians).
    delta : ndarray, shape (n + 1,)
        Node ordinates ``delta_j = j h`` (radians).
    category : ndarray of int8, shape (n + 1, n + 1)
        ``category[j, i]`` is the index into :data:`CATEGORIES` of the node
        ``(gamma_i, delta_j)``, or :data:`OUTSIDE` where ``delta_j > gamma_i``.
    upsilon : ndarray, shape (n + 1, n + 1)
        Rolling ``R phi / Z`` at each node (NaN outside the domain).
    """

    k: float
    gamma: np.ndarray = field(repr=False)
    delta: np.ndarray = field(repr=False)
    category: np.ndarray = field(repr=False)
    upsilon: np.ndarray = field(repr=False)

    @property
    def step(self) -> float:
        """Grid step ``h`` in radians."""
        return float(self.gamma[1] - self.gamma[0])

    @property
    def inside(self) -> np.ndarray:
        """Boolean mask of the nodes in the domain."""
        return self.category != OUTSIDE

    def counts(self) -> dict:
        """Number of nodes in each category (every category present, zeros included)."""
        return {name: int(np.count_nonzero(self.category == code))
                for name, code in CATEGORY_CODE.items()}

    def names(self) -> np.ndarray:
        """The category of each node as a string array (``"outside"`` outside the domain)."""
        table = np.array([*CATEGORIES, "outside"], dtype=object)
        return table[np.where(self.category == OUTSIDE, len(CATEGORIES), self.category)]


def classify_points(gamma, delta, k) -> np.ndarray:
    """Category code (index into :data:`CATEGORIES`) of each point ``(gamma, delta)``.

    Parameters
    ----------
    gamma, delta : array_like
        Points of the domain ``0 <= delta <= gamma <= pi/2``, radians, broadcastable shapes.
    k : float or Parameters
        Friction coefficient, finite and > 0.

    Returns
    -------
    ndarray of int8
        Codes of the broadcast shape.

    Raises
    ------
    ValueError
        If ``k`` or a point is outside its allowed range (from the point solver).

    Notes
    -----
    The regime is the point solver's (double rolling where ``T/N <= k`` on both walls, double
    sliding on ``delta = 0`` beyond ``arctan k``, rolling sliding elsewhere); the rotation sense
    is the sign of ``upsilon``. On ``delta = 0`` the double-rolling state is the symmetric one,
    ``beta_L = beta_R = pi/2 - gamma``, ``upsilon = 0`` (paper, "Rolling solutions").
    """
    return _categories(gamma, delta, Parameters.coerce(k))


def _categories(gamma, delta, params: Parameters) -> np.ndarray:
    gamma, delta = np.broadcast_arrays(np.asarray(gamma, float), np.asarray(delta, float))
    eq = solve_equilibrium(np.atleast_1d(gamma), np.atleast_1d(delta), params)  # checks domain
    regime = np.asarray(eq.regime, dtype=object).reshape(gamma.shape)
    upsilon = np.asarray(eq.upsilon, dtype=float).reshape(gamma.shape)
    axis = delta == 0.0
    code = np.full(gamma.shape, CATEGORY_CODE["no_rotation"], dtype=np.int8)
    for name in ("double_rolling", "rolling_sliding"):
        here = (regime == name) & ~axis
        code[here & (upsilon < 0.0)] = CATEGORY_CODE[f"{name}_clockwise"]
        code[here & (upsilon > 0.0)] = CATEGORY_CODE[f"{name}_counterclockwise"]
    # On the axis the category follows gamma against arctan(k/c) alone: exactly there the
    # solver's T/N = tan gamma may round either way.
    below = gamma <= params.gamma_limit
    code[axis & below] = CATEGORY_CODE["symmetric_no_rotation"]
    code[axis & ~below] = CATEGORY_CODE["double_sliding"]
    return code


def classify_grid(k, n: int = 400) -> RegimeGrid:
    """Classify the nodes of an ``(n + 1) x (n + 1)`` grid over the domain.

    Parameters
    ----------
    k : float or Parameters
        Friction coefficient, finite and > 0.
    n : int
        Number of grid steps along each axis of ``[0, pi/2]``, ``2 <= n <= 20000``; the step is
        ``h = (pi/2)/n``. Nodes with ``delta > gamma`` are marked :data:`OUTSIDE`.

    Returns
    -------
    RegimeGrid

    Raises
    ------
    ValueError
        If ``n`` or ``k`` is outside its allowed range.
    """
    params = Parameters.coerce(k)
    n = check_resolution(n)
    axis = np.linspace(0.0, _HALF_PI, n + 1)
    category = np.full((n + 1, n + 1), OUTSIDE, dtype=np.int8)
    upsilon = np.full((n + 1, n + 1), np.nan)
    for rows, gamma, delta, inside in _row_blocks(axis):
        category[rows][inside] = _categories(gamma, delta, params)
        upsilon[rows][inside] = solve_equilibrium(gamma, delta, params).upsilon
    return RegimeGrid(params.k, _readonly(axis.copy()), _readonly(axis.copy()),
                      _readonly(category), _readonly(upsilon))


def classify_cells(k, n: int) -> np.ndarray:
    """Category codes at the centres of the ``n x n`` cells of ``[0, pi/2]^2``.

    Parameters
    ----------
    k : float or Parameters
        Friction coefficient, finite and > 0.
    n : int
        Cells along each axis, ``2 <= n <= 20000``; cell ``(j, i)`` has its centre at
        ``((i + 1/2) h, (j + 1/2) h)``, ``h = (pi/2)/n``.

    Returns
    -------
    ndarray of int8, shape (n, n)
        Codes, :data:`OUTSIDE` for cells whose centre has ``delta > gamma``.
    """
    params = Parameters.coerce(k)
    n = check_resolution(n)
    centres = (np.arange(n) + 0.5) * (_HALF_PI / n)
    codes = np.full((n, n), OUTSIDE, dtype=np.int8)
    for rows, gamma, delta, inside in _row_blocks(centres):
        codes[rows][inside] = _categories(gamma, delta, params)
    return codes


#: points solved at once by the grids: the solver's temporaries take about 300 bytes per point
_BLOCK = 1 << 17


def _row_blocks(axis: np.ndarray):
    """Blocks of rows ``delta = axis[rows]`` of the grid ``axis x axis``, about
    :data:`_BLOCK` nodes each: ``(rows, gamma, delta, inside)`` with the nodes inside the
    domain (``delta <= gamma``) as flat arrays, row by row, and where they are in the block
    (memory stays bounded at any resolution; each node is solved on its own)."""
    step = max(1, _BLOCK // axis.size)
    for start in range(0, axis.size, step):
        rows = slice(start, start + step)
        D, G = np.meshgrid(axis[rows], axis, indexing="ij")
        inside = D <= G
        yield rows, G[inside], D[inside], inside


def check_resolution(n, largest: int | None = None) -> int:
    """Return the grid resolution ``n`` as an int, or raise if it is not in ``2 <= n <= 20000``
    (or ``<= largest``).

    Raises
    ------
    TypeError
        If ``n`` is not an integer.
    ValueError
        If ``n`` is outside its allowed range.
    """
    lo, hi = _RESOLUTION_RANGE
    hi = hi if largest is None else largest
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)):
        raise TypeError(f"grid resolution n must be an integer, got {n!r}")
    if not lo <= n <= hi:
        raise ValueError(f"grid resolution n = {n} is outside the allowed range {lo} <= n <= {hi}")
    return int(n)
