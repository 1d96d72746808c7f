"""Run the audit: every claim of ``claims.ini`` checked for the friction coefficients given."""

from __future__ import annotations

import logging
import time

from ...model.parameters import check_flag, check_friction
from . import caption, contact, rolling, rolling_sliding  # noqa: F401  (their @claim register the checks)
from .context import Context
from .registry import CHECKS, CLAIM_TEXTS
from .report import DEFAULT_KS, AuditReport

__all__ = ["run_audit"]

log = logging.getLogger(__name__)


def run_audit(ks=DEFAULT_KS, use_tracer: bool = True) -> AuditReport:
    """Check every claim for each friction coefficient in ``ks``.

    Parameters
    ----------
    ks : sequence of float
        Friction coefficients, each finite and > 0 (duplicates are dropped). Claims about
        ``k < sqrt 2`` or ``k > sqrt 2`` need at least one ``k`` on that side.
    use_tracer : bool
        Add the tracer's curves as a cross-check (the verdicts do not depend on it).

    Returns
    -------
    AuditReport

    Raises
    ------
    ValueError
        If ``ks`` is empty or a ``k`` is outside its range.
    TypeError
        If ``use_tracer`` is not a bool.
    """
    ks = tuple(dict.fromkeys(check_friction(k) for k in ks))
    use_tracer = check_flag("use_tracer", use_tracer)
    if not ks:
        raise ValueError("ks is empty: give at least one friction coefficient k > 0")
    missing = [text.id for text in CLAIM_TEXTS if text.id not in CHECKS]
    if missing:
        raise RuntimeError(f"claims without a check: {', '.join(missing)}")
    start = time.perf_counter()
    ctx = Context(ks, use_tracer)
    claims = []
    for text in CLAIM_TEXTS:
        claim = text.state(CHECKS[text.id](ctx))
        log.info("%s: %s", claim.id, claim.verdict)
        claims.append(claim)
    for k in ks:
        ctx.traced(k)
    return AuditReport(ks=ks, claims=tuple(claims), tracer=dict(ctx.tracer_status),
                       seconds=time.perf_counter() - start)
