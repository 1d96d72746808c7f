"""Figures of the atlas: each special point against ``k`` (log axis) or ``nu``, thresholds marked.

:func:`save_atlas_figure` draws one atlas in four panels (``gamma``, ``delta``, ``beta_L`` on a
log axis, ``upsilon``), one colour per curve of special points (dots: the computed points;
lines: the engine's cubic Hermite arcs between them), and a vertical line at each threshold.
:func:`save_compliance_figure` overlays the atlases in ``k`` of several Poisson ratios and shows
the atlases in ``nu`` at fixed ``k``.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.ticker import FuncFormatter

from ..io.atomic import atomic_write_all
from ..tracing.atlas import Atlas
from .files import figure_files

__all__ = ["CURVE_COLOURS", "atlas_figure_files", "compliance_figure_files", "draw_atlas",
           "save_atlas_figure", "save_compliance_figure"]

# Okabe & Ito's colour-blind-safe palette.
_PALETTE = ("#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000")
CURVE_COLOURS = {"junction": _PALETTE[0], "dr_limit_fold_delta": _PALETTE[1],
                 "rs_no_roll_fold_gamma": _PALETTE[2]}
# plain text, no mathtext: parsing it would cost more than the rest of the figure
_LABELS = {"junction": "junction (\u03c5 = 0 on dr_limit)",
           "dr_limit_fold_delta": "max of \u03b4 along dr_limit",
           "rs_no_roll_fold_gamma": "fold in \u03b3 of rs_no_roll"}
_PANELS = (("gamma", "\u03b3 [rad]", 0), ("delta", "\u03b4 [rad]", 1),
           ("beta_L", "\u03b2_L [rad]", 2), ("upsilon", "\u03c5", 3))
_LINESTYLES = ("-", "--", ":", "-.")


def _colour(name: str, i: int) -> str:
    return CURVE_COLOURS.get(name, _PALETTE[3 + i % 4])


def _axis_label(atlas: Atlas) -> str:
    return "friction coefficient k" if atlas.axis.name == "k" else "Poisson ratio \u03bd"


def _powers_of_ten(value, _position) -> str:
    """A log axis's major tick label, ``1e-4``, in plain text."""
    return f"1e{math.log10(value):.0f}" if value > 0 else ""


def draw_atlas(axes, atlas: Atlas, linestyle: str = "-", label_suffix: str = "",
               thresholds: bool = True) -> list:
    """Draw the curves of ``atlas`` on four ``Axes`` (gamma, delta, beta_L, upsilon).

    Returns the line artists (one per curve in the first panel, for a legend).
    """
    handles = []
    for i, (name, curve) in enumerate(atlas.curves.items()):
        values, x = curve.dense(6)
        for ax, (_, _, column) in zip(axes, _PANELS, strict=True):
            y, computed = x[:, column], curve.x[:, column]
            if column == 2:  # log axis: beta_L = 0 only at the corner, never on these curves
                y, computed = np.where(y > 0, y, np.nan), np.where(computed > 0, computed, np.nan)
            line, = ax.plot(values, y, linestyle=linestyle, color=_colour(name, i), lw=1.4,
                            label=_LABELS.get(name, name) + label_suffix)
            ax.plot(curve.values, computed, ".", color=_colour(name, i), ms=3)
            if ax is axes[0]:
                handles.append(line)
    if thresholds:
        for j, t in enumerate(atlas.thresholds):
            for ax in axes:
                ax.axvline(t.value, color="0.5", lw=0.8, ls=linestyle, zorder=0)
            # staggered, so that the labels of neighbouring thresholds do not overlap
            axes[0].annotate(f"{t.name} = {t.value:.6g}", (t.value, 1.0 - 0.3 * (j % 2)),
                             xycoords=("data", "axes fraction"), rotation=90, fontsize=7,
                             va="top", ha="right", color="0.3")
    for ax, (_, ylabel, column) in zip(axes, _PANELS, strict=True):
        ax.set_ylabel(ylabel)
        if atlas.axis.name == "k":
            ax.set_xscale("log")
            ax.xaxis.set_major_formatter(FuncFormatter(_powers_of_ten))
        if column == 2:
            ax.set_yscale("log")
            ax.yaxis.set_major_formatter(FuncFormatter(_powers_of_ten))
        ax.grid(True, lw=0.3, alpha=0.5)
    for ax in axes[-2:]:
        ax.set_xlabel(_axis_label(atlas))
    return handles


def _files(fig: Figure, stem, formats) -> list:
    """``(stem.<format>, write)`` for each format (:func:`figure_files`)."""
    stem = Path(stem)
    return figure_files(fig, [(stem.with_name(f"{stem.name}.{fmt}"), fmt) for fmt in formats],
                        dpi=120)


def save_atlas_figure(atlas: Atlas, stem, formats=("png",), title: str | None = None
                      ) -> list[Path]:
    """Write the figure of one atlas as ``stem.png`` (and the other ``formats``), every format or
    none."""
    return atomic_write_all(atlas_figure_files(atlas, stem, formats, title))


