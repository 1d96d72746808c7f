"""The regime map: grid classification, its agreement with the traced boundaries, drawing, files."""

import math
import os
from dataclasses import FrozenInstanceError

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.colors import to_rgba
from matplotlib.image import AxesImage
from matplotlib.lines import Line2D

from groove_model.analysis.regimes import (
    CATEGORIES,
    OUTSIDE,
    classify_cells,
    classify_grid,
    classify_points,
)
from groove_model.cli.main import build_parser, main
from groove_model.model.boundaries import boundary_system
from groove_model.model.equilibrium import double_rolling_state, solve_equilibrium
from groove_model.model.lines import dr_limit_no_roll_point, dr_no_roll_line
from groove_model.model.parameters import Compliance, Parameters
from groove_model.plots import regime_map
from groove_model.plots.overlay import MARKER_LABELS, STYLE_LABELS
from groove_model.plots.regime_map import (
    CATEGORY_COLOURS,
    CATEGORY_LABELS,
    SEED_LEGEND,
    draw_regime_map,
    save_regime_map,
    seed_points,
)
from groove_model.tracing import trace_boundaries

KS = [0.3, 1.0, 1.2, 2.0, 10.0, 100.0]
SQRT2 = math.sqrt(2.0)
N = 300  # grid steps along each axis: h = (pi/2)/300 = 5.2e-3 rad
CODE = {name: i for i, name in enumerate(CATEGORIES)}


@pytest.fixture(scope="module")
def traced():
    return {k: trace_boundaries(k) for k in KS}


@pytest.fixture(scope="module")
def grids():
    return {k: classify_grid(k, N) for k in KS}


def polyline_distance(points, polyline):
    """Distance from each of ``points`` (m, 2) to the polyline (p, 2)."""
    a, b = polyline[:-1], polyline[1:]
    ab = b - a
    length2 = np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300)
    out = np.full(len(points), np.inf)
    for i, p in enumerate(points):
        t = np.clip(np.einsum("ij,ij->i", p - a, ab) / length2, 0.0, 1.0)
        out[i] = np.min(np.hypot(*(a + t[:, None] * ab - p).T))
    return out


def physical_curve(bs, name):
    if name not in bs.curves:
        return np.empty((0, 2))
    curve = bs.curves[name]
    return curve.x[np.asarray(curve.physical, bool)][:, :2]


# --------------------------------------------------------------------------------------------
# Classification
# --------------------------------------------------------------------------------------------


def test_grid_shape_mask_and_axis_segments():
    grid = classify_grid(2.0, 40)
    assert grid.gamma.shape == grid.delta.shape == (41,)
    assert grid.category.shape == grid.upsilon.shape == (41, 41)
    G, D = np.meshgrid(grid.gamma, grid.delta)
    assert np.array_equal(grid.category == OUTSIDE, D > G)
    assert np.all(np.isnan(grid.upsilon[D > G])) and np.all(np.isfinite(grid.upsilon[D <= G]))
    axis = grid.category[0]
    below = grid.gamma <= math.atan(2.0)
    assert np.all(axis[below] == CODE["symmetric_no_rotation"])
    assert np.all(axis[~below] == CODE["double_sliding"])
    counts = grid.counts()
    assert set(counts) == set(CATEGORIES)
    assert sum(counts.values()) == np.count_nonzero(D <= G)
    assert counts["double_rolling_counterclockwise"] > 0  # k = 2 > sqrt 2
    assert grid.names()[5, 2] == "outside"


def test_grid_is_immutable():
    grid = classify_grid(1.0, 10)
    with pytest.raises(FrozenInstanceError):
        grid.k = 2.0
    with pytest.raises(ValueError):
        grid.category[1, 1] = 0


@pytest.mark.parametrize("n, error, match", [
    (1, ValueError, r"grid resolution n = 1 is outside the allowed range 2 <= n <= 20000"),
    (30000, ValueError, r"n = 30000 is outside the allowed range"),
    (2.5, TypeError, r"grid resolution n must be an integer, got 2.5"),
])
def test_bad_resolution_is_rejected(n, error, match):
    with pytest.raises(error, match=match):
        classify_grid(1.0, n)


