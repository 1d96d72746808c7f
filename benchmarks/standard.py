"""The engine's standard problems (cubic, circle) with ``ours`` and the Python peers.

Settings everywhere: tolerance 1e-10, initial step 0.05, maximum step 0.2.

* ``cubic``: ``u^3 - u - lambda = 0`` in ``x = (lambda, u)`` from ``lambda = -6`` (``u = -2``)
  to ``u = 2``, folds at ``(+-2/(3 sqrt 3), -+1/sqrt 3)``.
* ``circle``: ``x0^2 + x1^2 = 1``, one loop from ``(1, 0)``; folds at the four poles (the
  peers, which continue in a parameter, can see only the two folds in ``x1``).

Peers are imported inside their functions: one that is not installed or fails gives a record
with ``ok = False`` and the reason, never an exception.
"""

from __future__ import annotations

import contextlib
import io
import logging
import math

import numpy as np

from .records import Record, failed, timed

__all__ = ["CIRCLE_FOLDS", "CUBIC_FOLDS", "DS", "DS_MAX", "TOL", "run_standard"]

TOL, DS, DS_MAX = 1e-10, 0.05, 0.2
_FOLD = 2.0 / (3.0 * math.sqrt(3.0))
#: analytic folds, x = (lambda, u)
CUBIC_FOLDS = np.array([[_FOLD, -1.0 / math.sqrt(3.0)], [-_FOLD, 1.0 / math.sqrt(3.0)]])
#: analytic folds of the circle in x0 (at (0, +-1)) and in x1 (at (+-1, 0))
CIRCLE_FOLDS = np.array([[0.0, 1.0], [-1.0, 0.0], [0.0, -1.0], [1.0, 0.0]])
#: folds visible to a tool continuing in the parameter x1 with state x0


def cubic_residual(x):
    return np.array([x[1] ** 3 - x[1] - x[0]])


def cubic_jacobian(x):
    return np.array([[-1.0, 3.0 * x[1] ** 2 - 1.0]])


def circle_residual(x):
    return np.array([x[0] ** 2 + x[1] ** 2 - 1.0])


def circle_jacobian(x):
    return np.array([[2.0 * x[0], 2.0 * x[1]]])


def fold_error(located, expected) -> tuple[float | None, int]:
    """Largest coordinate error of located folds against the analytic ones, and how many of
    the expected folds were found (each matched to its nearest located fold within 1e-3)."""
    located = np.asarray(located, dtype=float).reshape(-1, expected.shape[1])
    if not located.size:
        return None, 0
    found, worst = 0, 0.0
    for point in expected:
        errors = np.max(np.abs(located - point), axis=1)
        if errors.min() <= 1e-3:
            found += 1
            worst = max(worst, float(errors.min()))
    return (worst if found else None), found


# --------------------------------------------------------------------------- ours

def _ours(problem: str, repeats: int) -> Record:
    from continuation import Options, Problem, box_events, trace

    if problem == "cubic":
        cubic = Problem(cubic_residual, cubic_jacobian, names=("lambda", "u"))
        options = Options(tol=TOL, ds=DS, ds_max=DS_MAX, fold_coordinates=(0,))
        events = box_events(upper={1: 2.0})

        def run():
            return trace(cubic, [-6.0, -2.0], direction=(1.0, 0.0), options=options,
                         events=events)
        expected = CUBIC_FOLDS
    else:
        circle = Problem(circle_residual, circle_jacobian)
        options = Options(tol=TOL, ds=DS, ds_max=DS_MAX, fold_coordinates=(0, 1))

        def run():
            return trace(circle, [1.0, 0.0], options=options)
        expected = CIRCLE_FOLDS
    wall, curve = timed(run, repeats)
    folds = [p.x for p in curve.special("fold")]
    error, found = fold_error(folds, expected)
    ok = curve.ok and found == len(expected) and error is not None and error <= 1e-10
    return Record(problem, "ours", wall, len(curve), curve.residual_evals, curve.jacobian_evals,
                  curve.max_residual, error, ok,
                  f"status {curve.status.name}; {found}/{len(expected)} folds; "
                  f"{curve.rejected_steps} rejected steps")


