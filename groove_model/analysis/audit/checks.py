r"""An audit of the paper's quantitative statements, each checked by computation.

Every statement of fact in the paragraphs "Rolling solutions" and "Rolling-sliding solutions"
of Halsey & Ertas, "A Ball in a Groove" (and the two statements of the caption of their
Fig. 2 that describe the same curves) is a :class:`Claim`: the sentence quoted verbatim from
the LaTeX source, how it was checked, the verdict and the numbers behind it, and, where the
statement is false as written, a concrete counterexample ``(k, gamma, delta, values)``.

The verdicts are computed, never written in: each check evaluates the point solver
(:mod:`groove_model.equilibrium`) on grids and with bracketed root finding
(``scipy.optimize.elementwise.find_root``, Chandrupatla's method, and ``brentq``) and compares
with the statement, for every friction coefficient ``k`` of the audit. Where the tracer
(:func:`groove_model.tracer.trace_boundaries`) runs, its curves and special points are reported
beside the root-finding numbers as an independent cross-check; the verdicts do not depend on it.

Verdicts
--------
``holds``
    True at every point checked, to the tolerance stated in the numbers.
``holds with qualification``
    True on the open part of the domain the paper describes, but false or only true in a
    limiting sense on a set the sentence does not exclude (an axis, a line, an edge), or only
    part of a compound statement holds; the qualification is stated with numbers.
``fails``
    False as written: the counterexample is a point where the statement is violated by far
    more than the numerical tolerance.

All angles are in radians; forces are the paper's ratios (``T/N``) and displacements are per
unit approach ``Z``. The compliance is the paper's, ``u_t/u_n = T/N``.
"""

from __future__ import annotations

import json
import logging
import math
import re
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from scipy import optimize
from scipy.optimize import elementwise

from ...model.equilibrium import double_rolling_state, rolling_sliding_state, solve_equilibrium
from ...model.parameters import Parameters, check_friction
from ...analysis.regimes import CATEGORIES, classify_grid
from ...model.lines import dr_limit_no_roll_point, dr_no_roll_line

__all__ = [
    "DEFAULT_KS",
    "VERDICTS",
    "AuditReport",
    "Claim",
    "Counterexample",
    "dr_limit_delta",
    "normalise_tex",
    "rs_limit_delta",
    "rs_no_roll_gamma",
    "run_audit",
]

log = logging.getLogger(__name__)

VERDICTS = ("holds", "holds with qualification", "fails")
#: Friction coefficients audited by default: both sides of k = sqrt 2 and of k = 1, and the
#: k = 1 and k = 10 of the paper's Fig. 2.
DEFAULT_KS = (0.3, 1.0, 1.2, 1.4, 1.5, 2.0, 10.0, 100.0)

_EPS = np.finfo(float).eps
_ROOT_TOL = dict(xatol=0.0, xrtol=4.0 * _EPS, fatol=0.0, frtol=0.0)
_HALF_PI = 0.5 * math.pi
_SQRT2 = math.sqrt(2.0)
_CORNER = (0.25 * math.pi, 0.25 * math.pi)
#: Residual of an identity evaluated in floating point (relative).
_IDENTITY_TOL = 1e-9
#: Distance below which two independently computed points are "the same point".
_POINT_TOL = 1e-7
#: Size of a violation that is far beyond round-off.
_VIOLATION = 1e-6
_GRID_N = 200
_MAP_N = 200
_LINE_N = 200

PAPER = "Halsey & Ertas, 'A Ball in a Groove'"
_ROLLING = "Rolling solutions"
_SLIDING = "Rolling-sliding solutions"
_CAPTION = "Caption of Fig. 2"


# --------------------------------------------------------------------------------------------
# Results
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Counterexample:
    """A point where a statement, read literally, is false.

    Attributes
    ----------
    k, gamma, delta : float
        Friction coefficient and the groove (radians). ``delta < 0`` means ``theta_R > theta_L``,
        the mirror image of the groove ``(gamma, -delta)`` with the walls' names swapped.
    values : dict of str to float or str
        What the statement predicts against what is computed.
    solver_fields : tuple of str
        Keys of ``values`` that are fields of ``solve_equilibrium(gamma, delta, k)`` and can be
        recomputed from it directly.
    note : str
    """

    k: float
    gamma: float
    delta: float
    values: dict
    solver_fields: tuple = ()
    note: str = ""

    def to_dict(self) -> dict:
        return dict(k=self.k, gamma=self.gamma, delta=self.delta,
                    theta_L=self.gamma + self.delta, theta_R=self.gamma - self.delta,
                    values=_jsonable(self.values), solver_fields=list(self.solver_fields),
                    note=self.note)


@dataclass(frozen=True)
class Claim:
    """One statement of the paper and the computed verdict on it.

    Attributes
    ----------
    id : str
        Short stable name.
    section : str
        The paragraph (or caption) it comes from.
    quote : str
        Verbatim from the LaTeX source (runs of white space collapsed); ``" ... "`` joins
        non-adjacent pieces.
    method : str
        How it was checked.
    verdict : str
        One of :data:`VERDICTS`.
    summary : str
        The finding in one or two sentences, with the key numbers.
    numbers : dict
        The numbers behind the verdict (``"k = ..."`` keys hold per-k results).
    counterexample : Counterexample or None
        For ``fails`` (and for a qualification, a point where the unqualified statement is false).
    """

    id: str
    section: str
    quote: str
    method: str
    verdict: str
    summary: str
    numbers: dict = field(default_factory=dict)
    counterexample: Counterexample | None = None

    def __post_init__(self) -> None:
        if self.verdict not in VERDICTS:
            raise ValueError(f"verdict = {self.verdict!r} is not one of {', '.join(VERDICTS)}")

    def to_dict(self) -> dict:
        return dict(id=self.id, section=self.section, quote=self.quote, method=self.method,
                    verdict=self.verdict, summary=self.summary, numbers=_jsonable(self.numbers),
                    counterexample=None if self.counterexample is None
                    else self.counterexample.to_dict())


@dataclass(frozen=True)
class AuditReport:
    """All claims for the friction coefficients ``ks``.

    Attributes
    ----------
    ks : tuple of float
    claims : tuple of Claim
    tracer : dict of str to str
        ``"k = ..." -> "ok"`` or the reason the tracer's cross-check is missing for that ``k``.
    seconds : float
        Wall-clock time of the audit (not written to JSON, so that files are reproducible).
    """

    ks: tuple
    claims: tuple
    tracer: dict = field(default_factory=dict)
    seconds: float = field(default=0.0, compare=False)

    def claim(self, claim_id: str) -> Claim:
        """The claim with this id."""
        for c in self.claims:
            if c.id == claim_id:
                return c
        raise KeyError(f"claim id = {claim_id!r} is not one of "
                       f"{', '.join(c.id for c in self.claims)}")

    def counts(self) -> dict:
        """Number of claims per verdict."""
        return {v: sum(c.verdict == v for c in self.claims) for v in VERDICTS}

    def to_json(self, indent: int = 2) -> str:
        """The report as a JSON document (non-finite numbers as the strings "inf", "nan")."""
        doc = dict(paper=PAPER, ks=list(self.ks), verdicts=list(VERDICTS), counts=self.counts(),
                   tracer=self.tracer, claims=[c.to_dict() for c in self.claims])
        return json.dumps(doc, indent=indent, allow_nan=False)

    def to_markdown(self) -> str:
        """The report as Markdown: a verdict table, then each claim with its numbers."""
        lines = [
            f"# Audit of the claims of {PAPER}",
            "",
            ("Every quantitative statement of the paragraphs *Rolling solutions* and "
             "*Rolling-sliding solutions* (and of the caption of Fig. 2), checked by computation "
             f"for k = {', '.join(f'{k:g}' for k in self.ks)}. Generated by `groove audit` "
             "(`groove_model.audit`); the verdicts are computed by the code, see the module "
             "docstring for what each verdict means. Angles in radians."),
            "",
            "Counts: " + ", ".join(f"{n} {v}" for v, n in self.counts().items()) + ".",
            "",
            "| id | section | statement | verdict |",
            "| --- | --- | --- | --- |",
        ]
        for c in self.claims:
            lines.append(f"| [`{c.id}`](#{c.id}) | {c.section} | {_short(c.quote)} | "
                         f"**{c.verdict}** |")
        lines += ["", "Tracer cross-check: " + "; ".join(f"{k}: {v}" for k, v in
                                                           self.tracer.items()) + ".", ""]
        for c in self.claims:
            lines += [f"## <a id=\"{c.id}\"></a>`{c.id}` — {c.verdict}", "",
                      f"*{c.section}*:", "", f"> {_markdown_escape(c.quote)}", "",
                      f"**Verdict: {c.verdict}.** {c.summary}", "",
                      f"**How checked.** {c.method}", ""]
            if c.counterexample is not None:
                ce = c.counterexample
                label = ("Counterexample" if c.verdict == "fails"
                         else "Where the unqualified statement is false")
                note = ce.note[:1].upper() + ce.note[1:]
                lines += [f"**{label}.** k = {ce.k!r}, gamma = {ce.gamma!r}, "
                          f"delta = {ce.delta!r} (theta_L = {ce.gamma + ce.delta!r}, "
                          f"theta_R = {ce.gamma - ce.delta!r}): "
                          + ", ".join(f"{key} = {_fmt(v, full=True)}"
                                      for key, v in ce.values.items())
                          + (f". {note}." if note else "."), ""]
            lines += _numbers_markdown(c.numbers) + [""]
        return "\n".join(lines).rstrip() + "\n"


def _short(quote: str, n: int = 90) -> str:
    text = _markdown_escape(quote)
    return text if len(text) <= n else text[: n - 1].rstrip() + "…"


def _markdown_escape(text: str) -> str:
    return text.replace("|", r"\|")


def _fmt(value, full: bool = False) -> str:
    if isinstance(value, (bool, np.bool_)):
        return str(bool(value))
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        value = float(value)
        if not math.isfinite(value):
            return str(value)
        return repr(value) if full else f"{value:.6g}"
    if isinstance(value, (list, tuple)):
        return "(" + ", ".join(_fmt(v, full) for v in value) + ")"
    return str(value)


def _numbers_markdown(numbers: dict) -> list:
    scalars = {k: v for k, v in numbers.items() if not isinstance(v, dict)}
    per_k = {k: v for k, v in numbers.items() if isinstance(v, dict)}
    lines = []
    if scalars:
        lines += ["| quantity | value |", "| --- | --- |"]
        lines += [f"| {_markdown_escape(key)} | {_markdown_escape(_fmt(v))} |"
                  for key, v in scalars.items()]
        lines.append("")
    if per_k:
        keys = list(dict.fromkeys(key for v in per_k.values() for key in v))
        lines += ["| " + " | ".join(["k", *map(_markdown_escape, keys)]) + " |",
                  "|" + " --- |" * (len(keys) + 1)]
        for label, row in per_k.items():
            cells = [_markdown_escape(_fmt(row.get(key, ""))) for key in keys]
            lines.append("| " + " | ".join([label.removeprefix("k = "), *cells]) + " |")
    return lines


def _jsonable(value):
    if isinstance(value, dict):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_jsonable(v) for v in value]
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        value = float(value)
        return value if math.isfinite(value) else str(value)
    return value


# --------------------------------------------------------------------------------------------
# Curves by bracketed root finding with the point solver
# --------------------------------------------------------------------------------------------


def _root(f: Callable, lo, hi, args=()) -> np.ndarray:
    """Vectorised bracketed root (Chandrupatla) of ``f(x, *args)`` between ``lo`` and ``hi``.

    Raises
    ------
    ArithmeticError
        If a bracket does not enclose a sign change.
    """
    res = elementwise.find_root(f, (np.asarray(lo, float), np.asarray(hi, float)), args=args,
                                tolerances=_ROOT_TOL)
    if not np.all(res.success):
        bad = np.flatnonzero(~np.atleast_1d(res.success))
        raise ArithmeticError(f"root finding failed for {bad.size} brackets "
                              f"(status {np.atleast_1d(res.status)[bad[0]]})")
    return res.x