def test_grids_are_solved_in_blocks_with_the_same_result():
    # the map at N = 20000 needed 130 GB when every cell was solved in one call: the grids are
    # now solved in blocks of rows (about 131072 nodes: three at n = 600), each node on its
    # own, so the blocks change no bit against the points solved in one call
    n = 600
    centres = (np.arange(n) + 0.5) * (0.5 * math.pi / n)
    G, D = np.meshgrid(centres, centres)
    inside = D <= G
    cells = classify_cells(10.0, n)
    assert np.array_equal(cells[inside], classify_points(G[inside], D[inside], 10.0))
    assert np.all(cells[~inside] == OUTSIDE)
    grid = classify_grid(10.0, n)
    G, D = np.meshgrid(grid.gamma, grid.delta)
    inside = D <= G
    assert np.array_equal(grid.category[inside], classify_points(G[inside], D[inside], 10.0))
    assert np.array_equal(grid.upsilon[inside],
                          solve_equilibrium(G[inside], D[inside], 10.0).upsilon)


def test_a_drawn_map_takes_at_most_the_resolution_its_memory_allows(tmp_path, capsys):
    assert regime_map.MAP_RESOLUTION_MAX == 5000
    fig, ax = plt.subplots()
    with pytest.raises(ValueError, match=r"n = 5001 is outside the allowed range 2 <= n <= 5000"):
        regime_map.draw_regime_map(ax, 1.0, n=5001, boundaries=False)
    plt.close(fig)
    with pytest.raises(SystemExit):
        main(["map", "-k", "1", "-o", str(tmp_path / "m.png"), "--resolution", "5001"])
    assert "N = 5001 is outside the allowed range 2 <= N <= 5000" in capsys.readouterr().err
    assert build_parser().parse_args(
        ["map", "-k", "1", "-o", "m.png", "--resolution", "5000"]).resolution == 5000


def test_bad_friction_is_rejected():
    with pytest.raises(ValueError, match="friction coefficient k = -1.0 is outside"):
        classify_grid(-1.0, 10)


@pytest.mark.parametrize("k", KS)
def test_categories_match_the_point_solver(k):
    rng = np.random.default_rng(7)
    gamma = rng.uniform(0.0, 0.5 * math.pi, 500)
    delta = rng.uniform(0.0, 1.0, 500) * gamma
    codes = classify_points(gamma, delta, k)
    eq = solve_equilibrium(gamma, delta, k)
    for code, regime, upsilon in zip(codes, eq.regime, eq.upsilon):
        name = CATEGORIES[code]
        assert name.startswith(regime)
        assert name.endswith("_clockwise") == (upsilon < 0.0)


def test_axis_point_exactly_at_arctan_k_is_on_the_axis():
    # T/N = tan(pi/4) rounds above 1 there; the axis category follows gamma <= arctan k.
    assert CATEGORIES[classify_points(math.pi / 4, 0.0, 1.0)] == "symmetric_no_rotation"


# --------------------------------------------------------------------------------------------
# Cross-check: grid classification against the traced boundaries
# --------------------------------------------------------------------------------------------


def _changes(grid, along_rows: bool):
    """Midpoints (gamma, delta) and category pairs of neighbouring nodes that differ."""
    cat = grid.category if along_rows else grid.category.T
    a, b = cat[:, :-1], cat[:, 1:]
    differ = (a != b) & (a != OUTSIDE) & (b != OUTSIDE)
    if along_rows:
        differ[0] = False  # the row on the axis delta = 0
    else:
        differ[:, 0] = False  # from the axis node delta = 0 to the first node above it
    j, i = np.nonzero(differ)
    h = grid.step
    if along_rows:
        mid = np.column_stack([(i + 0.5) * h, j * h])
    else:
        mid = np.column_stack([j * h, (i + 0.5) * h])
    return mid, a[j, i], b[j, i]


def _expected_curve(code_a, code_b):
    a, b = CATEGORIES[code_a], CATEGORIES[code_b]
    if a.startswith("double_rolling") != b.startswith("double_rolling"):
        return "dr_limit"
    return "dr_no_roll" if a.startswith("double_rolling") else "rs_no_roll"


@pytest.mark.parametrize("along_rows", [True, False], ids=["rows", "columns"])
@pytest.mark.parametrize("k", KS)
def test_grid_changes_only_within_one_step_of_a_traced_boundary(k, along_rows, traced, grids):
    grid, bs = grids[k], traced[k]
    assert bs.ok, bs.failures
    mid, a, b = _changes(grid, along_rows)
    assert len(mid) > 50
    assert not np.any(a == CODE["no_rotation"]) and not np.any(b == CODE["no_rotation"])
    worst = {}
    for name in ("dr_limit", "dr_no_roll", "rs_no_roll"):
        mine = np.array([_expected_curve(x, y) == name for x, y in zip(a, b)])
        if not mine.any():
            continue
        curve = physical_curve(bs, name)
        assert len(curve) >= 2, f"changes across {name} but no physical {name} traced"
        dist = polyline_distance(mid[mine], curve)
        worst[name] = float(dist.max())
        assert dist.max() <= grid.step, (name, mid[mine][np.argmax(dist)], dist.max())
    # Every change of regime is across the limit, and rotation changes exist in both regimes
    # (for k > sqrt 2 inside double rolling too).
    assert "dr_limit" in worst and "rs_no_roll" in worst
    assert ("dr_no_roll" in worst) == (k > SQRT2)


