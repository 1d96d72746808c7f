"""The problem: a residual ``H: R^(n+1) -> R^n`` and its Jacobian.

No coordinate is privileged (Allgower & Georg's formulation): the curve
``H(x) = 0`` may turn with respect to any coordinate.
"""

from __future__ import annotations

import functools
import logging
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .errors import CallbackError, CallbackShapeError

__all__ = ["Evaluator", "Problem", "as_vector", "check_jacobian", "finite_difference_jacobian",
           "probe_jacobian"]

logger = logging.getLogger(__name__)

_EPS = np.finfo(float).eps


@dataclass(frozen=True)
class Problem:
    """An underdetermined system ``H(x) = 0`` whose solution set is a curve.

    Parameters
    ----------
    residual : callable
        ``residual(x) -> ndarray, shape (n,)`` for ``x`` of shape ``(n + 1,)``.
    jacobian : callable or None, optional
        ``jacobian(x) -> ndarray, shape (n, n + 1)``, the derivative
        ``dH/dx``. ``None`` (default) uses central finite differences
        (:func:`finite_difference_jacobian`), costing ``2 (n + 1)`` residual
        evaluations per Jacobian.
    names : tuple of str or None, optional
        Names of the ``n + 1`` coordinates, used in messages, fold names and
        box event names. ``None`` names them ``x[0]``, ``x[1]``, ...

    Notes
    -----
    Regular points of the curve are those where ``rank H'(x) = n``; there the
    curve has a unique unit tangent ``t`` with ``H'(x) t = 0`` [1]_.

    References
    ----------
    .. [1] E. L. Allgower and K. Georg, *Introduction to Numerical Continuation
       Methods*, SIAM Classics in Applied Mathematics 45, 2003, ch. 2.
    """

    residual: Callable[[np.ndarray], np.ndarray]
    jacobian: Callable[[np.ndarray], np.ndarray] | None = None
    names: tuple[str, ...] | None = None

    def __post_init__(self) -> None:
        if not callable(self.residual):
            raise TypeError(
                f"Problem.residual must be callable, got {type(self.residual).__name__}"
            )
        if self.jacobian is not None and not callable(self.jacobian):
            raise TypeError(
                "Problem.jacobian must be callable or None, got "
                f"{type(self.jacobian).__name__}"
            )
        if self.names is not None:
            names = tuple(self.names)
            if not all(isinstance(name, str) for name in names):
                raise TypeError(f"Problem.names must be a tuple of str, got {self.names!r}")
            object.__setattr__(self, "names", names)

    def coordinate_name(self, index: int) -> str:
        """Return the name of coordinate ``index`` (``names[index]`` or ``x[index]``)."""
        if self.names is not None and 0 <= index < len(self.names):
            return self.names[index]
        return f"x[{index}]"

    def describe(self, x: np.ndarray) -> str:
        """Return ``x`` formatted with the coordinate names, for messages."""
        return "(" + ", ".join(
            f"{self.coordinate_name(i)}={value:.10g}" for i, value in enumerate(x)
        ) + ")"


def as_vector(name: str, value) -> np.ndarray:
    """``value`` as a finite 1-D float array, or a ``ValueError`` naming ``name``."""
    array = np.array(value, dtype=float)
    if array.ndim != 1 or not np.isfinite(array).all():
        raise ValueError(f"{name} must be a finite 1-D array, got {value!r}")
    return array


