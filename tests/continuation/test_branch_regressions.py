"""Regressions of two silent wrong results near branch points (review of the engine).

* ``switch_branch`` took a first step from the branch point whose corrector converged back to
  the branch it came from, and traced the old branch as the new one, reporting success.
* ``trace`` took a step across a branch point at a sharp turn of the curve onto the crossing
  branch; the determinant ``det [H'; t^T]`` kept its sign over the step (it does on such a
  jump), so nothing checked the step, and the run reported success on the wrong curve.

The problems are two curves crossing transversally, ``H = f_1 f_2`` (plus coordinates that
follow them), with analytic crossings.
"""

import numpy as np
import pytest

from continuation import Event, Options, Problem, Status, box_events, switch_branch, trace

# --- two cubics crossing twice at 0.065 and 0.209 rad, embedded in R^5 -----------------------
# y = A x: (y1 - g1(y0)) (y1 - g2(y0)) = 0, y_k = p_k(y0, y1); crossings at y0 in CROSSINGS

A = np.array([
    [0.5623576750677762, 0.3572800801026084, -1.1700525097455203, 0.3270123507044952,
     2.618649590869992],
    [-1.1396561574463, 1.6685237748546353, 1.4011911326213533, -0.7837598491312248,
     0.7671494647868896],
    [0.35150198447460884, 1.128333937299271, 0.6481724452323504, 0.8399373237218782,
     -0.23878158259511958],
    [-1.3757038826285335, 0.9733988065839941, -1.1714196230878358, 1.573606116941311,
     -0.5949474649023114],
    [-1.1261533623777875, -0.516439084860044, 0.6416464858822555, 0.9912179093739018,
     0.4869435795582916]])
G1 = np.array([-0.08429880487284597, 0.6554372397249413, 0.6386798401178467,
               -0.3990980075644809])[::-1]
G2 = np.array([0.5085477379533727, 2.5689489225213897, 2.1629340911817083,
               -0.3990980075644809])[::-1]
P = np.array([
    [-1.2626722080098831, 1.079539146589146, -0.21277634818704533, 0.050650115637344874,
     -0.025032550046121576],
    [0.4747207458982391, 1.7586005225833379, 0.13490220914425663, -0.03001739367805318,
     0.16950600279265537],
    [0.11588640746924374, -1.6537599883688663, -0.4585120517252322, -0.1350257782394549,
     0.5040235190983978]])
CROSSINGS = [-0.6987510422986627, -0.5566246153128562]


def _monomials(y):
    return np.array([y[0], y[1], y[0] ** 2, y[0] * y[1], y[1] ** 2])


class Cubics:
    """Two cubics ``y1 = g1(y0)``, ``y1 = g2(y0)`` crossing in the plane of ``y = a x``, the other
    coordinates following them (``y_k = p_k . (y0, y1, y0^2, y0 y1, y1^2)``); terminal events at
    ``y0 = +-2``."""

    def __init__(self, a, g1, g2, p):
        self.a, self.g1, self.g2, self.p = a, g1, g2, p
        self.problem = Problem(self.residual, self.jacobian)
        self.events = [Event(name, lambda x, c=c: float(a[0] @ x - c),
                             gradient=lambda x: a[0], linear=True, terminal=True)
                       for name, c in (("hi", 2.0), ("lo", -2.0))]

    def residual(self, x):
        y = self.a @ x
        f = (y[1] - np.polyval(self.g1, y[0])) * (y[1] - np.polyval(self.g2, y[0]))
        return np.concatenate([[f], y[2:] - self.p @ _monomials(y)])

    def jacobian(self, x):
        y = self.a @ x
        J = np.zeros((4, 5))
        u, v = y[1] - np.polyval(self.g1, y[0]), y[1] - np.polyval(self.g2, y[0])
        J[0, 0] = (-np.polyval(np.polyder(self.g1), y[0]) * v
                   - u * np.polyval(np.polyder(self.g2), y[0]))
        J[0, 1] = u + v
        J[1:, 0] = -(self.p @ np.array([1.0, 0.0, 2.0 * y[0], y[1], 0.0]))
        J[1:, 1] = -(self.p @ np.array([0.0, 1.0, 0.0, y[0], 2.0 * y[1]]))
        J[1:, 2:] = np.eye(3)
        return J @ self.a

    def on_g1(self, y0):
        y1 = np.polyval(self.g1, y0)
        return np.linalg.solve(self.a, np.concatenate([[y0, y1], self.p @ _monomials([y0, y1])]))

    def distances(self, curve):
        """The largest distances of the curve's points from g1 and g2 (in y1)."""
        Y = curve.x @ self.a.T
        return (float(np.max(np.abs(Y[:, 1] - np.polyval(self.g1, Y[:, 0])))),
                float(np.max(np.abs(Y[:, 1] - np.polyval(self.g2, Y[:, 0])))))


PAIR = Cubics(A, G1, G2, P)
CUBICS, CUBIC_EVENTS = PAIR.problem, PAIR.events
CUBIC_OPTIONS = Options(tol=2.8229630938921816e-10, ds=0.05, ds_max=0.1201193596059635,
                        max_steps=20000)