def _on_curve_points(bs, name, k):
    """The traced points of a curve and, between each pair, a point projected onto the curve.

    The midpoint of two traced points (in ``w = (gamma, delta, sqrt(beta_L), upsilon)``) is moved onto
    the boundary by Gauss-Newton with the minimum-norm step ``-J^+ H`` and kept if its residual
    is below 1e-12, so the sides are checked densely even where the tracer takes long steps.
    """
    curve = bs.curves[name]
    x = curve.x[np.asarray(curve.physical, bool)]
    # the sqrt(beta_L) chart: smooth where beta_L -> 0, which the beta_L chart is not
    system = boundary_system(name, k, chart="sqrt_beta_L")
    points = [x[0]]
    for a, b in zip(x[:-1], x[1:]):
        y = 0.5 * (system.from_x(a) + system.from_x(b))
        for _ in range(8):
            H, J = system.residual_and_jacobian(y)
            if not (np.isfinite(H).all() and np.isfinite(J).all()):
                break
            y = y - np.linalg.lstsq(J, H, rcond=None)[0]
        if (np.isfinite(y).all() and np.max(np.abs(system.residual(y))) <= 1e-12
                and system.is_physical(y)):
            points.append(system.to_x(y))
        points.append(b)
    return np.array(points)


def _sides(bs, name, k):
    """Categories a small distance either side of each interior point of a traced curve."""
    x = _on_curve_points(bs, name, k)[:, :2]
    specials = np.array([p.x[:2] for c in bs.curves.values() for p in c.special_points])
    pairs = []
    for i in range(1, len(x) - 1):
        p = x[i]
        if np.min(np.hypot(*(specials - p).T)) < 1e-4:
            continue
        tangent = x[i + 1] - x[i - 1]
        normal = np.array([-tangent[1], tangent[0]]) / np.hypot(*tangent)
        room = min(p[1], (p[0] - p[1]) / SQRT2, 0.5 * math.pi - p[0])
        eps = min(1e-6, 0.25 * room)
        if eps < 1e-9:
            continue
        codes = classify_points(np.array([p[0] + eps * normal[0], p[0] - eps * normal[0]]),
                                np.array([p[1] + eps * normal[1], p[1] - eps * normal[1]]), k)
        pairs.append((CATEGORIES[codes[0]], CATEGORIES[codes[1]]))
    return pairs


@pytest.mark.parametrize("k", KS)
def test_every_traced_boundary_has_different_regimes_on_its_two_sides(k, traced):
    bs = traced[k]
    expected = {"dr_limit", "rs_no_roll"} | ({"dr_no_roll"} if k > SQRT2 else set())
    assert expected <= set(bs.curves)
    for name in expected:
        pairs = _sides(bs, name, k)
        assert len(pairs) >= 5, name
        for one, other in pairs:
            if name == "dr_limit":
                assert {one.split("_clockwise")[0].split("_counter")[0],
                        other.split("_clockwise")[0].split("_counter")[0]} == {
                    "double_rolling", "rolling_sliding"}, (one, other)
            else:
                regime = "double_rolling" if name == "dr_no_roll" else "rolling_sliding"
                assert {one, other} == {f"{regime}_clockwise",
                                        f"{regime}_counterclockwise"}, (name, one, other)


@pytest.mark.parametrize("k", [1.5, 2.0, 10.0, 100.0])
def test_dr_limit_no_roll_point_solves_the_equations_and_matches_the_tracer(k, traced):
    x = dr_limit_no_roll_point(k)
    assert x[3] == 0.0
    assert np.max(np.abs(boundary_system("dr_limit", k).residual(x))) <= 1e-12
    assert 1.0 / math.tan(x[2]) == pytest.approx(k, rel=1e-12)  # T/N_L = cot beta_L = k
    bs = traced.get(k) or trace_boundaries(k)
    junction = bs.curves["dr_limit"].special("junction")[0].x
    assert x == pytest.approx(junction, abs=1e-9)


@pytest.mark.parametrize("k", [0.3, 1.0, SQRT2])
def test_no_upsilon_zero_point_on_the_limit_for_k_up_to_sqrt2(k):
    assert dr_limit_no_roll_point(k) is None


