"""The audit's results: a claim with its verdict, the report of all claims, and their files.

This module is what the audit produces; the checks that compute it are in
:mod:`groove_model.analysis.audit.rolling`, :mod:`~groove_model.analysis.audit.caption` and
:mod:`~groove_model.analysis.audit.rolling_sliding`, run by
:func:`groove_model.analysis.audit.run.run_audit`. It imports neither scipy nor the solver, so
the command line can name :data:`DEFAULT_KS` (from :mod:`.defaults`) without loading them.
"""

from __future__ import annotations

import json
import math
import re
from dataclasses import dataclass, field
from enum import Enum

import numpy as np

from ...model.parameters import k_text
from .defaults import DEFAULT_KS

__all__ = [
    "DEFAULT_KS",
    "PAPER",
    "VERDICTS",
    "VERDICT_MEANINGS",
    "AuditReport",
    "Claim",
    "Counterexample",
    "Verdict",
    "normalise_tex",
]


class Verdict(str, Enum):
    """The verdict on one claim; values are the words written to the report.

    What each one means is in the docstring of :mod:`groove_model.analysis.audit` and in
    :data:`VERDICT_MEANINGS`. ``FAILS`` always comes with a counterexample; a check that does
    not confirm a statement but cannot point to where it is false gives ``INCONCLUSIVE``.
    ``NOT_APPLICABLE`` is not about truth: the statement is about friction coefficients none of
    which was audited, and the claim's summary says which. The report counts, lists and writes
    every member, in this order.
    """

    HOLDS = "holds"
    QUALIFIED = "holds with qualification"
    FAILS = "fails"
    INCONCLUSIVE = "inconclusive"
    NOT_APPLICABLE = "not applicable"


VERDICTS = tuple(v.value for v in Verdict)
#: What each verdict means, in the words of the report.
VERDICT_MEANINGS = {
    Verdict.HOLDS: "true at every point checked, to the tolerance stated in the numbers",
    Verdict.QUALIFIED: "true on the part of the domain the paper describes, false or true only "
                       "in a limiting sense on a set the sentence does not exclude (stated "
                       "with numbers), or only part of a compound statement holds",
    Verdict.FAILS: "false as written: the counterexample is a point where the statement is "
                   "violated by far more than the numerical tolerance",
    Verdict.INCONCLUSIVE: "the check did not confirm the statement at the resolution it uses "
                          "for these k, but found no point where it is false (the numbers say "
                          "what was not resolved)",
    Verdict.NOT_APPLICABLE: "not checked: the statement is about friction coefficients none "
                            "of which was audited (the summary says which it is about)",
}
PAPER = "Halsey & Ertas, 'A Ball in a Groove'"


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
        One of :data:`VERDICTS` (the value of a :class:`Verdict`).
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
        object.__setattr__(self, "verdict", Verdict(self.verdict).value)

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
             "*Rolling-sliding solutions* (and of the caption of Fig. 2), and the paper's "
             "sentence on the compliance of the contact, checked by computation "
             f"for k = {', '.join(map(k_text, self.ks))}. Generated by `groove audit` "
             "(`groove_model.analysis.audit`); the verdicts are computed by the code, never "
             "written in. Angles in radians."),
            "",
            "Verdicts:",
            "",
            *(f"- **{v.value}**: {meaning}." for v, meaning in VERDICT_MEANINGS.items()),
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


def normalise_tex(text: str) -> str:
    """Collapse runs of white space, as the quotes do."""
    return re.sub(r"\s+", " ", text).strip()
