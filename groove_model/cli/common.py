"""What every ``groove`` command shares: exit codes, the usage error, argument types, paths.

Exit codes: 0 success, 1 a computation failed (e.g. a boundary could not be traced),
2 bad input (argument out of range, unreadable file); a message for bad input names the
quantity, its value and the allowed range.

The contact's compliance is one helper for every command that computes states: a command
adds ``--compliance RATIO`` and ``--poisson NU`` with one line in its ``add_parser``,
``add_compliance_options(p)``, and reads them in ``run`` with ``compliance_from(args)`` (a
:class:`~groove_model.model.parameters.Compliance`, passed as ``Parameters(k, compliance)``);
``compliance_label(compliance)`` ends its file names (``""`` for the paper's law, ``_nu0.3``,
``_c0.8``).

Nothing here imports numpy or the solver at module level: ``groove --help`` loads only this
package (see ``computation_errors`` and ``friction``).
"""

from __future__ import annotations

import argparse
import math
import os
import re
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # the model loads numpy, which `groove --help` does not need
    from ..model.parameters import Compliance

__all__ = [
    "COMMANDS",
    "EXIT_FAILED",
    "EXIT_INTERRUPTED",
    "EXIT_OK",
    "EXIT_USAGE",
    "FIGURE_FORMATS",
    "UsageError",
    "add_command",
    "add_compliance_options",
    "add_friction",
    "add_verbose",
    "compliance_from",
    "compliance_label",
    "computation_errors",
    "figure_target",
    "friction",
    "one_friction",
    "output_directory",
    "poisson",
    "positive_integer",
    "real",
    "refuse_blocked",
    "require_certify_extra",
    "traced_friction",
    "traced_poisson",
]

EXIT_OK, EXIT_FAILED, EXIT_USAGE = 0, 1, 2
#: interrupted by Ctrl-C (128 + SIGINT, as shells report it)
EXIT_INTERRUPTED = 130
FIGURE_FORMATS = ("png", "svg", "pdf")


def computation_errors() -> tuple:
    """Errors of a computation (root finding, continuation, linear algebra): exit code 1."""
    # Imported here, not at the top: numpy is what `groove --help` should not wait for.
    import numpy as np

    return (ArithmeticError, RuntimeError, np.linalg.LinAlgError)


class UsageError(Exception):
    """Bad input from the command line: message printed, exit code 2."""


def add_verbose(parser: argparse.ArgumentParser) -> None:
    """``-v``: log progress. Given to ``groove`` and to every command, so it goes before or
    after the command's name; no default here, so a command's parser does not reset it."""
    parser.add_argument("-v", "--verbose", action="store_true", default=argparse.SUPPRESS,
                        help="log progress on standard error")


class _Formatter(argparse.RawDescriptionHelpFormatter):
    """The help of a command: its examples as written, and ``-k K`` for a command of one k."""

    def _format_args(self, action, default_metavar):
        if getattr(action, "one_value", False):
            # read with nargs="+" so that `-k 1 10` gets a message that names both values
            return self._metavar_formatter(action, default_metavar)(1)[0]
        return super()._format_args(action, default_metavar)


#: what argparse takes for a negative number (a value, not an option): its own ``-1`` and
#: ``-0.5``, and also ``-1e-3``, ``-inf`` and ``-nan``, so that ``-k -inf`` gets the message
#: that names k and its range rather than "expected at least one argument"
_NEGATIVE_NUMBER = re.compile(r"^-(\d|\.\d|inf|nan)", re.IGNORECASE)