def finite_difference_jacobian(
    residual: Callable[[np.ndarray], np.ndarray],
    x: np.ndarray,
    step: float | np.ndarray | None = None,
) -> np.ndarray:
    """Approximate the Jacobian of ``residual`` at ``x`` by central differences.

    Parameters
    ----------
    residual : callable
        ``residual(x) -> ndarray, shape (n,)``.
    x : array_like, shape (n + 1,)
        Point of evaluation.
    step : float or array_like of shape (n + 1,) or None, optional
        Difference step per coordinate. ``None`` (default) uses
        ``h_j = eps^(1/3) max(1, |x_j|)``, which balances the truncation error
        ``O(h^2)`` against the rounding error ``O(eps / h)``.

    Returns
    -------
    ndarray, shape (n, n + 1)
        ``J[:, j] = (H(x + h_j e_j) - H(x - h_j e_j)) / (2 h_j)``.

    Raises
    ------
    ValueError
        If ``x`` is not a finite 1-D array or a step is not positive.

    Notes
    -----
    Costs ``2 (n + 1)`` residual evaluations; the error is
    ``O(h^2 |H'''| + eps |H| / h)``, about ``1e-10`` relative for smooth ``H``
    (Dennis & Schnabel, *Numerical Methods for Unconstrained Optimization and
    Nonlinear Equations*, SIAM 1996, sec. 5.6).
    """
    x = np.asarray(x, dtype=float)
    if x.ndim != 1 or not np.all(np.isfinite(x)):
        raise ValueError(f"x must be a finite 1-D array, got {x!r}")
    if step is None:
        steps = _EPS ** (1.0 / 3.0) * np.maximum(1.0, np.abs(x))
    else:
        steps = np.broadcast_to(np.asarray(step, dtype=float), x.shape)
        if not np.all(steps > 0):
            raise ValueError(f"step must be positive, got {step!r}")
    columns = []
    for j in range(x.size):
        forward = x.copy()
        backward = x.copy()
        forward[j] += steps[j]
        backward[j] -= steps[j]
        # the actually representable difference, not the nominal step
        width = forward[j] - backward[j]
        columns.append(
            (np.asarray(residual(forward), dtype=float)
             - np.asarray(residual(backward), dtype=float)) / width
        )
    return np.stack(columns, axis=-1).reshape(-1, x.size)


def check_jacobian(
    problem_or_residual: Problem | Callable[[np.ndarray], np.ndarray],
    jacobian: Callable[[np.ndarray], np.ndarray] | None,
    x: np.ndarray,
    rtol: float = 1e-6,
    atol: float = 1e-8,
    *,
    raise_on_error: bool = False,
) -> float:
    """Compare a Jacobian with central finite differences of the residual.

    Parameters
    ----------
    problem_or_residual : Problem or callable
        The problem (its residual is differenced) or a residual function.
    jacobian : callable or None
        The Jacobian to check; ``None`` takes ``problem.jacobian``.
    x : array_like, shape (n + 1,)
        Point of the check.
    rtol, atol : float, optional
        An entry fails when ``|J - J_fd| > atol + rtol |J_fd|``.
    raise_on_error : bool, optional
        Raise instead of logging a warning when an entry fails.

    Returns
    -------
    float
        ``max |J - J_fd|`` over all entries.

    Raises
    ------
    ValueError
        If no Jacobian is available, shapes disagree, or (with
        ``raise_on_error=True``) an entry exceeds the tolerance; the message
        names the worst entry.
    """
    if isinstance(problem_or_residual, Problem):
        residual = problem_or_residual.residual
        if jacobian is None:
            jacobian = problem_or_residual.jacobian
        names = problem_or_residual
    else:
        residual = problem_or_residual
        names = Problem(residual)
    if jacobian is None:
        raise ValueError("check_jacobian needs a jacobian: the problem has none and none was "
                         "passed")
    if rtol < 0 or atol < 0:
        raise ValueError(f"rtol and atol must be >= 0, got rtol={rtol!r}, atol={atol!r}")
    x = np.asarray(x, dtype=float)
    reference = finite_difference_jacobian(residual, x)
    supplied = np.asarray(jacobian(x), dtype=float)
    if supplied.shape != reference.shape:
        raise ValueError(
            f"jacobian(x) has shape {supplied.shape}, expected {reference.shape} "
            "(n equations by n + 1 unknowns)"
        )
    error = np.abs(supplied - reference)
    excess = error - (atol + rtol * np.abs(reference))
    worst = np.unravel_index(int(np.argmax(excess)), excess.shape)
    if excess[worst] > 0 or not np.all(np.isfinite(supplied)):
        row, col = int(worst[0]), int(worst[1])
        message = (
            f"Jacobian entry dH[{row}]/d{names.coordinate_name(col)} at x={names.describe(x)} "
            f"is {supplied[row, col]:.10g}, central differences give {reference[row, col]:.10g} "
            f"(error {error[row, col]:.3g} > atol + rtol*|J_fd| = "
            f"{atol + rtol * abs(reference[row, col]):.3g})"
        )
        if raise_on_error:
            raise ValueError(message)
        logger.warning(message)
    return float(np.max(error)) if error.size else 0.0


