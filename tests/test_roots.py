"""The numpy Chandrupatla root finder against scipy's ``elementwise.find_root``."""

import numpy as np
import pytest
from scipy.optimize import elementwise

from groove_model.model import equilibrium
from groove_model.model.roots import chandrupatla

TOL = dict(xatol=2.0 * np.finfo(float).smallest_subnormal, xrtol=2.0 * np.finfo(float).eps)


def _double_rolling_brackets(n: int, seed: int):
    """Arguments of the double-rolling equation at random points, down to subnormal gamma."""
    rng = np.random.default_rng(seed)
    gamma = np.concatenate([rng.uniform(0.0, 0.5 * np.pi, n), 10.0 ** rng.uniform(-320, 0, n)])
    delta = gamma * np.concatenate([rng.uniform(0.0, 1.0, n), 1.0 - 10.0 ** rng.uniform(-17, 0, n)])
    walls = equilibrium.wall_terms(gamma, delta)
    K, rho0 = walls["E"] * walls["tan_g"], walls["rho0"]
    keep = (delta > 0.0) & (walls["cos_g"] > 0.0) & (rho0 > 0.0)
    upper = (rho0[keep] > 0.125 + 5.0 / 12.0 * K[keep]).astype(float)
    return upper, rho0[keep], walls["one_minus_rho0"][keep], K[keep]


def test_same_roots_as_scipy_to_the_last_bit():
    args = _double_rolling_brackets(20000, seed=7)
    lo, hi = np.zeros(args[0].shape), np.full(args[0].shape, 0.5)
    ref = elementwise.find_root(equilibrium.double_rolling_equation, (lo, hi), args=args,
                                tolerances=dict(fatol=0.0, frtol=0.0, **TOL))
    mine = chandrupatla(equilibrium.double_rolling_equation, lo, hi, args=args, **TOL)
    assert np.all(ref.success)
    np.testing.assert_array_equal(mine, ref.x)


def test_polynomial_roots_and_exact_zeros():
    c = np.array([2.0, 3.0, 5.0, 0.0])
    x = chandrupatla(lambda x, c: x**3 - c, np.zeros(4), np.full(4, 2.0), args=(c,), **TOL)
    np.testing.assert_allclose(x, np.cbrt(c), rtol=4e-16, atol=0.0)
    assert x[-1] == 0.0


@pytest.mark.parametrize("lo, hi", [(1.0, 2.0), (np.nan, 2.0)])
def test_no_sign_change_or_nan_gives_nan(lo, hi):
    x = chandrupatla(lambda x: x * x + 1.0, np.array([lo]), np.array([hi]), **TOL)
    assert np.isnan(x[0])