#: Every ``groove`` command, in the order ``groove --help`` lists them, with its line there. Each
#: is the module of that name in this package; ``groove`` loads only the one it runs.
COMMANDS = {
    "solve": "equilibrium of the ball at one point (gamma, delta)",
    "trace": "trace every regime boundary for one or more k; write CSVs and an overlay",
    "plot": "draw an overlay from existing boundaries CSV files",
    "map": "shade the regime map of the (gamma, delta) plane for one k",
    "audit": "check every quantitative claim of the paper, with numbers",
    "sweep": "trace every boundary for many log-spaced k, in parallel, into one CSV",
    "atlas": "follow every special point as a curve in k; locate the k where the diagram "
             "changes shape",
    "compliance": "how the special points and thresholds move with the contact's Poisson ratio",
    "reproduce": "regenerate every committed result: Figure 2, regime maps, atlas, claims audit",
}


def add_command(subparsers, name: str, description: str,
                examples: str) -> argparse.ArgumentParser:
    """Register the ``groove`` command ``name`` (its line in ``groove --help`` is
    :data:`COMMANDS`'s) whose help ends with its examples; returns its parser."""
    parser = subparsers.add_parser(name, help=COMMANDS[name], description=description,
                                   epilog=examples, formatter_class=_Formatter)
    # argparse has no public setting for this; where its attribute is missing, nothing changes
    if hasattr(parser, "_negative_number_matcher"):
        parser._negative_number_matcher = _NEGATIVE_NUMBER
    add_verbose(parser)
    return parser


def _float(text: str) -> float:
    """``float(text)`` without Python's digit separators: ``1_0`` is a typo, not 10.

    Raises
    ------
    ValueError
        If ``text`` is not a number written the usual way.
    """
    if "_" in text:
        raise ValueError(f"{text!r} is not a number")
    return float(text)


def _number(text: str, message: str) -> float:
    """``float(text)``, or argparse's error with ``message`` if it is not a number."""
    try:
        return _float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(message) from None


def _argument(check, value: float, text: str) -> float:
    """``check(value)``, its ``ValueError`` turned into argparse's error (same message), which
    also says so where the number typed, ``text``, is not a double (``1e-400`` reads as 0)."""
    try:
        return check(value)
    except ValueError as exc:
        message = str(exc)
        typed = text.strip().lower().lstrip("+-")
        if value == 0.0 and any(c in "123456789" for c in typed.partition("e")[0]):
            message += f" ({text} is below the smallest double and reads as 0)"
        elif math.isinf(value) and "inf" not in typed:
            message += f" ({text} is beyond the largest double and reads as {value!r})"
        raise argparse.ArgumentTypeError(message) from None


def positive_integer(name: str, maximum: int | None = None):
    """Argument type of an integer ``>= 1`` (and ``<= maximum``), written in ASCII digits;
    messages name it ``name``."""
    allowed = "an integer >= 1" if maximum is None else f"an integer from 1 to {maximum}"

    def parse(text: str) -> int:
        try:
            # ASCII digits only: not '３' or '٣', nor '1_000', which int() reads
            value = int(text) if re.fullmatch(r"\s*[+-]?[0-9]+\s*", text) else None
        except ValueError:
            value = None
        if value is None:
            raise argparse.ArgumentTypeError(f"{name} = {text!r} is not an integer in ASCII "
                                             f"digits; allowed range: {allowed}")
        if value < 1 or (maximum is not None and value > maximum):
            raise argparse.ArgumentTypeError(f"{name} = {text!r} is outside the allowed range: "
                                             + allowed)
        return value

    parse.__name__ = name
    return parse


def require_certify_extra() -> None:
    """:class:`UsageError` naming the extra to install if python-flint is missing (before
    anything is computed)."""
    # Imported here: only --certify needs to know whether python-flint is installed.
    from continuation.numbers import require_flint

    try:
        require_flint()
    except ImportError as exc:
        raise UsageError(str(exc)) from None


def require_plotting() -> None:
    """Load matplotlib before anything is computed or written: a :class:`UsageError` if the
    environment variable ``MPLBACKEND`` names a backend matplotlib does not know (matplotlib
    refuses to load then), instead of a traceback after the CSVs are written."""
    try:
        import matplotlib  # noqa: F401
    except ValueError as exc:
        backend = os.environ.get("MPLBACKEND")
        if backend is None:
            raise
        raise UsageError(f"the environment variable MPLBACKEND = {backend!r} is not a backend "
                         f"matplotlib knows ({exc}); unset it or set MPLBACKEND=Agg") from None