def _dr_margins(gamma, delta, k):
    """``(k sin beta_L - A, k sin beta_R - B)`` of the double-rolling state; ``>= 0`` where valid.

    ``A = cos beta_L + upsilon = q_R S / (q_L + q_R)`` and ``B = cos beta_R - upsilon = q_L S /
    (q_L + q_R)`` with ``S = cos beta_L + cos beta_R = 2 sin gamma cos((beta_L - beta_R)/2)``
    (torque balance with ``upsilon`` eliminated), which keeps full relative accuracy where both
    are small, near the origin.
    """
    dr = double_rolling_state(gamma, delta, Parameters(1.0))
    q_L, q_R = np.sqrt(np.sin(dr["beta_L"])), np.sqrt(np.sin(dr["beta_R"]))
    S = 2.0 * np.sin(gamma) * np.cos(0.5 * (dr["beta_L"] - dr["beta_R"]))
    A, B = q_R * S / (q_L + q_R), q_L * S / (q_L + q_R)
    return k * np.sin(dr["beta_L"]) - A, k * np.sin(dr["beta_R"]) - B


def dr_limit_delta(k: float, gamma) -> np.ndarray:
    """``delta`` of the double-rolling limit ``T/N_L = k`` above each ``gamma`` in ``(0, arctan k)``.

    The margin ``k sin beta_L - (cos beta_L + upsilon)`` is ``k cos gamma - sin gamma > 0`` on
    ``delta = 0`` and ``-2 sin^2 gamma < 0`` on ``delta = gamma``; the root between is bracketed.
    """
    gamma = np.asarray(gamma, dtype=float)
    return _root(lambda d, g: _dr_margins(g, d, k)[0], np.zeros_like(gamma), gamma, args=(gamma,))


def rs_limit_delta(k: float, gamma) -> np.ndarray:
    """``delta`` where the rolling-sliding slip ``d_L`` vanishes above each ``gamma`` in ``(0, arctan k)``.

    ``d_L/Z = 2 (sin gamma - k cos gamma) < 0`` on ``delta = 0`` and ``2 sin^2 gamma > 0`` on
    ``delta = gamma``.
    """
    gamma = np.asarray(gamma, dtype=float)
    params = Parameters(k)
    return _root(lambda d, g: rolling_sliding_state(g, d, params)["d_L"],
                 np.zeros_like(gamma), gamma, args=(gamma,))


def rs_no_roll_gamma(k: float, delta) -> np.ndarray:
    """``gamma`` of the rolling-sliding ``upsilon = 0`` line on each row ``delta`` in ``(0, pi/4)``.

    ``upsilon = -cos 2 delta < 0`` on ``gamma = delta`` and ``upsilon = 1`` on ``gamma = pi/2``.
    """
    delta = np.asarray(delta, dtype=float)
    params = Parameters(k)
    return _root(lambda g, d: rolling_sliding_state(g, d, params)["upsilon"],
                 delta, np.full_like(delta, _HALF_PI), args=(delta,))


def _sign_changes(values: np.ndarray, axis: int = -1) -> np.ndarray:
    """Number of changes between strictly negative and strictly positive values along ``axis``.

    A zero carries the sign before it, so ``-, 0, +`` is one change and ``-, 0, -`` none.
    """
    s = np.sign(np.moveaxis(np.asarray(values), axis, -1))
    idx = np.where(s != 0, np.arange(s.shape[-1]), 0)
    np.maximum.accumulate(idx, axis=-1, out=idx)
    filled = np.take_along_axis(s, idx, axis=-1)
    return np.count_nonzero(filled[..., 1:] * filled[..., :-1] < 0, axis=-1)


# --------------------------------------------------------------------------------------------
# Shared computations
# --------------------------------------------------------------------------------------------


class _Context:
    """Lazily computed grids, lines and traced boundaries shared by the checks."""

    def __init__(self, ks, use_tracer: bool):
        self.ks = tuple(ks)
        self.use_tracer = use_tracer
        self._cache: dict = {}
        self.tracer_status: dict = {}

    def cached(self, key, compute):
        if key not in self._cache:
            self._cache[key] = compute()
        return self._cache[key]

    def grid(self):
        """Interior grid ``gamma in (0, pi/2)``, ``delta = r gamma``, ``r in (0, 1)``."""
        def compute():
            g = np.linspace(0.0, _HALF_PI, _GRID_N + 1)[1:-1]
            r = np.linspace(0.0, 1.0, _GRID_N + 1)[1:-1]
            G, R = np.meshgrid(g, r)
            return G.ravel(), (R * G).ravel()
        return self.cached("grid", compute)

    def dr_grid(self):
        """Double-rolling state on :meth:`grid` (independent of ``k``)."""
        return self.cached("dr_grid", lambda: double_rolling_state(*self.grid(), Parameters(1.0)))

    def rs_grid(self, k):
        return self.cached(("rs_grid", k),
                           lambda: rolling_sliding_state(*self.grid(), Parameters(k)))

    def regime_grid(self, k):
        return self.cached(("map", k), lambda: classify_grid(k, _MAP_N))

    def dr_limit(self, k):
        """``(gamma, delta)`` of the double-rolling limit on columns ``gamma in (0, arctan k)``."""
        def compute():
            g = math.atan(k) * np.linspace(0.0, 1.0, _LINE_N + 1)[1:-1]
            return g, dr_limit_delta(k, g)
        return self.cached(("dr_limit", k), compute)

    def dr_no_roll(self):
        """``(gamma, delta, state)`` of the double-rolling ``upsilon = 0`` line on rows.

        Rows ``delta`` in ``[1e-6, pi/4 - 1e-9]``, dense towards both ends (below ~1e-6 the
        line's distance ``O(delta^2)`` from ``gamma = arctan sqrt 2`` is lost in round-off).
        """
        def compute():
            q = 0.25 * math.pi
            d = np.unique(np.concatenate([np.geomspace(1e-6, 1e-2, 41),
                                          q * np.linspace(0.0, 1.0, _LINE_N + 1)[1:-1],
                                          q - np.geomspace(1e-9, 1e-2, 41)]))
            g, _ = dr_no_roll_line(d)
            return g, d, double_rolling_state(g, d, Parameters(1.0))
        return self.cached("dr_no_roll", compute)

    def rs_no_roll(self, k):
        """``(gamma, delta, state)`` on rows ``delta in (0, pi/4)``."""
        def compute():
            d = 0.25 * math.pi * np.linspace(0.0, 1.0, _LINE_N + 1)[1:-1]
            g = rs_no_roll_gamma(k, d)
            return g, d, rolling_sliding_state(g, d, Parameters(k))
        return self.cached(("rs_no_roll", k), compute)

    def junction(self, k):
        return self.cached(("junction", k), lambda: dr_limit_no_roll_point(k))

    def traced(self, k):
        """The tracer's boundaries with their unphysical parts, or None (reason recorded)."""
        def compute():
            label = f"k = {k:g}"
            if not self.use_tracer:
                self.tracer_status[label] = "not used (use_tracer=False)"
                return None
            try:
                from ...tracer import trace_boundaries

                bs = trace_boundaries(k, keep_unphysical=True)
            except (ArithmeticError, RuntimeError, ValueError, np.linalg.LinAlgError) as exc:
                # The cross-check is optional (the verdicts do not use it); its absence is
                # reported in the report's tracer status.
                self.tracer_status[label] = f"unavailable: {type(exc).__name__}: {exc}"
                log.warning("tracer cross-check unavailable for k = %g: %s", k, exc)
                return None
            self.tracer_status[label] = "ok" if bs.ok else "partial: " + "; ".join(bs.failures)
            return bs
        return self.cached(("traced", k), compute)


def _special(bs, name, kind):
    """``(gamma, delta)`` of the first special point ``kind`` of curve ``name``, or None."""
    if bs is None or name not in bs.curves:
        return None
    points = bs.curves[name].special(kind)
    return (float(points[0].x[0]), float(points[0].x[1])) if points else None


def _dist(a, b) -> float:
    if a is None or b is None:
        return math.nan
    return float(math.hypot(a[0] - b[0], a[1] - b[1]))


def _k_label(k: float) -> str:
    return f"k = {k:g}"


def _verdict(holds: bool, qualified: bool = False) -> str:
    if not holds:
        return "fails"
    return "holds with qualification" if qualified else "holds"


# --------------------------------------------------------------------------------------------
# Rolling solutions
# --------------------------------------------------------------------------------------------


def _claim_dr_contacts(ctx: _Context) -> Claim:
    dr = ctx.dr_grid()
    per_k, exceptions = {}, []
    for k in ctx.ks:
        valid = (dr["t"] <= k * dr["n_L"]) & (dr["t"] <= k * dr["n_R"])
        ups = dr["upsilon"][valid]
        # Contact motion down each wall (paper): u_c;L = -Z upsilon, u_c;R = +Z upsilon (d = 0).
        opposite = np.count_nonzero(-ups * ups < 0.0)
        row = {"DR grid points (delta > 0)": int(valid.sum()),
               "one up, one down": int(opposite),
               "min |upsilon|": float(np.min(np.abs(ups))) if ups.size else math.nan}
        junction = ctx.junction(k)
        row["upsilon = 0 line in DR"] = junction is not None
        if junction is not None:
            exceptions.append(k)
        per_k[_k_label(k)] = row
    all_opposite = all(r["one up, one down"] == r["DR grid points (delta > 0)"]
                       for r in per_k.values())
    gamma0 = 0.5 * math.atan(ctx.ks[0])
    at_axis = solve_equilibrium(gamma0, 0.0, ctx.ks[0])
    ce = Counterexample(
        k=ctx.ks[0], gamma=gamma0, delta=0.0,
        values={"upsilon": at_axis.upsilon, "regime": at_axis.regime},
        solver_fields=("upsilon", "regime"),
        note="on delta = 0 (and on the upsilon = 0 line of double rolling) upsilon = 0: "
             "u_c;L = u_c;R = 0, both contacts are stuck, neither moves up nor down")
    return Claim(
        id="dr_contacts_opposite", section=_ROLLING,
        quote="One of the contact points retrogrades up its contact plane, while the other "
              "rolls down its plane.",
        method="In double rolling d_L = d_R = 0, so the paper's contact motions down the walls are "
               "u_c;L = -Z upsilon and u_c;R = +Z upsilon: opposite whenever upsilon != 0. "
               f"Counted on a {_GRID_N - 1}^2 interior grid (delta = r gamma, 0 < r < 1) of the "
               "double-rolling region for each k, and located the set where upsilon = 0.",
        verdict=_verdict(all_opposite, qualified=True),
        summary="At every double-rolling grid point off the axis one contact moves up and the "
                "other down (clockwise: the left contact moves down its wall). Exceptions: "
                "the axis delta = 0 (upsilon = 0 exactly, both contacts stuck, as the paper "
                "itself says two sentences later) and, for k > sqrt 2, the upsilon = 0 line "
                f"inside double rolling (present here for k = {', '.join(f'{k:g}' for k in exceptions) or 'none'}).",
        numbers=per_k, counterexample=ce)


