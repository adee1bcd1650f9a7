"""The result of an overlap computation and the ranges derived from it."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import _checks
from .system import LidarSystem


@dataclass(frozen=True)
class OverlapResult:
    """Overlap function G(z) on a range grid.

    Attributes
    ----------
    ranges : m, the ranges asked for.
    overlap : G at each range (dimensionless, 0..1).
    method : the model that computed it (``"rt"`` or ``"fo"``).
    error_estimate : estimated absolute error of each G value (NaN where the method gives none).
    system : the lidar it describes.
    tolerance : the absolute tolerance that was asked for.
    """

    ranges: np.ndarray
    overlap: np.ndarray
    method: str
    error_estimate: np.ndarray
    system: LidarSystem
    tolerance: float

    def full_overlap_range(self, threshold: float = 0.99) -> float:
        """First range (m) of the grid where G >= threshold · max G; NaN if G is zero everywhere.

        Relative to the maximum, so an obstructed system (max G = 1 - (r_obs/R)²) has one too."""
        threshold = _checks.unit_interval("threshold", threshold, include_one=True)
        peak = float(np.max(self.overlap))
        if peak <= 0.0:
            return float("nan")
        return float(self.ranges[np.argmax(self.overlap >= threshold * peak)])

    def first_signal_range(self, threshold: float = 1e-3) -> float:
        """First range (m) of the grid where G >= threshold (absolute fraction); NaN if never."""
        threshold = _checks.unit_interval("threshold", threshold)
        hit = self.overlap >= threshold
        return float(self.ranges[np.argmax(hit)]) if hit.any() else float("nan")

    def plot(self, ax=None, **line_kwargs):
        """Plot G(z) on a logarithmic range axis, with the full-overlap and first-signal ranges marked.
        Returns the matplotlib Axes (needs ``pip install lidar-overlap[plot]``)."""
        from .plotting import plot_overlap

        return plot_overlap(self, ax=ax, **line_kwargs)