# --------------------------------------------------------------------------- pycont-lite

class _Counter:
    def __init__(self, function):
        self.function = function
        self.calls = 0

    def __call__(self, *args):
        self.calls += 1
        return self.function(*args)


class _LoopDone(Exception):
    """Raised by the circle's residual once the trial points have gone once around."""


class _Winding:
    """Residual wrapper that stops a peer after one loop of the circle (accumulated angle)."""

    def __init__(self, function, angle_of):
        self.function = function
        self.angle_of = angle_of
        self.calls = 0
        self.last = None
        self.total = 0.0

    def __call__(self, *args):
        self.calls += 1
        angle = self.angle_of(*args)
        if self.last is not None:
            step = (angle - self.last + math.pi) % (2.0 * math.pi) - math.pi
            self.total += step
            if abs(self.total) >= 2.0 * math.pi:
                raise _LoopDone
        self.last = angle
        return self.function(*args)


def _pycont(problem: str, repeats: int) -> Record:
    try:
        import pycont
    except Exception as error:  # noqa: BLE001 - any import failure is a result
        return failed(problem, "pycont-lite", f"import failed: {error!r}")
    settings = {"tolerance": TOL, "analyze_stability": False, "initial_directions": "increase_p"}
    if problem == "cubic":
        # state u, parameter lambda; from (lambda, u) = (-6, -2) to lambda = 6 (u = 2)
        settings["param_max"] = 6.0
        counter = _Counter(lambda u, p: u ** 3 - u - p)
        u0, p0, n_steps = np.array([-2.0]), -6.0, 2000
        expected = CUBIC_FOLDS
    else:
        # state u = x0, parameter p = x1; folds in p are at (x0, x1) = (0, +-1)
        counter = _Winding(lambda u, p: u ** 2 + p ** 2 - 1.0,
                           lambda u, p: math.atan2(float(p), float(np.ravel(u)[0])))
        u0, p0, n_steps = np.array([1.0]), 0.0, 2000
        expected = CIRCLE_FOLDS[[0, 2]]

    def run():
        counter.calls = 0
        if isinstance(counter, _Winding):
            counter.last, counter.total = None, 0.0
        logging.getLogger("pycont").setLevel(logging.ERROR)
        try:
            with contextlib.redirect_stdout(io.StringIO()):
                result = pycont.arclengthContinuation(
                    counter, u0, p0, ds_min=1e-12, ds_max=DS_MAX, ds_0=DS, n_steps=n_steps,
                    solver_parameters=dict(settings), verbosity=pycont.Verbosity.OFF)
        except _LoopDone:
            return None, counter.calls
        return result, counter.calls

    try:
        wall, (result, calls) = timed(run, repeats)
    except Exception as error:  # noqa: BLE001
        return failed(problem, "pycont-lite", f"run failed: {error!r}")
    if result is None:
        return Record(problem, "pycont-lite", wall, 0, calls, 0, None, None, False,
                      "pycont-lite never stops on a closed curve: after one loop of the trial "
                      "points it was interrupted, its branches and fold events are lost; "
                      "residual evaluations include its finite-difference Jacobian-vector "
                      "products")
    points = [np.column_stack([b.p_path, b.u_path[:, 0]]) for b in result.branches]
    xs = np.vstack(points)  # (lambda, u) for the cubic, (x1, x0) for the circle
    if problem == "circle":
        xs = xs[:, ::-1]
    residual = float(np.max(np.abs([counter.function(x[1], x[0]) if problem == "cubic"
                                    else counter.function(x[0], x[1]) for x in xs])))
    folds = [(e.p, float(np.ravel(e.u)[0])) if problem == "cubic"
             else (float(np.ravel(e.u)[0]), e.p) for e in result.events if e.kind == "LP"]
    error, found = fold_error(folds, expected)
    kinds = [e.kind for e in result.events]
    ok = found == len(expected) and error is not None and error <= 1e-10
    return Record(problem, "pycont-lite", wall, len(xs), calls, 0, residual, error, ok,
                  f"events {kinds}; {found}/{len(expected)} folds located; Jacobian-free "
                  "(Newton-Krylov), residual evaluations include its finite-difference "
                  "Jacobian-vector products")