def _claim_dr_unique(ctx: _Context) -> Claim:
    n = 40
    g = np.linspace(0.0, _HALF_PI, n + 1)[1:-1]
    r = np.linspace(0.0, 1.0, n + 1)[1:-1]
    G, R = np.meshgrid(g, r)
    G, D = G.ravel()[:, None], (R * G).ravel()[:, None]
    a = np.linspace(0.0, 1.0, 801)[None, :]
    omega = math.pi - 2.0 * G
    beta_L, beta_R = a * omega, (1.0 - a) * omega
    s_L, s_R, c_L, c_R = np.sin(beta_L), np.sin(beta_R), np.cos(beta_L), np.cos(beta_R)
    q_L, q_R = np.sqrt(s_L), np.sqrt(s_R)
    # Torque (T_L = T_R) solved for upsilon, put into the horizontal balance (paper Eq. 2),
    # multiplied by q_L + q_R > 0: no root is added or lost.
    t = q_L * q_R * (c_L + c_R) / np.where(q_L + q_R > 0.0, q_L + q_R, 1.0)
    horizontal = (s_L * q_L * np.sin(G + D) - s_R * q_R * np.sin(G - D)
                  + t * (np.cos(G - D) - np.cos(G + D)))
    roots = _sign_changes(horizontal, axis=1)
    ok = bool(np.all(roots == 1))
    return Claim(
        id="dr_unique", section=_ROLLING,
        quote="In principle, we have a uniquely soluble system, since we have the three "
              "variables $Z$, $\\beta_L$ and $\\upsilon$ describing the kinematics, with three "
              "conditions of static equilibrium.",
        method="upsilon enters the torque balance linearly; eliminating it leaves the horizontal "
               "balance as one equation in beta_L on (0, pi - 2 gamma) (Z only sets the scale). "
               f"Counted its sign changes on 801 values of beta_L at {G.size} interior points "
               f"(delta = r gamma, 0 < r < 1).",
        verdict=_verdict(ok),
        summary=f"Exactly one root at every point checked (sign changes: min {int(roots.min())}, "
                f"max {int(roots.max())}).",
        numbers={"points": int(G.size), "min roots": int(roots.min()),
                 "max roots": int(roots.max())})


def _claim_dr_equations(ctx: _Context) -> Claim:
    G, D = ctx.grid()
    dr = ctx.dr_grid()
    keep = (G - D > 1e-3) & (dr["beta_L"] > 1e-3) & (dr["beta_R"] > 1e-3)
    g, d = G[keep], D[keep]
    bL, bR, ups = dr["beta_L"][keep], dr["beta_R"][keep], dr["upsilon"][keep]
    tL, tR = g + d, g - d
    lhs1 = (np.sin(bR) / np.sin(bL)) ** 1.5
    rhs1 = (np.sin(tL) / np.sin(tR)
            + (np.cos(bL) + ups) * (np.cos(tR) - np.cos(tL)) / (np.sin(bL) * np.sin(tR)))
    lhs2 = (np.sin(bR) / np.sin(bL)) ** 0.5
    rhs2 = (np.cos(bL) + ups) / (np.cos(bR) - ups)
    err1 = float(np.max(np.abs(lhs1 - rhs1) / np.maximum(np.abs(lhs1), 1.0)))
    err2 = float(np.max(np.abs(lhs2 - rhs2) / np.maximum(np.abs(lhs2), 1.0)))
    ok = err1 <= _IDENTITY_TOL and err2 <= _IDENTITY_TOL
    return Claim(
        id="dr_equations", section=_ROLLING,
        quote="Substituting Eqs. (\\ref{eq:norm}) and (\\ref{eq:rollt}) into Eqs. "
              "(\\ref{eq:equil1}-\\ref{eq:equil3}), we obtain ... \\left (\\frac{\\sin \\beta_R}"
              "{\\sin \\beta_L} \\right )^{\\frac{3}{2}} \\!\\!\\!\\!= \\frac{\\sin \\theta_L}"
              "{\\sin \\theta_R} + \\frac{\\left( \\cos \\beta_L+\\upsilon\\right)\\left(\\cos "
              "\\theta_R -\\cos \\theta_L\\right)}{\\sin \\beta_L \\sin \\theta_R}, ... \\left( "
              "\\frac{\\sin \\beta_R}{\\sin \\beta_L} \\right )^{\\frac{1}{2}} \\!\\!\\!\\!= "
              "\\frac{\\cos \\beta_L + \\upsilon}{\\cos \\beta_R - \\upsilon}.",
        method="The point solver solves the unreduced balances (horizontal Eq. 2, torque Eq. 3 "
               "with Hertz and proportional loading). Evaluated the paper's Eqs. (tran1) and "
               f"(tran2) at its double-rolling states on {keep.sum()} interior grid points "
               "(theta_R, beta_L, beta_R > 1e-3); relative residuals.",
        verdict=_verdict(ok),
        summary=f"Both equations are satisfied by the solutions of the balance equations: "
                f"largest relative residuals {err1:.1e} (tran1) and {err2:.1e} (tran2).",
        numbers={"points": int(keep.sum()), "max residual tran1": err1,
                 "max residual tran2": err2})


def _claim_delta0_state(ctx: _Context) -> Claim:
    g = np.linspace(0.0, _HALF_PI, 401)[1:-1]
    # Independently of the solver's special case on delta = 0: bracket the reduced equation
    # (Eq. 2 with upsilon eliminated) over beta_L on (0, pi - 2 gamma), and the limit delta -> 0+.
    a = np.linspace(0.0, 1.0, 2001)[None, :]
    omega = (math.pi - 2.0 * g)[:, None]
    s_L, s_R = np.sin(a * omega), np.sin((1.0 - a) * omega)
    horizontal = (s_L ** 1.5 - s_R ** 1.5) * np.sin(g)[:, None]  # D = 0 on delta = 0
    roots = _sign_changes(horizontal, axis=1)

    def reduced(beta, gg):
        return (np.sin(beta) ** 1.5 - np.sin(math.pi - 2.0 * gg - beta) ** 1.5) * np.sin(gg)

    beta_root = _root(reduced, np.full_like(g, 1e-12), math.pi - 2.0 * g - 1e-12, args=(g,))
    err_beta = float(np.max(np.abs(beta_root - (_HALF_PI - g))))
    # The limit delta -> 0+: the deviation must shrink in proportion to delta (it is large
    # only near the closed-groove edge gamma -> pi/2, where it scales like delta / (pi - 2 gamma)^2).
    devs = []
    for small in (1e-9, 1e-12):
        near = double_rolling_state(g, np.full_like(g, small), Parameters(1.0))
        devs.append((float(np.max(np.abs(near["beta_L"] - (_HALF_PI - g)))),
                     float(np.max(np.abs(near["upsilon"])))))
    err_limit, ups_limit = devs[1]
    shrink = devs[1][0] / devs[0][0] if devs[0][0] > 0 else 0.0
    ups_axis = (np.sqrt(np.cos(g)) * np.sin(g) - np.sqrt(np.cos(g)) * np.sin(g))
    ok = bool(np.all(roots == 1)) and err_beta <= 1e-12 and shrink <= 1e-2 and ups_limit <= 1e-6
    return Claim(
        id="delta0_symmetric_state", section=_ROLLING,
        quote="For $\\theta_L = \\theta_R$ (or $\\delta = 0$), $\\beta_L = \\beta_R = "
              "\\frac{\\pi}{2}-\\gamma$ and $\\upsilon = 0$, i.e., there is no rolling and both "
              "contacts are stuck.",
        method="On delta = 0 the horizontal balance reduces to sin(gamma) (sin^1.5 beta_L - "
               "sin^1.5 beta_R) = 0: counted its roots in beta_L on 2001 values for 399 gammas "
               "and located the root (Chandrupatla); with beta_L = beta_R the torque balance "
               "gives upsilon = 0. Also the solver's limit delta -> 0+ (delta = 1e-9 and 1e-12).",
        verdict=_verdict(ok),
        summary=f"Unique root beta_L = pi/2 - gamma (max error {err_beta:.1e}); the solver's "
                f"states converge to it as delta -> 0+ (at delta = 1e-12: |beta_L - (pi/2 - "
                f"gamma)| <= {err_limit:.1e}, |upsilon| <= {ups_limit:.1e}; shrinking "
                f"{1 / shrink if shrink else math.inf:.3g}-fold from delta = 1e-9).",
        numbers={"gammas": int(g.size), "roots per gamma (min, max)": (int(roots.min()),
                                                                       int(roots.max())),
                 "max |beta_L - (pi/2 - gamma)|": err_beta,
                 "delta = 1e-9: max |beta_L - (pi/2 - gamma)|": devs[0][0],
                 "delta = 1e-9: max |upsilon|": devs[0][1],
                 "delta = 1e-12: max |beta_L - (pi/2 - gamma)|": err_limit,
                 "delta = 1e-12: max |upsilon|": ups_limit,
                 "upsilon from torque at beta_L = beta_R": float(np.max(np.abs(ups_axis)))})


def _claim_delta0_ratio(ctx: _Context) -> Claim:
    g = np.linspace(0.0, _HALF_PI, 401)[1:-1]
    dr = double_rolling_state(g, np.zeros_like(g), Parameters(1.0))
    tn_L, tn_R = dr["T_over_N_L"], dr["T_over_N_R"]
    err = float(np.max(np.abs(np.concatenate([tn_L, tn_R]) / np.tan(np.concatenate([g, g])) - 1)))
    per_k = {}
    for k in ctx.ks:
        below = tn_L < k
        per_k[_k_label(k)] = {"largest gamma with T/N < k": float(g[below].max()),
                              "arctan k": math.atan(k),
                              "gammas with T/N >= k": int(np.count_nonzero(~below))}
    some_exceed = any(r["gammas with T/N >= k"] > 0 for r in per_k.values())
    k0 = ctx.ks[0]
    g0 = 0.5 * (math.atan(k0) + _HALF_PI)
    eq = solve_equilibrium(g0, 0.0, k0)
    ce = Counterexample(
        k=k0, gamma=g0, delta=0.0,
        values={"tan gamma (= T/N of the symmetric state)": math.tan(g0), "k": k0,
                "regime": eq.regime},
        solver_fields=("regime",),
        note="the identity T/N = tan gamma holds, but '< k' only for gamma < arctan k; beyond, "
             "the point solver reports double sliding")
    return Claim(
        id="delta0_ratio_tan_gamma", section=_ROLLING,
        quote="\\frac{u_{t;L}}{u_{n;L}} = \\frac{u_{t;R}}{u_{n;R}} = \\cot \\beta_L = \\tan "
              "\\gamma = \\frac{T_L}{N_L} = \\frac{T_R}{N_R}<k.",
        method="T/N of both walls of the double-rolling state on delta = 0 (399 gammas) against "
               "tan gamma; the inequality compared with k for each k.",
        verdict=_verdict(err <= _IDENTITY_TOL, qualified=some_exceed),
        summary=f"T/N_L = T/N_R = cot beta_L = tan gamma to {err:.1e} (relative). The final "
                "'< k' is a condition, not a consequence: it holds only for gamma < arctan k, "
                "as the next sentence of the paper says.",
        numbers={"max relative error of T/N = tan gamma": err, **per_k}, counterexample=ce)


def _claim_delta0_validity(ctx: _Context) -> Claim:
    g = np.linspace(0.0, _HALF_PI, 4001)[1:-1]
    per_k, ok = {}, True
    for k in ctx.ks:
        eq = solve_equilibrium(g, np.zeros_like(g), k)
        dr = eq.regime == "double_rolling"
        last = float(g[dr].max()) if np.any(dr) else math.nan
        first_out = float(g[~dr].min()) if np.any(~dr) else math.nan
        # The step where validity is lost brackets arctan k.
        brackets = last <= math.atan(k) <= first_out
        # Exactly at arctan k the ratio equals k up to round-off: either answer is right.
        decided = np.abs(g - math.atan(k)) > 1e-12
        ok &= brackets and bool(np.all(dr[decided] == (g <= math.atan(k))[decided]))
        per_k[_k_label(k)] = {"last double-rolling gamma": last, "arctan k": math.atan(k),
                              "first gamma with T/N > k": first_out}
    return Claim(
        id="delta0_valid_below_arctan_k", section=_ROLLING,
        quote="Hence, the solution for $\\delta=0$ can only exist for $\\gamma < \\arctan(k)$, "
              "because for $\\gamma > \\arctan(k)$, the values of $T/N$ corresponding to this "
              "solution exceed $k$.",
        method="Point solver on delta = 0 at 3999 gammas (step 3.9e-4): where is the symmetric "
               "double-rolling state valid (T/N <= k)?",
        verdict=_verdict(ok),
        summary="Valid exactly for gamma <= arctan k for every k (the last valid and first "
                "invalid grid gammas bracket arctan k).",
        numbers=per_k)


