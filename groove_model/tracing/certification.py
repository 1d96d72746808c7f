"""Certify traced boundaries in ball arithmetic (``trace_boundaries(k, certify=True)``).

Each engine curve behind the boundaries is handed to :func:`continuation.certify`
with the system it was traced in (the chart ``y = (gamma/g, delta/g, w, upsilon)``, the
conditioned forms: the same zero sets as the paper's equations, see
:mod:`groove_model.model.boundaries`) and its events, each evaluated by the same formula in
balls; ``delta = gamma`` is certified through a function with the same sign along the
boundary (:meth:`~groove_model.model.boundaries.BoundarySystem.edge_function`). Only the rows
a boundary keeps are certified (its physical part, unless the unphysical parts are kept).
What is proven, and what is not, is in ``docs/certification.md``.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from continuation import Curve, Event
from continuation.certification import Certificate, CertifyOptions, Check, Exclusion, certify

from ..model.boundaries import corner_point
from .assembly import Role
from .curves import BoundaryCurve, Where

__all__ = ["CERTIFY_OPTIONS", "certified_events", "certify_boundaries", "outside_domain"]

#: tolerances of the boundaries' certificates: every point within 1e-9 of the curve (the
#: tracer's Newton tolerance is 1e-12), special points in boxes of radius <= 1e-5 (the end of
#: a curve at the corner may be a few 1e-6 from the corner in w, where beta_L = w^2 ~ 1e-12)
CERTIFY_OPTIONS = CertifyOptions(node_tolerance=1e-9, special_tolerance=1e-5)

#: the roles of the events that bound the domain (each positive inside)
_DOMAIN = (Role.DOMAIN_EDGE, Role.GAMMA_MIN, Role.CORNER)


def certified_events(tagged) -> list[Event]:
    """The tracer's events as certified: the same functions, or their certified forms."""
    return [Event(t.event.name, t.certified or t.event.function, t.event.direction,
                  t.event.terminal) for t in tagged]


def _rows(curve: Curve, first: int, last: int) -> Curve:
    """The engine curve restricted to its rows ``first`` to ``last`` (special points re-indexed)."""
    points = tuple(dataclasses.replace(p, index=p.index - first) for p in curve.special_points
                   if first <= p.index <= last)
    keep = slice(first, last + 1)
    return dataclasses.replace(curve, x=curve.x[keep], s=curve.s[keep],
                               tangents=curve.tangents[keep], ds=curve.ds[keep],
                               newton_iterations=curve.newton_iterations[keep],
                               residuals=curve.residuals[keep], special_points=points)


def _not_covered(curve: BoundaryCurve, system, gamma_min: float) -> tuple:
    """What a boundary's certificate leaves out, by where it ends."""
    out = []
    if curve.end is Where.GAMMA_MIN:
        out.append(Exclusion(np.zeros(2), math.hypot(gamma_min, gamma_min),
                             f"the continuation towards the singular origin below gamma = "
                             f"{gamma_min:.3g} is not traced"))
    if curve.end is Where.CORNER:
        # radius 0: nothing is left out (the CLI says "covered")
        out.append(Exclusion(corner_point()[:2], 0.0, "the corner (pi/4, pi/4) itself, a "
                             "regular point of the chart w = sqrt(beta_L), proven as the zero "
                             "of the end event"))
    return tuple(out)


def outside_domain(certificate: Certificate, tagged) -> list[str]:
    """The domain's edges (the events of roles ``DOMAIN_EDGE``, ``GAMMA_MIN`` and ``CORNER``,
    all positive inside) on whose outer side, or leaving to it, a certified curve starts
    (:attr:`~continuation.Certificate.start_sides`); empty if it starts inside.

    The certificate proves that these events cross zero, leaving the domain, only where
    reported; with a start inside, the whole curve is then inside. (The validity conditions
    are not held to this: a boundary started at a junction may start a rounding outside its
    regime, where the crossing is reported at its next point.)
    """
    return [t.event.name for t, side in zip(tagged, certificate.start_sides, strict=True)
            if t.role in _DOMAIN and side != 1]


def _rows_on_curve(curve: BoundaryCurve, certificate: Certificate, system, first: int,
                   tolerance: float) -> str:
    """Why a row the boundary reports is not proven on the curve (empty if every one is).

    The tracer moves a few rows after tracing (onto the domain's edges, the junction of
    ``dr_limit`` to where ``dr_no_roll`` meets it, the last row onto the corner). A row is on
    the curve to within ``tolerance`` (max-norm, chart) if it is that close to its engine
    point (itself within the certificate's ``node_distance``) or to the box of a special
    point proven at that row.
    """
    engine = curve.engine[0]
    boxes: dict = {}
    for p in certificate.special_points:
        boxes.setdefault(p.index + first, []).append(p)
    for i, (row, x) in enumerate(zip(curve.engine_rows, curve.x, strict=True)):
        y = system.from_x(x)
        scale = 1.0 + float(np.max(np.abs(y)))
        moved = float(np.max(np.abs(y - engine.x[row])))
        if moved + certificate.node_distance <= tolerance * scale:
            continue
        near = [float(np.max(np.abs(y - p.centre))) + p.radius for p in boxes.get(row, ())]
        if near and min(near) <= tolerance * scale:
            continue
        return (f"row {i} of {curve.name} is {moved:.3g} from the traced point it replaces and "
                f"not within {tolerance * scale:.3g} of a proven special point")
    return ""


def certify_boundaries(curves: dict, traced: dict, gamma_min: float,
                       options: CertifyOptions | None = None) -> dict:
    """Each traced boundary with its :class:`~continuation.Certificate`.

    ``traced`` maps a boundary's name to ``(system, tagged events)`` of its engine curve;
    boundaries sharing an engine curve (``dr_limit`` and ``rs_limit``) share one proof over
    the rows either keeps.
    """
    options = options or CERTIFY_OPTIONS
    by_engine: dict = {}
    for name, curve in curves.items():
        if name in traced and curve.engine and curve.ok and len(curve.engine_rows) >= 2:
            by_engine.setdefault(id(curve.engine[0]), []).append(name)
    out = dict(curves)
    for names in by_engine.values():
        engine = curves[names[0]].engine[0]
        system, tagged = traced[names[0]]
        first = min(int(curves[n].engine_rows[0]) for n in names)
        last = max(int(curves[n].engine_rows[-1]) for n in names)
        certificate = certify(_rows(engine, first, last), system, certified_events(tagged),
                              options=options)
        outside = outside_domain(certificate, tagged) if certificate.proven else []
        if outside:
            certificate = dataclasses.replace(
                certificate, proven=False, check=Check.EVENT,
                message=f"not proven: {Check.EVENT}: the first point is not proven inside the "
                        f"domain (on or beyond {', '.join(outside)})")
        for name in names:
            cert = dataclasses.replace(certificate, excluded=certificate.excluded
                                       + _not_covered(curves[name], system, gamma_min))
            problem = _rows_on_curve(curves[name], cert, system, first, options.node_tolerance)
            if cert.proven and problem:
                cert = dataclasses.replace(cert, proven=False, check=Check.POINT,
                                           message=f"not proven: {Check.POINT}: {problem}")
            out[name] = dataclasses.replace(curves[name], certificate=cert)
    for name, curve in curves.items():
        if name not in out or out[name].certificate is None:
            reason = "the trace failed" if not curve.ok else "fewer than two points"
            out[name] = dataclasses.replace(curve, certificate=Certificate(
                False, f"not proven: {reason}", Check.INPUT))
    return out