def friction(text: str) -> float:
    """Argument type of a friction coefficient ``k``: a finite number > 0."""
    value = _number(text, f"friction coefficient k = {text!r} is not a number; k must be "
                          "finite and > 0")
    # Imported here, not at the top: the model loads numpy, which `groove --help` does not need.
    from ..model.parameters import check_friction

    return _argument(check_friction, value, text)


def traced_friction(text: str) -> float:
    """Argument type of a ``k`` whose boundaries are traced: ``1e-4 <= k <= 1e6`` (the range
    the messages name, also for a ``k`` that is not finite or not positive)."""
    value = _number(text, f"friction coefficient k = {text!r} is not a number; allowed range "
                          "1e-4 <= k <= 1e6")
    # Imported here, not at the top: the model loads numpy, which `groove --help` does not need.
    from ..model.parameters import check_traced_friction

    return _argument(check_traced_friction, value, text)


def add_friction(parser: argparse.ArgumentParser, required: bool = True, help: str = "",
                 traced: bool = True, several: bool = True) -> None:
    """``-k K [K ...]``, repeatable: every command reads ``-k 1 10`` and ``-k 1 -k 10`` alike.

    The values go to ``args.ks`` (a list, in the order given; None when not given). ``traced``:
    the command traces boundaries, so ``1e-4 <= k <= 1e6`` (else any ``k > 0``). A command of
    one ``k`` (``several=False``) shows ``-k K`` in its help and refuses several with
    :func:`one_friction`.
    """
    action = parser.add_argument("-k", action="extend", nargs="+",
                        type=traced_friction if traced else friction, dest="ks",
                        metavar="K", required=required,
                        help=help or "friction coefficients (1e-4 <= k <= 1e6): -k 1 10 or "
                                     "-k 1 -k 10")
    action.one_value = not several  # type: ignore[attr-defined]


def one_friction(args, command: str) -> float:
    """The one ``k`` of a command that takes one.

    Raises
    ------
    UsageError
        If several different values were given.
    """
    # Imported here, not at the top: the model loads numpy, which `groove --help` does not need.
    from ..model.parameters import k_text

    ks = list(dict.fromkeys(args.ks))
    if len(ks) != 1:
        raise UsageError(f"{command} takes one friction coefficient, got k = "
                         f"{', '.join(map(k_text, ks))}: run it once per k")
    return ks[0]


def real(name: str, allowed: str = "a finite number"):
    """Argument type of a finite real number; messages name it ``name`` with range ``allowed``."""
    def parse(text: str) -> float:
        try:
            value = _float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"{name} = {text!r} is not a number; allowed range: {allowed}") from None
        if not math.isfinite(value):
            raise argparse.ArgumentTypeError(
                f"{name} = {text} is not a finite number; allowed range: {allowed}")
        return value

    parse.__name__ = name
    return parse


def output_directory(text: str) -> Path:
    """The ``--out`` directory (created later if needed).

    Raises
    ------
    UsageError
        If it exists and is not a directory, or it (or the directory it would be created in)
        is not writable: checked before anything is computed.
    """
    if not text.strip():
        raise UsageError(f"--out {text!r} is empty: give a directory ('.' for this one)")
    out = Path(text)
    _refuse_dangling_link("--out", out, out)
    if out.exists() and not out.is_dir():
        raise UsageError(f"--out {out} exists and is not a directory")
    existing = out if out.exists() else _existing_ancestor(out)
    if existing is not None and not existing.is_dir():
        raise UsageError(f"--out {out} cannot be created: {existing} is a file, not a directory")
    if existing is not None:
        _refuse_unwritable(f"--out {out}", existing)
    return out