def _claim_dr_limit_start(ctx: _Context) -> Claim:
    per_k, ok = {}, True
    G, _ = ctx.grid()
    dr = ctx.dr_grid()
    for k in ctx.ks:
        gk = math.atan(k)
        # One transition per column below arctan k.
        col_g = gk * np.linspace(0.0, 1.0, 41)[1:-1]
        r = np.linspace(0.0, 1.0, 801)[1:][None, :]
        margin = _dr_margins(col_g[:, None], r * col_g[:, None], k)[0]
        transitions = _sign_changes(margin, axis=1)
        # Approach to the seed along the limit.
        near_g = gk - np.array([1e-2, 1e-3, 1e-4, 1e-5]) * gk
        near_d = dr_limit_delta(k, near_g)
        # No double rolling beyond arctan k (off the axis).
        beyond = (G > gk)
        valid = (dr["t"] <= k * dr["n_L"]) & (dr["t"] <= k * dr["n_R"])
        n_beyond = int(np.count_nonzero(beyond & valid))
        bs = ctx.traced(k)
        start = _special(bs, "dr_limit", "start")
        row = {"transitions per column (min, max)": (int(transitions.min()),
                                                       int(transitions.max())),
               "delta_b at gamma = arctan k (1 - 1e-5)": float(near_d[-1]),
               "slope delta_b / (arctan k - gamma)": float(near_d[-1] / (gk - near_g[-1])),
               "DR grid points with gamma > arctan k": n_beyond,
               "tracer: |start - (arctan k, 0)|": _dist(start, (gk, 0.0))}
        ok &= (bool(np.all(transitions == 1)) and n_beyond == 0 and near_d[-1] < 1e-4)
        per_k[_k_label(k)] = row
    return Claim(
        id="dr_limit_from_arctan_k", section=_ROLLING,
        quote="Thus, emanating from the point $(\\gamma,\\delta) = (\\arctan(k),0)$ is a boundary "
              "beyond which double rolling is impossible, because it would require illegal "
              "values of $T/N >k$.",
        method="For each k: sign changes of the margin k sin beta_L - (cos beta_L + upsilon) on "
               "800 deltas in each of 39 columns gamma < arctan k; the limit delta_b(gamma) by "
               "bracketed root finding as gamma -> arctan k; double-rolling validity on the "
               f"{_GRID_N - 1}^2 interior grid beyond arctan k; the tracer's start point of "
               "dr_limit.",
        verdict=_verdict(ok),
        summary="Every column below arctan k has exactly one double-rolling limit, its delta "
                "tends to 0 linearly as gamma -> arctan k, and no point with gamma > arctan k, "
                "delta > 0 is double rolling.",
        numbers=per_k)


def _claim_dr_limit_steeper(ctx: _Context) -> Claim:
    dr = ctx.dr_grid()
    per_k, ok = {}, True
    for k in ctx.ks:
        g, d = ctx.dr_limit(k)
        st = double_rolling_state(g, d, Parameters(1.0))
        worst_R = float(np.max(st["T_over_N_R"] / k))
        right_first = int(np.count_nonzero((dr["t"] > k * dr["n_R"]) & (dr["t"] <= k * dr["n_L"])))
        per_k[_k_label(k)] = {"max T/N_R / k on the limit": worst_R,
                              "grid points with T/N_R > k >= T/N_L": right_first}
        ok &= worst_R < 1.0 and right_first == 0
    steeper_larger = int(np.count_nonzero(dr["T_over_N_L"] < dr["T_over_N_R"]))
    return Claim(
        id="dr_limit_steeper_wall_first", section=_ROLLING,
        quote="This bound is exceeded first on the steeper of the two walls.",
        method=f"T/N_R along the limit (T/N_L = k) on {_LINE_N - 1} columns per k; on the "
               f"{_GRID_N - 1}^2 interior grid, points where the right (less steep) wall exceeds "
               "k while the left does not, and points where T/N_L < T/N_R.",
        verdict=_verdict(ok and steeper_larger == 0),
        summary="On the limit T/N_R stays below k for every k, and nowhere does the less steep "
                f"wall reach k first; in fact T/N_L >= T/N_R everywhere (points with T/N_L < "
                f"T/N_R: {steeper_larger}).",
        numbers={"grid points with T/N_L < T/N_R": steeper_larger, **per_k})


def _claim_dr_limit_end(ctx: _Context) -> Claim:
    per_k, ok = {}, True
    gammas = np.array([1e-1, 1e-2, 1e-3, 1e-4])
    for k in ctx.ks:
        g = gammas[gammas < 0.5 * math.atan(k)]
        d = dr_limit_delta(k, g)
        gap = (g - d) / g
        st = double_rolling_state(g, d, Parameters(1.0))
        slope = float(np.polyfit(np.log(g[-3:]), np.log(g[-3:] - d[-3:]), 1)[0])
        bs = ctx.traced(k)
        end = _special(bs, "dr_limit", "end")
        row = {"(gamma - delta)/gamma at gamma = 1e-4": float(gap[-1]),
               "log-log slope of gamma - delta": slope,
               "beta_L k / (2 gamma^2) at 1e-4": float(st["beta_L"][-1] * k / (2 * g[-1] ** 2)),
               "tracer end: delta/gamma": (end[1] / end[0]) if end else math.nan,
               "tracer end: gamma": end[0] if end else math.nan}
        ok &= bool(np.all(np.diff(gap) < 0)) and gap[-1] < 1e-3 and slope > 1.5
        per_k[_k_label(k)] = row
    return Claim(
        id="dr_limit_to_origin_along_diagonal", section=_ROLLING,
        quote="This boundary, shown as a solid line in Fig.~\\ref{graph}, rejoins the "
              "$\\gamma$-axis at $\\gamma =0$, asymptotically merging with the line "
              "$\\delta = \\gamma$.",
        method="The limit delta_b(gamma) by bracketed root finding at gamma = 1e-1 ... 1e-4 "
               "(those below arctan(k)/2), using the torque-eliminated margin that keeps full "
               "accuracy near the origin; the relative gap (gamma - delta_b)/gamma, the power "
               "law of gamma - delta_b, and beta_L against the asymptote 2 gamma^2 / k. The "
               "tracer stops at gamma = 1e-3 on its way to the singular corner.",
        verdict=_verdict(ok),
        summary="The limit reaches the origin tangent to delta = gamma: (gamma - delta_b)/gamma "
                "falls to ~1e-6 at gamma = 1e-4, gamma - delta_b ~ gamma^2.5, and beta_L ~ "
                "2 gamma^2 / k.",
        numbers=per_k)


def _claim_dr_no_roll_interval(ctx: _Context) -> Claim:
    gs = np.linspace(0.0, _HALF_PI, 801)[1:-1]
    # Ratios delta/gamma, dense towards both ends where the line meets delta = 0 and delta = gamma.
    r = np.unique(np.concatenate([np.linspace(0.0, 1.0, 201)[1:-1], np.geomspace(1e-7, 1e-2, 15),
                                  1.0 - np.geomspace(1e-9, 1e-2, 15)]))
    G, R = np.meshgrid(gs, r, indexing="ij")
    ups = double_rolling_state(G, R * G, Parameters(1.0))["upsilon"]
    roots = _sign_changes(ups, axis=1)
    with_root = gs[roots > 0]
    h = gs[1] - gs[0]
    lo, hi = 0.25 * math.pi, math.atan(_SQRT2)
    inside = (gs > lo + h) & (gs < hi - h)
    g, d, st = ctx.dr_no_roll()
    beta_gap = float(np.min(np.abs(st["beta_L"] - st["beta_R"])))
    traced = {}
    for k in ctx.ks:
        bs = ctx.traced(k)
        if bs is not None and "dr_no_roll" in bs.curves and len(bs.curves["dr_no_roll"].x):
            x = bs.curves["dr_no_roll"].x
            traced[_k_label(k)] = {"tracer: min gamma": float(x[:, 0].min()),
                                   "tracer: max gamma": float(x[:, 0].max())}
    ok = (with_root.size > 0 and with_root.min() >= lo - h and with_root.max() <= hi + h
          and bool(np.all(roots[inside] == 1)) and beta_gap > 0.0
          and g.min() >= lo - 1e-9 and g.max() <= hi + 1e-9)
    return Claim(
        id="dr_no_roll_interval", section=_ROLLING,
        quote="There is an additional solution for which $\\upsilon =0$ (no rolling), with "
              "$\\beta_L \\ne \\beta_R$, that exists for $\\frac{\\pi}{4} \\le \\gamma \\le "
              "\\arctan(\\sqrt{2})$.",
        method="The double-rolling state does not depend on k. Sign changes of upsilon along "
               f"{gs.size} columns 0 < gamma < pi/2 ({r.size} values of delta/gamma each, dense "
               "near both ends); the line gamma(delta) by bracketed root finding on "
               f"{d.size} rows 1e-6 <= delta < pi/4; the tracer's dr_no_roll (with its "
               "unphysical part).",
        verdict=_verdict(ok),
        summary=f"upsilon = 0 off the axis only in columns {with_root.min():.5f} <= gamma <= "
                f"{with_root.max():.5f} (grid step {h:.1e}; pi/4 = {lo:.5f}, arctan sqrt 2 = "
                f"{hi:.5f}), exactly once per column inside; on the rows the line spans "
                f"{g.min():.9f} <= gamma <= {g.max():.9f}, from (arctan sqrt 2, 0) to "
                f"(pi/4, pi/4), with beta_L != beta_R (min |beta_L - beta_R| = {beta_gap:.1e}, "
                "at the branch-point end).",
        numbers={"columns with a root: min gamma": float(with_root.min()),
                 "columns with a root: max gamma": float(with_root.max()), "pi/4": lo,
                 "arctan sqrt 2": hi, "grid step": float(h),
                 "roots per column inside (min, max)": (int(roots[inside].min()),
                                                        int(roots[inside].max())),
                 "line on rows: min gamma": float(g.min()),
                 "line on rows: max gamma": float(g.max()),
                 "line: gamma at delta = 1e-6": float(g[0]),
                 "line: (gamma, delta) nearest the corner": (float(g[-1]), float(d[-1])),
                 "min |beta_L - beta_R| on the line": beta_gap, **traced})


def _claim_dr_no_roll_ratio(ctx: _Context) -> Claim:
    g, d, st = ctx.dr_no_roll()
    worst = np.maximum(st["T_over_N_L"], st["T_over_N_R"])
    i = int(np.argmin(worst))
    monotone = bool(np.all(np.diff(st["T_over_N_L"]) > 0))
    ok = float(worst.min()) >= _SQRT2 * (1.0 - 1e-12)
    return Claim(
        id="dr_no_roll_ratio_sqrt2", section=_ROLLING,
        quote="This additional solution always has at least one of the ratios $T/N \\ge "
              "\\sqrt{2}$",
        method="max(T/N_L, T/N_R) along the upsilon = 0 line of double rolling (bracketed roots "
               f"on {g.size} rows 1e-6 <= delta < pi/4). With upsilon = 0, T/N = cot beta.",
        verdict=_verdict(ok),
        summary=f"The larger ratio is T/N_L = cot beta_L; it falls monotonically from infinity "
                f"at (pi/4, pi/4) to sqrt 2 at the branch point (arctan sqrt 2, 0): minimum on "
                f"the line {worst.min():.9f} at gamma = {g[i]:.6f} (sqrt 2 = {_SQRT2:.9f}).",
        numbers={"min max(T/N) on the line": float(worst.min()), "at gamma": float(g[i]),
                 "at delta": float(d[i]), "sqrt 2": _SQRT2,
                 "T/N_L increasing with delta": monotone,
                 "max T/N_R on the line": float(st["T_over_N_R"].max())})


