"""A figure as files: one ``(path, write)`` per format, for writing as one group.

Every format of a figure is written to its temporary and moved into place together with the
others (:func:`~groove_model.io.atomic.atomic_write_all`), so a failed write leaves no PNG of
one run beside an SVG of another. The SVG is the same on every run: a fixed hash salt for its
element ids and no date.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib
from matplotlib.figure import Figure

__all__ = ["figure_files"]


def figure_files(fig: Figure, targets, dpi: float) -> list:
    """``(path, write)`` for each ``(path, format)`` of ``targets``: ``write(tmp)`` saves
    ``fig`` in that format at ``dpi``."""
    def write(tmp, fmt):
        with matplotlib.rc_context({"svg.hashsalt": "groove"}):
            fig.savefig(tmp, format=fmt, dpi=dpi, metadata={"Date": None} if fmt == "svg" else None)
    return [(Path(path), lambda tmp, f=fmt: write(tmp, f)) for path, fmt in targets]
