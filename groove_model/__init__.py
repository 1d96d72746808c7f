"""The ball in a groove (Halsey & Ertas): equilibria, regime boundaries, tracing, export.

The physics lives here; the generic continuation engine is the sibling package
``continuation``.
"""

from .model.boundaries import BOUNDARY_NAMES, BoundarySystem, boundary_system
from .model.dimensional import DimensionalState, dimensional_state
from .model.equilibrium import Equilibrium, Regime, Rotation, regime_validity, solve_equilibrium
from .model.parameters import Compliance, Parameters, check_domain

__all__ = [
    "BOUNDARY_NAMES",
    "BoundarySystem",
    "Compliance",
    "DimensionalState",
    "Equilibrium",
    "Parameters",
    "Regime",
    "Rotation",
    "boundary_system",
    "check_domain",
    "dimensional_state",
    "regime_validity",
    "solve_equilibrium",
]
