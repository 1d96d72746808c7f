r"""How the regime diagram depends on the compliance: the atlas for several Poisson ratios.

The paper takes ``u_t/u_n = T/N`` (Eq. prop), Mindlin's law in the limit of a small Poisson
ratio, and says that "the qualitative properties of the solution are relatively independent of
the exact form of the compliance". For a sphere on a rigid wall Mindlin's law is
``T/N = c u_t/u_n`` with ``c(nu) = 2 (1 - nu)/(2 - nu)``, 1 at ``nu = 0`` and ``2/3`` at
``nu = 1/2`` (:meth:`~groove_model.model.parameters.Compliance.from_poisson`). This module
traces the atlas of special points (:mod:`groove_model.tracing.atlas`) in ``k`` for several
``nu`` and in ``nu`` at fixed ``k``, and says what moves and by how much
(:func:`compliance_study`):

* the thresholds in ``k`` for each ``nu``, and their ratio to the paper's;
* the topology in each range of ``k`` (:func:`~groove_model.tracing.topology.topology_table`):
  the same sequence of topologies for every ``nu``, or not;
* how far each special point moves at a fixed ``k``, compared on a log-spaced sample of ``k``;
* at fixed ``k`` (the paper's 1 and 10) the thresholds in ``nu``: where the diagram of that
  ``k`` changes shape as ``nu`` goes from 0 to 1/2.
"""

from __future__ import annotations

import functools
import math
import time
from dataclasses import dataclass, field

import numpy as np

from ..model.parameters import Compliance, k_text
from ..tracing.atlas import (
    DEFAULT_K_RANGE,
    DEFAULT_POISSON_RANGE,
    Atlas,
    trace_atlas,
    trace_atlas_in_poisson,
)
from ..tracing.topology import topology_table

__all__ = ["DEFAULT_KS", "DEFAULT_POISSONS", "SHIFT_SAMPLES", "ComplianceStudy",
           "compliance_study"]

DEFAULT_POISSONS = (0.0, 0.3, 0.5)
#: the paper's Fig. 2 values of k
DEFAULT_KS = (1.0, 10.0)
#: values of k (log-spaced over the range) at which the special points of two atlases are compared
SHIFT_SAMPLES = 41

_COLUMNS = ("dr_limit", "dr_no_roll", "rs_no_roll")


@dataclass(frozen=True, eq=False)
class ComplianceStudy:
    """The atlases for several compliances and what changes between them.

    Attributes
    ----------
    in_k : dict of float to Atlas
        ``{nu: atlas in k}``, the first ``nu`` the reference.
    in_nu : dict of float to Atlas
        ``{k: atlas in nu}``.
    thresholds : dict
        ``{nu: {threshold name: k}}``.
    topologies : dict
        ``{nu: ((range label, (dr_limit, dr_no_roll, rs_no_roll descriptions)), ...)}``.
    shifts : dict
        ``{nu: {curve: {"max shift": rad, "at k": k, "compared at": n, "exists on one side
        only": n}}}``: the largest distance in the ``(gamma, delta)`` plane between the
        special point at ``nu`` and at the reference ``nu``, at the same ``k``.
    seconds : float
    """

    in_k: dict = field(repr=False)
    in_nu: dict = field(repr=False)
    thresholds: dict
    topologies: dict = field(repr=False)
    shifts: dict = field(repr=False)
    seconds: float = 0.0

    @property
    def reference(self) -> float:
        """The reference Poisson ratio (the first)."""
        return next(iter(self.in_k))

    @property
    def same_topology_in_k(self) -> bool:
        """Whether every ``nu`` goes through the same topologies, in the same order, in ``k``."""
        first = [row[1] for row in self.topologies[self.reference]]
        return all([row[1] for row in rows] == first for rows in self.topologies.values())

    @property
    def ok(self) -> bool:
        return all(a.ok for a in (*self.in_k.values(), *self.in_nu.values()))

    def changes_at_fixed_k(self) -> dict:
        """``{k: ((threshold name, nu), ...)}``: where the diagram of each ``k`` changes shape."""
        return {k: tuple((t.name, t.value) for t in atlas.thresholds)
                for k, atlas in self.in_nu.items()}

    def span_in_nu(self) -> dict:
        """``{k: {curve: (span of gamma, span of delta)}}`` over the range of ``nu``."""
        return {k: {name: (float(np.ptp(c.x[:, 0])), float(np.ptp(c.x[:, 1])))
                    for name, c in atlas.curves.items() if len(c.p)}
                for k, atlas in self.in_nu.items()}

    def to_markdown(self) -> str:
        """The comparison as a report (thresholds, topologies, shifts, changes at fixed k)."""
        ratios = {nu: _compliance(nu).ratio for nu in self.in_k}
        low, high = self.in_k[self.reference].range
        lines = ["# The atlas for Mindlin's compliance c = 2 (1 - nu)/(2 - nu)", "",
                 "Poisson ratios " + ", ".join(f"nu = {k_text(nu)} (c = {c:.6g})"
                                               for nu, c in ratios.items())
                 + f"; k in [{low:g}, {high:g}].", ""]
        lines += _threshold_lines(self, ratios)
        same = self.same_topology_in_k
        lines += ["", "## Topology in each range of k", "",
                  ("The same topologies, in the same order, for every nu:" if same else
                   "The topologies in k DIFFER between the Poisson ratios:"), ""]
        for nu, rows in self.topologies.items():
            if same and nu != self.reference:
                continue
            lines += ([f"nu = {k_text(nu)}:"] if not same else []) + ["```"]
            lines += [f"{label:<24}  " + "  |  ".join(cells) for label, cells in rows]
            lines += ["```", ""]
        lines += ["## How far each special point moves at a fixed k", "",
                  f"Distance in the (gamma, delta) plane to the point of nu = "
                  f"{k_text(self.reference)} at the same k, over {SHIFT_SAMPLES} log-spaced k.", "",
                  "| nu | curve | largest shift [rad] | at k | compared at | on one side only |",
                  "|---:|---|---:|---:|---:|---:|"]
        for nu, curves in self.shifts.items():
            for name, row in curves.items():
                lines.append(f"| {k_text(nu)} | `{name}` | {row['max shift']:.4g} | "
                             f"{row['at k']:.4g} | {row['compared at']} | "
                             f"{row['exists on one side only']} |")
        lines += ["", "## At a fixed k, in nu", ""]
        for k, changes in self.changes_at_fixed_k().items():
            text = "; ".join(f"{name} = {nu:.12g} (c = {_compliance(nu).ratio:.6g})"
                             for name, nu in changes) or "none"
            spans = ", ".join(f"`{name}` moves by {dg:.3g} in gamma and {dd:.3g} in delta"
                              for name, (dg, dd) in self.span_in_nu()[k].items())
            lines.append(f"- k = {k_text(k)}: thresholds in nu: {text}. Over the range: {spans}.")
        return "\n".join(lines) + "\n"


