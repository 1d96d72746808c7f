"""The point solver against an independent 50-digit reference built from first principles.

The reference (mpmath) solves the paper's balance equations (Halsey & Ertas, "A Ball in a
Groove", Eqs. 1-3) with the Hertz normal forces ``N = C (Z sin beta)^(3/2)`` and proportional
loading ``T/N = c u_t/u_n`` (Eqs. norm, tang, prop) directly in the angle ``beta_L``: the torque
balance ``T_L = T_R`` is linear in ``upsilon``, and the horizontal balance is then one monotone
equation in ``beta_L`` (or in ``e = pi/2 - gamma - beta_L`` near the symmetric state), bracketed
and solved by the Illinois method. Rolling sliding solves ``N_L/N_R = (sin beta_L /
sin beta_R)^(3/2)`` for ``beta_L`` the same way. It shares no code and no reduction with the
solver (which eliminates everything in favour of ``w = sqrt(sin beta_L / sin beta_R)``); besides
the balance equations it uses only ``sin(pi - x) = sin x`` and two sum-to-product identities,
``cos theta_R - cos theta_L = 2 sin gamma sin delta`` and ``cos beta_L + cos beta_R =
2 sin gamma sin(beta_L + gamma)``, which remove the cancellations of order ``gamma^2`` near the
origin. It raises its working precision by what the remaining equations cancel (near the
symmetric state), so that every returned quantity carries at least 50 correct digits, which
:func:`test_reference_is_converged` checks by recomputing with 30 more digits.
"""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from groove_model.model.equilibrium import double_rolling_state, solve_equilibrium
from groove_model.model.parameters import HALF_PI, Compliance, Parameters

DIGITS = 50
EPS = np.finfo(float).eps
TINY = 2.0**-1074

FIELDS_RELATIVE = ("beta_L", "beta_R", "T_over_N_L", "T_over_N_R", "N_L_over_N_R",
                   "n_L", "n_R", "t")
FIELDS_CONDITIONED = ("upsilon", "d_L", "d_R")


# --------------------------------------------------------------------------------------------
# The reference
# --------------------------------------------------------------------------------------------


def _angle(x: float):
    """The float as an exact mpf; the float nearest pi/2 stands for pi/2 (the domain edge)."""
    return mp.pi / 2 if x == HALF_PI else mp.mpf(x)


def _working_dps(gamma: float, delta: float) -> int:
    """Digits for the reference: 50 kept, 20 guard, plus what the equations cancel.

    Near the symmetric state the horizontal and torque balances are differences of terms of
    size ``sin gamma`` whose result is of size ``e sin gamma``, where the root
    ``e = (beta_R - beta_L)/2`` is at least about ``delta/(3 gamma)``; ``log10(gamma/delta) + 1``
    more digits keep 50 in ``e`` and ``upsilon``. Forming ``pi - 2 gamma`` near ``pi/2`` costs
    up to 16.
    """
    extra = 1 + max(0, math.ceil(math.log10(gamma) - math.log10(delta))) if delta > 0.0 else 0
    return DIGITS + 20 + 16 + extra


def _illinois(f, lo, hi, flo, fhi, rel):
    """Root of ``f`` on ``[lo, hi]`` (``flo, fhi`` of opposite signs) to relative width ``rel``."""
    side = 0
    for _ in range(2000):
        x = (lo * fhi - hi * flo) / (fhi - flo)
        if not lo < x < hi:
            x = (lo + hi) / 2
        fx = f(x)
        if fx == 0:
            return x
        if (fx > 0) == (fhi > 0):
            hi, fhi = x, fx
            if side == 1:
                flo /= 2
            side = 1
        else:
            lo, flo = x, fx
            if side == -1:
                fhi /= 2
            side = -1
        if hi - lo <= rel * abs(hi):
            return (lo + hi) / 2
    raise RuntimeError("reference root finder did not converge")