#: the step of :func:`probe_jacobian`, about the cube root of the float epsilon
PROBE_STEP = 2.0 ** -17
#: relative disagreement (in a row, against ``|J| |d|``) that :func:`probe_jacobian` reports
PROBE_RTOL = 1e-4
#: the three steps of :func:`probe_jacobian`, as fractions of ``d``
_PROBE_SCALES = (1.0, 1.0 / 16.0, 1.0 / 256.0)


@functools.lru_cache(maxsize=8)
def _probe_direction(n1: int) -> np.ndarray:
    """``h v`` of :func:`probe_jacobian`: sizes from the golden-ratio sequence in
    ``[1/2, 3/2)``, alternating in sign."""
    v = [(0.5 + (0.6180339887498949 * (j + 1)) % 1.0) * (-1.0) ** j for j in range(n1)]
    direction = PROBE_STEP * np.array(v)
    direction.flags.writeable = False
    return direction


def probe_jacobian(evaluator: Evaluator, x: np.ndarray, J: np.ndarray) -> str | None:
    r"""Whether ``J`` is the derivative of the residual at ``x``: 2 residuals, 6 if in doubt.

    Along one fixed direction ``d`` (``d_j = h (1 + |x_j|) v_j``, ``h = 2^-17``, ``v`` a fixed
    pattern of signs and sizes that no coordinate direction or tangent is likely to cancel),
    ``J d`` is compared with the central difference ``D = (H(x + d) - H(x - d)) / 2``, row
    by row. A row disagrees when ``|J d - D|_i`` exceeds ``PROBE_RTOL (|J| |d|)_i`` and the
    rounding of the difference, ``8 eps (|H(x + d)| + |H(x - d)|)_i``. Where a row does, the
    same is done over ``d/16`` and ``d/256``: the error of a wrong ``J`` is the same fraction of
    the step at every scale, while the differences' own error (truncation ``O(h^3)``, a residual
    that varies on a scale shorter than ``d``) shrinks with the step. ``J`` is reported only
    if a row disagrees at all three steps, by a fraction of the step at ``d/256`` at least half
    of that at ``d/16``.

    An approximate ``J`` (finite differences, ``1e-8`` relative) passes. Blind spots: an error
    whose share of ``|J| |d|`` is below ``PROBE_RTOL`` (a column whose coordinate is ``1e6``
    times smaller than another's), an error that ``d`` cancels, a residual that is not finite
    within ``d`` of ``x`` (it cannot tell), and a residual that varies on a scale below
    ``d/256`` (about ``3e-8 (1 + |x|)``), which can be reported though ``J`` is right.

    Returns
    -------
    str or None
        ``None`` if ``J`` agrees or the check cannot tell; else what disagrees, for a message.
    """
    d = (1.0 + np.abs(x)) * _probe_direction(x.size)
    errors: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []
    for scale in _PROBE_SCALES:
        step = scale * d
        plus, minus = evaluator.residual(x + step), evaluator.residual(x - step)
        D = 0.5 * (plus - minus)
        error = np.abs(J @ step - D)
        allowed = PROBE_RTOL * (np.abs(J) @ np.abs(step)) \
            + 8.0 * np.finfo(float).eps * (np.abs(plus) + np.abs(minus))
        wrong = error > allowed          # (NaN compares False: it cannot tell)
        if errors:
            wrong &= errors[-1][2]
        if not wrong.any():
            return None
        errors.append((error / scale, D / (scale * PROBE_STEP), wrong))
    (middle, _, _), (last, _, wrong) = errors[1:]
    steady = wrong & (last >= 0.5 * middle)
    if not steady.any():
        return None
    i = int(np.flatnonzero(steady)[0])
    slopes = ", ".join(f"{slope[i]:.10g}" for _, slope, _ in errors)
    return (f"row {i} of the Jacobian gives the derivative {(J @ d)[i] / PROBE_STEP:.10g} "
            f"along the direction (1 + |x|) v of the check, but the residual changes along it "
            f"at {slopes} (central differences over h, h/16 and h/256 times it, h = 2^-17): "
            "the same disagreement at every step is an error of the Jacobian, not of the "
            "differences")


