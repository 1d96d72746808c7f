"""Dimensional forces and displacements of an equilibrium (paper Eq. hertz).

Hertz: a sphere of radius ``R`` pressed by ``N`` approaches the wall by
``u = (G N / sqrt(R))^(2/3)`` with a contact circle of radius ``a = (G N R)^(1/3)``,
``G = 3 (1 - nu^2) / (4 E)``. So ``N = C u^(3/2)`` with ``C = sqrt(R) / G``, and with
``u = Z sin(beta)`` every force is ``C Z^(3/2)`` times its scaled value ``n`` or ``t``.
The vertical balance (paper Eq. 1) fixes the scale:
``C Z^(3/2) (n_L cos theta_L + t sin theta_L + n_R cos theta_R + t sin theta_R) = M g``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .equilibrium import Equilibrium
from .parameters import check_poisson, number_text

__all__ = ["DimensionalState", "dimensional_state"]


@dataclass(frozen=True)
class DimensionalState:
    """Forces in newtons and lengths in metres at an equilibrium (shape of the equilibrium).

    Attributes
    ----------
    Z : approach of the ball's centre along its loading path (m)
    N_L, N_R, T : normal forces and the common tangential force (N)
    a_L, a_R : Hertz contact radii (m)
    d_L, d_R : slip of each contact down its wall (m)
    """

    Z: object
    N_L: object
    N_R: object
    T: object
    a_L: object
    a_R: object
    d_L: object
    d_R: object

    def to_dict(self) -> dict:
        return {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in vars(self).items()}


def _positive(name: str, value, unit: str) -> float:
    try:
        value = float(value)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name} must be a real number, got {value!r}") from exc
    if not math.isfinite(value) or value <= 0.0:
        raise ValueError(f"{name} = {number_text(value)} {unit} is outside the allowed range: "
                         "finite and > 0")
    return value


def dimensional_state(eq: Equilibrium, radius, young, poisson, mass, g=9.81) -> DimensionalState:
    """Forces and displacements in SI units.

    Parameters
    ----------
    eq : Equilibrium
        From :func:`groove_model.solve_equilibrium` (scalar or array).
    radius : float
        Ball radius ``R`` in m, > 0.
    young : float
        Young's modulus ``E`` in Pa, > 0.
    poisson : float
        Poisson ratio ``nu``, ``-1 < nu <= 0.5``.
    mass : float
        Ball mass ``M`` in kg, > 0.
    g : float
        Gravitational acceleration in m/s^2, > 0 (default 9.81).

    Returns
    -------
    DimensionalState

    Raises
    ------
    ValueError
        For a parameter outside its range, or where the scaled vertical force is not above
        its rounding (it vanishes at ``gamma = pi/2`` and underflows on ``delta = gamma`` for
        ``gamma`` below about ``1e-215``), so no finite approach ``Z`` carries the weight.
    """
    R = _positive("radius R", radius, "m")
    E = _positive("Young's modulus E", young, "Pa")
    M = _positive("mass M", mass, "kg")
    g = _positive("gravitational acceleration g", g, "m/s^2")
    nu = check_poisson(poisson)  # -1 < nu <= 1/2: Hertz holds for an incompressible ball too
    G = 3.0 * (1.0 - nu * nu) / (4.0 * E)
    C = math.sqrt(R) / G
    n_L, n_R, t = (np.asarray(v, float) for v in (eq.n_L, eq.n_R, eq.t))
    terms = (n_L * np.cos(eq.theta_L), t * np.sin(eq.theta_L), n_R * np.cos(eq.theta_R),
             t * np.sin(eq.theta_R))
    vertical = sum(terms)
    # its rounding: a few units of the largest term (the terms cancel where a wall overhangs);
    # a sum not above it is no force that carries the weight (at gamma = pi/2 it is exactly 0)
    rounding = 8.0 * np.finfo(float).eps * np.maximum.reduce([np.abs(v) for v in terms])
    degenerate = ~(np.asarray(vertical) > rounding)
    if np.any(degenerate):
        where = np.flatnonzero(np.ravel(degenerate))[0]
        gamma = float(np.ravel(eq.gamma)[where])
        delta = float(np.ravel(eq.delta)[where])
        raise ValueError(
            f"no dimensional equilibrium at gamma = {gamma!r} rad, delta = {delta!r} rad: the "
            f"scaled vertical force of the Hertz contacts, {float(np.ravel(vertical)[where]):.3g},"
            " is not above its rounding, so no finite approach Z carries the weight. It is 0 at "
            "gamma = pi/2 (the groove closed) and underflows where the one loaded contact meets "
            "its wall at a grazing angle (beta near 0 or pi: on delta = gamma, for gamma below "
            "about 1e-215); allowed range for dimensional results: the points where that force "
            "is above its rounding")
    with np.errstate(over="ignore", invalid="ignore"):  # an overflow is named below
        Z = (M * g / (C * vertical)) ** (2.0 / 3.0)
        scale = C * Z**1.5
        N_L, N_R = scale * n_L, scale * n_R
        values = dict(Z=Z, N_L=N_L, N_R=N_R, T=scale * t, a_L=np.cbrt(G * N_L * R),
                      a_R=np.cbrt(G * N_R * R), d_L=Z * np.asarray(eq.d_L, float),
                      d_R=Z * np.asarray(eq.d_R, float))
    if not all(np.all(np.isfinite(v)) for v in values.values()):
        name = next(key for key, v in values.items() if not np.all(np.isfinite(v)))
        where = np.flatnonzero(~np.isfinite(np.ravel(values[name])))[0] \
            if np.ndim(values[name]) else 0
        raise ValueError(f"the dimensional results overflow double precision ({name} is not "
                         f"finite) for R = {R!r} m, E = {E!r} Pa, M = {M!r} kg, g = {g!r} m/s^2 "
                         f"and the scaled vertical force v = "
                         f"{float(np.ravel(vertical)[where]):.3g} of the Hertz contacts at this "
                         "point: give parameters and a point where Z = (M g / (C v))^(2/3), "
                         "C = sqrt(R) 4 E / (3 (1 - nu^2)), is finite")
    if np.ndim(Z) == 0:
        values = {key: float(v) for key, v in values.items()}
    return DimensionalState(**values)
