"""Whether an overlap curve has shown its far-range limit: the rule behind
:meth:`~lidar_overlap.forward.result.OverlapResult.full_overlap_range`'s warning and
:meth:`~lidar_overlap.forward.result.OverlapResult.reaches_far_range` (G still rising at the end of
the ranges by more than :data:`FAR_SLOPE` of its maximum per decade, or a single range)."""

from __future__ import annotations

import math
from typing import Optional

import numpy as np

#: full_overlap_range warns when G still rises at the end of the ranges by more than this fraction
#: of its maximum per decade of range.
FAR_SLOPE = 0.01


def still_rising(z: np.ndarray, g: np.ndarray, error: np.ndarray, peak: float) -> Optional[str]:
    """Why the curve has not shown its far-range limit, by the rule of
    :meth:`~lidar_overlap.forward.result.OverlapResult.full_overlap_range`; None when it has (or G
    is zero everywhere)."""
    if peak <= 0.0:
        return None
    if z.size == 1:
        return (
            f"one range ({z[0]:.4g} m) cannot show whether G has reached its far-range limit; "
            "compute more ranges, out to where G stops rising"
        )
    start = max(z[-1] / 2.0, float(z[0]))
    log_z = np.log(z)
    g_start, e_start = (
        float(np.interp(np.log(start), log_z, values)) for values in (g, np.nan_to_num(error))
    )
    decades = math.log10(z[-1] / start)
    rise = float(g[-1]) - g_start - (float(np.nan_to_num(error[-1])) + e_start)
    if rise <= FAR_SLOPE * peak * decades:
        return None
    return (
        f"G is still rising at the end of the ranges: it gains {rise / peak:.2g} of its maximum "
        f"{peak:.4g} from {start:.4g} m to {z[-1]:.4g} m, more than {FAR_SLOPE:.0%} per decade of "
        "range, so max G may be short of its far-range limit and the range found too early; "
        "extend the ranges farther"
    )