def atlas_figure_files(atlas: Atlas, stem, formats=("png",), title: str | None = None) -> list:
    """The figure of one atlas as ``(path, write)`` for each format, to be written with other
    files as one group (:func:`~groove_model.io.atomic.atomic_write_all`)."""
    # fixed margins: the constrained layout would cost more than the rest of `groove atlas`
    fig = Figure(figsize=(10.0, 7.0))
    fig.subplots_adjust(left=0.08, right=0.98, bottom=0.08, top=0.93, wspace=0.22, hspace=0.08)
    axes = fig.subplots(2, 2, sharex=True).ravel()
    handles = draw_atlas(axes, atlas)
    axes[0].legend(handles=handles, fontsize=7, loc="lower right")
    fig.suptitle(title or _default_title(atlas), fontsize=10)
    return _files(fig, stem, formats)


def _default_title(atlas: Atlas) -> str:
    if atlas.axis.name == "k":
        return (f"Special points of the regime boundaries against k (compliance ratio "
                f"c = {atlas.axis.fixed:.4g}); thresholds where the diagram changes shape")
    return (f"Special points against the Poisson ratio at k = {atlas.axis.fixed:g} "
            "(Mindlin: c = 2(1 - \u03bd)/(2 - \u03bd))")


def save_compliance_figure(in_k: dict, in_nu: dict, stem, formats=("png", "svg")
                           ) -> list[Path]:
    """Write :func:`compliance_figure_files`, every format or none."""
    return atomic_write_all(compliance_figure_files(in_k, in_nu, stem, formats))


def compliance_figure_files(in_k: dict, in_nu: dict, stem, formats=("png", "svg")) -> list:
    """The atlases in ``k`` for several ``nu`` (``{nu: Atlas}``, one line style each) over the
    atlases in ``nu`` at fixed ``k`` (``{k: Atlas}``), ``gamma`` and ``delta`` only, as
    ``(path, write)`` for each format."""
    # the atlases in nu get one panel each in the second row (every k given is drawn)
    columns = max(2, len(in_nu))
    fig = Figure(figsize=(5.5 * columns, 8.0))
    fig.subplots_adjust(left=0.07, right=0.98, bottom=0.07, top=0.92, wspace=0.2, hspace=0.25)
    grid = fig.subplots(2, columns, squeeze=False)
    for ax in (*grid[0][2:], *grid[1][len(in_nu):]):
        ax.set_visible(False)
    styles = []
    for j, (nu, atlas) in enumerate(in_k.items()):
        style = _LINESTYLES[j % len(_LINESTYLES)]
        styles.append(Line2D([], [], color="0.2", ls=style, label=f"\u03bd = {nu:g}"))
        for ax, column in zip(grid[0][:2], (0, 1), strict=True):
            for i, (name, curve) in enumerate(atlas.curves.items()):
                values, x = curve.dense(6)
                ax.plot(values, x[:, column], ls=style, color=_colour(name, i), lw=1.2,
                        label=_LABELS.get(name, name) if j == 0 else None)
            for t in atlas.thresholds:
                ax.axvline(t.value, color="0.5", lw=0.7, ls=style, zorder=0)
    for ax, column in zip(grid[0][:2], (0, 1), strict=True):
        ax.set_xscale("log")
        ax.xaxis.set_major_formatter(FuncFormatter(_powers_of_ten))
        ax.set_xlim(1e-2, 1e4)
        ax.set_xlabel("friction coefficient k (1e-2 to 1e4 shown)")
        ax.set_ylabel(_PANELS[column][1])
        ax.grid(True, lw=0.3, alpha=0.5)
    grid[0][0].legend(fontsize=7, loc="upper left")
    grid[0][1].legend(handles=styles, fontsize=7, loc="upper left")
    for ax, (k, atlas) in zip(grid[1][:len(in_nu)], in_nu.items(), strict=True):
        for i, (name, curve) in enumerate(atlas.curves.items()):
            values, x = curve.dense(6)
            ax.plot(values, x[:, 0], color=_colour(name, i), lw=1.4)
            ax.plot(values, x[:, 1], color=_colour(name, i), lw=1.4, ls="--")
        for t in atlas.thresholds:
            ax.axvline(t.value, color="0.5", lw=0.8)
            ax.annotate(f"{t.name} = {t.value:.4g}", (t.value, 0.02),
                        xycoords=("data", "axes fraction"), rotation=90, fontsize=7,
                        ha="right", color="0.3")
        ax.set_xlabel("Poisson ratio \u03bd")
        ax.set_ylabel("\u03b3 (solid), \u03b4 (dashed) [rad]")
        ax.set_title(f"k = {k:g}", fontsize=9)
        ax.grid(True, lw=0.3, alpha=0.5)
    fig.suptitle("Special points for Mindlin's compliance c = 2(1 - \u03bd)/(2 - \u03bd): "
                 "in k for \u03bd = " + ", ".join(f"{nu:g}" for nu in in_k)
                 + " (thresholds as vertical lines), and in \u03bd at fixed k", fontsize=9)
    return _files(fig, stem, formats)