def _claim_dr_no_roll_k(ctx: _Context) -> Claim:
    _, _, st = ctx.dr_no_roll()
    per_k, ok = {}, True
    for k in ctx.ks:
        physical = (st["T_over_N_L"] <= k) & (st["T_over_N_R"] <= k)
        rg = ctx.regime_grid(k)
        codes = rg.category[1:]  # rows delta > 0
        dr_cw = CATEGORIES.index("double_rolling_clockwise")
        dr_ccw = CATEGORIES.index("double_rolling_counterclockwise")
        n_ccw = int(np.count_nonzero(codes == dr_ccw))
        bs = ctx.traced(k)
        traced = (bs is not None and "dr_no_roll" in bs.curves
                  and bool(np.any(bs.curves["dr_no_roll"].physical)))
        per_k[_k_label(k)] = {"physical points of the line": int(physical.sum()),
                              "DR counter-clockwise grid nodes": n_ccw,
                              "DR clockwise grid nodes": int(np.count_nonzero(codes == dr_cw)),
                              "tracer: physical dr_no_roll": traced if bs is not None else "n/a"}
        ok &= (physical.sum() > 0) == (k > _SQRT2) and (n_ccw > 0) == (k > _SQRT2)
    return Claim(
        id="dr_no_roll_needs_k_above_sqrt2", section=_ROLLING,
        quote="so it can only appear for $k > \\sqrt{2}$",
        method="Physical part (T/N <= k on both walls) of the upsilon = 0 double-rolling line "
               f"for each k; counter-clockwise double rolling on the {_MAP_N}-step map grid; the "
               "tracer's physical dr_no_roll.",
        verdict=_verdict(ok),
        summary="The line has a physical part, and double rolling has a counter-clockwise "
                "region, exactly for the k above sqrt 2.",
        numbers=per_k)


def _rotation_rows(rg, regime: str):
    """Per row (delta > 0): sign changes of upsilon among the nodes of one regime, left-to-right order."""
    cw = CATEGORIES.index(f"{regime}_clockwise")
    ccw = CATEGORIES.index(f"{regime}_counterclockwise")
    bad_order, changes = 0, []
    for row in rg.category[1:]:
        seq = row[(row == cw) | (row == ccw)]
        n = int(np.count_nonzero(np.diff(seq)))
        changes.append(n)
        if n > 1 or (n == 1 and seq[0] != cw):
            bad_order += 1
    return np.array(changes), bad_order


def _claim_dr_no_roll_sides(ctx: _Context) -> Claim:
    per_k, ok, checked = {}, True, 0
    g_line, d_line, _ = ctx.dr_no_roll()
    for k in ctx.ks:
        if k <= _SQRT2:
            continue
        rg = ctx.regime_grid(k)
        changes, bad = _rotation_rows(rg, "double_rolling")
        # Where the change happens on each row against the line.
        offsets = []
        cw = CATEGORIES.index("double_rolling_clockwise")
        ccw = CATEGORIES.index("double_rolling_counterclockwise")
        for j, row in enumerate(rg.category[1:], start=1):
            idx = np.flatnonzero((row == cw) | (row == ccw))
            if idx.size < 2:
                continue
            jumps = idx[:-1][np.diff(row[idx]) != 0]
            if jumps.size == 1:
                i = jumps[0]
                g_cross = float(np.interp(rg.delta[j], d_line, g_line))
                offsets.append(abs(g_cross - 0.5 * (rg.gamma[i] + rg.gamma[i + 1])))
        worst = max(offsets) if offsets else math.nan
        per_k[_k_label(k)] = {"rows with a change": int(np.count_nonzero(changes)),
                              "rows cw -> ccw only": int(np.count_nonzero(changes == 1)) - bad,
                              "rows violating": bad,
                              "max |change - line| / step": worst / rg.step}
        checked += 1
        ok &= bad == 0 and worst <= rg.step
    return Claim(
        id="dr_no_roll_sides", section=_ROLLING,
        quote="and constitutes a boundary between a regime in which the ball rolls clockwise "
              "(i.e., down the steeper surface) for smaller $\\gamma$, and a regime in which the "
              "ball rolls counter-clockwise (i.e., up the steeper surface) for larger $\\gamma$.",
        method=f"On each row delta > 0 of the {_MAP_N}-step map grid (k > sqrt 2): the order of "
               "clockwise and counter-clockwise double-rolling nodes, and where the rotation "
               "changes against the line found by root finding.",
        verdict=_verdict(ok and checked > 0),
        summary="On every row the double-rolling nodes are clockwise below the line and "
                "counter-clockwise above it in gamma, and the change sits within one grid step "
                "of the line.",
        numbers=per_k)


def _claim_amontons_sign(ctx: _Context) -> Claim:
    dr = ctx.dr_grid()
    min_t = float(np.min(dr["t"]))
    per_k, ok = {}, min_t >= 0.0
    for k in ctx.ks:
        rs = ctx.rs_grid(k)
        valid_rs = rs["d_L"] >= 0.0
        per_k[_k_label(k)] = {"min mu = T/N_R in RS": float(np.min(rs["mu"][valid_rs]))}
        ok &= per_k[_k_label(k)]["min mu = T/N_R in RS"] >= 0.0
    return Claim(
        id="amontons_one_sided", section=_ROLLING,
        quote="However, we must also impose Eqs. (\\ref{eq:Amont}) constraining the values of "
              "$T/N$.",
        method="Eq. (Amont) is written one-sided, T <= k N; that is Amontons' law only if the "
               "common tangential force T is never negative (the wall never pushes the ball "
               "down). Minimum of T over the double-rolling states of the interior grid "
               "(T = c q_L q_R (cos beta_L + cos beta_R)/(q_L + q_R), cos beta_L + cos beta_R = "
               "2 sin gamma cos((beta_L - beta_R)/2) >= 0) and of mu over the rolling-sliding "
               "states.",
        verdict=_verdict(ok),
        summary=f"T >= 0 everywhere (min scaled T in double rolling {min_t:.2e}, zero only on "
                "the edges), so -k N <= T holds automatically and the one-sided form suffices.",
        numbers={"min scaled T in double rolling": min_t, **per_k})


def _claim_caption_dr_below(ctx: _Context) -> Claim:
    per_k, ok = {}, True
    for k in ctx.ks:
        rg = ctx.regime_grid(k)
        names = rg.names()
        bad_cols = 0
        for i in range(1, rg.gamma.size):
            col = names[1: i + 1, i]
            is_dr = np.array([n.startswith("double_rolling") for n in col])
            # Double rolling must be a (possibly empty) run starting at the bottom.
            if is_dr.any() and not np.all(is_dr[: np.flatnonzero(is_dr)[-1] + 1]):
                bad_cols += 1
        per_k[_k_label(k)] = {"columns checked": int(rg.gamma.size - 1),
                              "columns with RS below DR": bad_cols}
        ok &= bad_cols == 0
    return Claim(
        id="caption_dr_below_rs_above", section=_CAPTION,
        quote="Solid lines mark the boundary between the elastic double-rolling regime below "
              "and the plastic rolling-sliding regime above.",
        method=f"Every column gamma = const of the {_MAP_N}-step map grid (delta > 0): the "
               "double-rolling nodes must form one run starting at the bottom.",
        verdict=_verdict(ok),
        summary="In every column double rolling lies below the limit and rolling sliding above.",
        numbers=per_k)


def _claim_caption_rotation(ctx: _Context) -> Claim:
    per_k, ok = {}, True
    for k in ctx.ks:
        rg = ctx.regime_grid(k)
        cw = np.isin(rg.category, [CATEGORIES.index("double_rolling_clockwise"),
                                   CATEGORIES.index("rolling_sliding_clockwise")])
        ccw = np.isin(rg.category, [CATEGORIES.index("double_rolling_counterclockwise"),
                                    CATEGORIES.index("rolling_sliding_counterclockwise")])
        bad, changes = 0, []
        for j in range(1, rg.delta.size):
            seq = np.where(cw[j], -1, np.where(ccw[j], 1, 0))
            seq = seq[seq != 0]
            n = int(np.count_nonzero(np.diff(seq)))
            changes.append(n)
            if n > 1 or (n == 1 and seq[0] != -1):
                bad += 1
        per_k[_k_label(k)] = {"rows with one cw -> ccw change": int(np.sum(np.array(changes) == 1)),
                              "rows all one sense": int(np.sum(np.array(changes) == 0)),
                              "rows violating": bad}
        ok &= bad == 0
    return Claim(
        id="caption_rotation_sides", section=_CAPTION,
        quote="The dashed and dot-dashed lines mark the boundaries between clockwise "
              "(low-$\\gamma$) and counter-clockwise (high-$\\gamma$) rolling.",
        method=f"Every row delta = const > 0 of the {_MAP_N}-step map grid, across both regimes: "
               "the rotation sense may change at most once, and then from clockwise (low gamma) "
               "to counter-clockwise (high gamma).",
        verdict=_verdict(ok),
        summary="On every row the rotation changes at most once, always from clockwise at low "
                "gamma to counter-clockwise at high gamma (rows above delta = pi/4 are all "
                "counter-clockwise).",
        numbers=per_k)


# --------------------------------------------------------------------------------------------
# Rolling-sliding solutions
# --------------------------------------------------------------------------------------------


def _claim_rs_only(ctx: _Context) -> Claim:
    G, D = ctx.grid()
    dr = ctx.dr_grid()
    tL, tR = G + D, G - D
    per_k, ok = {}, True
    for k in ctx.ks:
        rs = ctx.rs_grid(k)
        dr_valid = (dr["t"] <= k * dr["n_L"]) & (dr["t"] <= k * dr["n_R"])
        rs_valid = (rs["d_L"] >= 0.0) & (rs["mu"] <= k)
        # The shallower (right) wall sliding instead: T/N_L = mu' from the mirrored formula.
        den_mirror = np.cos(tL) - np.cos(tR) + np.sin(tR) / k
        mirror_ok = (den_mirror > 0.0) & (np.sin(tL) <= k * den_mirror)
        # Both walls sliding: horizontal balance with N_L = N_R, T = kN leaves
        # 2 sin(delta) (cos gamma + k sin gamma) N, zero only on delta = 0.
        ds_residual = 2.0 * np.sin(D) * (np.cos(G) + k * np.sin(G))
        row = {"DR-invalid points": int(np.count_nonzero(~dr_valid)),
               "of which without an RS state": int(np.count_nonzero(~dr_valid & ~rs_valid)),
               "points where RS and DR both valid": int(np.count_nonzero(dr_valid & rs_valid)),
               "admissible right-wall sliding": int(np.count_nonzero(mirror_ok)),
               "min double-sliding residual": float(ds_residual.min())}
        per_k[_k_label(k)] = row
        ok &= (row["of which without an RS state"] == 0 and row["admissible right-wall sliding"] == 0
               and row["min double-sliding residual"] > 0.0)
    return Claim(
        id="rs_only_solution_beyond_limit", section=_SLIDING,
        quote="Beyond the boundary at which the steeper wall has $T=kN$, the only solutions "
              "possible are ``rolling-sliding\" solutions, in which one contact rolls without "
              "sliding while the other slides.",
        method=f"On the {_GRID_N - 1}^2 interior grid for each k: where double rolling is "
               "invalid, is the rolling-sliding state valid (d_L >= 0, mu <= k)? Alternatives: "
               "the shallower wall sliding (mirrored mu formula, admissible only if its "
               "denominator > 0 and T/N_L <= k) and double sliding (horizontal balance "
               "residual 2 sin delta (cos gamma + k sin gamma) N).",
        verdict=_verdict(ok),
        summary="Everywhere beyond the limit the steeper-wall rolling-sliding state is valid, "
                "the shallower wall can never slide, double sliding is impossible off the axis; "
                "and inside double rolling no rolling-sliding state is valid (the regimes do "
                "not overlap).",
        numbers=per_k)