# --------------------------------------------------------------------------- bice

def _bice(problem: str, repeats: int) -> Record:
    try:
        import bice
        from bice.continuation import PseudoArclengthContinuation
    except Exception as error:  # noqa: BLE001
        return failed(problem, "bice", f"import failed: {error!r}")

    counts = {"rhs": 0, "jacobian": 0}

    class Scalar(bice.Equation):
        def __init__(self, u0, p0):
            super().__init__(shape=(1,))
            self.u = np.array([u0])
            self.p = p0

        def rhs(self, u):
            counts["rhs"] += 1
            if problem == "cubic":
                return u ** 3 - u - self.p
            return u ** 2 + self.p ** 2 - 1.0

        def jacobian(self, u):
            counts["jacobian"] += 1
            return np.diag(3.0 * u ** 2 - 1.0 if problem == "cubic" else 2.0 * u)

    def run():
        counts["rhs"] = counts["jacobian"] = 0
        equation = Scalar(-2.0, -6.0) if problem == "cubic" else Scalar(1.0, 0.0)
        solver = bice.Problem()
        solver.add_equation(equation)
        solver.continuation_parameter = (equation, "p")
        stepper = PseudoArclengthContinuation(ds=DS)
        stepper.ds_max = DS_MAX
        stepper.convergence_tolerance = TOL
        solver.continuation_stepper = stepper
        solver.settings.neigs = None  # all eigenvalues: the fold is a zero eigenvalue of J_u
        solver.settings.always_locate_bifurcations = True
        solver.settings.use_sparse_matrices = False
        points = []
        angle = 0.0
        last = 0.0
        with contextlib.redirect_stdout(io.StringIO()):
            for _ in range(2000):
                solver.continuation_step()
                u, p = float(equation.u[0]), float(equation.p)
                points.append((p, u) if problem == "cubic" else (u, p))
                if problem == "cubic" and u >= 2.0:
                    break
                if problem == "circle":
                    now = math.atan2(p, u)
                    angle += (now - last + math.pi) % (2.0 * math.pi) - math.pi
                    last = now
                    if abs(angle) >= 2.0 * math.pi:
                        break
        folds = []
        for solution in solver.bifurcation_diagram.active_branch.solutions:
            if solution.is_bifurcation():
                u = float(np.ravel(solution.data["Scalar.u"])[0])
                folds.append((solution.p, u) if problem == "cubic" else (u, solution.p))
        return np.array(points), folds, dict(counts)

    try:
        wall, (xs, folds, calls) = timed(run, repeats)
    except Exception as error:  # noqa: BLE001
        return failed(problem, "bice", f"run failed: {error!r}")
    expected = CUBIC_FOLDS if problem == "cubic" else CIRCLE_FOLDS[[0, 2]]
    residual = float(np.max(np.abs([cubic_residual(x) if problem == "cubic"
                                    else circle_residual(x) for x in xs])))
    error, found = fold_error(folds, expected)
    ok = found == len(expected) and error is not None and error <= 1e-10
    return Record(problem, "bice", wall, len(xs), calls["rhs"], calls["jacobian"], residual,
                  error, ok,
                  f"{found}/{len(expected)} folds located (zero eigenvalue of J_u, bisection "
                  "to bice's 1e-5); d/dparameter by finite differences (2 residuals per "
                  "Newton step); convergence on |dx| < tol")


TOOLS = {"ours": _ours, "pycont-lite": _pycont, "bice": _bice}


def run_standard(problems=("cubic", "circle"), tools=tuple(TOOLS), repeats: int = 5):
    """Records of every tool on every standard problem."""
    records = []
    for problem in problems:
        for tool in tools:
            try:
                records.append(TOOLS[tool](problem, repeats))
            except Exception as error:  # noqa: BLE001 - the harness never crashes
                records.append(failed(problem, tool, f"harness error: {error!r}"))
    return records