def _compliance(nu: float) -> Compliance:
    return Compliance.from_poisson(nu)


def _topology_rows(atlas: Atlas) -> tuple:
    return tuple((r.label(), tuple(r.curves[name].describe() for name in _COLUMNS))
                 for r in topology_table(atlas))


def _shifts(reference: Atlas, other: Atlas, samples: int) -> dict:
    """How far each special point of ``other`` is from that of ``reference`` at the same ``k``."""
    low, high = reference.range
    result = {}
    for name, curve in reference.curves.items():
        if name not in other.curves:
            result[name] = {"max shift": math.nan, "at k": math.nan, "compared at": 0,
                            "exists on one side only": samples}
            continue
        worst, where, compared, one_side = 0.0, math.nan, 0, 0
        for k in np.geomspace(low, high, samples):
            a, b = curve.physical_at(k), other.curves[name].physical_at(k)
            if len(a) != len(b):
                one_side += 1
                continue
            for x, y in zip(a, b, strict=True):
                compared += 1
                distance = math.hypot(x[0] - y[0], x[1] - y[1])
                if distance > worst:
                    worst, where = distance, float(k)
        result[name] = {"max shift": worst, "at k": where, "compared at": compared,
                        "exists on one side only": one_side}
    return result


@functools.lru_cache(maxsize=8)
def compliance_study(poissons=DEFAULT_POISSONS, ks=DEFAULT_KS, k_range=DEFAULT_K_RANGE,
                     nu_range=DEFAULT_POISSON_RANGE,
                     samples: int = SHIFT_SAMPLES) -> ComplianceStudy:
    """Trace the atlas in ``k`` for each Poisson ratio and in ``nu`` at each ``k``; compare.

    Parameters
    ----------
    poissons : tuple of float
        Poisson ratios; the first is the reference (default ``(0, 0.3, 0.5)``, ``nu = 0`` the
        paper's law).
    ks : tuple of float
        Friction coefficients of the atlases in ``nu`` (default the paper's 1 and 10).
    k_range, nu_range : (float, float)
        Ranges of the atlases.
    samples : int
        Values of ``k`` at which the special points are compared.

    Returns
    -------
    ComplianceStudy
        (Cached: the same arguments return the same study.)
    """
    began = time.perf_counter()
    in_k = {float(nu): trace_atlas(k_range, compliance=_compliance(nu)) for nu in poissons}
    in_nu = {float(k): trace_atlas_in_poisson(k, nu_range) for k in ks}
    reference = in_k[float(poissons[0])]
    thresholds = {nu: {t.name: t.value for t in atlas.thresholds} for nu, atlas in in_k.items()}
    topologies = {nu: _topology_rows(atlas) for nu, atlas in in_k.items() if atlas.ok}
    shifts = {nu: _shifts(reference, atlas, samples) for nu, atlas in in_k.items()
              if atlas is not reference}
    return ComplianceStudy(in_k, in_nu, thresholds, topologies, shifts,
                           time.perf_counter() - began)


def _threshold_lines(study: ComplianceStudy, ratios: dict) -> list[str]:
    names = list(dict.fromkeys(name for values in study.thresholds.values() for name in values))
    reference = study.thresholds[study.reference]
    lines = ["## Thresholds in k", "",
             "| nu | c | " + " | ".join(names) + " | "
             + " | ".join(f"{n} / {n}(nu = {k_text(study.reference)})" for n in names) + " |",
             "|---:|---:|" + "---:|" * (2 * len(names))]
    for nu, values in study.thresholds.items():
        cells = [f"{values[n]:.12g}" if n in values else "-" for n in names]
        cells += [f"{values[n] / reference[n]:.9f}" if n in values and n in reference else "-"
                  for n in names]
        lines.append(f"| {k_text(nu)} | {ratios[nu]:.6g} | " + " | ".join(cells) + " |")
    return lines
