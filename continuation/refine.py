"""The points :func:`continuation.certify` proves: the caller's curve with repeated points
merged and, where a segment's tube cannot be proven, points of the arc inserted; the map
back to the caller's indices, in which the certificate names points and segments.

A traced curve's steps follow its own accuracy, not the tubes': where the curve bends on a
scale far below its step (a boundary near a corner at large friction), Krawczyk's operator
does not contract on any tube around the cubic between two points, however short the piece.
A point of the arc at the middle of such a segment (Newton's method on the slice there, in
floats; its distance from the arc is then proven like any point's) halves the segment and
the error of the cubic through it by about 16.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from .krawczyk import Frame, kernel
from .numbers import FLOATS
from .result import Curve

__all__ = ["Points", "merge_duplicates"]


def merge_duplicates(curve: Curve, tolerance: float) -> tuple[Curve, list]:
    """The curve without points that repeat the last point kept (special points located
    twice at one place) and the kept rows; their special points move to the kept point.

    A point is dropped if it is within ``tolerance (1 + |x|)`` of the last point kept (not of
    the point before it: a chain of such steps may drift). Returns the curve and the indices
    of the kept rows in the given curve.
    """
    x = np.asarray(curve.x, float)
    kept = [0] if len(x) else []
    for i in range(1, len(x)):
        step = float(np.max(np.abs(x[i] - x[kept[-1]])))
        if not step <= tolerance * (1.0 + float(np.max(np.abs(x[i])))):
            kept.append(i)
    if len(kept) == len(x):
        return curve, kept
    keep = np.array(kept)
    new_index = np.searchsorted(keep, np.arange(len(x)), side="right") - 1
    points = tuple(dataclasses.replace(p, index=int(new_index[p.index]))
                   for p in curve.special_points)
    return dataclasses.replace(curve, x=curve.x[keep], s=curve.s[keep],
                               tangents=curve.tangents[keep], ds=curve.ds[keep],
                               newton_iterations=curve.newton_iterations[keep],
                               residuals=curve.residuals[keep],
                               special_points=points), keep.tolist()


def _on_slice(problem, frame: Frame, tau: float, iterations: int = 40):
    """The zero of ``H`` on the slice ``tau`` of ``frame`` near its centerline (Newton's
    method in floats, in the offsets along the frame's axes), or ``None``."""
    axes = list(frame.axes)
    x = np.array(frame.tube_box(tau, [0.0] * len(axes)), float)
    for _ in range(iterations):
        H = np.array(problem.residual(list(x), FLOATS), float)
        J = np.array([[float(v) for v in row] for row in problem.jacobian(list(x), FLOATS)])
        try:
            step = np.linalg.solve(J[:, axes], -H)
        except np.linalg.LinAlgError:
            return None
        if not np.all(np.isfinite(step)):
            return None
        x[axes] += step
        if np.max(np.abs(step)) <= 1e-15 * (1.0 + np.max(np.abs(x))):
            return x
    return x if np.max(np.abs(step)) <= 1e-12 * (1.0 + np.max(np.abs(x))) else None


@dataclass
class Points:
    """The working curve, with the caller's index of each point (``None`` if inserted), the
    last of the caller's points merged into it (``None`` if inserted), and the number of
    halvings of each segment by inserted points."""

    curve: Curve
    origin: list
    last: list
    level: list

    @classmethod
    def of(cls, curve: Curve, tolerance: float) -> tuple[Points, list]:
        """The caller's curve with repeated points merged; and the merged rows."""
        merged, keep = merge_duplicates(curve, tolerance)
        dropped = sorted(set(range(len(curve.x))) - set(keep))
        last = [b - 1 for b in keep[1:]] + ([len(curve.x) - 1] if keep else [])
        return cls(merged, list(keep), last, [0] * max(len(keep) - 1, 0)), dropped

    @property
    def inserted(self) -> int:
        return sum(o is None for o in self.origin)

    def insert(self, s: int, frame: Frame, problem) -> bool:
        """Insert the point of the arc on the middle slice of segment ``s`` (whose frame is
        ``frame``); False if Newton's method does not find it."""
        x = _on_slice(problem, frame, 0.5 * frame.length)
        if x is None:
            return False
        J = [[float(v) for v in row] for row in problem.jacobian(list(x), FLOATS)]
        t = np.array(kernel(J), float)
        size = float(np.linalg.norm(t))
        if not (size > 0.0 and np.all(np.isfinite(t))):
            return False
        t /= size
        if float(np.dot(t, frame.v)) < 0.0:
            t = -t
        c = self.curve
        residual = float(np.max(np.abs(np.array(problem.residual(list(x), FLOATS), float))))
        s_mid = float(c.s[s]) + float(np.linalg.norm(x - c.x[s]))
        self.curve = dataclasses.replace(
            c, x=np.insert(c.x, s + 1, x, axis=0), s=np.insert(c.s, s + 1, s_mid),
            tangents=np.insert(c.tangents, s + 1, t, axis=0),
            ds=np.insert(c.ds, s + 1, s_mid - float(c.s[s])),
            newton_iterations=np.insert(c.newton_iterations, s + 1, 0),
            residuals=np.insert(c.residuals, s + 1, residual) if len(c.residuals) else
            c.residuals,
            special_points=tuple(dataclasses.replace(p, index=p.index + 1)
                                 if p.index > s else p for p in c.special_points))
        self.origin.insert(s + 1, None)
        self.last.insert(s + 1, None)
        level = self.level[s] + 1
        self.level[s:s + 1] = [level, level]
        return True

    def merged_distances(self, x, dropped, nodes, upper):
        """``(r, k, d)`` for each merged point ``r`` of the caller's points ``x``: ``k`` the
        caller's index of the point kept for it, ``d`` an upper bound (``upper`` of a ball) of
        its distance from that point's node box (``nodes``, one per point here)."""
        for r in dropped:
            j = max(i for i, o in enumerate(self.origin) if o is not None and o < r)
            yield r, self.origin[j], max(upper(b - float(v))
                                         for b, v in zip(nodes[j].box, x[r], strict=True))

    # -- the caller's indices -------------------------------------------------------------

    def segment_of(self, s: int) -> int:
        """The caller's segment holding segment ``s`` (or point ``s``): it starts at the last of
        the caller's points merged into the point before."""
        return next(o for o in reversed(self.last[:s + 1]) if o is not None)

    def point(self, i: int) -> str:
        o = self.origin[i]
        return f"point {o}" if o is not None else \
            f"a point inserted in segment {self.segment_of(i)}"

    def segment(self, s: int) -> str:
        """``segment S (points a to b)``, or of a part of a caller's segment."""
        a, b = self.last[s], self.origin[s + 1]
        if a is not None and b is not None:
            return f"segment {a} (points {a} to {b})"
        return f"segment {self.segment_of(s)} (a part between points inserted in it)"