_on_g1, _distances = PAIR.on_g1, PAIR.distances


@pytest.fixture(scope="module")
def g1_curve():
    u0 = -1.999
    return trace(CUBICS, _on_g1(u0), direction=_on_g1(u0 + 1e-6) - _on_g1(u0),
                 options=CUBIC_OPTIONS, events=CUBIC_EVENTS)


def test_the_traced_branch_has_both_crossings(g1_curve):
    assert g1_curve.status is Status.TERMINAL_EVENT
    found = [float((A @ p.x)[0]) for p in g1_curve.special("branch_point")]
    assert found == pytest.approx(CROSSINGS, abs=1e-8)


@pytest.mark.parametrize("which", [0, 1])
@pytest.mark.parametrize("direction", [1, -1])
def test_switch_branch_follows_the_other_branch(g1_curve, which, direction):
    # at the second crossing, direction -1, the first corrected point was back on g1
    point = g1_curve.special("branch_point")[which]
    curve = switch_branch(CUBICS, point, direction=direction, options=CUBIC_OPTIONS,
                          events=CUBIC_EVENTS)
    assert curve.status is Status.TERMINAL_EVENT, curve.message
    off_g1, off_g2 = _distances(curve)
    assert off_g2 < 1e-7
    assert off_g1 > 1.0


def test_the_first_points_after_a_switch_leave_the_old_branch(g1_curve):
    point = g1_curve.special("branch_point")[1]
    curve = switch_branch(CUBICS, point, direction=-1, options=CUBIC_OPTIONS,
                          events=CUBIC_EVENTS)
    Y = curve.x[1:4] @ A.T
    assert np.all(np.abs(Y[:, 1] - np.polyval(G2, Y[:, 0])) < 1e-7)
    assert np.all(np.abs(Y[:, 1] - np.polyval(G1, Y[:, 0])) > 1e-5)


def test_a_switch_without_a_first_step_on_the_new_branch_fails_loudly(g1_curve):
    # the new branch bends back to the old one: the step 0.05 lands on the old branch, and
    # ds_min forbids the shorter steps that would reach the new one
    point = g1_curve.special("branch_point")[1]
    options = Options(tol=CUBIC_OPTIONS.tol, ds=0.05, ds_min=0.03, ds_max=0.12)
    curve = switch_branch(CUBICS, point, direction=-1, options=options, events=CUBIC_EVENTS)
    assert curve.status is Status.STEP_TOO_SMALL
    assert "new branch" in curve.message
    assert len(curve) == 1 and curve.special_points[0].kind == "branch_point"


# --- two parabolas crossing at 1.04 and 1.32 rad, 0.57 apart along the curve -----------------

ANGLE, K1, K2, SX = 0.6205584494628031, -1.1563301836662445, 1.1808083558298765, 0.1844117723830772
ROTATION = np.array([[np.cos(ANGLE), np.sin(ANGLE)], [-np.sin(ANGLE), np.cos(ANGLE)]])
SCALE = np.diag([1.0, SX])
U0 = -0.6006932591583614


def _f1(z):
    return z[1] - K1 * z[0] ** 2


def _f2(z):
    w = ROTATION @ z
    return w[1] - K2 * w[0] ** 2


def _parabolas_jacobian(x):
    z = SCALE @ x
    g1 = np.array([-2.0 * K1 * z[0], 1.0])
    g2 = np.array([-2.0 * K2 * (ROTATION @ z)[0], 1.0]) @ ROTATION
    return ((g1 * _f2(z) + _f1(z) * g2) @ SCALE)[None, :]


PARABOLAS = Problem(lambda x: np.array([_f1(SCALE @ x) * _f2(SCALE @ x)]), _parabolas_jacobian)


def test_a_step_across_a_branch_point_at_a_sharp_turn_stays_on_its_branch():
    events = [Event("end", lambda x: float((SCALE @ x)[0] - 1.0), terminal=True),
              Event("back", lambda x: float((SCALE @ x)[0] - (U0 - 0.5)), terminal=True)]
    curve = trace(PARABOLAS, np.linalg.solve(SCALE, [U0, K1 * U0 ** 2]), direction=[1, 0],
                  options=Options(tol=1.5101970821691737e-09, ds_max=0.43591151248782933,
                                  ds=0.05), events=events)
    assert curve.status is Status.TERMINAL_EVENT, curve.message
    assert curve.special_points[-2].name == "end"
    Z = curve.x @ SCALE
    assert np.max(np.abs(Z[:, 1] - K1 * Z[:, 0] ** 2)) < 1e-6
    found = [float(p.x[0]) for p in curve.special("branch_point")]
    assert found == pytest.approx([-0.274632865, 0.0], abs=1e-8)