def test_dr_no_roll_line_runs_from_the_branch_point_to_the_corner():
    delta = np.array([1e-5, 0.3, math.pi / 4 - 1e-4])
    gamma, beta_L = dr_no_roll_line(delta)
    assert gamma[0] == pytest.approx(math.atan(SQRT2), abs=1e-9)
    dr = double_rolling_state(gamma, delta, Parameters(1.0))
    assert np.max(np.abs(dr["upsilon"])) <= 1e-12
    assert beta_L == pytest.approx(dr["beta_L"], abs=1e-12)
    corner, beta_corner = dr_no_roll_line(np.array([math.pi / 4 - 1e-9]))
    assert corner[0] == pytest.approx(math.pi / 4, abs=1e-8) and beta_corner[0] < 1e-7


def test_seed_points():
    assert set(seed_points(1.0)) == {r"$(\arctan k,\,0)$", r"$(\arctan\sqrt{2},\,0)$",
                                     r"$(\pi/4,\,\pi/4)$"}
    points = seed_points(10.0)
    assert points[r"$(\arctan k,\,0)$"] == (math.atan(10.0), 0.0)
    assert points[r"$\upsilon = 0$ on the limit"] == pytest.approx((0.89981228, 0.5713154),
                                                                  abs=1e-7)


# --------------------------------------------------------------------------------------------
# Drawing and files
# --------------------------------------------------------------------------------------------


def test_map_draws_onto_the_given_axes(traced):
    fig, ax = plt.subplots()
    try:
        artists = draw_regime_map(ax, 10.0, n=200, boundary_set=traced[10.0])
        image = artists["image"]
        assert isinstance(image, AxesImage) and list(ax.images) == [image]
        assert image.get_clip_path() is not None  # masked to the triangle
        rgba = image.get_array()
        assert rgba.shape == (200, 200, 4)
        h = 0.5 * math.pi / 200
        # Cell of (gamma, delta) = (1.2, 0.1): counter-clockwise double rolling for k = 10.
        j, i = int(0.1 / h), int(1.2 / h)
        assert tuple(rgba[j, i]) == pytest.approx(to_rgba(CATEGORY_COLOURS[
            "double_rolling_counterclockwise"]))
        assert rgba[150, 20, 3] == 0.0  # outside the triangle: transparent
        seg_colours = {to_rgba(line.get_color()) for line in artists["segments"]}
        assert to_rgba(CATEGORY_COLOURS["double_sliding"]) in seg_colours
        assert to_rgba(CATEGORY_COLOURS["symmetric_no_rotation"]) in seg_colours
        assert artists["boundaries"] and all(a.axes is ax for a in artists["boundaries"])
        styles = {a.get_linestyle() for a in artists["boundaries"] if isinstance(a, Line2D)}
        assert {"-", "-.", "--"} <= styles
        texts = [t.get_text() for t in artists["legend"].get_texts()]
        for name in CATEGORIES[:6]:
            assert CATEGORY_LABELS[name] in texts
        labels = {a.get_text() for a in artists["seeds"] if hasattr(a, "get_text")}
        assert labels == set(seed_points(10.0))
        assert texts[-1] == SEED_LEGEND + ", and the junction"
        assert ax.get_legend() is artists["legend"]
        assert plt.gcf() is fig and len(plt.get_fignums()) == 1
    finally:
        plt.close(fig)


def test_map_legend_lists_only_what_is_drawn(traced):
    fig, ax = plt.subplots()
    try:
        artists = draw_regime_map(ax, 1.0, n=100, boundary_set=traced[1.0], degrees=True)
        texts = [t.get_text() for t in artists["legend"].get_texts()]
        assert CATEGORY_LABELS["double_rolling_counterclockwise"] not in texts  # k < sqrt 2
        assert STYLE_LABELS["dr_no_roll"] not in texts
        assert MARKER_LABELS["junction"] not in texts
        assert STYLE_LABELS["rs_no_roll"] in texts and MARKER_LABELS["fold_gamma"] in texts
        # the open circles of the labelled points are explained, last, without the junction
        # there is none at k = 1; the circle at (arctan sqrt 2, 0), where nothing is drawn
        # below k = sqrt 2, read as a point of a boundary and is gone
        assert texts[-1] == SEED_LEGEND == "labelled: the seed points of the boundaries"
        circle = artists["legend"].legend_handles[-1]
        assert circle.get_marker() == "o" and circle.get_markerfacecolor() == "none"
        labels = {a.get_text() for a in artists["seeds"] if hasattr(a, "get_text")}
        assert labels == set(seed_points(1.0)) - {r"$(\arctan\sqrt{2},\,0)$"}
        assert ax.get_xlim()[1] == pytest.approx(90.0 * 1.02)
        assert "deg" in ax.get_xlabel()
    finally:
        plt.close(fig)


