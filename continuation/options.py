"""The numbers that steer a continuation run."""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass
from functools import cached_property

__all__ = ["Newton", "Options"]


@dataclass(frozen=True)
class Newton:
    """The settings of one Newton correction, passed whole to the corrector.

    Parameters
    ----------
    tol : float
        Residual tolerance, ``max |H(x)| <= tol``.
    xtol : float
        Correction tolerance, ``max |dx| <= xtol (1 + max |x|)``.
    max_iterations : int
        Most Newton steps.
    max_contraction : float
        Largest accepted ratio ``|dx_(k+1)| / |dx_k|`` of consecutive corrections.
    """

    tol: float
    xtol: float
    max_iterations: int
    max_contraction: float


@dataclass(frozen=True)
class Options:
    """Tolerances, step sizes and switches of :func:`continuation.trace`.

    Parameters
    ----------
    tol : float
        Newton tolerance. A point is accepted when ``max |H(x)| <= tol`` and
        the next Newton correction satisfies ``max |dx| <= tol (1 + max |x|)``
        (and, on a curve, its 2-norm is at most a tenth of the step size: where
        ``tol`` is too loose for the curve's scale the run fails instead). The
        residual test is absolute, the correction test relative to
        ``1 + max |x|``: scale the problem so that its residual and coordinates
        near the curve are of order one.
    ds : float
        Initial pseudo-arclength step.
    ds_min, ds_max : float
        Bounds of the step. A step rejected at ``ds_min`` ends the run with
        ``Status.STEP_TOO_SMALL`` (or ``Status.NON_FINITE``). The step is the predictor's:
        where ``tol`` is loose for it (above about ``ds_max / 100``), the points' noise turns
        the predictor and the corrected point can land a few steps further along the curve
        (on it; up to 3.7 steps at ``tol = ds_max / 10``).
    max_steps : int
        Maximum number of accepted steps (a normal end, ``Status.MAX_STEPS``).
    max_arclength : float
        The run stops exactly at this arclength (``Status.MAX_ARCLENGTH``).
    max_newton : int
        Maximum Newton iterations per corrector call.
    newton_contraction : float
        Largest accepted contraction rate ``|dx_(k+1)| / |dx_k|`` of the
        corrector; a larger one rejects the step. Half of it is the nominal
        contraction of the step-size control.
    max_angle : float
        Largest accepted angle (radians) between consecutive unit tangents;
        half of it is the nominal angle of the step-size control.
    max_correction : float
        Largest accepted length (2-norm) of the first Newton correction; half
        of it is the nominal distance of the step-size control.
    event_tol : float
        Width in arclength of the final root bracket of every located special
        point (events, folds, branch points); trial points are corrected to
        ``max |dx| <= event_tol (1 + max |x|)``, so the located point is within
        about ``event_tol`` of the exact one in ``x``.
    fold_coordinates : tuple of int
        Coordinates ``i`` with respect to which folds (sign changes of the
        tangent component ``t_i``) are detected and located.
    detect_branch_points : bool
        Detect and locate simple branch points (sign changes of
        ``det [H'(x); t^T]``).
    detect_closed : bool
        Detect a return to the start point and close the curve there: the curve's point in
        the hyperplane through the start, normal to its tangent, must lie within ``1e-6 (1 +
        max|x0|)`` of the start, or within twice the points' accuracy ``tol (1 + max|x0|)``
        at a loose ``tol``; a curve that comes back closer than that without closing (a helix
        of a smaller pitch) is taken as closed.
    check_jacobian : bool
        At the start, compare the problem's Jacobian with central differences of its
        residual along one direction (2 residuals, 6 if they disagree;
        :func:`continuation.problem.probe_jacobian`); a Jacobian that is not the residual's
        derivative ends the run with ``Status.JACOBIAN_MISMATCH`` before it traces (a wrong
        Jacobian still lets Newton converge onto the curve, but tilts the tangents, and so
        the folds and branch points, and collapses the steps). The same check runs at every
        located fold and branch point, and where a run ended at ``max_steps`` with its steps
        collapsed: a Jacobian wrong there only fails the run there, with its partial curve
        (:func:`continuation.special.jacobian_at_special_points`). Turn it off for a residual
        that is not differentiable there.
    raise_on_failure : bool
        Raise :class:`continuation.ContinuationError` (carrying the partial
        curve) when the run ends with a failure status.

    Raises
    ------
    ValueError
        If a value is out of its range; the message names the field, its value
        and the allowed range.
    TypeError
        If a switch is not a bool or a fold coordinate not an integer.

    Notes
    -----
    The step-size control follows Allgower & Georg, *Introduction to Numerical
    Continuation Methods*, SIAM 2003, sec. 6.1, and Den Heijer & Rheinboldt,
    SIAM J. Numer. Anal. 18 (1981) 925-948: the contraction rate, the first
    correction and the tangent angle are compared with nominal values.
    """

    tol: float = 1e-10
    ds: float = 0.05
    ds_min: float = 1e-12
    ds_max: float = 0.2
    max_steps: int = 10_000
    max_arclength: float = math.inf
    max_newton: int = 10
    newton_contraction: float = 0.5
    max_angle: float = 0.5
    max_correction: float = 0.1
    event_tol: float = 1e-12
    fold_coordinates: tuple[int, ...] = ()
    detect_branch_points: bool = True
    detect_closed: bool = True
    check_jacobian: bool = True
    raise_on_failure: bool = False

    @cached_property
    def newton(self) -> Newton:
        """The corrector's settings for curve points: ``xtol = tol``."""
        return Newton(self.tol, self.tol, self.max_newton, self.newton_contraction)

    @cached_property
    def locate_newton(self) -> Newton:
        """The corrector's settings for located points: ``xtol = event_tol``."""
        return Newton(self.tol, self.event_tol, self.max_newton, self.newton_contraction)

    def __post_init__(self) -> None:
        for name in ("tol", "ds", "ds_min", "ds_max", "max_correction", "event_tol"):
            _check_positive_finite(name, getattr(self, name))
        if not self.ds_min <= self.ds_max:
            raise ValueError(
                f"Options.ds_min must be <= ds_max, got ds_min={self.ds_min!r}, "
                f"ds_max={self.ds_max!r}"
            )
        if not self.ds_min <= self.ds <= self.ds_max:
            raise ValueError(
                f"Options.ds must satisfy ds_min <= ds <= ds_max, got ds={self.ds!r} "
                f"with ds_min={self.ds_min!r}, ds_max={self.ds_max!r}"
            )
        _check_int("max_steps", self.max_steps, 1)
        _check_int("max_newton", self.max_newton, 1)
        if not (isinstance(self.max_arclength, numbers.Real) and self.max_arclength > 0):
            raise ValueError(
                f"Options.max_arclength must be > 0 (inf allowed), got {self.max_arclength!r}"
            )
        if not (isinstance(self.newton_contraction, numbers.Real)
                and 0 < self.newton_contraction < 1):
            raise ValueError(
                "Options.newton_contraction must be in (0, 1), got "
                f"{self.newton_contraction!r}"
            )
        if not (isinstance(self.max_angle, numbers.Real) and 0 < self.max_angle <= math.pi / 2):
            raise ValueError(
                f"Options.max_angle must be in (0, pi/2] radians, got {self.max_angle!r}"
            )
        message = ("Options.fold_coordinates must be a tuple of coordinate indices >= 0, got "
                   f"{self.fold_coordinates!r}")
        try:
            folds = tuple(self.fold_coordinates)
        except TypeError:
            raise TypeError(message) from None
        if not all(isinstance(i, numbers.Integral) and not isinstance(i, bool) for i in folds):
            raise TypeError(message)
        if not all(i >= 0 for i in folds):
            raise ValueError(
                "Options.fold_coordinates must be a tuple of coordinate indices >= 0, got "
                f"{self.fold_coordinates!r}"
            )
        object.__setattr__(self, "fold_coordinates", tuple(int(i) for i in folds))
        for name in ("detect_branch_points", "detect_closed", "check_jacobian",
                     "raise_on_failure"):
            if not isinstance(getattr(self, name), bool):
                raise TypeError(
                    f"Options.{name} must be True or False, got {getattr(self, name)!r}"
                )


def _check_positive_finite(name: str, value: object) -> None:
    if not (isinstance(value, numbers.Real) and 0 < float(value) < math.inf):
        raise ValueError(f"Options.{name} must be a finite number > 0, got {value!r}")


def _check_int(name: str, value: object, minimum: int) -> None:
    if not (isinstance(value, numbers.Integral) and not isinstance(value, bool)
            and int(value) >= minimum):
        raise ValueError(f"Options.{name} must be an integer >= {minimum}, got {value!r}")
