"""Figures: axes that hold every point drawn, legends and titles in words, regions named."""

import math

import matplotlib
import numpy as np
import pytest
from matplotlib.figure import Figure

from groove_model.analysis.regimes import classify_points
from groove_model.plots.labels import REGION_NAMES, region_label_positions
from groove_model.plots.overlay import MARKER_LABELS, STYLE_LABELS, draw_boundaries, save_overlay
from groove_model.plots.regime_map import draw_regime_map
from groove_model.tracing import trace_boundaries

matplotlib.use("Agg")


@pytest.fixture(scope="module")
def large_k():
    return trace_boundaries(300.0)


def test_overlay_axes_hold_the_highest_point_of_every_curve(large_k):
    highest = float(large_k.to_frame().query("physical")["delta"].max())
    assert highest > 0.55 * 0.5 * math.pi  # above the old fixed limit
    for degrees, scale in ((False, 1.0), (True, 180.0 / math.pi)):
        ax = Figure().subplots()
        draw_boundaries(ax, [large_k], degrees=degrees)
        bottom, top = ax.get_ylim()
        assert bottom == 0.0 and highest * scale < top <= 0.5 * math.pi * scale
        assert ax.get_xlim() == pytest.approx((0.0, 0.5 * math.pi * scale))


def test_legends_are_in_words():
    texts = [*STYLE_LABELS.values(), *MARKER_LABELS.values()]
    for text in texts:
        assert "DR" not in text and "RS" not in text and "_" not in text.replace("$", "")
    assert "double rolling below, rolling sliding above" in STYLE_LABELS["dr_limit"]
    assert "turning point" in MARKER_LABELS["fold_gamma"]


def _texts(ax):
    return [t.get_text() for t in ax.texts]


def test_overlay_has_a_title_and_names_the_regions(tmp_path):
    sets = [trace_boundaries(1.0), trace_boundaries(10.0)]
    paths = save_overlay(sets, tmp_path / "overlay", formats=("svg",))
    svg = paths[0].read_text()
    assert "Regime boundaries of a ball in a groove" in svg
    positions = region_label_positions([1.0, 10.0])
    # Below the k = 1 limit both k roll on both walls clockwise: named without a k.
    assert positions["double_rolling_clockwise"][2] is None
    # Counter-clockwise double rolling exists for k = 10 only, and says so.
    assert positions["double_rolling_counterclockwise"][2] == 10.0
    for name, (g, d, k) in positions.items():
        for kk in ([1.0, 10.0] if k is None else [k]):
            code = classify_points(g, d, kk)
            assert code == list(REGION_NAMES).index(name), (name, kk)


def test_map_names_each_region_inside_it():
    ax = Figure(figsize=(7.2, 6.6)).subplots()
    artists = draw_regime_map(ax, 10.0, n=200)
    names = {t.get_text() for t in artists["regions"]}
    assert names == set(REGION_NAMES.values())
    for text in artists["regions"]:
        g, d = text.get_position()
        name = next(n for n, words in REGION_NAMES.items() if words == text.get_text())
        assert classify_points(g, d, 10.0) == list(REGION_NAMES).index(name)
    assert np.all([t in _texts(ax) for t in names])
