"""Names of the regions written into the figures, placed where each region is widest.

The four regions of the ``(gamma, delta)`` plane (double rolling or rolling sliding, clockwise
or counter-clockwise) are found by classifying the centres of a grid of cells with the point
solver (:func:`groove_model.analysis.regimes.classify_cells`). A region's name goes where the
region leaves the most room for it: the cell farthest from every other region, from the
domain's edges and from the top of the axes, with horizontal distances counted less than
vertical ones because the text is wider than it is tall. On an overlay of several ``k`` only
the cells in the same region for every ``k`` count; a region with too little room is not
labelled.
"""

from __future__ import annotations

import math

import numpy as np

from ..analysis.regimes import CATEGORY_CODE, classify_cells
from ..model.parameters import Parameters, k_text

__all__ = ["REGION_NAMES", "label_regions", "region_label_positions"]

#: The regions labelled, with the words written into the figures.
REGION_NAMES = {
    "double_rolling_clockwise": "double rolling,\nclockwise",
    "double_rolling_counterclockwise": "double rolling,\ncounter-clockwise",
    "rolling_sliding_clockwise": "rolling sliding,\nclockwise",
    "rolling_sliding_counterclockwise": "rolling sliding,\ncounter-clockwise",
}
_HALF_PI = 0.5 * math.pi
#: Cells along each axis of ``[0, pi/2]`` used to place the labels.
_CELLS = 160
#: A label's half width and half height in radians of the axes (for the default figure sizes
#: and font size 7: about 0.12 and 0.035).
_HALF_SIZE = (0.12, 0.035)


def region_label_positions(params_list, top: float = _HALF_PI, codes_list=None,
                           avoid=()) -> dict:
    """Where to write the name of each region, in radians, and for which ``k``.

    Parameters
    ----------
    params_list : sequence of Parameters or float
        The friction coefficients drawn.
    top : float
        Upper limit of ``delta`` on the axes (radians): labels stay below it.
    codes_list : sequence of ndarray, optional
        Category codes on an ``n x n`` grid of cells (as from ``classify_cells``), one per
        entry of ``params_list``; computed here on a 160 x 160 grid when omitted.
    avoid : sequence of (gamma, delta)
        Points (radians) a label must not cover, e.g. other annotations.

    Returns
    -------
    dict
        ``category name -> (gamma, delta, k)`` for each region with room for its label:
        ``k`` is None where the position is in that region for every ``k`` drawn, else the
        largest ``k`` whose region has room (the label then names it).
    """
    params_list = [Parameters.coerce(p) for p in params_list]
    if codes_list is None:
        codes_list = [classify_cells(p, _CELLS) for p in params_list]
    if not codes_list:
        return {}
    n = codes_list[0].shape[0]
    centres = (np.arange(n) + 0.5) * (_HALF_PI / n)
    below_top = np.broadcast_to(centres[:, None] <= top - _HALF_SIZE[1], (n, n)).copy()
    for g, d in avoid:
        below_top &= ~((np.abs(centres[None, :] - g) < 0.5 * _HALF_SIZE[0])
                       & (np.abs(centres[:, None] - d) < 0.5 * _HALF_SIZE[1]))
    # For a label about one k: how much room each cell leaves inside one region of every k.
    room_any = [np.maximum.reduce([_room(codes == code) for code in np.unique(codes)])
                for codes in codes_list]
    positions = {}
    free = below_top
    for name in REGION_NAMES:
        masks = [codes == CATEGORY_CODE[name] for codes in codes_list]
        candidates = [(None, _room(np.logical_and.reduce(masks) & free))]
        if len(codes_list) > 1:
            for m in sorted(range(len(codes_list)), key=lambda m: -params_list[m].k):
                others = [r for o, r in enumerate(room_any) if o != m]
                candidates.append((params_list[m].k,
                                   np.minimum.reduce([_room(masks[m] & free), *others])))
        for k, room in candidates:
            j, i = np.unravel_index(int(np.argmax(room)), room.shape)
            if room[j, i] >= 1.0:
                positions[name] = (float(centres[i]), float(centres[j]), k)
                # the next labels keep clear of this one (two half-sizes between centres)
                free = free & ~((np.abs(centres[None, :] - centres[i]) < 2.0 * _HALF_SIZE[0])
                                & (np.abs(centres[:, None] - centres[j]) < 2.0 * _HALF_SIZE[1]))
                break
    return positions


def _room(inside: np.ndarray) -> np.ndarray:
    """For each cell of ``inside``, the room for a label around it, in label half-sizes (1: the
    label just fits; 0 outside; the grid's border counts as outside)."""
    from scipy.ndimage import distance_transform_edt  # scipy's image tools only for figures

    h = _HALF_PI / inside.shape[0]
    return distance_transform_edt(np.pad(inside, 1),
                                  sampling=(h / _HALF_SIZE[1], h / _HALF_SIZE[0]))[1:-1, 1:-1]


def label_regions(ax, positions: dict, scale: float = 1.0, **text_options) -> list:
    """Write each region's name at its position (radians times ``scale``), with ``k`` where it
    holds for one ``k`` only; returns the texts."""
    options = dict(fontsize=7, ha="center", va="center", color="0.25", style="italic",
                   zorder=2.5)
    options.update(text_options)
    return [ax.text(g * scale, d * scale,
                    REGION_NAMES[name] + ("" if k is None else f"\n(k = {k_text(k)})"),
                    **options)
            for name, (g, d, k) in positions.items()]
