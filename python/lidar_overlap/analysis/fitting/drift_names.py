"""The names of a drift fit's own parameters (``lo.fit_drift``), beside the free paths themselves:
one place for their spellings, importing nothing of the fit layer so that every drift module (the
basis, the reference, the result, the fit) can take them without an import cycle.

- ``path@slope``: a drifting path's slope per covariate unit (a spline's mean slope over the span;
  :mod:`lidar_overlap.analysis.fitting.drift_basis`);
- ``path@knot[j]``: a spline's departure from its chord at interior knot j;
- ``covariate@reference``: the covariate value c_ref at which the reference lies on the drift line
  (:mod:`lidar_overlap.analysis.fitting.drift_reference`);
- ``path@reference_offset``: a path's own offset at the reference.
"""

#: The suffix of a drifting parameter's slope (per covariate unit): for a spline, its mean slope.
SLOPE = "@slope"
#: The name of the reference's covariate value c_ref among a drift fit's parameters.
REFERENCE = "covariate@reference"
#: The suffix of a path's own offset at the reference (``reference_offsets``).
OFFSET = "@reference_offset"


def knot_name(path: str, j: int) -> str:
    """The name of a spline's departure from its chord at interior knot ``j`` (1 .. K-2)."""
    return f"{path}@knot[{j}]"