def _monotone_root(f, top, rel):
    """Root of a monotone ``f`` on ``[0, top]`` that may lie many decades below ``top``.

    The bracket is first narrowed geometrically (``[top 2^-2^j, top]``, then bisection in
    ``log x`` down to a factor 2), so a root of any magnitude costs a few dozen evaluations.
    """
    f0, ftop = f(mp.mpf(0)), f(top)
    if f0 == 0:
        return mp.mpf(0)
    if ftop == 0:
        return top
    assert (f0 > 0) != (ftop > 0), "reference: root not bracketed"
    hi, fhi, step = top, ftop, 1
    lo = top / 2
    flo = f(lo)
    while (flo > 0) == (fhi > 0):
        hi, fhi = lo, flo
        step *= 2
        lo = hi * mp.mpf(2) ** (-step)
        flo = f(lo)
    while hi / lo > 2:
        mid = mp.sqrt(lo * hi)
        fmid = f(mid)
        if (fmid > 0) == (fhi > 0):
            hi, fhi = mid, fmid
        else:
            lo, flo = mid, fmid
    return _illinois(f, lo, hi, flo, fhi, rel)


class _Geometry:
    """Angles and wall terms at one point ``(G, D)`` (mpf), at the working precision."""

    def __init__(self, G, D, c):
        self.G, self.D, self.c = G, D, mp.mpf(c)
        self.sin_tL, self.sin_tR = mp.sin(G + D), mp.sin(G - D)
        if G + D == mp.pi:  # theta_L = pi exactly (gamma = delta = pi/2): mp.sin(pi) is not 0
            self.sin_tL = mp.mpf(0)
        self.cos_diff = 2 * mp.sin(G) * mp.sin(D)  # cos theta_R - cos theta_L
        self.omega = mp.pi - 2 * G

    def walls(self, x, form):
        """``sin, cos`` of ``beta_L`` and ``beta_R = pi - 2 gamma - beta_L``, and the sum of the cosines.

        ``form = "b"``: ``x = beta_L`` (used where ``beta_L <= omega/4``); ``form = "e"``:
        ``x = e``, ``beta_L = pi/2 - gamma - e``, ``beta_R = pi/2 - gamma + e``. The sum
        ``cos beta_L + cos beta_R = 2 sin gamma sin(beta_L + gamma)`` (sum-to-product) is ``O(gamma^2)``
        near the origin, where the two cosines are +-1.
        """
        G = self.G
        if form == "b":
            return (mp.sin(x), mp.cos(x), mp.sin(2 * G + x), -mp.cos(2 * G + x),
                    2 * mp.sin(G) * mp.sin(G + x))
        return (mp.cos(G + x), mp.sin(G + x), mp.cos(G - x), mp.sin(G - x),
                2 * mp.sin(G) * mp.cos(x))

    def beta_L(self, x, form):
        return x if form == "b" else mp.pi / 2 - self.G - x


def _solve_beta(geo: _Geometry, residual, rel):
    """``(x, form)`` of the root of ``residual`` (increasing in ``beta_L``) on ``[0, omega/2]``."""
    quarter = geo.omega / 4
    if residual(geo.walls(quarter, "b")) >= 0:
        return _monotone_root(lambda x: residual(geo.walls(x, "b")), quarter, rel), "b"
    return _monotone_root(lambda x: -residual(geo.walls(x, "e")), quarter, rel), "e"


def _dr_reference(geo: _Geometry) -> dict:
    """Double rolling: torque (T_L = T_R) and horizontal balance, d_L = d_R = 0."""
    rel = mp.mpf(10) ** -(DIGITS + 10)

    def forces(walls):
        sb, cb, sB, cB, cos_sum = walls
        qL, qR = mp.sqrt(sb), mp.sqrt(sB)
        # Torque: c qL (cb + u) = c qR (cB - u), linear in u.
        upsilon = (qR * cB - qL * cb) / (qL + qR)
        t = geo.c * qL * qR * cos_sum / (qL + qR)  # = c qL (cb + u)
        return upsilon, t, sb * qL, sB * qR

    def horizontal(walls):  # paper Eq. 2: N_L sin tL - N_R sin tR + T (cos tR - cos tL)
        _, t, nL, nR = forces(walls)
        return nL * geo.sin_tL - nR * geo.sin_tR + t * geo.cos_diff

    x, form = (mp.mpf(0), "e") if geo.D == 0 else _solve_beta(geo, horizontal, rel)
    upsilon, t, nL, nR = forces(geo.walls(x, form))
    beta_L = geo.beta_L(x, form)
    return dict(beta_L=beta_L, beta_R=geo.omega - beta_L, upsilon=upsilon, d_L=mp.mpf(0),
                d_R=mp.mpf(0), T_over_N_L=t / nL if nL else mp.inf, T_over_N_R=t / nR,
                N_L_over_N_R=nL / nR, n_L=nL, n_R=nR, t=t)