def _refuse_unwritable(what: str, directory: Path) -> None:
    """:class:`UsageError` if no file can be created in ``directory``.

    The permission bits are read first (the plain answer for a user); then a nameless file is
    created and dropped there, since the bits do not tell everything: root passes every
    permission check, yet nothing can be created under ``/proc`` or on a read-only mount.
    """
    if not os.access(directory, os.W_OK | os.X_OK):
        raise UsageError(f"{what} cannot be written: {directory} is not writable")
    import tempfile  # only a command that writes reaches here

    try:
        with tempfile.TemporaryFile(dir=directory):
            pass
    except OSError as exc:
        raise UsageError(f"{what} cannot be written: creating a file in {directory} failed: "
                         f"{exc.strerror or exc}") from None


def _refuse_dangling_link(option: str, directory: Path, given: Path) -> None:
    """:class:`UsageError` if ``directory`` or a parent of it is a link to nothing (it could be
    neither created nor written)."""
    for path in (directory, *directory.parents):
        if path.exists():
            return
        if path.is_symlink():
            raise UsageError(f"{option} {given}: {path} is a link to {os.readlink(path)}, which "
                             "does not exist")


def refuse_blocked(paths) -> None:
    """:class:`UsageError` if a directory stands where one of the output files ``paths`` is to
    be written (:func:`~groove_model.io.atomic.check_targets`): seen before anything is
    computed, so it is bad input (exit code 2)."""
    from ..io.atomic import WriteError, check_targets  # light, but only a writing command needs it

    try:
        check_targets(paths)
    except WriteError as exc:
        raise UsageError(f"{exc.strerror}: move it or write elsewhere") from None


def _existing_ancestor(path: Path) -> Path | None:
    """The nearest existing ancestor of ``path``, or ``None``."""
    for parent in path.parents:
        if parent.exists():
            return parent
    return None


def figure_target(text: str) -> tuple[Path, str]:
    """A figure file to write and its format, read from its suffix.

    Its directory is created when the figure is written (and removed if none is), as
    ``--out`` creates its directory.

    Raises
    ------
    UsageError
        If the suffix is not one of :data:`FIGURE_FORMATS`, a directory is in the file's place,
        or its directory cannot be created or written (a file in the way, no permission):
        checked before anything is computed.
    """
    target = Path(text)
    fmt = target.suffix.lstrip(".").lower()
    if target.is_dir():
        example = target / ("figure." + (fmt if fmt in FIGURE_FORMATS else "png"))
        raise UsageError(f"-o {target} is a directory; give a file name such as {example}")
    if fmt not in FIGURE_FORMATS:
        raise UsageError(f"output format {target.suffix or '(none)'!r} of {target} is not one "
                         "of .png, .svg, .pdf")
    _refuse_dangling_link("-o", target.parent, target)
    existing = target.parent if target.parent.exists() else _existing_ancestor(target.parent)
    if existing is not None and not existing.is_dir():
        raise UsageError(f"{existing} of {target} is a file, not a directory")
    if existing is not None:
        _refuse_unwritable(f"-o {target}", existing)
    return target, fmt


def poisson(text: str) -> float:
    """Argument type of a Poisson ratio ``nu``: ``-1 < nu <= 1/2``."""
    # Imported here, not at the top: the model loads numpy, which `groove --help` does not need.
    from ..model.parameters import POISSON_RANGE, check_poisson

    value = _number(text, f"Poisson ratio nu = {text!r} is not a number; allowed range "
                          f"{POISSON_RANGE[0]:g} < nu <= {POISSON_RANGE[1]:g}")
    return _argument(check_poisson, value, text)


def _ratio(text: str) -> float:
    """Argument type of a compliance ratio: a finite number > 0."""
    # Imported here, not at the top: the model loads numpy, which `groove --help` does not need.
    from ..model.parameters import Compliance

    value = _number(text, f"compliance ratio c = {text!r} is not a number; allowed range: "
                          "finite and > 0")
    try:
        return Compliance(value).ratio
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"compliance ratio c = {value!r} is outside the allowed range: finite and > 0"
        ) from None