def _force_balance_mu(gamma, delta, k):
    """``T/N_R`` with ``T = k N_L`` from the vertical and horizontal balances as a 2x2 solve."""
    tL, tR = gamma + delta, gamma - delta
    # Unknowns (N_L, N_R), Mg = 1, T_L = T_R = k N_L (paper Eqs. 1-3).
    A = np.array([[k * math.sin(tL) + math.cos(tL) + k * math.sin(tR), math.cos(tR)],
                  [-k * math.cos(tL) + math.sin(tL) + k * math.cos(tR), -math.sin(tR)]])
    N_L, N_R = np.linalg.solve(A, [1.0, 0.0])
    return k * N_L / N_R, N_L, N_R


def _mu(theta_L, theta_R, k):
    return np.sin(theta_R) / (np.cos(theta_R) - np.cos(theta_L) + np.sin(theta_L) / k)


def _claim_rs_mu_formula(ctx: _Context) -> Claim:
    rng = np.random.default_rng(20260101)
    per_k, ok = {}, True
    for k in ctx.ks:
        g = rng.uniform(0.02, _HALF_PI - 0.02, 300)
        d = rng.uniform(0.0, 0.98, 300) * g
        errs = []
        for gi, di in zip(g, d):
            mu_fb, _, _ = _force_balance_mu(gi, di, k)
            errs.append(abs(mu_fb / _mu(gi + di, gi - di, k) - 1.0))
        per_k[_k_label(k)] = {"max relative difference": float(max(errs))}
        ok &= max(errs) <= _IDENTITY_TOL
    return Claim(
        id="rs_mu_formula", section=_SLIDING,
        quote="The equations of static equilibrium then imply ... \\frac{T}{N_R} = "
              "\\frac{\\sin \\theta_R}{\\cos\\theta_R - \\cos\\theta_L + \\frac{1}{k} \\sin "
              "\\theta_L} \\equiv \\mu,",
        method="For 300 random grooves per k: solved the vertical and horizontal balances "
               "(paper Eqs. 1, 2) with T_L = T_R = k N_L as a 2x2 linear system for (N_L, N_R) "
               "and compared k N_L / N_R with the formula.",
        verdict=_verdict(ok),
        summary="The formula is what the balances give (relative differences at round-off).",
        numbers=per_k)


def _theta_grid(n=400, shallower_left=False):
    """Wall angles with ``theta_R < theta_L`` (or ``>`` if ``shallower_left``), ``theta_L + theta_R <= pi``."""
    t = np.linspace(0.0, math.pi, n + 1)
    TL, TR = np.meshgrid(t, t)
    keep = (TL + TR <= math.pi) & ((TR > TL) if shallower_left else (TR < TL))
    return TL[keep], TR[keep]


def _claim_rs_mu_below(ctx: _Context) -> Claim:
    tL, tR = _theta_grid()
    per_k, ok = {}, True
    for k in ctx.ks:
        mu = _mu(tL, tR, k)
        per_k[_k_label(k)] = {"max mu / k": float(np.max(mu / k)),
                              "min denominator": float(np.min(np.cos(tR) - np.cos(tL)
                                                              + np.sin(tL) / k))}
        ok &= per_k[_k_label(k)]["max mu / k"] < 1.0
    return Claim(
        id="rs_mu_below_k", section=_SLIDING,
        quote="Note that for $\\theta_R < \\theta_L$, $\\mu < k$",
        method=f"mu/k on a grid of {tL.size} pairs 0 <= theta_R < theta_L, theta_L + theta_R <= "
               "pi. Analytically k - mu has the sign of sin theta_L - sin theta_R + k (cos "
               "theta_R - cos theta_L) = 2 sin delta (cos gamma + k sin gamma) > 0.",
        verdict=_verdict(ok),
        summary="mu < k at every point (and the denominator is positive).",
        numbers=per_k)


def _claim_rs_mu_above(ctx: _Context) -> Claim:
    tL, tR = _theta_grid(shallower_left=True)
    ordinary = (tL >= 0.05) & (tR <= _HALF_PI - 0.05)  # both walls between 0.05 and pi/2 - 0.05
    per_k, ok = {}, True
    first_bad = {}
    for k in ctx.ks:
        den = np.cos(tR) - np.cos(tL) + np.sin(tL) / k
        mu = np.full_like(den, -np.inf)
        np.divide(np.sin(tR), den, out=mu, where=den != 0.0)
        below = mu <= k
        per_k[_k_label(k)] = {"pairs": int(tL.size), "pairs with mu <= k": int(below.sum()),
                              "of which denominator > 0": int(np.count_nonzero(below & (den > 0))),
                              "ordinary grooves with mu <= k": int(np.count_nonzero(below & ordinary))}
        ok &= not np.any(below)
        if np.any(below & ordinary):
            # A representative violation: the ordinary groove with the most negative denominator.
            first_bad[k] = int(np.argmin(np.where(below & ordinary, den, np.inf)))
    ce = None
    if first_bad:
        k = 1.0 if 1.0 in first_bad else next(iter(first_bad))
        i = first_bad[k]
        g, d = 0.5 * (tL[i] + tR[i]), 0.5 * (tL[i] - tR[i])
        mu_fb, N_L, N_R = _force_balance_mu(g, d, k)
        ce = Counterexample(
            k=float(k), gamma=float(g), delta=float(d),
            values={"mu": float(_mu(tL[i], tR[i], k)),
                    "denominator": float(np.cos(tR[i]) - np.cos(tL[i]) + np.sin(tL[i]) / k),
                    "k N_L / N_R from the balances": float(mu_fb),
                    "N_R / N_L": float(N_R / N_L)},
            note="theta_R > theta_L (the mirror image of the groove (gamma, -delta) with the "
                 "shallower wall on the left): the formula's denominator is negative, so "
                 "mu < 0 < k; the balances with the left wall sliding then need N_R < 0, i.e. "
                 "no such state exists at all. The conclusion 'sliding always occurs on the "
                 "steeper wall' survives; the inequality mu > k does not")
    strict = all(r["of which denominator > 0"] == 0 for r in per_k.values())
    if ok:
        summary = "mu > k at every pair checked."
    else:
        summary = ("False as written: wherever the denominator cos theta_R - cos theta_L + "
                   "sin(theta_L)/k is negative (a steep right wall, a shallow left one; for "
                   "large k almost every pair) the formula gives mu < 0 < k. "
                   + ("Where the denominator is positive, mu > k does hold." if strict else
                      "Even with a positive denominator mu <= k occurs."))
    return Claim(
        id="rs_mu_above_k_if_shallower_slides", section=_SLIDING,
        quote="while for $\\theta_R > \\theta_L$, $\\mu > k$.",
        method=f"mu from the formula on a grid of {tL.size} pairs 0 <= theta_L < theta_R, "
               "theta_L + theta_R <= pi (the left, sliding wall is now the shallower one) for "
               "each k, with the sign of its denominator; at the counterexample, the balances "
               "(Eqs. 1-2 with T = k N_L) solved as a 2x2 linear system for (N_L, N_R).",
        verdict=_verdict(ok),
        summary=summary, numbers=per_k, counterexample=ce)


def _claim_rs_sliding_steeper(ctx: _Context) -> Claim:
    G, D = ctx.grid()
    tL, tR = G + D, G - D
    per_k, ok = {}, True
    for k in ctx.ks:
        den = np.cos(tL) - np.cos(tR) + np.sin(tR) / k  # right wall slides: T = k N_R
        admissible = (den > 0.0) & (np.sin(tL) <= k * den)
        # The left-sliding state where double rolling fails: is it admissible (d_L >= 0)?
        dr, rs = ctx.dr_grid(), ctx.rs_grid(k)
        beyond = (dr["t"] > k * dr["n_L"]) | (dr["t"] > k * dr["n_R"])
        left_ok = int(np.count_nonzero(beyond & (rs["d_L"] >= 0.0) & (rs["mu"] <= k)))
        per_k[_k_label(k)] = {"admissible right-wall sliding": int(admissible.sum()),
                              "DR-invalid points": int(beyond.sum()),
                              "of which left-wall sliding admissible": left_ok}
        ok &= admissible.sum() == 0 and left_ok == beyond.sum()
    return Claim(
        id="rs_sliding_on_steeper_wall", section=_SLIDING,
        quote="Thus, sliding always occurs on the steeper wall, which is indeed the left-hand "
              "wall for $\\delta \\ge 0$.",
        method=f"On the {_GRID_N - 1}^2 interior grid (delta > 0): whether a state with the "
               "right (shallower) wall sliding, T = k N_R, could satisfy the balances with "
               "N_L > 0 and T/N_L <= k; and whether the left (steeper) wall sliding is "
               "admissible wherever double rolling fails.",
        verdict=_verdict(ok),
        summary="The shallower wall can never be the sliding one off the axis; every "
                "rolling-sliding state slips on the left (steeper) wall.",
        numbers=per_k)


def _claim_rs_continuation(ctx: _Context) -> Claim:
    per_k, ok = {}, True
    for k in ctx.ks:
        g, d = ctx.dr_limit(k)
        dr = double_rolling_state(g, d, Parameters(1.0))
        rs = rolling_sliding_state(g, d, Parameters(k))
        row = {"max |beta_L(DR) - beta_L(RS)|": float(np.max(np.abs(dr["beta_L"] - rs["beta_L"]))),
               "max |upsilon(DR) - upsilon(RS)|": float(np.max(np.abs(dr["upsilon"] - rs["upsilon"]))),
               "max |d_L(RS)|": float(np.max(np.abs(rs["d_L"])))}
        per_k[_k_label(k)] = row
        ok &= max(row.values()) <= 1e-8
    return Claim(
        id="rs_continues_dr", section=_SLIDING,
        quote="This is the simplest continuation of the double-rolling solution, which failed "
              "at the boundary through incipient sliding at the steeper wall.",
        method=f"On {_LINE_N - 1} points of the double-rolling limit per k (bracketed roots of "
               "T/N_L = k): the double-rolling and rolling-sliding states compared.",
        verdict=_verdict(ok),
        summary="On the limit the two states coincide (same beta_L, upsilon; d_L = 0): the "
                "rolling-sliding solution continues the double-rolling one without a jump.",
        numbers=per_k)


def _claim_rs_beta_unique(ctx: _Context) -> Claim:
    per_k, ok = {}, True
    # f(beta_L) = sin beta_L / sin(omega - beta_L) has derivative sin omega / sin^2 > 0.
    g = np.linspace(0.0, _HALF_PI, 201)[1:-1][:, None]
    a = np.linspace(0.0, 1.0, 2001)[1:-1][None, :]
    omega = math.pi - 2.0 * g
    f = np.sin(a * omega) / np.sin((1.0 - a) * omega)
    increasing = bool(np.all(np.diff(f, axis=1) > 0.0))
    for k in ctx.ks:
        rs = ctx.rs_grid(k)
        ratio = rs["n_L"] / rs["n_R"]
        err = float(np.max(np.abs(ratio - rs["mu"] / k) / np.maximum(rs["mu"] / k, 1e-300)))
        per_k[_k_label(k)] = {"max relative error of N_L/N_R = mu/k": err}
        ok &= err <= _IDENTITY_TOL
    return Claim(
        id="rs_beta_unique", section=_SLIDING,
        quote="\\frac{N_L}{N_R} = \\left ( \\frac{\\sin \\beta_L}{\\sin \\beta_R} \\right "
              ")^{\\frac{3}{2}} = \\frac{\\mu}{k} , ... which can be uniquely solved for "
              "$\\beta_L$ and $\\beta_R$.",
        method="sin(beta_L)/sin(pi - 2 gamma - beta_L) is strictly increasing from 0 to infinity "
               "on (0, pi - 2 gamma) (derivative sin(2 gamma)/sin^2 beta_R > 0): checked on 1999 "
               "beta_L for 199 gammas; the solver's rolling-sliding states (closed form) "
               "checked against N_L/N_R = mu/k on the interior grid.",
        verdict=_verdict(ok and increasing),
        summary="The ratio is monotonic in beta_L for every 0 < gamma < pi/2, so the root is "
                "unique, and the solver's states satisfy the equation.",
        numbers={"monotonic on every column": increasing, **per_k})