def _rs_reference(geo: _Geometry, k) -> dict:
    """Rolling sliding: T = k N_L, horizontal balance, right wall rolling, left wall's slip."""
    k = mp.mpf(k)
    rel = mp.mpf(10) ** -(DIGITS + 10)
    # Horizontal balance with T = k N_L: N_L (sin tL + k (cos tR - cos tL)) = N_R sin tR.
    ratio = geo.sin_tR / (geo.sin_tL + k * geo.cos_diff)
    if geo.omega == 0:  # closed groove: the limit gamma -> pi/2 (beta -> 0, cos beta -> 1)
        return dict(beta_L=mp.mpf(0), beta_R=mp.mpf(0), upsilon=mp.mpf(1), d_L=mp.mpf(2),
                    d_R=mp.mpf(0), T_over_N_L=k, T_over_N_R=k * ratio, N_L_over_N_R=ratio,
                    n_L=mp.mpf(0), n_R=mp.mpf(0), t=mp.mpf(0))

    def load_share(walls):  # (sin beta_L)^(3/2) - (N_L/N_R) (sin beta_R)^(3/2), increasing
        sb, _, sB, _, _ = walls
        return sb * mp.sqrt(sb) - ratio * sB * mp.sqrt(sB)

    x, form = (mp.mpf(0), "e") if geo.D == 0 else _solve_beta(geo, load_share, rel)
    sb, cb, sB, cB, cos_sum = geo.walls(x, form)
    mu = k * ratio  # T / N_R
    upsilon = cB - mu * sB / geo.c  # right wall rolls: mu = c (cos beta_R - upsilon)/sin beta_R
    # Left wall slides: k = c (cos beta_L + upsilon - d_L)/sin beta_L, with cb + cB = cos_sum.
    d_L = cos_sum - (mu * sB + k * sb) / geo.c
    nL, nR = sb * mp.sqrt(sb), sB * mp.sqrt(sB)
    beta_L = geo.beta_L(x, form)
    return dict(beta_L=beta_L, beta_R=geo.omega - beta_L, upsilon=upsilon, d_L=d_L,
                d_R=mp.mpf(0), T_over_N_L=k, T_over_N_R=mu, N_L_over_N_R=ratio, n_L=nL,
                n_R=nR, t=k * nL)


def _ds_reference(geo: _Geometry, k) -> dict:
    """Double sliding on delta = 0: the symmetric state with T = k N on both walls."""
    k = mp.mpf(k)
    cos_g = mp.mpf(0) if geo.omega == 0 else mp.cos(geo.G)  # mp.cos(pi/2) is not 0
    slip = mp.sin(geo.G) - k * cos_g / geo.c
    n = cos_g * mp.sqrt(cos_g)
    beta = mp.pi / 2 - geo.G
    return dict(beta_L=beta, beta_R=beta, upsilon=mp.mpf(0), d_L=slip, d_R=slip,
                T_over_N_L=k, T_over_N_R=k, N_L_over_N_R=mp.mpf(1), n_L=n, n_R=n, t=k * n)


_STATE = {"double_rolling": lambda geo, k: _dr_reference(geo),
          "rolling_sliding": _rs_reference,
          "double_sliding": _ds_reference}


def reference_states(gamma: float, delta: float, k: float, c: float = 1.0,
                     extra_digits: int = 0) -> tuple[str, object, dict]:
    """``(regime, margin, states)`` in mpf at the working precision (see :func:`reference`)."""
    with mp.workdps(_working_dps(gamma, delta) + extra_digits):
        geo = _Geometry(_angle(gamma), _angle(delta), c)
        closed = geo.omega == 0
        names = [] if closed else ["double_rolling"]
        names.append("double_sliding" if delta == 0.0 else "rolling_sliding")
        states = {name: _STATE[name](geo, k) for name in names}
        if closed:
            margin = mp.mpf(-1)
        elif delta == 0.0:
            # The solver decides on the axis by the angle: gamma <= arctan(k/c).
            margin = (mp.atan(mp.mpf(k) / c) - geo.G) / geo.G
        else:
            margin = 1 - states["double_rolling"]["T_over_N_L"] / k
            # The regimes exclude each other: rolling sliding's d_L has the opposite sign.
            d_L = states["rolling_sliding"]["d_L"]
            assert margin * d_L <= 0 or min(abs(margin), abs(d_L)) < 1e-40, (margin, d_L)
        regime = names[0] if margin >= 0 else names[-1]
        return regime, margin, states


