r"""An audit of the paper's quantitative statements, each checked by computation.

Every statement of fact in the paragraphs "Rolling solutions" and "Rolling-sliding solutions"
of Halsey & Ertas, "A Ball in a Groove" (and the two statements of the caption of their
Fig. 2 that describe the same curves, and the sentence of the paragraph on contact mechanics
that the compliance hardly matters) is a :class:`~.report.Claim`: the sentence quoted
verbatim from the LaTeX source, how it was checked, the verdict and the numbers behind it, and,
where the statement is false as written, a concrete counterexample ``(k, gamma, delta, values)``.

The verdicts are computed, never written in: each check evaluates the point solver
(:mod:`groove_model.model.equilibrium`) on grids and with bracketed root finding
(``scipy.optimize.elementwise.find_root``, Chandrupatla's method, and ``brentq``) and compares
with the statement, for every friction coefficient ``k`` of the audit. Where the tracer
(:func:`groove_model.tracing.trace_boundaries`) runs, its curves and special points are reported
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
    more than the numerical tolerance. There is no ``fails`` without a counterexample.
``inconclusive``
    The check's criterion was not met at its resolution (e.g. a region thinner than the grid
    step just above ``k = sqrt 2``), but no point where the statement is false was found.
``not applicable``
    The statement is about friction coefficients none of which was audited (e.g. ``k > sqrt
    2`` when only ``k = 1`` is); the summary says which, and nothing was checked.

All angles are in radians; forces are the paper's ratios (``T/N``) and displacements are per
unit approach ``Z``. The compliance is the paper's, ``u_t/u_n = T/N``, except in the check of
the compliance claim (:mod:`~.contact`), which traces the atlas of special points for Mindlin's
compliance at several Poisson ratios (:mod:`groove_model.analysis.compliance`).

Modules
-------
``claims.ini``
    The fixed text of every claim, as data, in the paper's order: section, quote, method and,
    where it does not depend on the numbers, the summary.
``registry``
    Reads ``claims.ini``; ``@claim("id")`` registers the function that checks a claim, which
    returns only what it computed (a :class:`~.registry.Finding`).
``context``
    The grids, lines and traced boundaries the checks share, computed once.
``contact``, ``rolling``, ``caption``, ``rolling_sliding``
    The checks, one file per paragraph of the paper.
``report``
    What the audit produces: :class:`~.report.Claim`, :class:`~.report.AuditReport` (JSON and
    Markdown), :data:`~.report.DEFAULT_KS`.
``run``
    :func:`~.run.run_audit`.
``defaults``
    :data:`~.defaults.DEFAULT_KS`, in a module that imports nothing.

This package's ``__init__`` imports nothing, so that ``groove --help`` can read
:data:`~.defaults.DEFAULT_KS` without loading numpy, scipy and the solver.
"""
