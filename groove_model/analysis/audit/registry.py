"""The claims' fixed text, read as data, and the ``@claim`` decorator that registers each check.

What the paper says, where, how it is checked and (when it does not depend on the numbers) the
finding in words are data in ``claims.ini`` beside this module, in the paper's order. A check
is a function of the shared computations (:class:`~.context.Context`) that returns only what
it computed, a :class:`Finding`; it is registered under its claim's id::

    @claim("dr_unique")
    def check_dr_unique(ctx: Context) -> Finding:
        ...
        return Finding(verdict(ok), numbers=numbers, summary=f"Exactly one root ...")

:meth:`ClaimText.state` joins the two into the report's :class:`~.report.Claim`.
"""

from __future__ import annotations

import configparser
from collections.abc import Callable
from dataclasses import dataclass, field
from importlib import resources

from ...model.parameters import k_text
from .context import GRID_N, LINE_N, MAP_N
from .report import Claim, Counterexample, Verdict

__all__ = ["CHECKS", "CLAIM_TEXTS", "ClaimText", "Finding", "applicable", "claim",
           "not_applicable", "verdict"]

_INCONCLUSIVE = ("Inconclusive: not confirmed at the check's resolution for every k audited, "
                 "yet no point where it is false was found; the numbers show what was not "
                 "resolved.")
#: Resolutions the methods in ``claims.ini`` name: ``{grid_points}`` etc.
_RESOLUTIONS = dict(grid_points=GRID_N - 1, map_steps=MAP_N, line_points=LINE_N - 1)


@dataclass(frozen=True)
class Finding:
    """What one check computed: its ``verdict`` and the ``numbers`` behind it (``"k = ..."``
    keys hold per-k results); the ``summary`` in words when it quotes numbers (None: the
    claim's fixed summary in ``claims.ini``); a ``counterexample`` for ``fails`` (and for a
    qualification, a point where the unqualified statement is false); and ``method_values``,
    the sizes the method names as ``{name}`` fields (e.g. how many grid points were kept).
    """

    verdict: Verdict
    numbers: dict = field(default_factory=dict)
    summary: str | None = None
    counterexample: Counterexample | None = None
    method_values: dict = field(default_factory=dict)


def verdict(holds: bool, qualified: bool = False) -> Verdict:
    """``FAILS`` unless ``holds``; then ``QUALIFIED`` or ``HOLDS``."""
    if not holds:
        return Verdict.FAILS
    return Verdict.QUALIFIED if qualified else Verdict.HOLDS


def applicable(ks, about: Callable[[float], bool], scope: str) -> tuple[list, dict]:
    """The ``k`` a claim about ``scope`` (e.g. ``"k > sqrt 2"``) applies to, of those audited.

    Returns the list of those ``k`` and the numbers to report for the others (empty if none).
    """
    ks = list(ks)
    inside = [k for k in ks if about(k)]
    outside = [k_text(k) for k in ks if not about(k)]
    numbers = {f"not applicable (the statement is about {scope})":
               "k = " + ", ".join(outside)} if outside else {}
    return inside, numbers


def not_applicable(ks, scope: str) -> Finding:
    """The finding on a claim about ``scope`` when no ``k`` audited is in it."""
    listed = ", ".join(k_text(k) for k in ks)
    return Finding(Verdict.NOT_APPLICABLE,
                   numbers={"the statement is about": scope, "k audited": listed},
                   summary=f"Not applicable: about {scope}; no k audited is (k = {listed}). "
                           "Audit such a k to check it.")


@dataclass(frozen=True)
class ClaimText:
    """The fixed text of one claim.

    ``id``, ``section``, ``quote`` and ``method`` are those of :class:`~.report.Claim`
    (``method`` with ``{name}`` fields still to fill). ``summaries`` maps a verdict's value to
    the summary for that verdict, and ``"any"`` to the summary for every verdict: they are used
    when the check returns no summary of its own.
    """

    id: str
    section: str
    quote: str
    method: str
    summaries: dict = field(default_factory=dict)

    def state(self, finding: Finding) -> Claim:
        """The claim with what its check found.

        A ``fails`` without a counterexample becomes ``inconclusive``.

        Raises
        ------
        ValueError
            If neither the check nor ``claims.ini`` gives a summary.
        """
        if finding.verdict is Verdict.FAILS and finding.counterexample is None:
            # "fails" is a finding only with the point where the statement is false; without
            # one the check's criterion was not met at its resolution (e.g. a region thinner
            # than the grid step near k = sqrt 2).
            finding = Finding(Verdict.INCONCLUSIVE, numbers=finding.numbers,
                              summary=_INCONCLUSIVE, method_values=finding.method_values)
        summary = finding.summary or self.summaries.get(Verdict(finding.verdict).value,
                                                        self.summaries.get("any"))
        if summary is None:
            raise ValueError(f"claim {self.id!r} has no summary for the verdict "
                             f"{Verdict(finding.verdict).value!r}: give one in claims.ini or in "
                             "its Finding")
        method = self.method.format_map({**_RESOLUTIONS, **finding.method_values})
        return Claim(id=self.id, section=self.section, quote=self.quote, method=method,
                     verdict=finding.verdict, summary=summary, numbers=finding.numbers,
                     counterexample=finding.counterexample)


def _read_texts() -> tuple:
    """``claims.ini``: one section per claim; a wrapped line continues its value after a space.

    Keys ``section``, ``quote``, ``method``, and ``summary`` (any verdict) or
    ``summary if VERDICT`` (one verdict).
    """
    parser = configparser.ConfigParser(interpolation=None, empty_lines_in_values=False)
    parser.read_string(resources.files(__package__).joinpath("claims.ini")
                       .read_text(encoding="utf-8"))
    texts = []
    for cid in parser.sections():
        values = {key: " ".join(value.split("\n")) for key, value in parser[cid].items()}
        summaries = {key.removeprefix("summary if ") if key != "summary" else "any": value
                     for key, value in values.items() if key.startswith("summary")}
        texts.append(ClaimText(cid, values["section"], values["quote"], values["method"],
                               summaries))
    return tuple(texts)


#: Every claim's fixed text, in the paper's order.
CLAIM_TEXTS = _read_texts()
#: The check of each claim id, filled by :func:`claim`.
CHECKS: dict = {}


def claim(id: str) -> Callable:
    """Register the decorated function as the check of claim ``id``.

    Raises
    ------
    ValueError
        If ``id`` is not a claim of ``claims.ini`` or already has a check.
    """
    if id not in {text.id for text in CLAIM_TEXTS}:
        raise ValueError(f"claim id = {id!r} is not in claims.ini")
    if id in CHECKS:
        raise ValueError(f"claim id = {id!r} already has a check: {CHECKS[id].__name__}")

    def register(check: Callable) -> Callable:
        CHECKS[id] = check
        return check

    return register