def reference(gamma: float, delta: float, k: float, c: float = 1.0) -> dict:
    """The reference equilibrium at one point, every field with at least 50 correct digits.

    Returns
    -------
    dict
        ``regime``; ``margin``, the signed relative distance to the regime boundary (``>= 0``:
        double rolling): ``1 - (T/N_L of double rolling)/k`` off the axis, and
        ``(arctan(k/c) - gamma)/gamma`` on ``delta = 0``; ``states``: the state (floats rounded
        from mpf) of each regime that exists at the point.
    """
    regime, margin, states = reference_states(gamma, delta, k, c)
    return dict(regime=regime, margin=float(margin),
                states={name: {key: float(v) for key, v in st.items()}
                        for name, st in states.items()})


def sensitivity(gamma: float, delta: float, k: float, regime: str, name: str,
                c: float = 1.0) -> float:
    """How much field ``name`` of ``regime``'s state moves under unit relative input changes.

    ``min(|gamma df/dgamma| + |delta df/ddelta|, |theta_L df/dtheta_L| + |theta_R df/dtheta_R|)``:
    a relative rounding of the inputs moves the field by ``eps`` times this, so it is the error
    floor of an algorithm that rounds at the level of its inputs, and the absolute scale of a
    field that crosses zero inside the domain (``upsilon`` on the no-roll lines, ``d_L`` at the
    regime boundary). Both input pairs are natural (the walls' angles, or the groove's opening
    and tilt); the smaller of the two keeps the measure tight near ``delta = 0`` (where a
    relative change of ``theta_L`` is a large one of ``delta``) and near ``delta = gamma``
    (where a relative change of ``gamma`` is a large one of ``theta_R``). Forward differences
    with relative steps of ``1e-20`` on the exact inputs, at 25 more digits.
    """
    G, D = _angle(gamma), _angle(delta)
    if G == mp.pi / 2:
        return 0.0  # closed groove: the limit state is constant
    with mp.workdps(_working_dps(gamma, delta) + 25):
        G, D, h = _angle(gamma), _angle(delta), mp.mpf(10) ** -20
        base = _STATE[regime](_Geometry(G, D, c), k)[name]

        def moved(dG, dD):
            return abs(_STATE[regime](_Geometry(G + dG, D + dD, c), k)[name] - base) / h

        # Steps that stay in the domain: gamma and theta_L up, delta and theta_R down.
        tL, tR = G + D, G - D
        by_gamma_delta = moved(h * G, 0) + moved(0, -h * D)
        by_thetas = moved(h * tL / 2, h * tL / 2) + moved(-h * tR / 2, h * tR / 2)
        return float(min(by_gamma_delta, by_thetas))


# --------------------------------------------------------------------------------------------
# The comparison
# --------------------------------------------------------------------------------------------

# Measured worst errors (2400 points over all scales of gamma) are 11 eps, in
# n_L = sin(beta_L)^(3/2); 32 eps leaves room for points not sampled. Subnormal results carry absolute rounding errors of
# a few subnormal spacings (each product that lands below 2^-1022 rounds on the subnormal grid).
RTOL = 32.0 * EPS
ATOL = 16.0 * TINY


