"""Which fitted divergences end at the diffraction limit: a Gaussian beam cannot spread more slowly
than λ/(π w0) (rad, 1/e² half-angle, w0 its 1/e² waist radius), so a fit that drives a divergence
there found the data asking for a beam better than physics allows (or a waist the model holds
wrong), as a value on a bound is set by the bound and not by the data. The default lower bound of a
divergence (:data:`lidar_overlap.model.parameters.DIFFRACTION_MARGIN`) lies just above the limit."""

from __future__ import annotations

import math
from typing import Iterable, Tuple

from ...model import parameters as _parameters

#: A fitted divergence at most this many times λ/(π w0) is "at the diffraction limit": the
#: parameter table's default lower bound (DIFFRACTION_MARGIN, 1.05) and the presets' lie below it,
#: and a value the optimiser leaves on such a bound (a fraction of the bounds' width above it) too.
AT_LIMIT = 1.06


def diffraction_limit(system, path: str) -> float:
    """λ/(π w0) (rad) of the beam (or beam component) whose divergence ``path`` names; NaN where
    the system has no such waist."""
    waist = path[: -len("divergence")] + "waist_radius"
    try:
        w0 = _parameters.get(system, waist)
    except ValueError:
        return math.nan
    return system.beam.wavelength / (math.pi * w0)


def at_diffraction_limit(system, paths: Iterable[str]) -> Tuple[str, ...]:
    """The divergence ``paths`` (``beam.divergence``, ``beam.components[i].divergence``) whose value
    in ``system`` is at most AT_LIMIT times their diffraction limit."""
    out = []
    for path in paths:
        if not path.endswith("divergence"):
            continue
        limit = diffraction_limit(system, path)
        if _parameters.get(system, path) <= AT_LIMIT * limit:
            out.append(path)
    return tuple(out)
