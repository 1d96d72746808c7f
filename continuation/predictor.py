"""The predictor: Hermite arcs through accepted curve points.

A curve point with its unit tangent is a Hermite node. The cubic Hermite arc
between two nodes predicts points inside a step (for the locators and dense
output); the interpolant of the last two or three accepted nodes, extrapolated,
predicts the next step (:func:`extrapolate`). :func:`arc_length` measures a step.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from .linalg import norm

__all__ = ["arc_length", "extrapolate", "hermite", "tangent_beyond"]


def hermite(x_a, t_a, x_b, t_b, h, sigma):
    """Cubic Hermite arc between two curve points and its derivative.

    Parameters
    ----------
    x_a, x_b : ndarray, shape (n + 1,)
        End points, ``h`` apart in pseudo-arclength.
    t_a, t_b : ndarray, shape (n + 1,)
        Unit tangents (derivatives with respect to arclength) at the ends.
    h : float
        Pseudo-arclength between the ends.
    sigma : float
        Pseudo-arclength from ``x_a``, ``0 <= sigma <= h``.

    Returns
    -------
    point, derivative : ndarray, shape (n + 1,)
        ``p(sigma)`` and ``p'(sigma)``; ``|p - x(s_a + sigma)| = O(h^4)``.

    Notes
    -----
    ``p = h00 x_a + h10 h t_a + h01 x_b + h11 h t_b`` with the cubic Hermite
    basis of ``u = sigma / h`` (de Boor, *A Practical Guide to Splines*).
    """
    u = sigma / h
    u2 = u * u
    u3 = u2 * u
    point = ((2 * u3 - 3 * u2 + 1) * x_a + (u3 - 2 * u2 + u) * h * t_a
             + (-2 * u3 + 3 * u2) * x_b + (u3 - u2) * h * t_b)
    derivative = ((6 * u2 - 6 * u) / h * x_a + (3 * u2 - 4 * u + 1) * t_a
                  + (-6 * u2 + 6 * u) / h * x_b + (3 * u2 - 2 * u) * t_b)
    return point, derivative


def extrapolate(nodes: Sequence, h: float):
    """Prediction ``h`` beyond the last node on the Hermite interpolant of the nodes.

    Parameters
    ----------
    nodes : sequence of objects with ``x``, ``s`` and ``tangent``
        Two or three accepted curve points, oldest first.
    h : float
        Arclength beyond the last node.

    Returns
    -------
    x_pred : ndarray
        The predicted point.
    border : ndarray
        The unit tangent of the interpolant there (the border row of the corrector).
    order : int
        The order of the prediction error.

    Notes
    -----
    With ``m`` nodes ``(s_j, x_j, t_j)``, the last one ``b``, and the variable
    ``sigma = (s - s_b) / H`` (``H`` the last span, nodes at ``z_j``), the
    interpolant of degree ``2m - 1`` matching every ``x_j`` and ``t_j`` is

    .. math::

        p(\\sigma) = \\sum_j \\left[1 - 2 L_j'(z_j) (\\sigma - z_j)\\right]
                     L_j(\\sigma)^2 \\, x_j
                   + (\\sigma - z_j) L_j(\\sigma)^2 \\, H t_j,

    with the Lagrange polynomials ``L_j`` of the nodes (the Hermite basis,
    e.g. Stoer & Bulirsch, *Introduction to Numerical Analysis*, sec. 2.1.5).
    Its weights at ``sigma = u = h / H``, and those of ``p'(u)``, are a few
    scalar products and sums, so the prediction is one small matrix product
    with the node vectors. With two nodes this is the cubic Hermite arc of
    the last step (order 4), with three the quintic (order 6). Beyond twice
    the last span (``u > 2``) the node errors would be amplified as
    ``u^(2m-1)``: only the quadratic Taylor part of the last step's cubic at
    ``b`` is kept, ``x_b + h t_b + h^2 c / 2`` with
    ``c = 6 (x_a - x_b) / H^2 + (2 t_a + 4 t_b) / H`` (order 3).
    """
    b = nodes[-1]
    span = b.s - nodes[-2].s
    u = h / span
    if u > 2.0:
        a = nodes[-2]
        q = 3.0 * u * u
        weights = ([1.0 - q, h + 2.0 * span * u * u, q, span * u * u],
                   [-6.0 * u / span, 1.0 + 4.0 * u, 6.0 * u / span, 2.0 * u])
        vectors = [b.x, b.tangent, a.x, a.tangent]
        order = 3
    else:
        z = [(node.s - b.s) / span for node in nodes]
        values, slopes, vectors = [], [], []
        for j, node in enumerate(nodes):
            # L_j(u), L_j'(u) / L_j(u) and L_j'(z_j) from the other nodes
            lagrange, log_slope, at_node = 1.0, 0.0, 0.0
            for i, z_i in enumerate(z):
                if i != j:
                    lagrange *= (u - z_i) / (z[j] - z_i)
                    log_slope += 1.0 / (u - z_i)
                    at_node += 1.0 / (z[j] - z_i)
            offset = u - z[j]
            square = lagrange * lagrange
            d_square = 2.0 * square * log_slope
            values += [(1.0 - 2.0 * at_node * offset) * square, span * offset * square]
            slopes += [-2.0 * at_node * square + (1.0 - 2.0 * at_node * offset) * d_square,
                       span * (square + offset * d_square)]
            vectors += [node.x, node.tangent]
        weights = (values, slopes)
        order = 2 * len(nodes)
    x_pred, border = np.array(weights) @ np.array(vectors)
    return x_pred, border / norm(border), order


def tangent_beyond(a, b, h: float) -> np.ndarray:
    """The unit tangent of the cubic Hermite arc through the nodes ``a`` and ``b`` (objects with
    ``x``, ``s`` and ``tangent``, ``a`` first), extrapolated ``h`` beyond ``b``.

    What the last step predicts for the tangent at the end of the next one: on a smooth curve
    it differs from the tangent there by the interpolant's error, a small part of the turn the
    step control allows; a step that landed on another branch has the crossing angle between
    them (:meth:`continuation.scan.StepScan.det_clear`). ``p'`` of :func:`hermite` at
    ``u = 1 + h / (s_b - s_a)``, three vector operations.
    """
    span = b.s - a.s
    u = 1.0 + h / span
    derivative = (((6.0 * u - 6.0) * u / span) * (a.x - b.x)
                  + ((3.0 * u - 4.0) * u + 1.0) * a.tangent + ((3.0 * u - 2.0) * u) * b.tangent)
    return derivative / norm(derivative)


def arc_length(chord: np.ndarray, alpha: float) -> float:
    """Arclength of a step from its chord and the angle between its end tangents.

    ``|chord| (alpha / 2) / sin(alpha / 2)``: exact on a circular arc, with an
    error ``O(h^5)`` on a smooth curve; the pseudo-arclength ``h`` itself is
    off by ``O(h^3)``.
    """
    length = math.sqrt(float(chord @ chord))
    half = 0.5 * alpha
    return length * half / math.sin(half) if half > 1e-8 else length
