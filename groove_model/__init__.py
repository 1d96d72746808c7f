"""The ball in a groove (Halsey & Ertas, "A Ball in a Groove"): equilibria, regime boundaries.

An elastic ball rests in a rigid V-groove whose walls make angles ``theta_L >= theta_R`` with
the horizontal. It either rolls on both walls (DR, *double rolling*) or rolls on the shallower
wall and slides on the steeper one (RS, *rolling sliding*), turning clockwise or
counter-clockwise. This package finds every equilibrium and traces the boundaries between
these behaviours in the plane of ``gamma = (theta_L + theta_R)/2``, ``delta = (theta_L -
theta_R)/2``; the generic continuation engine is the sibling package ``continuation``.

Glossary (in full: ``docs/glossary.md``)
---------------------------------------
``dr_limit``, ``rs_limit``
    where double rolling reaches ``T/N = k`` on the steeper wall, and where the rolling-sliding
    slip ``d_L`` vanishes: one curve, seen from each regime.
``dr_no_roll``, ``rs_no_roll``
    ``upsilon = 0`` (no rolling) in double rolling and in rolling sliding.
``beta_L``, ``beta_R``
    the loading direction measured from each wall, ``beta_L + beta_R = pi - 2 gamma``.
``upsilon``
    the rolling ``R phi / Z``, negative clockwise (down the steeper wall).
``T/N``, ``k``, ``c``, ``mu``, ``d_L``
    tangential over normal force, friction coefficient, compliance ratio, ``T/N_R`` in
    rolling sliding, slip of the left contact per approach ``Z``.

Layout
------
``model``
    parameters, equilibria (:func:`solve_equilibrium`), boundary equations, SI units, lines
    by root finding.
``tracing``
    every boundary for one ``k`` (:func:`trace_boundaries`), the topology it must have, and the
    atlas: every special point followed as a curve in ``k`` (:func:`trace_atlas`).
``analysis``
    regime classification and the audit of the paper's claims.
``io``, ``plots``, ``cli``
    CSV files, figures, the ``groove`` command.
"""

import importlib

#: The package's version (also ``groove --version``; pyproject.toml reads it from here).
__version__ = "0.1.0"

# Where each public name lives. They are imported on first use (PEP 562), not here, because
# the ``groove`` command line lives in this package: `groove --help` should not wait for
# scipy, which the solver imports.
_SOURCES = {
    "BOUNDARY_NAMES": "model.boundaries",
    "BoundarySystem": "model.boundaries",
    "Compliance": "model.parameters",
    "DimensionalState": "model.dimensional",
    "Equilibrium": "model.equilibrium",
    "Parameters": "model.parameters",
    "Regime": "model.equilibrium",
    "Rotation": "model.equilibrium",
    "boundary_system": "model.boundaries",
    "check_domain": "model.parameters",
    "dimensional_state": "model.dimensional",
    "regime_validity": "model.equilibrium",
    "solve_equilibrium": "model.equilibrium",
    "trace_boundaries": "tracing.tracer",
    "trace_many": "tracing.sweep",
    "BoundarySet": "tracing.curves",
    "TraceError": "tracing.curves",
    "SweepError": "tracing.sweep",
    "Atlas": "tracing.atlas",
    "trace_atlas": "tracing.atlas",
    "trace_atlas_in_poisson": "tracing.atlas",
}

__all__ = sorted(_SOURCES)


def __getattr__(name: str):
    try:
        module = _SOURCES[name]
    except KeyError:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}") from None
    value = getattr(importlib.import_module(f".{module}", __name__), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted({*globals(), *__all__})
