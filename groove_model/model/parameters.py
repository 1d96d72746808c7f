"""Parameters of the ball-in-a-groove model and the geometry of the groove.

Conventions follow Halsey & Ertas, "A Ball in a Groove" (see ``docs/model.md``): walls at
angles ``theta_L >= theta_R`` to the horizontal, ``gamma = (theta_L + theta_R)/2``,
``delta = (theta_L - theta_R)/2``, domain ``0 <= delta <= gamma <= pi/2``, radians.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, field

import numpy as np

__all__ = [
    "POISSON_RANGE",
    "TRACED_COMPLIANCE_RANGE",
    "TRACED_K_RANGE",
    "TRACED_POISSON_RANGE",
    "Compliance",
    "Parameters",
    "check_domain",
    "check_flag",
    "check_friction",
    "check_poisson",
    "check_traced",
    "check_traced_friction",
    "check_traced_poisson",
    "check_traced_ratio",
    "gamma_delta_from_thetas",
    "k_text",
    "number_text",
    "thetas_from_gamma_delta",
    "traced_compliance",
    "traced_friction",
    "traced_parameters",
]

HALF_PI = 0.5 * math.pi


def _check_real(name: str, value: object) -> float:
    if isinstance(value, np.ndarray) and value.shape == () and value.dtype.kind in "fiu":
        value = value.item()  # a 0-d array, as numpy's reductions return them
    if isinstance(value, bool) or not isinstance(value, (numbers.Real, np.floating, np.integer)):
        raise TypeError(f"{name} must be a real number, got {value!r} of type "
                        f"{type(value).__name__}")
    try:
        return float(value)
    except OverflowError:  # an integer (or fraction) beyond the floats: infinite as a float,
        positive = value > 0  # type: ignore[operator]  # (every Real here compares with 0)
        return math.inf if positive else -math.inf  # so that every range check names its range


def check_flag(name: str, value: object) -> bool:
    """``value`` as a bool if it is one (Python's or numpy's).

    Raises
    ------
    TypeError
        Naming the flag, for anything else: ``certify="no"`` would otherwise read as true.
    """
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name} must be True or False, got {value!r} of type "
                        f"{type(value).__name__}")
    return bool(value)


def check_friction(k: object) -> float:
    """Return the friction coefficient as a float, or raise if it is not finite and > 0.

    Raises
    ------
    TypeError
        If ``k`` is not a real number.
    ValueError
        If ``k`` is not finite or not positive; the message names the value and the range.
    """
    value = _check_real("friction coefficient k", k)
    if not math.isfinite(value) or value <= 0.0:
        raise ValueError(
            f"friction coefficient k = {number_text(value)} is outside the allowed range: "
            "k must be finite and > 0"
        )
    return value


#: the Poisson ratios of an isotropic elastic solid: -1 < nu <= 1/2
POISSON_RANGE = (-1.0, 0.5)


def check_poisson(nu: object) -> float:
    """Return the Poisson ratio as a float, or raise if it is outside ``-1 < nu <= 1/2``.

    Raises
    ------
    TypeError
        If ``nu`` is not a real number.
    ValueError
        If ``nu`` is not finite or outside the range; the message names the value and range.
    """
    value = _check_real("Poisson ratio nu", nu)
    low, high = POISSON_RANGE
    if not (math.isfinite(value) and low < value <= high):
        raise ValueError(f"Poisson ratio nu = {value!r} is outside the allowed range "
                         f"{low:g} < nu <= {high:g} (an isotropic elastic solid)")
    return value


#: The friction coefficients, compliance ratios and Poisson ratios the tracer is verified for:
#: sweeps there check every curve against independent solves. The point solver is exact for
#: any k > 0 and any ratio > 0; outside these ranges a boundary may have another topology.
TRACED_K_RANGE = (1e-4, 1e6)
TRACED_POISSON_RANGE = (0.0, 0.5)
#: Mindlin's ratio 2 (1 - nu)/(2 - nu) over TRACED_POISSON_RANGE
TRACED_COMPLIANCE_RANGE = (2.0 / 3.0, 1.0)
#: relative slack at the ends of the traced ranges (a ratio computed from nu = 1/2 may round)
_RANGE_SLACK = 1e-12


def _in_traced_range(name: str, value: float, bounds: tuple, allowed: str) -> float:
    """``value`` if within ``bounds`` (with :data:`_RANGE_SLACK`), else ``ValueError``."""
    low, high = bounds
    if not low * (1.0 - _RANGE_SLACK) <= value <= high * (1.0 + _RANGE_SLACK):
        raise ValueError(f"{name} = {number_text(value)} is outside the range the boundaries "
                         f"are traced for: {allowed}")
    return value


def check_traced_friction(k: float) -> float:
    """``k`` if inside :data:`TRACED_K_RANGE`, else ``ValueError`` naming it and the range."""
    return _in_traced_range("friction coefficient k", k, TRACED_K_RANGE,
                            "1e-4 <= k <= 1e6 (the point solver, groove solve, takes any k > 0)")


def traced_friction(k: object) -> float:
    """``k`` as a float if it is a real number in :data:`TRACED_K_RANGE` (a ``k`` that is not
    finite or not positive named with that range too), else ``TypeError`` / ``ValueError``."""
    return check_traced_friction(_check_real("friction coefficient k", k))


def check_traced_ratio(c: float) -> float:
    """``c`` if inside :data:`TRACED_COMPLIANCE_RANGE`, else ``ValueError``."""
    return _in_traced_range("compliance ratio c", c, TRACED_COMPLIANCE_RANGE,
                            "2/3 <= c <= 1 (Mindlin's ratio for Poisson ratios 0 <= nu <= 1/2)")


def check_traced_poisson(nu: float) -> float:
    """``nu`` if inside :data:`TRACED_POISSON_RANGE`, else ``ValueError`` (naming that range,
    not the wider one of :func:`check_poisson`)."""
    nu = _check_real("Poisson ratio nu", nu)
    if not TRACED_POISSON_RANGE[0] <= nu <= TRACED_POISSON_RANGE[1]:
        raise ValueError(f"Poisson ratio nu = {nu!r} is outside the range the boundaries are "
                         "traced for: 0 <= nu <= 0.5")
    return nu


def traced_parameters(k_or_params, compliance: Compliance | float | None = None) -> Parameters:
    """:class:`Parameters` for tracing, checked against the traced ranges (:func:`check_traced`).

    ``k_or_params`` is a :class:`Parameters` (then no ``compliance``: it has its own) or a
    friction coefficient (with ``compliance``, a :class:`Compliance` or its ratio ``c``, default
    the paper's ``c = 1``); a ``k`` that is not finite
    or not positive gets the message of the traced range ``1e-4 <= k <= 1e6``, not only
    "finite and > 0".

    Raises
    ------
    TypeError
        If ``k`` is not a real number, or a :class:`Parameters` comes with a ``compliance``.
    ValueError
        If ``k`` or the compliance ratio is outside the traced ranges.
    """
    if isinstance(k_or_params, Parameters):
        if compliance is not None:
            raise TypeError(f"give the compliance once: in the Parameters or as compliance=, "
                            f"not both (got {k_or_params!r} and compliance={compliance!r})")
        check_traced(k_or_params)
        return k_or_params
    return Parameters(traced_friction(k_or_params), traced_compliance(compliance))


def traced_compliance(compliance: Compliance | float | None) -> Compliance:
    """``compliance`` (a :class:`Compliance`, its ratio ``c``, or ``None`` for the paper's
    ``c = 1``) as a :class:`Compliance`, its ratio checked against the traced range."""
    if compliance is None:
        return Compliance()
    if not isinstance(compliance, Compliance):
        # the traced range first: it is the one to name, for a ratio <= 0 or not finite too
        compliance = Compliance(check_traced_ratio(_check_real("compliance ratio c", compliance)))
    check_traced_ratio(compliance.ratio)
    return compliance


def check_traced(params: Parameters) -> None:
    """Raise ``ValueError`` if ``k`` or the compliance ratio is outside the traced ranges.

    The message names the quantity, its value and the range (:data:`TRACED_K_RANGE`,
    :data:`TRACED_COMPLIANCE_RANGE`).
    """
    check_traced_friction(params.k)
    check_traced_ratio(params.c)


def k_text(k: float) -> str:
    """``k`` as the shortest text that reads back as the same float, without a trailing ``.0``.

    ``1``, ``0.5``, ``1.0000001``, ``1e-05``: two different ``k`` never get the same text, so it
    is safe in file names and labels (``f"{k:g}"`` makes 1.0000001 and 1.0000002 both ``1``).
    """
    text = repr(float(k))
    return text[:-2] if text.endswith(".0") else text


def number_text(value: float) -> str:
    """``value`` for a message: its ``repr``, but in powers of ten from ``1e6`` on.

    ``repr`` reads back as the same float but writes ``1e7`` as ``10000000.0``; here it is
    ``1e+07``, and ``12345678.9`` is ``1.23456789e+07`` (the fewest digits that read back).
    """
    text = repr(float(value))
    if "e" in text or "n" in text or abs(value) < 1e6:
        return text
    for digits in range(17):
        short = f"{value:.{digits}e}"
        if float(short) == value:
            return short
    return text


@dataclass(frozen=True)
class Compliance:
    r"""Tangential compliance of a proportionally loaded Hertz-Mindlin contact.

    The paper (Eq. prop) uses ``u_t/u_n = T/N``. This object keeps that law replaceable:
    ``T/N = ratio * u_t/u_n``, with ``ratio = 1`` the paper's small-Poisson-ratio limit;
    :meth:`from_poisson` gives Mindlin's ratio for a Poisson ratio ``nu``.

    Parameters
    ----------
    ratio : float
        ``(T/N) / (u_t/u_n)`` under proportional loading, finite and > 0. The paper derives
        ``ratio = 1`` from Mindlin & Deresiewicz in the small-Poisson-ratio limit.
    poisson : float or None
        The Poisson ratio the ratio was computed from (:meth:`from_poisson`), else ``None``;
        for reports only (two compliances with the same ratio are equal).
    """

    ratio: float = 1.0
    poisson: float | None = field(default=None, compare=False)

    def __post_init__(self) -> None:
        value = _check_real("compliance ratio", self.ratio)
        if not math.isfinite(value) or value <= 0.0:
            raise ValueError(
                f"compliance ratio = {value!r} is outside the allowed range: finite and > 0"
            )
        object.__setattr__(self, "ratio", value)

    @classmethod
    def from_poisson(cls, nu) -> Compliance:
        r"""Mindlin's compliance of a sphere on a rigid flat: ``ratio = 2 (1 - nu)/(2 - nu)``.

        Parameters
        ----------
        nu : float
            Poisson ratio of the ball, ``-1 < nu <= 1/2``.

        Raises
        ------
        ValueError, TypeError
            If ``nu`` is outside its range or not a number.

        Notes
        -----
        The wall is rigid, so only the ball (shear modulus ``G = E / (2 (1 + nu))``) deforms.
        At a contact of radius ``a`` the incremental normal stiffness is Hertz's
        ``dN/du_n = 2 a E / (1 - nu^2)`` (from ``N = (4 E / (3 (1 - nu^2))) sqrt(R) u_n^(3/2)``,
        ``a = sqrt(R u_n)``, paper Eq. hertz) and the tangential one, without microslip,
        Mindlin's ``dT/du_t = 8 a G / (2 - nu)`` (R. D. Mindlin, "Compliance of elastic bodies
        in contact", J. Appl. Mech. 16 (1949) 259-268; K. L. Johnson, *Contact Mechanics*,
        1985, ch. 7, with a rigid counterface). Proportional loading keeps ``dT/dN = T/N`` with
        ``|dT| < k dN``, so no microslip occurs (Mindlin & Deresiewicz), and both
        displacements grow with the same ``a``:

        .. math::

            \frac{du_t}{du_n} = \frac{T}{N}\,\frac{2 a E/(1 - \nu^2)}{8 a G/(2 - \nu)}
            = \frac{T}{N}\,\frac{2 - \nu}{2 (1 - \nu)},

        the same ratio at every ``a``, hence for the totals:
        ``T/N = 2 (1 - nu)/(2 - nu) u_t/u_n``; ``ratio = 1`` at ``nu = 0`` (the paper's law)
        and ``2/3`` at ``nu = 1/2``.
        """
        value = check_poisson(nu)
        return cls(2.0 * (1.0 - value) / (2.0 - value), poisson=value)


@dataclass(frozen=True)
class Parameters:
    """Validated, immutable model parameters.

    Parameters
    ----------
    k : float
        Friction coefficient of both walls (Amontons: ``|T| <= k N``); finite and > 0.
    compliance : Compliance
        Tangential compliance law; the default is the paper's ``u_t/u_n = T/N``.
    """

    k: float
    compliance: Compliance = field(default_factory=Compliance)

    def __post_init__(self) -> None:
        object.__setattr__(self, "k", check_friction(self.k))
        if not isinstance(self.compliance, Compliance):
            raise TypeError(
                f"compliance must be a Compliance, got {type(self.compliance).__name__}"
            )

    @classmethod
    def coerce(cls, k_or_params) -> Parameters:
        """``k_or_params`` itself if it is a :class:`Parameters`, else
        ``Parameters(k_or_params)``."""
        return k_or_params if isinstance(k_or_params, cls) else cls(k_or_params)

    @property
    def c(self) -> float:
        """The compliance ratio ``T/N`` per ``u_t/u_n``."""
        return self.compliance.ratio

    @property
    def gamma_limit(self) -> float:
        """``arctan(k/c)``: on ``delta = 0`` double rolling holds below it (paper: ``arctan k``)."""
        return math.atan2(self.k, self.c)


def thetas_from_gamma_delta(gamma, delta):
    """Wall angles ``theta_L = gamma + delta``, ``theta_R = gamma - delta`` (radians)."""
    gamma = np.asarray(gamma, dtype=float)
    delta = np.asarray(delta, dtype=float)
    return gamma + delta, gamma - delta


def gamma_delta_from_thetas(theta_L, theta_R):
    """Half-sum and half-difference of the wall angles.

    ``gamma = (theta_L + theta_R)/2``, ``delta = (theta_L - theta_R)/2`` (radians).
    """
    theta_L = np.asarray(theta_L, dtype=float)
    theta_R = np.asarray(theta_R, dtype=float)
    return 0.5 * (theta_L + theta_R), 0.5 * (theta_L - theta_R)


#: the spacing of floats near 0
_SMALLEST_SUBNORMAL = 5e-324


def check_domain(gamma, delta):
    """Return ``gamma, delta`` as float arrays, or raise if any point is outside the domain.

    The domain is ``0 <= delta <= gamma <= pi/2`` (paper, below Eq. 3); a relative slack of
    ``4 eps`` (and of 4 units of the smallest subnormal number, where ``gamma`` is subnormal)
    absorbs round-off in angles computed as ``pi/2`` or ``arctan`` of something. A ``delta``
    within that slack above ``gamma`` is returned as ``gamma``.

    Raises
    ------
    TypeError
        If an angle is not numeric.
    ValueError
        Naming the first offending quantity, its value and the allowed range.
    """
    for name, value in (("gamma", gamma), ("delta", delta)):
        kind = np.asarray(value).dtype.kind
        if kind not in "fiu":  # strings, booleans, None and other objects are not angles
            raise TypeError(f"{name} must be a real number or an array of them, got "
                            f"{value!r}")
    try:
        gamma_a = np.asarray(gamma, dtype=float)
        delta_a = np.asarray(delta, dtype=float)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"gamma and delta must be real numbers, got {gamma!r} and "
                        f"{delta!r}") from exc
    gamma_a, delta_a = np.broadcast_arrays(gamma_a, delta_a)
    slack = 4.0 * np.finfo(float).eps
    bad_delta = delta_a > gamma_a * (1.0 + slack) + 4.0 * _SMALLEST_SUBNORMAL
    gamma_range = f"0 <= gamma <= pi/2 = {HALF_PI!r} (to 4 eps relative, then taken as pi/2)"
    checks = (
        (~np.isfinite(gamma_a), "gamma", gamma_range),
        (gamma_a > HALF_PI * (1.0 + slack), "gamma", gamma_range),
        (gamma_a < 0.0, "gamma", gamma_range),
        (~np.isfinite(delta_a), "delta", "0 <= delta <= gamma"),
        (delta_a < 0.0, "delta", "0 <= delta <= gamma"),
        (bad_delta, "delta", "0 <= delta <= gamma"),
    )
    for bad, name, allowed in checks:
        if np.any(bad):
            i = np.flatnonzero(bad.ravel())[0]
            value = float((gamma_a if name == "gamma" else delta_a).flat[i])
            if name == "delta":
                allowed += f" (gamma = {float(gamma_a.flat[i])!r} rad)"
            if not math.isfinite(value):
                raise ValueError(f"{name} = {value!r} is not a finite number; allowed range: "
                                 f"{allowed}")
            raise ValueError(f"{name} = {value!r} rad is outside the allowed range {allowed}")
    return np.minimum(gamma_a, HALF_PI), np.minimum(delta_a, np.minimum(gamma_a, HALF_PI))
