"""``method="auto"``: the cheapest model whose error stays within the tolerance, and why.

Ray tracing is exact geometric optics; what it misses is diffraction at the receiver. Its error on G
is estimated per scene, before anything else is computed, from two terms measured on the RT curve:

- the Airy tail beyond the detector edge, lost where the image is inside the detector:
  e_tail G with e_tail = 2 λ d / (π² D r_d) (:func:`validity.rt_diffraction_error`);
- the blur of the detector edge by the point image's diffraction width λ d / D where the beam image
  crosses that edge: (λ d / D) |∂G/∂r_d|, from RT at r_d (1 ± 1e-2) on a subsample of 16 ranges.

Their maximum over the ranges, times a safety factor of 1.25, bounded the measured |G_RT - G_FO| on every
scene tried (eleven: Table 1 at 355 and 1064 nm, obstructed and defocused, wide and narrow fields of view,
M² = 3, 0.3 and 0.4 m telescopes, out to 3000 m; the tightest, a 3 mrad field of view, at 1.11;
docs/auto_method.md). The
edge term is pessimistic for detectors overfilled by a blurred image (diffraction moves light in as well
as out): there it keeps Fourier optics where RT would do. RT is chosen when that estimate plus its quadrature tolerance
is within ``tolerance``; otherwise Fourier optics: the radial path for axisymmetric Gaussian scenes
(exact to ~1e-9), the 2-D path otherwise (~1e-6). A transmitted field that is not Gaussian always needs
Fourier optics.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import List, Optional

import numpy as np

from . import _checks, _core
from .field_beam import FieldBeam
from .validity import rt_diffraction_error

#: Factor between the estimated and the largest measured RT model error.
RT_ESTIMATE_SAFETY = 1.25
#: Ranges on which the edge term is sampled (it varies smoothly along the curve).
EDGE_SAMPLES = 16
#: Numerical accuracy of the Fourier-optics paths (measured against direct quadratures).
FO_RADIAL_ACCURACY = 1e-8
FO_2D_ACCURACY = 1e-6


@dataclass
class Decision:
    """What ``method="auto"`` computes, with the estimates behind the choice."""

    method: str                      # "rt" or "fo"
    fo_path: str                     # "radial", "2d" or "" for RT
    rt_model_error: float            # estimated max |G_RT - G_exact| (NaN when RT cannot model the beam)
    rt_quadrature_tolerance: float
    reasons: List[str] = field(default_factory=list)
    rt_raw: Optional[dict] = None   # the RT run on all ranges made for the estimate, reused when RT is chosen

    def __str__(self) -> str:
        model = "ray tracing" if self.method == "rt" else f"Fourier optics ({self.fo_path} path)"
        return "\n".join([f"auto: {model}"] + [f"  - {r}" for r in self.reasons])


def rt_model_error(system, ranges: np.ndarray, g: np.ndarray, threads: int = 0) -> float:
    """Estimated largest |G_RT - G_FO| over ``ranges`` given the RT curve ``g`` there (module docstring)."""
    z = ranges if ranges.size <= EDGE_SAMPLES else np.geomspace(ranges[0], ranges[-1], EDGE_SAMPLES)
    r_d = system.detector.radius
    # A 1 % step and 1e-6 quadrature: the slope to ~1e-3 of itself, at a fraction of the main run's cost.
    h = 1e-2 * r_d
    up, down = (np.asarray(_core.overlap_rt(dataclasses.replace(
        system, detector=dataclasses.replace(system.detector, radius=r_d + s))._native, z, 1e-6, threads, 4000)["overlap"])
        for s in (h, -h))
    t, d = system.telescope, system.detector
    blur = system.beam.wavelength * (t.focal_length + d.defocus) / t.diameter
    edge = np.interp(np.log(ranges), np.log(z), blur * np.abs(up - down) / (2.0 * h))
    return RT_ESTIMATE_SAFETY * float(np.max(rt_diffraction_error(system) * g + edge))


def radial_fo_applies(system) -> bool:
    """True when the radial FO path models the scene: a Gaussian beam on the axis of an axisymmetric lidar."""
    return (not isinstance(system.beam, FieldBeam) and system.is_axisymmetric
            and system.beam.width_law == "gaussian")


def decide(system, ranges: np.ndarray, tolerance: float, threads: int = 0) -> Decision:
    """The model ``overlap(..., method="auto", tolerance=...)`` uses for this scene."""
    radial_ok = radial_fo_applies(system)
    fo_path = "radial" if radial_ok else "2d"
    fo_accuracy = FO_RADIAL_ACCURACY if radial_ok else FO_2D_ACCURACY
    if isinstance(system.beam, FieldBeam):
        return Decision("fo", fo_path, float("nan"), 0.0, [
            f"the beam is a {type(system.beam).__name__}: ray tracing models Gaussian beams only",
            f"Fourier optics on the field's own grid, numerical accuracy ~{fo_accuracy:.0e}"])
    quadrature = 0.01 * tolerance   # RT is cheap: leave the budget to the model error
    raw = _core.overlap_rt(system._native, ranges, quadrature, threads, 4000)
    error = rt_model_error(system, ranges, np.asarray(raw["overlap"]), threads)
    reasons = [f"diffraction at the receiver: RT misses up to {error:.2g} of G here (Airy tail beyond the detector "
               f"edge {rt_diffraction_error(system):.2g} x G, plus the edge blur lambda d/D x |dG/dr_d|, x "
               f"{RT_ESTIMATE_SAFETY})"]
    if error + quadrature <= tolerance:
        reasons.append(f"{error:.2g} + quadrature {quadrature:.1g} <= tolerance {tolerance:g}: ray tracing "
                       f"({'radial' if system.is_axisymmetric else 'two-dimensional'} integrals) is enough")
        return Decision("rt", "", error, quadrature, reasons, raw)
    reasons.append(f"{error:.2g} > tolerance {tolerance:g}: diffraction matters, Fourier optics is needed")
    reasons.append("axisymmetric Gaussian scene: the radial FO path (one integral per range)" if radial_ok else
                   "not axisymmetric: the 2-D FO path (propagated beam, Parseval sum on a grid)")
    if fo_accuracy > tolerance:
        reasons.append(f"warning: the FO path's own accuracy ~{fo_accuracy:.0e} exceeds the tolerance")
    return Decision("fo", fo_path, error, 0.0, reasons)


def explain(system, ranges, tolerance: float = 1e-3) -> Decision:
    """Print and return the decision ``lo.overlap(system, ranges, method="auto", tolerance=tolerance)``
    makes, with the estimates behind it."""
    z = _checks.ranges("ranges", ranges)
    decision = decide(system, z, _checks.unit_interval("tolerance", tolerance))
    print(decision)
    return decision