def assert_matches_reference(gamma: float, delta: float, k: float, c: float = 1.0) -> None:
    """Regime, rotation and every field of the solver against the reference at one point.

    A regime or rotation may differ from the reference's only where the reference's distance to
    that boundary is within the tolerance of the quantity that decides it: ``|margin| <= RTOL``
    for the regime (the solver compares ``T/N_L``, accurate to ``RTOL``, with ``k``), and
    ``|upsilon| <= RTOL (|upsilon| + sensitivity)`` for the rotation. Fields are then compared
    with the reference state of the regime the solver chose (at the boundary the two agree).
    """
    eq = solve_equilibrium(gamma, delta, Parameters(k, Compliance(c)))
    ref = reference(gamma, delta, k, c)
    where = f"at gamma = {gamma!r}, delta = {delta!r}, k = {k!r}, c = {c!r}"
    if eq.regime != ref["regime"]:
        assert abs(ref["margin"]) <= RTOL, (
            f"regime {eq.regime}, reference {ref['regime']} (margin {ref['margin']:.3g}) {where}")
    assert eq.regime in ref["states"], f"regime {eq.regime} does not exist {where}"
    state = ref["states"][eq.regime]

    def scale(name):
        return sensitivity(gamma, delta, k, eq.regime, name, c)

    for name in FIELDS_RELATIVE + FIELDS_CONDITIONED:
        got, want = getattr(eq, name), state[name]
        if math.isinf(want):
            assert got == want, f"{name} = {got!r}, reference {want!r} {where}"
            continue
        err = abs(got - want)
        if err <= RTOL * abs(want) + ATOL:
            continue
        # Only fields that cross zero get the conditioning allowance (computed only when needed).
        assert name in FIELDS_CONDITIONED and err <= RTOL * (abs(want) + scale(name)) + ATOL, (
            f"{name} = {got!r}, reference {want!r}, error {err / max(abs(want), TINY):.3g} "
            f"relative {where}")
    u = state["upsilon"]
    expected = "clockwise" if u < 0 else "counterclockwise" if u > 0 else "none"
    if eq.rotation != expected:
        assert abs(u) <= RTOL * (abs(u) + scale("upsilon")) + ATOL, (
            f"rotation {eq.rotation}, reference {expected} (upsilon {u!r}) {where}")


# --------------------------------------------------------------------------------------------
# Tests
# --------------------------------------------------------------------------------------------


def _ratio_strategy():
    """``delta/gamma``: uniform on [0, 1] (both ends included), plus both edges approached
    geometrically (the reference's cost grows with ``log10(gamma/delta)``, so not below 1e-30;
    subnormal ``delta`` is in :func:`test_subnormal_delta`)."""
    return st.one_of(
        st.integers(0, 2**53).map(lambda i: i / 2**53),
        st.floats(-30.0, -1.0).map(lambda e: 10.0**e),  # near delta = 0
        st.floats(-16.0, -1.0).map(lambda e: 1.0 - 10.0**e),  # near delta = gamma
    )


@settings(max_examples=100, deadline=None)
@given(log_gamma=st.floats(-300.0, math.log10(HALF_PI)), ratio=_ratio_strategy(),
       log_k=st.floats(-4.0, 6.0))
@example(log_gamma=math.log10(HALF_PI), ratio=0.5, log_k=0.0)  # the closed groove
@example(log_gamma=-300.0, ratio=1.0, log_k=-4.0)
def test_solver_matches_the_reference(log_gamma, ratio, log_k):
    gamma = min(10.0**log_gamma, HALF_PI)
    assert_matches_reference(gamma, ratio * gamma, 10.0**log_k)


# The three failures of the previous solver, each checked to fail against it.


@pytest.mark.parametrize("gamma", [1e-310, 3e-318, 5e-324])
@pytest.mark.parametrize("ratio", [0.0, 0.25, 0.5, 0.9, 1.0])
def test_subnormal_gamma(gamma, ratio):
    """Subnormal gamma: the double-rolling state exists (it was NaN, and the regime wrong)."""
    delta = ratio * gamma
    dr = double_rolling_state(gamma, delta, Parameters(1.0))
    assert all(np.isfinite(dr[name]) for name in ("beta_L", "upsilon", "T_over_N_R")), dr
    for k in (1e-4, 1.0, 1e6):
        assert_matches_reference(gamma, delta, k)


@pytest.mark.parametrize("gamma", [1e-3, 1e-8, 1e-12, 1e-100, 1e-300])
def test_beta_L_near_the_origin_is_exact(gamma):
    """beta_L and T/N_L keep their relative accuracy as gamma -> 0 (the error was 1e-16/gamma)."""
    eq = solve_equilibrium(gamma, 0.5 * gamma, 1.0)
    ref = reference(gamma, 0.5 * gamma, 1.0)["states"]["double_rolling"]
    assert abs(eq.beta_L - ref["beta_L"]) <= RTOL * ref["beta_L"]
    assert abs(eq.T_over_N_L - ref["T_over_N_L"]) <= RTOL * ref["T_over_N_L"]
    assert_matches_reference(gamma, 0.5 * gamma, 1.0)