def test_a_map_for_another_compliance_says_so(tmp_path):
    # the seed and the axis segments move to arctan(k/c), and the title names c: two maps of
    # one k for two Poisson ratios cannot be mistaken for each other
    params = Parameters(1.0, Compliance.from_poisson(0.5))
    assert seed_points(params)[r"$(\arctan(k/c),\,0)$"] == (math.atan(1.5), 0.0)
    fig, ax = plt.subplots()
    try:
        artists = draw_regime_map(ax, params, n=60, boundaries=False)
        texts = [t.get_text() for t in artists["legend"].get_texts()]
        assert r"double sliding ($\delta = 0$, $\gamma > \arctan(k/c)$)" in texts
        assert not any(r"\arctan k" in text for text in texts)
    finally:
        plt.close(fig)
    written = save_regime_map(params, tmp_path / "m.svg", n=60, formats=("svg",),
                              boundaries=False)
    assert "compliance ratio c = 0.6667" in written[0].read_text()


@pytest.mark.parametrize("k, offset", [(1.5, (78, 34)), (10.0, (22, 26))])
def test_the_junction_label_keeps_clear_of_the_seed_label(k, offset):
    # just above k = sqrt 2 the junction lies next to the seed (arctan k, 0): its label goes
    # to the right, clear of the seed's (they overlapped at k = 1.5)
    fig, ax = plt.subplots()
    try:
        artists = draw_regime_map(ax, k, n=40, boundaries=False, legend=False)
        label = next(a for a in artists["seeds"] if hasattr(a, "get_text")
                     and a.get_text() == r"$\upsilon = 0$ on the limit")
        assert tuple(label.xyann) == offset
    finally:
        plt.close(fig)


def test_map_without_boundaries_traces_nothing(monkeypatch):
    monkeypatch.setattr(regime_map, "trace_boundaries", lambda *a, **kw: pytest.fail("traced"))
    fig, ax = plt.subplots()
    try:
        artists = draw_regime_map(ax, 2.0, n=50, boundaries=False)
        assert artists["boundaries"] == [] and artists["boundary_set"] is None
    finally:
        plt.close(fig)


def test_save_writes_png_and_svg(tmp_path, traced):
    paths = save_regime_map(1.0, tmp_path / "map_k1.png", n=80, boundary_set=traced[1.0])
    assert [p.name for p in paths] == ["map_k1.png", "map_k1.svg"]
    assert paths[0].read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    svg = paths[1].read_text()
    assert svg.startswith("<?xml") and "<svg" in svg
    assert sorted(os.listdir(tmp_path)) == ["map_k1.png", "map_k1.svg"]


def test_save_is_atomic(tmp_path, monkeypatch, traced):
    target = tmp_path / "map_k1.png"
    target.write_bytes(b"old")
    from matplotlib.figure import Figure

    def broken_savefig(self, fname, **kwargs):
        with open(fname, "wb") as f:
            f.write(b"partial")
        raise OSError("disk full")

    monkeypatch.setattr(Figure, "savefig", broken_savefig)
    with pytest.raises(OSError, match="disk full"):
        save_regime_map(1.0, target, n=40, boundary_set=traced[1.0])
    assert target.read_bytes() == b"old"  # the old file is untouched
    assert os.listdir(tmp_path) == ["map_k1.png"]  # no temporary file left behind


def test_save_rejects_bad_format_and_makes_a_missing_directory(tmp_path):
    with pytest.raises(ValueError, match="format = 'gif' is not one of png, svg, pdf"):
        save_regime_map(1.0, tmp_path / "m.gif", formats=("gif",), boundaries=False)
    assert list(tmp_path.iterdir()) == []
    target = tmp_path / "missing" / "m.png"
    assert save_regime_map(1.0, target, n=12, boundaries=False)[0] == target


def test_a_map_draws_a_failed_trace_in_part_and_warns(caplog):
    # the overlay of a failed trace raises TraceError; the map draws what was traced, and says so
    from matplotlib.figure import Figure

    failed = trace_boundaries(1.0, gamma_min=0.5)
    assert not failed.ok
    ax = Figure().subplots()
    with caplog.at_level("WARNING"):
        artists = draw_regime_map(ax, 1.0, n=20, boundary_set=failed)
    assert artists["boundaries"] and "drawn in part" in caplog.text
