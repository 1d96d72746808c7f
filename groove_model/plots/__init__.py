"""Figures: the boundary overlay and the regime map (matplotlib)."""