def test_a_traced_branch_keeps_to_itself_past_all_its_crossings():
    # g1 of another pair of cubics: the step across the crossing at y0 = 0.754 landed on g2
    a = np.array([
        [1.8005730379271283, -0.10491980802318457, -7.4470938157003124, 0.36841750813612056,
         10.681587336634811],
        [-5.8705919098707122, -0.030333225157695001, 13.507108870147222, -0.20623961612627886,
         24.823161907706936],
        [6.1555579578117392, 0.071336899163449499, 3.8332547778470309, -1.1496137125443557,
         0.13243739668888210],
        [-5.7818716798399095, -0.0016380315428262242, -16.985100995997364,
         -0.40042549237863750, 4.7444469722861378],
        [6.4960472550561725, 0.14501259966412128, 5.4272992633015598, 0.75010324762229885,
         3.6120499470733565]])
    g1 = np.array([0.15582400035898053, -0.1248190966291536, -0.3170081091087748,
                   -0.30193706967869244])[::-1]
    g2 = np.array([1.1065074099240657, 1.0738814526162133, -2.334682067890667,
                   -1.9476920897893015])[::-1]
    p = np.array([
        [-0.29737617711179, -0.38201813147946434, -0.313160347312358, 0.21075654093205043,
         0.2772102580232252],
        [-0.5641675681698397, -0.3444514077774843, 0.19638545666075485, -0.1478715765669374,
         -0.4834088331088394],
        [-0.06756824481107009, -0.9042325062053423, 0.1120649107049703, -0.17404162509167104,
         -0.06516639587087744]])

    other = Cubics(a, g1, g2, p)
    curve = trace(other.problem, other.on_g1(-1.999),
                  direction=other.on_g1(-1.999 + 1e-6) - other.on_g1(-1.999),
                  events=other.events,
                  options=Options(tol=1.503993645572423e-11, ds=0.05,
                                  ds_max=0.2747161072617414, max_steps=20000))
    assert curve.status is Status.TERMINAL_EVENT, curve.message
    assert curve.special_points[-2].name == "hi"
    assert other.distances(curve)[0] < 1e-8
    found = [float((a @ q.x)[0]) for q in curve.special("branch_point")]
    assert found == pytest.approx([-1.4536727285166489, -0.5267337064210245,
                                   0.7544196178679694], abs=1e-8)


@pytest.mark.parametrize("angle", [1e-3, 3e-3])
@pytest.mark.parametrize("direction", [1, -1])
def test_a_switch_at_a_small_angle_with_a_short_ds_starts_with_a_step_that_tells(angle,
                                                                                 direction):
    # two lines crossing at 1e-3 rad, tol 1e-6: a first step below ~8e-3 cannot tell them
    # apart, and the check only halved ds = 1e-3, failing where ds = 1e-2 switches
    slope = np.tan(angle)
    lines = Problem(lambda z: np.array([z[1] * (z[1] - slope * z[0])]),
                    lambda z: np.array([[-slope * z[1], 2.0 * z[1] - slope * z[0]]]))
    box = [Event(name, lambda z, i=i, s=s: s * (z[i] - s), terminal=True)
           for name, i, s in (("x > 1", 0, 1.0), ("x < -1", 0, -1.0))]
    curve = switch_branch(lines, np.zeros(2), direction=direction,
                          options=Options(tol=1e-6, ds=1e-3, ds_max=0.2), events=box,
                          tangent_hint=[1.0, 0.0])
    assert curve.status is Status.TERMINAL_EVENT, curve.message
    assert abs(curve.x[-1, 0]) == pytest.approx(1.0)
    assert np.max(np.abs(curve.x[:, 1] - slope * curve.x[:, 0])) <= 1e-5


def test_a_branch_point_carries_the_tangent_of_the_traced_branch():
    # located at the singular point itself, its tangent was the corrector's, from the bordered
    # system there, up to 0.09 rad off the traced branch (0.2 rad in the review, where
    # switch_branch then took the traced branch for the new one)
    worst = 0.0
    for c in np.linspace(-1.5, 1.5, 13):
        for angle in (0.2, 0.3, 0.7, 1.2):
            s, co = np.sin(angle), np.cos(angle)
            problem = Problem(
                lambda z, c=c, s=s, co=co: np.array([(z[1] - c * z[0] ** 2)
                                                     * (co * z[1] - s * z[0])]),
                lambda z, c=c, s=s, co=co: np.array([[
                    -2.0 * c * z[0] * (co * z[1] - s * z[0]) - s * (z[1] - c * z[0] ** 2),
                    (co * z[1] - s * z[0]) + co * (z[1] - c * z[0] ** 2)]]))
            curve = trace(problem, [-1.0, c], direction=[1.0, 0.0], options=Options(tol=1e-10),
                          events=box_events(upper={0: 1.0}))
            assert curve.status is Status.TERMINAL_EVENT
            for point in curve.special("branch_point"):
                along = np.array([1.0, 2.0 * c * point.x[0]]) / np.hypot(1.0, 2.0 * c * point.x[0])
                worst = max(worst, float(np.arccos(min(1.0, abs(along @ point.tangent)))))
    assert worst <= 5e-3