def _claim_rs_upsilon(ctx: _Context) -> Claim:
    per_k, ok = {}, True
    for k in ctx.ks:
        rs = ctx.rs_grid(k)
        keep = np.sin(rs["beta_R"]) > 1e-6
        lhs = (np.cos(rs["beta_R"][keep]) - rs["upsilon"][keep]) / np.sin(rs["beta_R"][keep])
        err = float(np.max(np.abs(lhs - rs["mu"][keep]) / np.maximum(rs["mu"][keep], 1.0)))
        per_k[_k_label(k)] = {"max error of mu = (cos beta_R - upsilon)/sin beta_R": err}
        ok &= err <= _IDENTITY_TOL
    return Claim(
        id="rs_upsilon_from_right_wall", section=_SLIDING,
        quote="the criterion that the ball rolls at the right-hand contact implies that ... "
              "\\frac{T}{N_R} = \\mu = \\frac{\\cos \\beta_R - \\upsilon}{\\sin \\beta_R}, ... "
              "which allows us to solve for $\\upsilon(\\beta_R)$.",
        method="The rolling right wall's proportional loading (u_t/u_n = T/N) evaluated at the "
               "solver's rolling-sliding states on the interior grid.",
        verdict=_verdict(ok),
        summary="Satisfied to round-off; upsilon = cos beta_R - mu sin beta_R is explicit.",
        numbers=per_k)


def _claim_rs_dL_boundary(ctx: _Context) -> Claim:
    G, _ = ctx.grid()
    per_k, ok = {}, True
    for k in ctx.ks:
        g, d_dr = ctx.dr_limit(k)
        d_rs = rs_limit_delta(k, g)
        rs = ctx.rs_grid(k)
        beyond = G > math.atan(k)
        bs = ctx.traced(k)
        row = {"max |delta(d_L = 0) - delta(T/N_L = k)|": float(np.max(np.abs(d_rs - d_dr))),
               "min d_L for gamma > arctan k": float(np.min(rs["d_L"][beyond]))
               if np.any(beyond) else math.nan,
               "tracer: limit_distance": bs.limit_distance if bs is not None else math.nan}
        per_k[_k_label(k)] = row
        ok &= row["max |delta(d_L = 0) - delta(T/N_L = k)|"] <= _POINT_TOL and (
            not np.any(beyond) or row["min d_L for gamma > arctan k"] > 0.0)
    return Claim(
        id="rs_dL_boundary_is_dr_limit", section=_SLIDING,
        quote="The physical constraint $d_L > 0$ sets the boundary on the region with a "
              "rolling-sliding solution, which, for $\\gamma < \\arctan(k)$, coincides with the "
              "upper boundary of the double rolling solution discussed in the previous section.",
        method=f"On {_LINE_N - 1} columns gamma < arctan k per k: the root of d_L = 0 of the "
               "rolling-sliding state and the root of T/N_L = k of the double-rolling state, "
               "both bracketed independently; d_L on the interior grid beyond arctan k; the "
               "tracer's distance between rs_limit and dr_limit.",
        verdict=_verdict(ok),
        summary="The two curves are the same to round-off for gamma < arctan k; beyond arctan k "
                "d_L > 0 for all delta > 0, so there the rolling-sliding region reaches down "
                "to the axis.",
        numbers=per_k)


def _axis_limit_points(ctx: _Context, k: float, n: int = 200):
    g = np.linspace(math.atan(k), _HALF_PI, n + 1)[1:-1]
    return g


def _claim_rs_delta0_upsilon(ctx: _Context) -> Claim:
    per_k, ok, ce = {}, True, None
    for k in ctx.ks:
        g = _axis_limit_points(ctx, k)
        at0 = rolling_sliding_state(g, np.zeros_like(g), Parameters(k))
        near = solve_equilibrium(g, np.full_like(g, 1e-9), k)
        predicted = np.sin(g) - k * np.cos(g)
        worst = float(np.max(np.abs(near.upsilon)))
        err = float(np.max(np.abs(near.upsilon - predicted)))
        per_k[_k_label(k)] = {"max |upsilon| at delta = 1e-9": worst,
                              "max |upsilon - (sin gamma - k cos gamma)|": err,
                              "max |upsilon| of the RS formulas at delta = 0":
                                  float(np.max(np.abs(at0["upsilon"])))}
        ok &= worst <= _VIOLATION
    k0 = 1.0 if 1.0 in ctx.ks else ctx.ks[0]
    g0 = 0.5 * (math.atan(k0) + _HALF_PI)
    if not ok:
        eq = solve_equilibrium(g0, 1e-9, k0)
        rs0 = rolling_sliding_state(g0, 0.0, Parameters(k0))
        ce = Counterexample(
            k=k0, gamma=g0, delta=1e-9,
            values={"regime": eq.regime, "upsilon": eq.upsilon, "T_over_N_R": eq.T_over_N_R,
                    "d_L": eq.d_L, "d_R": eq.d_R,
                    "sin gamma - k cos gamma": math.sin(g0) - k0 * math.cos(g0),
                    "upsilon of the RS formulas at delta = 0": float(rs0["upsilon"])},
            solver_fields=("regime", "upsilon", "T_over_N_R", "d_L", "d_R"),
            note="the rolling-sliding state next to the axis (and its formulas on it) has "
                 "upsilon = sin gamma - k cos gamma > 0 for gamma > arctan k, not 0; "
                 "upsilon = 0 only at gamma = arctan k, where the rolling-sliding upsilon = 0 "
                 "line starts")
    return Claim(
        id="rs_delta0_upsilon_zero", section=_SLIDING,
        quote="For $\\delta = 0$ we have $\\upsilon = 0$",
        method="The rolling-sliding state on and next to the axis, for 199 gammas in (arctan k, "
               "pi/2) per k (where rolling sliding is the regime next to the axis): the paper's "
               "formulas at delta = 0 (mu = k, beta_L = beta_R = pi/2 - gamma, upsilon = cos "
               "beta_R - mu sin beta_R) and the point solver at delta = 1e-9.",
        verdict=_verdict(ok),
        summary=("upsilon = 0 on the axis." if ok else
                 "False: on the axis mu = k and beta_R = pi/2 - gamma give upsilon = sin gamma - "
                 "k cos gamma, which is positive (counter-clockwise) for every gamma > arctan k "
                 "and vanishes only at gamma = arctan k; the limit delta -> 0+ of the solver "
                 "agrees."),
        numbers=per_k, counterexample=ce)


def _claim_rs_delta0_ratio(ctx: _Context) -> Claim:
    per_k, ok = {}, True
    for k in ctx.ks:
        g = _axis_limit_points(ctx, k)
        at0 = rolling_sliding_state(g, np.zeros_like(g), Parameters(k))
        near = rolling_sliding_state(g, np.full_like(g, 1e-9), Parameters(k))
        per_k[_k_label(k)] = {"max |mu/k - 1| at delta = 0": float(np.max(np.abs(at0["mu"] / k - 1))),
                              "max |mu/k - 1| at delta = 1e-9":
                                  float(np.max(np.abs(near["mu"] / k - 1)))}
        ok &= per_k[_k_label(k)]["max |mu/k - 1| at delta = 0"] <= _IDENTITY_TOL
    return Claim(
        id="rs_delta0_ratio_k", section=_SLIDING,
        quote="and $T/N_R =k$",
        method="mu = T/N_R of the rolling-sliding state at delta = 0 and 1e-9 for 199 gammas in "
               "(arctan k, pi/2) per k.",
        verdict=_verdict(ok),
        summary="mu = k on the axis (theta_L = theta_R makes the formula sin theta / (sin "
                "theta / k)).",
        numbers=per_k)


def _claim_rs_delta0_double_sliding(ctx: _Context) -> Claim:
    per_k, forces_ok, kinematics_same = {}, True, True
    for k in ctx.ks:
        g = _axis_limit_points(ctx, k)
        near = solve_equilibrium(g, np.full_like(g, 1e-9), k)
        axis = solve_equilibrium(g, np.zeros_like(g), k)
        row = {"max |N_L/N_R - 1|": float(np.max(np.abs(near.N_L_over_N_R - 1))),
               "max |T/N_R - k| / k": float(np.max(np.abs(near.T_over_N_R - k)) / k),
               "max |upsilon(0+) - upsilon(DS)|": float(np.max(np.abs(near.upsilon - axis.upsilon))),
               "max d_R(0+)": float(np.max(near.d_R)),
               "max |d_L(0+) - 2 (sin gamma - k cos gamma)|":
                   float(np.max(np.abs(near.d_L - 2 * (np.sin(g) - k * np.cos(g)))))}
        per_k[_k_label(k)] = row
        forces_ok &= row["max |N_L/N_R - 1|"] <= 1e-6 and row["max |T/N_R - k| / k"] <= 1e-6
        kinematics_same &= row["max |upsilon(0+) - upsilon(DS)|"] <= _VIOLATION
    k0 = 1.0 if 1.0 in ctx.ks else ctx.ks[0]
    g0 = 0.5 * (math.atan(k0) + _HALF_PI)
    ce = None
    if not kinematics_same:
        eq = solve_equilibrium(g0, 1e-9, k0)
        ds = solve_equilibrium(g0, 0.0, k0)
        ce = Counterexample(
            k=k0, gamma=g0, delta=1e-9,
            values={"upsilon": eq.upsilon, "d_L": eq.d_L, "d_R": eq.d_R,
                    "N_L_over_N_R": eq.N_L_over_N_R, "T_over_N_R": eq.T_over_N_R,
                    "double sliding on the axis: upsilon": ds.upsilon,
                    "double sliding on the axis: d_L = d_R": ds.d_L},
            solver_fields=("upsilon", "d_L", "d_R", "N_L_over_N_R", "T_over_N_R"),
            note="next to the axis the forces are those of double sliding (T = kN on both "
                 "walls, N_L = N_R) but the right contact only reaches T = kN without slipping "
                 "(d_R = 0) and the ball turns counter-clockwise, whereas the symmetric "
                 "double-sliding state has upsilon = 0 and d_L = d_R; on the axis the "
                 "kinematics is indeterminate (any |upsilon| <= sin gamma - k cos gamma)")
    return Claim(
        id="rs_delta0_collapses_to_double_sliding", section=_SLIDING,
        quote="and this solution collapses onto a double sliding solution for $\\gamma > "
              "\\arctan(k)$.",
        method="The point solver at delta = 1e-9 (rolling sliding) against delta = 0 (its "
               "symmetric double-sliding state) for 199 gammas in (arctan k, pi/2) per k: "
               "forces (N_L/N_R, T/N_R) and kinematics (upsilon, d_L, d_R).",
        verdict=_verdict(forces_ok, qualified=not kinematics_same),
        summary=("The forces collapse: N_L/N_R -> 1 and T/N_R -> k, so T = kN on both walls. "
                 "The kinematics does not: the limit has d_R = 0, d_L = 2 (sin gamma - k cos "
                 "gamma) and upsilon = sin gamma - k cos gamma, one end of the one-parameter "
                 "family of double-sliding motions on the axis, not the symmetric one "
                 "(upsilon = 0, d_L = d_R)." if forces_ok and not kinematics_same else
                 "Forces and kinematics both collapse onto double sliding." if forces_ok else
                 "The forces do not collapse onto double sliding."),
        numbers=per_k, counterexample=ce)