def test_regime_near_gamma_1p6e_12():
    """Rolling sliding by a wide margin (T/N_L = 2.5 k), once classified as double rolling."""
    gamma, delta, k = 1.6e-12, 1.5999999999984e-12, 1e-4
    ref = reference(gamma, delta, k)
    assert ref["regime"] == "rolling_sliding" and ref["margin"] < -1.0
    assert solve_equilibrium(gamma, delta, k).regime == "rolling_sliding"
    assert_matches_reference(gamma, delta, k)


# Edges and special points of the domain.

_K_SPECIAL = [1e-4, 0.5, 1.0, math.sqrt(2.0), 10.0, 1e6]


@pytest.mark.parametrize("k", [1e-4, 1.0, 1e6])
@pytest.mark.parametrize("gamma", [1e-200, 1e-9, 0.3, math.pi / 4, 1.2, HALF_PI - 1e-9,
                                   np.nextafter(HALF_PI, 0.0), HALF_PI])
def test_edges_delta_zero_and_delta_gamma(gamma, k):
    for delta in (0.0, gamma * 1e-20, gamma * (1.0 - 1e-12), np.nextafter(gamma, 0.0), gamma):
        assert_matches_reference(float(gamma), float(delta), k)


@pytest.mark.parametrize("k", _K_SPECIAL)
def test_special_points(k):
    """The seeds named by the paper, approached from both sides where they are points."""
    gamma_limit = math.atan(k)
    points = [(gamma_limit, 0.0), (math.atan(math.sqrt(2.0)), 0.0),
              (math.pi / 4, math.pi / 4), (math.pi / 4, math.pi / 4 * (1 - 1e-9)),
              (HALF_PI, HALF_PI), (HALF_PI, 0.0), (HALF_PI, 1.0), (0.0, 0.0)]
    for g in (gamma_limit, math.atan(math.sqrt(2.0))):
        points += [(np.nextafter(g, 0.0), 0.0), (np.nextafter(g, 2.0), 0.0),
                   (g, 1e-12 * g), (g, 1e-3 * g)]
    for gamma, delta in points:
        if gamma == 0.0:
            eq = solve_equilibrium(0.0, 0.0, k)  # the origin: the symmetric limit
            assert (eq.regime, eq.rotation, eq.beta_L, eq.upsilon) == (
                "double_rolling", "none", HALF_PI, 0.0)
            continue
        assert_matches_reference(float(gamma), float(delta), k)


def test_subnormal_delta():
    """The smallest tilt: upsilon ~ 1e-324 keeps its sign (relative accuracy near delta = 0)."""
    for gamma, delta in [(1.0, 5e-324), (1e-300, 5e-324)]:
        assert_matches_reference(gamma, delta, 1.0)
    # Off the axis near delta = 0 the ball rolls clockwise below arctan sqrt 2, counter-clockwise
    # above (paper, "Rolling solutions").
    assert solve_equilibrium(0.9, 1e-310, 10.0).rotation == "clockwise"
    assert solve_equilibrium(1.0, 1e-310, 10.0).rotation == "counterclockwise"


@pytest.mark.parametrize("c", [0.6, 1.7])
def test_other_compliance_ratios(c):
    for gamma, delta, k in [(0.6, 0.2, 1.0), (1e-12, 5e-13, 1e-4), (1.2, 1.1, 10.0),
                            (1e-250, 1e-250 * (1 - 1e-15), 1e-4), (0.9, 1e-30, 0.3)]:
        assert_matches_reference(gamma, delta, k, c)


def test_reference_is_converged():
    """The reference's 50 digits: 30 more working digits change no field beyond 1e-50."""
    for gamma, delta, k in [(0.6, 0.2, 1.0), (1e-300, 0.5e-300, 1e-4), (1.0, 1e-40, 10.0),
                            (1e-12, 1e-12 * (1 - 1e-15), 1e-4), (HALF_PI - 1e-15, 0.7, 3.0)]:
        regime, margin, states = reference_states(gamma, delta, k)
        regime2, margin2, states2 = reference_states(gamma, delta, k, extra_digits=30)
        assert regime == regime2
        with mp.workdps(80):
            for name, state in states.items():
                for field, value in state.items():
                    other = states2[name][field]
                    if mp.isinf(value):
                        assert other == value
                        continue
                    assert abs(value - other) <= mp.mpf(10) ** -DIGITS * abs(other), (
                        name, field, value, other)
