r"""The claim of the paper's paragraph on contact mechanics: the compliance hardly matters.

The paper uses ``u_t/u_n = T/N`` "since the qualitative properties of the solution are
relatively independent of the exact form of the compliance". The check traces the atlas of
special points for Mindlin's compliance at several Poisson ratios
(:func:`groove_model.analysis.compliance.compliance_study`): the statement holds if the same
special points go through the same topologies in ``k``; it is qualified where, at a fixed
``k``, the diagram changes shape as ``nu`` moves (a threshold in ``nu``).
"""

from __future__ import annotations

from ...model.parameters import Compliance
from ...tracing.atlas import DEFAULT_K_RANGE
from ..compliance import DEFAULT_KS, DEFAULT_POISSONS, SHIFT_SAMPLES, compliance_study
from .context import Context
from .registry import Finding, claim, verdict
from .report import Counterexample

# The checks are registered with @claim and run by run.run_audit, not imported by name.
__all__: list = []


def _numbers(study) -> dict:
    """Scalars: compliance ratios, thresholds and their ratios, the largest shifts; per ``k``:
    the thresholds in ``nu`` and how far each special point moves."""
    reference = study.thresholds[study.reference]
    numbers: dict[str, object] = {}
    for nu, values in study.thresholds.items():
        numbers[f"c(nu = {nu:g})"] = Compliance.from_poisson(nu).ratio
        for name, value in values.items():
            numbers[f"{name}(nu = {nu:g})"] = value
            if nu != study.reference and name in reference:
                numbers[f"{name}(nu = {nu:g}) / {name}(nu = {study.reference:g})"] = \
                    value / reference[name]
    for nu, curves in study.shifts.items():
        for name, row in curves.items():
            numbers[f"largest shift of {name} at fixed k, nu = {nu:g} [rad]"] = row["max shift"]
    numbers["same topologies in k, in the same order"] = study.same_topology_in_k
    spans = study.span_in_nu()
    for k, changes in study.changes_at_fixed_k().items():
        row = {"thresholds in nu": "; ".join(f"{name} = {nu:.10g}" for name, nu in changes)
               or "none"}
        for name, (d_gamma, d_delta) in spans[k].items():
            row[f"{name}: span of (gamma, delta) over nu"] = (d_gamma, d_delta)
        numbers[f"k = {k:g}"] = row
    return numbers


def _counterexample(study):
    """The first special point that exists at ``nu = 1/2`` but not at ``nu = 0`` (or has crossed
    another) at a fixed ``k``: the diagram of that ``k`` has another shape."""
    for k, atlas in study.in_nu.items():
        for t in atlas.thresholds:
            high = atlas.range[1]
            curve = atlas.curves[t.curve]
            points = curve.physical_at(high)
            if not points:
                continue
            x = points[0]
            return Counterexample(
                k=k, gamma=float(x[0]), delta=float(x[1]),
                values={"nu": high, "c": Compliance.from_poisson(high).ratio,
                        "threshold": t.name, "at nu": t.value, "special point": t.curve},
                note=f"at k = {k:g}, {t.name} = {t.value:.10g}: {t.what}; the point given is "
                     f"the {t.curve} at nu = {high:g}, where the diagram of this k has another "
                     f"shape than at nu = {study.reference:g}")
    return None


def _summary(study, changes: dict) -> str:
    same = study.same_topology_in_k
    last = list(study.thresholds)[-1]
    c = Compliance.from_poisson(last).ratio
    reference = study.thresholds[study.reference]
    ratios = {name: value / reference[name] for name, value in study.thresholds[last].items()
              if name in reference}
    scaling = [name for name, ratio in ratios.items() if abs(ratio / c - 1.0) <= 1e-12]
    worst = max(row["max shift"] for row in study.shifts[last].values())
    text = (f"{'Qualitatively the same in k' if same else 'Not the same in k'}: for nu = "
            f"{', '.join(f'{nu:g}' for nu in study.in_k)} the special points go through "
            f"{'the same' if same else 'different'} topologies in k, in the same order, but the "
            f"thresholds move: at nu = {last:g} (c = {c:.4g}) "
            + ", ".join(f"{name} x {ratio:.4g}" for name, ratio in ratios.items())
            + (f" ({', '.join(scaling)} exactly c times the paper's)" if scaling else "")
            + f", and at a fixed k a special point moves by up to {worst:.3g} rad. ")
    if not changes:
        return text + "At the k checked no threshold in nu falls in [0, 1/2]."
    return text + "At a fixed k the diagram changes shape as nu goes from 0 to 1/2: " + "; ".join(
        f"at k = {k:g}, nu = {t.value:.4f} ({t.name}): {t.what}" for k, ts in changes.items()
        for t in ts) + "."


@claim("compliance_qualitative")
def check_compliance(ctx: Context) -> Finding:
    study = compliance_study()
    if not study.ok:
        failures = [f for a in (*study.in_k.values(), *study.in_nu.values()) for f in a.failures]
        raise RuntimeError("the atlas of the compliance study failed: " + "; ".join(failures))
    changes = {k: atlas.thresholds for k, atlas in study.in_nu.items() if atlas.thresholds}
    return Finding(verdict(study.same_topology_in_k, qualified=bool(changes)),
                   numbers=_numbers(study), summary=_summary(study, changes),
                   counterexample=_counterexample(study) if changes else None,
                   method_values=dict(k_min=f"{DEFAULT_K_RANGE[0]:g}",
                                      k_max=f"{DEFAULT_K_RANGE[1]:g}",
                                      poissons=", ".join(f"{nu:g}" for nu in DEFAULT_POISSONS),
                                      ks=" and ".join(f"{k:g}" for k in DEFAULT_KS),
                                      samples=SHIFT_SAMPLES))
