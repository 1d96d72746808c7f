"""The fixed text of each claim as data, registered with its check by a decorator.

A check is a function of the shared computations (:class:`~.context.Context`) that returns
only what it computed, a :class:`Finding`; what the paper says and how it is checked are the
arguments of the decorator that registers it::

    ROLLING = Section("Rolling solutions")

    @ROLLING.claim(id="dr_unique", quote="In principle, ...", method="upsilon enters ...")
    def check_dr_unique(ctx: Context) -> Finding:
        ...
        return Finding(verdict(ok), summary, numbers)

The report's :class:`~.report.Claim` joins the two (:meth:`ClaimCheck.assess`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from .report import Claim, Counterexample, Verdict

__all__ = ["ClaimCheck", "Finding", "Section", "verdict"]


@dataclass(frozen=True)
class Finding:
    """What one check computed.

    Attributes
    ----------
    verdict : Verdict
    summary : str
        The finding in one or two sentences, with the key numbers.
    numbers : dict
        The numbers behind the verdict (``"k = ..."`` keys hold per-k results).
    counterexample : Counterexample or None
        For ``fails`` (and for a qualification, a point where the unqualified statement is false).
    method_values : dict
        Sizes the check computed that its method names: they fill the method's ``{name}``
        fields (e.g. how many grid points were kept).
    """

    verdict: Verdict
    summary: str
    numbers: dict = field(default_factory=dict)
    counterexample: Counterexample | None = None
    method_values: dict = field(default_factory=dict)


def verdict(holds: bool, qualified: bool = False) -> Verdict:
    """``FAILS`` unless ``holds``; then ``QUALIFIED`` or ``HOLDS``."""
    if not holds:
        return Verdict.FAILS
    return Verdict.QUALIFIED if qualified else Verdict.HOLDS


@dataclass(frozen=True)
class ClaimCheck:
    """One statement of the paper (fixed text) and the function that checks it.

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
        How it is checked; ``{name}`` fields are filled from :attr:`Finding.method_values`.
    check : callable
        ``check(ctx) -> Finding``.
    """

    id: str
    section: str
    quote: str
    method: str
    check: Callable = field(repr=False)

    def assess(self, ctx) -> Claim:
        """Run the check on the shared computations ``ctx`` and state the claim with its verdict."""
        finding = self.check(ctx)
        return Claim(id=self.id, section=self.section, quote=self.quote,
                     method=self.method.format_map(finding.method_values),
                     verdict=finding.verdict, summary=finding.summary, numbers=finding.numbers,
                     counterexample=finding.counterexample)


class Section:
    """The checks of one paragraph of the paper, in the order they are registered.

    Parameters
    ----------
    title : str
        The paragraph's title (or "Caption of Fig. 2"), as the report names it.
    """

    def __init__(self, title: str) -> None:
        self.title = title
        self.checks: list[ClaimCheck] = []

    def claim(self, id: str, quote: str, method: str) -> Callable:
        """Register the decorated check with the fixed text of its claim.

        Raises
        ------
        ValueError
            If ``id`` is already registered in this section.
        """
        if any(c.id == id for c in self.checks):
            raise ValueError(f"claim id = {id!r} is registered twice in {self.title!r}")

        def register(check: Callable) -> Callable:
            self.checks.append(ClaimCheck(id, self.title, quote, method, check))
            return check

        return register