def _traced_ratio(text: str) -> float:
    """Argument type of the compliance ratio of a traced command: ``2/3 <= c <= 1`` (the range
    the messages name, also for a ratio that is not finite)."""
    value = _number(text, f"compliance ratio c = {text!r} is not a number; allowed range "
                          "2/3 <= c <= 1")
    # Imported here, not at the top: the model loads numpy, which `groove --help` does not need.
    from ..model.parameters import check_traced_ratio

    return _argument(check_traced_ratio, value, text)


def traced_poisson(text: str) -> float:
    """Argument type of the Poisson ratio of a traced command: ``0 <= nu <= 1/2``."""
    # Imported here, not at the top: the model loads numpy, which `groove --help` does not need.
    from ..model.parameters import check_traced_poisson

    value = _number(text, f"Poisson ratio nu = {text!r} is not a number; allowed range "
                          "0 <= nu <= 0.5")
    return _argument(check_traced_poisson, value, text)


def add_compliance_options(parser, poisson_help: str = "", traced: bool = True) -> None:
    """Add ``--compliance RATIO`` and ``--poisson NU`` to a command (one line per command).

    ``--poisson NU`` sets Mindlin's ratio ``2 (1 - nu)/(2 - nu)``
    (:meth:`~groove_model.model.parameters.Compliance.from_poisson`); ``--compliance RATIO``
    sets the ratio itself and, when both are given, wins (a command may use ``nu`` for more,
    e.g. ``groove solve`` for the Hertz contact in SI units). Neither: the paper's ratio 1.
    Read them back with :func:`compliance_from`. ``traced``: the command traces boundaries, so
    ``2/3 <= RATIO <= 1`` and ``0 <= NU <= 0.5`` (else any ratio > 0 and ``-1 < NU <= 0.5``).
    """
    group = parser.add_argument_group(
        "contact compliance (default: the paper's T/N = u_t/u_n)")
    group.add_argument("--compliance", type=_traced_ratio if traced else _ratio, default=None,
                       metavar="RATIO",
                       help="compliance ratio (T/N) / (u_t/u_n) under proportional loading, "
                            + ("2/3 <= RATIO <= 1" if traced else "> 0")
                            + " (overrides the ratio from --poisson)")
    group.add_argument("--poisson", type=traced_poisson if traced else poisson, default=None,
                       metavar="NU",
                       help="Poisson ratio of the ball, "
                            + ("0 <= NU <= 0.5" if traced else "-1 < NU <= 0.5")
                            + ": Mindlin's ratio 2 (1 - NU)/(2 - NU) (1 at NU = 0, 2/3 at "
                              "NU = 0.5)" + (f"; {poisson_help}" if poisson_help else ""))


def compliance_from(args) -> Compliance:
    """The :class:`Compliance` the options of :func:`add_compliance_options` ask for."""
    # Imported here, not at the top: the model loads numpy, which `groove --help` does not need.
    from ..model.parameters import Compliance

    if getattr(args, "compliance", None) is not None:
        return Compliance(args.compliance)
    if getattr(args, "poisson", None) is not None:
        return Compliance.from_poisson(args.poisson)
    return Compliance()


def compliance_label(compliance: Compliance) -> str:
    """A file-name suffix for a compliance: ``""`` for the paper's, ``"_nu0.3"`` for one from a
    Poisson ratio, ``"_c0.8"`` otherwise (values written exactly, as ``k`` is)."""
    # Imported here, not at the top: the model loads numpy, which `groove --help` does not need.
    from ..model.parameters import k_text

    if compliance.poisson is not None and compliance.poisson != 0.0:
        return f"_nu{k_text(compliance.poisson)}"
    if compliance.ratio == 1.0:
        return ""
    return f"_c{k_text(compliance.ratio)}"
