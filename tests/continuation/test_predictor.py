"""The predictor reproduces polynomials of its degree exactly."""

from types import SimpleNamespace

import numpy as np
import pytest

from continuation.predictor import extrapolate

rng = np.random.default_rng(7)


def _node(coefficients, s):
    """A node of the polynomial curve sum_k c_k s^k (its tangent need not be a unit vector)."""
    powers = np.arange(len(coefficients))
    x = (s ** powers) @ coefficients
    derivative = (powers[1:] * s ** (powers[1:] - 1)) @ coefficients[1:]
    return SimpleNamespace(x=x, s=s, tangent=derivative)


@pytest.mark.parametrize("stations, degree, h, order", [
    ((0.0, 0.3, 0.5), 5, 0.35, 6),   # quintic Hermite through three nodes
    ((0.3, 0.5), 3, 0.35, 4),        # cubic Hermite arc of the last step
    ((0.4, 0.5), 2, 0.5, 3),         # far beyond the last span: its quadratic Taylor part
])
def test_extrapolation_is_exact_on_polynomials_of_its_degree(stations, degree, h, order):
    coefficients = rng.normal(size=(degree + 1, 4))
    nodes = [_node(coefficients, s) for s in stations]
    x_pred, border, got_order = extrapolate(nodes, h)
    expected = _node(coefficients, stations[-1] + h)
    assert got_order == order
    assert x_pred == pytest.approx(expected.x, abs=1e-12)
    assert border == pytest.approx(expected.tangent / np.linalg.norm(expected.tangent), abs=1e-12)


def test_quintic_prediction_error_falls_as_h_to_the_sixth():
    # the unit circle by arclength; nodes one span h apart, prediction h ahead
    def node(s):
        return SimpleNamespace(x=np.array([np.cos(s), np.sin(s)]), s=s,
                               tangent=np.array([-np.sin(s), np.cos(s)]))
    errors = []
    for h in (0.2, 0.1):
        x_pred, _, _ = extrapolate([node(0.0), node(h), node(2 * h)], h)
        errors.append(np.linalg.norm(x_pred - node(3 * h).x))
    assert 2 ** 5.5 < errors[0] / errors[1] < 2 ** 6.5