def _claim_rs_no_roll_stuck(ctx: _Context) -> Claim:
    per_k, ok = {}, True
    for k in ctx.ks:
        _, _, st = ctx.rs_no_roll(k)
        physical = st["d_L"] >= 0.0
        # Contact motions (paper): u_c;L = -Z upsilon + d_L, u_c;R = Z upsilon + d_R, d_R = 0.
        u_cR = st["upsilon"][physical]
        u_cL = -st["upsilon"][physical] + st["d_L"][physical]
        row = {"physical points": int(physical.sum()),
               "max |u_c;R| / Z (stuck)": float(np.max(np.abs(u_cR))) if physical.any() else math.nan,
               "min u_c;L / Z (sliding)": float(np.min(u_cL)) if physical.any() else math.nan}
        per_k[_k_label(k)] = row
        ok &= physical.sum() > 0 and row["max |u_c;R| / Z (stuck)"] <= 1e-12
    return Claim(
        id="rs_no_roll_line_stuck", section=_SLIDING,
        quote="In addition, there is a line of solutions with $\\upsilon =0$, corresponding to "
              "one contact sliding and the other being stuck.",
        method=f"The rolling-sliding upsilon = 0 line by bracketed root finding on {_LINE_N - 1} "
               "rows delta in (0, pi/4) per k; on its physical part (d_L >= 0) the contact "
               "motions u_c;R = Z upsilon + d_R and u_c;L = -Z upsilon + d_L.",
        verdict=_verdict(ok),
        summary="For every k the line exists; on it the right contact does not move (stuck) "
                "and the left one slips down its wall (d_L > 0 except at its lower end on the "
                "limit).",
        numbers=per_k)


def _rs_no_roll_ends(ctx: _Context, k: float) -> dict:
    """Numbers on the physical part of the rolling-sliding upsilon = 0 line for one k."""
    g, d, st = ctx.rs_no_roll(k)
    # One crossing per row, from the left edge (upsilon = -cos 2 delta < 0) to gamma = pi/2.
    rows = 0.25 * math.pi * np.linspace(0.0, 1.0, 101)[1:-1]
    cols = np.linspace(0.0, 1.0, 2001)[None, :]
    G = rows[:, None] + (_HALF_PI - rows[:, None]) * cols
    ups = rolling_sliding_state(G, np.broadcast_to(rows[:, None], G.shape), Parameters(k))["upsilon"]
    crossings = _sign_changes(ups, axis=1)
    physical = st["d_L"] >= 0.0
    first = int(np.argmax(physical)) if physical.any() else None
    low_end = math.nan if first is None else float(d[first])
    unphysical_runs = int(np.count_nonzero(np.diff(physical.astype(int)) != 0))
    start_near_axis = float(rs_no_roll_gamma(k, np.array([1e-7]))[0])
    end_near_corner = float(rs_no_roll_gamma(k, np.array([0.25 * math.pi - 1e-7]))[0])
    bs = ctx.traced(k)
    curve = bs.curves.get("rs_no_roll") if bs is not None else None
    tr_start = tr_end = None
    if curve is not None and np.any(curve.physical):
        xs = curve.x[curve.physical]
        tr_start, tr_end = (float(xs[0, 0]), float(xs[0, 1])), (float(xs[-1, 0]), float(xs[-1, 1]))
    return dict(g=g, d=d, st=st, physical=physical, crossings=crossings, first=first,
                low_end=low_end, switches=unphysical_runs, start_near_axis=start_near_axis,
                end_near_corner=end_near_corner, tracer_start=tr_start, tracer_end=tr_end)


def _claim_rs_no_roll_small_k(ctx: _Context) -> Claim:
    per_k, ok, checked = {}, True, 0
    for k in ctx.ks:
        if k >= _SQRT2:
            continue
        e = _rs_no_roll_ends(ctx, k)
        row = {"crossings per row (min, max)": (int(e["crossings"].min()), int(e["crossings"].max())),
               "all physical": bool(np.all(e["physical"])),
               "gamma at delta = 1e-7": e["start_near_axis"], "arctan k": math.atan(k),
               "gamma at delta = pi/4 - 1e-7": e["end_near_corner"],
               "tracer: |start - (arctan k, 0)|": _dist(e["tracer_start"], (math.atan(k), 0.0)),
               "tracer: |end - (pi/4, pi/4)|": _dist(e["tracer_end"], _CORNER),
               "turns back in gamma": bool(np.any(np.diff(e["g"]) > 0) and np.any(np.diff(e["g"]) < 0))}
        per_k[_k_label(k)] = row
        checked += 1
        ok &= (bool(np.all(e["crossings"] == 1)) and row["all physical"]
               and abs(e["start_near_axis"] - math.atan(k)) < 1e-5
               and abs(e["end_near_corner"] - 0.25 * math.pi) < 1e-5)
    return Claim(
        id="rs_no_roll_small_k_ends", section=_SLIDING,
        quote="For $k < \\sqrt{2}$ this line emanates from $(\\gamma,\\delta) = (\\arctan(k), 0)$ "
              "and ends at $(\\gamma,\\delta) = (\\frac{\\pi}{4},\\frac{\\pi}{4})$",
        method="For each k < sqrt 2: sign changes of the rolling-sliding upsilon along 99 rows "
               f"delta in (0, pi/4) (2001 gammas each); the line on {_LINE_N - 1} rows by bracketed root "
               "finding, its d_L, and its gamma at delta = 1e-7 and pi/4 - 1e-7; the tracer's "
               "rs_no_roll end points.",
        verdict=_verdict(ok and checked > 0),
        summary="Exactly one crossing per row; the whole line is physical and runs from "
                "(arctan k, 0) to (pi/4, pi/4) (for k near 1 it turns back in gamma on the way).",
        numbers=per_k)


def _claim_rs_no_roll_large_k(ctx: _Context) -> Claim:
    per_k, ok, checked = {}, True, 0
    for k in ctx.ks:
        if k <= _SQRT2:
            continue
        e = _rs_no_roll_ends(ctx, k)
        junction = ctx.junction(k)
        # Where d_L = 0 on the line: the lower end of its physical part, located exactly.
        first = e["first"]
        if first is not None and first > 0:
            d_lo, d_hi = float(e["d"][first - 1]), float(e["d"][first])

            def slip(dd, k=k):
                gg = rs_no_roll_gamma(k, np.array([dd]))
                return float(rolling_sliding_state(gg, np.array([dd]), Parameters(k))["d_L"][0])

            d_end = optimize.brentq(slip, d_lo, d_hi, xtol=1e-15)
            g_end = float(rs_no_roll_gamma(k, np.array([d_end]))[0])
        else:
            d_end = g_end = math.nan
        row = {"crossings per row (min, max)": (int(e["crossings"].min()), int(e["crossings"].max())),
               "unphysical/physical switches on the line": e["switches"],
               "physical part from (gamma, delta)": (g_end, d_end),
               "DR-limit upsilon = 0 point": (float(junction[0]), float(junction[1])),
               "distance": _dist((g_end, d_end), junction[:2]),
               "gamma at delta = pi/4 - 1e-7": e["end_near_corner"],
               "tracer: |start - junction|": _dist(e["tracer_start"], junction[:2]),
               "tracer: |end - (pi/4, pi/4)|": _dist(e["tracer_end"], _CORNER)}
        per_k[_k_label(k)] = row
        checked += 1
        ok &= (bool(np.all(e["crossings"] == 1)) and e["switches"] == 1
               and row["distance"] <= _POINT_TOL
               and abs(e["end_near_corner"] - 0.25 * math.pi) < 1e-5)
    return Claim(
        id="rs_no_roll_large_k_ends", section=_SLIDING,
        quote="For $k > \\sqrt{2}$, this line emanates from the point on the boundary of the "
              "double rolling region for which $\\upsilon=0$, and ends at $(\\gamma,\\delta) = "
              "(\\frac{\\pi}{4},\\frac{\\pi}{4})$",
        method=f"For each k > sqrt 2: the rolling-sliding upsilon = 0 line on {_LINE_N - 1} rows (bracketed "
               "roots), its physical part d_L >= 0 and the exact start of that part (brentq on "
               "d_L along the line), compared with the point of the double-rolling limit where "
               "upsilon = 0 found from the double-rolling equations alone (cot beta_L = k on "
               "the double-rolling upsilon = 0 line, polished by Newton); the tracer's "
               "rs_no_roll.",
        verdict=_verdict(ok and checked > 0),
        summary="The full zero set of upsilon still starts at (arctan k, 0), but its part below "
                "the limit lies inside double rolling (d_L < 0, unphysical); the physical part "
                "is one piece from the upsilon = 0 point of the limit (the two independent "
                "computations agree) to (pi/4, pi/4).",
        numbers=per_k)


def _claim_rs_no_roll_sides(ctx: _Context) -> Claim:
    per_k, ok = {}, True
    for k in ctx.ks:
        rg = ctx.regime_grid(k)
        changes, bad = _rotation_rows(rg, "rolling_sliding")
        per_k[_k_label(k)] = {"rows with a change in RS": int(np.count_nonzero(changes)),
                              "rows violating": bad}
        ok &= bad == 0
    return Claim(
        id="rs_no_roll_sides", section=_SLIDING,
        quote="As for the double rolling $\\upsilon=0$ line, this line separates the "
              "low-$\\gamma$ clockwise rolling from the high-$\\gamma$ counterclockwise rolling.",
        method=f"On each row delta > 0 of the {_MAP_N}-step map grid: the rolling-sliding nodes "
               "must be clockwise up to at most one change and counter-clockwise after it.",
        verdict=_verdict(ok),
        summary="On every row rolling sliding is clockwise at low gamma and counter-clockwise "
                "at high gamma, with at most one change.",
        numbers=per_k)


_CHECKS = (
    _claim_dr_contacts,
    _claim_dr_unique,
    _claim_dr_equations,
    _claim_delta0_state,
    _claim_delta0_ratio,
    _claim_delta0_validity,
    _claim_dr_limit_start,
    _claim_dr_limit_steeper,
    _claim_dr_limit_end,
    _claim_dr_no_roll_interval,
    _claim_dr_no_roll_ratio,
    _claim_dr_no_roll_k,
    _claim_dr_no_roll_sides,
    _claim_amontons_sign,
    _claim_caption_dr_below,
    _claim_caption_rotation,
    _claim_rs_only,
    _claim_rs_mu_formula,
    _claim_rs_mu_below,
    _claim_rs_mu_above,
    _claim_rs_sliding_steeper,
    _claim_rs_continuation,
    _claim_rs_beta_unique,
    _claim_rs_upsilon,
    _claim_rs_dL_boundary,
    _claim_rs_delta0_upsilon,
    _claim_rs_delta0_ratio,
    _claim_rs_delta0_double_sliding,
    _claim_rs_no_roll_stuck,
    _claim_rs_no_roll_small_k,
    _claim_rs_no_roll_large_k,
    _claim_rs_no_roll_sides,
)


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
    """
    ks = tuple(dict.fromkeys(check_friction(k) for k in ks))
    if not ks:
        raise ValueError("ks is empty: give at least one friction coefficient k > 0")
    start = time.perf_counter()
    ctx = _Context(ks, use_tracer)
    claims = []
    for check in _CHECKS:
        claim = check(ctx)
        log.info("%s: %s", claim.id, claim.verdict)
        claims.append(claim)
    for k in ks:
        ctx.traced(k)
    return AuditReport(ks=ks, claims=tuple(claims), tracer=dict(ctx.tracer_status),
                       seconds=time.perf_counter() - start)


def normalise_tex(text: str) -> str:
    """Collapse runs of white space, as the quotes do."""
    return re.sub(r"\s+", " ", text).strip()