class Evaluator:
    """Counting, checking evaluator of a :class:`Problem` (internal).

    ``residual_evals`` counts every call of ``problem.residual``, including
    the ``2 (n + 1)`` calls of each finite-difference Jacobian;
    ``jacobian_evals`` counts Jacobians (supplied or finite-difference).
    Once :meth:`expect` has fixed ``n + 1``, every result is checked for its
    shape, and an exception raised by the problem's functions is re-raised as
    :class:`~continuation.result.CallbackError` naming the function and the
    point (the original exception is its ``__cause__``).
    """

    __slots__ = ("_jacobian", "_jacobian_shape", "_residual", "_residual_shape",
                 "jacobian_evals", "problem", "residual_evals")

    def __init__(self, problem: Problem) -> None:
        self.problem = problem
        self.residual_evals = 0
        self.jacobian_evals = 0
        self._residual = problem.residual
        self._jacobian = problem.jacobian
        self._residual_shape: tuple[int, ...] | None = None
        self._jacobian_shape: tuple[int, ...] | None = None

    def expect(self, n1: int) -> None:
        """Check every later result against ``n + 1 = n1`` unknowns."""
        self._residual_shape = (n1 - 1,)
        self._jacobian_shape = (n1 - 1, n1)

    def residual(self, x: np.ndarray) -> np.ndarray:
        """Return ``H(x)`` as a float array and count it."""
        self.residual_evals += 1
        try:
            value = self._residual(x)
        except Exception as exc:
            raise _raised("residual", self.problem, x, exc) from exc
        H = _real(value, "residual", self.problem, x)
        if self._residual_shape is not None and H.shape != self._residual_shape:
            raise _wrong_shape("residual", self.problem, x, H.shape, self._residual_shape)
        return H

    def jacobian(self, x: np.ndarray) -> np.ndarray:
        """Return ``H'(x)`` as a float array and count it."""
        self.jacobian_evals += 1
        if self._jacobian is None:
            return finite_difference_jacobian(self.residual, x)
        try:
            value = self._jacobian(x)
        except Exception as exc:
            raise _raised("jacobian", self.problem, x, exc) from exc
        J = _real(value, "jacobian", self.problem, x)
        if self._jacobian_shape is not None and J.shape != self._jacobian_shape:
            raise _wrong_shape("jacobian", self.problem, x, J.shape, self._jacobian_shape)
        return J


def _real(value, function: str, problem: Problem, x: np.ndarray) -> np.ndarray:
    """``value`` as a float array; complex values are an error, not silently made real."""
    array = np.asarray(value)
    if array.dtype == np.float64:
        return array
    if array.dtype.kind == "c":
        raise CallbackShapeError(
            f"{function}(x) returned complex values (dtype {array.dtype}) at "
            f"x={problem.describe(np.asarray(x, dtype=float))}: it must return real numbers")
    try:
        return array.astype(float)
    except (TypeError, ValueError) as exc:
        raise CallbackShapeError(
            f"{function}(x) returned {array.dtype} values that are not real numbers at "
            f"x={problem.describe(np.asarray(x, dtype=float))}: {exc}") from exc


def _raised(function: str, problem: Problem, x: np.ndarray, exc: Exception):
    return CallbackError(f"{function}(x) raised {type(exc).__name__}: {exc} at "
                         f"x={problem.describe(np.asarray(x, dtype=float))}")


def _wrong_shape(function: str, problem: Problem, x: np.ndarray, found: tuple,
                 expected: tuple):
    n = expected[0]
    hint = ""
    if function == "residual" and len(found) == 1:
        hint = (f"; or x0 has the wrong length: {found[0]} equations need {found[0] + 1} "
                "unknowns")
    return CallbackShapeError(
        f"{function}(x) returned shape {found}, expected {expected} (n = {n} equations in "
        f"n + 1 = {n + 1} unknowns) at x={problem.describe(np.asarray(x, dtype=float))}"
        + hint)
