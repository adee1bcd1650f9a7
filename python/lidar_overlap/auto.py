"""``method="auto"``: the cheapest model whose error stays within the tolerance, and why.

Ray tracing is exact geometric optics; what it misses is diffraction at the receiver. Its error on G
is estimated per scene from the receiver geometry alone, before anything is computed
(:func:`validity.rt_error_bound`, derived in docs/auto_method.md): at each range, the Airy tail of a
compact image beyond the detector edge, the Fresnel edges of the blur disc and of the obstruction shadow
near or through the detector, and the boundary waves the pupil edges focus on each image centre, all as
fractions of the coupling a lit detector would have.

Its maximum over the ranges, times a safety factor of 1.5, is the model error. The measured |G_RT - G_FO|
never exceeded 1.14 times the unscaled estimate at any range (where it exceeds 1 % of its maximum) of
51 chosen scenes and 157 of 160 drawn at random (4 um to 3 mm detectors, 355-1064 nm,
0.1-0.4 m telescopes, defocus, obstruction, NA, biaxial, 5-3000 m); in the other three FO's fixed NA cone
or obstruction shadow is itself the approximation. RT is chosen when the model error leaves at least 1 %
of ``tolerance`` for RT's quadrature, which then gets the rest; otherwise Fourier optics: the radial path
for Gaussian beams, whatever their pointing (exact to ~1e-9), the 2-D path for other fields (~1e-6). A field
that is not Gaussian always needs Fourier optics.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field
from typing import List, Optional

import numpy as np

from . import _checks, _core
from .field_beam import FieldBeam
from .system import LidarSystem
from .validity import rt_error_bound

#: Safety factor on the estimate: the measured error reached 1.14 times the unscaled estimate.
RT_ESTIMATE_SAFETY = 1.5
#: Least share of the tolerance left to RT's quadrature.
QUADRATURE_SHARE = 0.01
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
    rt_raw: Optional[_core.RtOverlap] = None   # the RT run when RT is chosen, reused by overlap()

    def __str__(self) -> str:
        model = "ray tracing" if self.method == "rt" else f"Fourier optics ({self.fo_path} path)"
        return "\n".join([f"auto: {model}"] + [f"  - {r}" for r in self.reasons])


def validate_ranges(system, ranges: np.ndarray) -> None:
    """Refuse, as the overlap paths do and naming ``ranges[i]``, a range outside the core's lengths (1e-10 to
    1e10 m) or, behind an obstruction, not beyond its distance (``LidarSystem.validate_ranges`` in C++)."""
    system._native.validate_ranges(ranges)


def validate_range(system, z: float, name: str) -> None:
    """:func:`validate_ranges` for one range ``z`` (m), refused as ``name``."""
    try:
        system._native.validate_ranges([z])
    except ValueError as exc:
        message = str(exc)
        raise ValueError(name + message.removeprefix("ranges[0]") if message.startswith("ranges[0]") else message) \
            from None


def rt_model_error(system, ranges: np.ndarray) -> float:
    """Estimated largest |G_RT - G_exact| over ``ranges`` (m), safety factor included (module docstring).
    Remembered for the last 32 (system, ranges): a curve computed again skips the ~50 µs estimate."""
    z = np.ascontiguousarray(ranges, dtype=float)
    try:
        return _model_error(system, z.tobytes())
    except TypeError:         # a system that cannot be hashed
        return RT_ESTIMATE_SAFETY * float(np.max(rt_error_bound(system, z)))


@functools.lru_cache(maxsize=32)
def _model_error(system, ranges: bytes) -> float:
    return RT_ESTIMATE_SAFETY * float(np.max(rt_error_bound(system, np.frombuffer(ranges))))


def radial_fo_applies(system) -> bool:
    """True when the radial FO path models the scene: a Gaussian beam (any pointing: the image offset enters
    as J0) following the Gaussian width law."""
    return not isinstance(system.beam, FieldBeam) and system.beam.width_law == "gaussian"


def decide(system, ranges: np.ndarray, tolerance: float, threads: int = 0) -> Decision:
    """The model ``overlap(..., method="auto", tolerance=...)`` uses for this scene; when it is RT, the RT
    run itself (``rt_raw``), at the quadrature tolerance the model error leaves. Refuses the ranges the
    overlap paths refuse (:func:`validate_ranges`), before any estimate is made of them."""
    validate_ranges(system, ranges)
    radial_ok = radial_fo_applies(system)
    fo_path = "radial" if radial_ok else "2d"
    fo_accuracy = FO_RADIAL_ACCURACY if radial_ok else FO_2D_ACCURACY
    if isinstance(system.beam, FieldBeam):
        return Decision("fo", fo_path, float("nan"), 0.0, [
            f"the beam is a {type(system.beam).__name__}: ray tracing models Gaussian beams only",
            f"Fourier optics on the field's own grid, numerical accuracy ~{fo_accuracy:.0e}"])
    if getattr(system, "aberrated", False):
        from .overlap_aberrated import decide_aberrated   # the aberrated paths build on this module

        return decide_aberrated(system, ranges, tolerance, threads)
    error = rt_model_error(system, ranges)
    reasons = [f"diffraction at the receiver: RT misses up to {error:.2g} of G here (Airy tail, Fresnel edges "
               f"and boundary waves of the blur disc, estimated from the geometry, x {RT_ESTIMATE_SAFETY})"]
    quadrature = tolerance - error
    if quadrature >= QUADRATURE_SHARE * tolerance:
        reasons.append(f"{error:.2g} + quadrature {quadrature:.2g} <= tolerance {tolerance:g}: ray tracing "
                       f"({'radial' if system.is_axisymmetric else 'two-dimensional'} integrals) is enough")
        raw = _core.overlap_rt(system._native, ranges, _core.RtOptions(tolerance=quadrature, threads=threads))
        return Decision("rt", "", error, quadrature, reasons, raw)
    if not radial_ok:   # a Gaussian beam on the linear width law: Fourier optics cannot model it
        reasons.append(f"{error:.2g} > tolerance {tolerance:g}, but width_law 'linear' (the paper's marginal ray) "
                       "exists only in ray tracing: RT, whose model error may exceed the tolerance")
        quadrature = QUADRATURE_SHARE * tolerance
        raw = _core.overlap_rt(system._native, ranges, _core.RtOptions(tolerance=quadrature, threads=threads))
        return Decision("rt", "", error, quadrature, reasons, raw)
    reasons.append(f"{error:.2g} > tolerance {tolerance:g}: diffraction matters, Fourier optics is needed")
    reasons.append("Gaussian beam: the radial FO path (one integral per range, the beam image's offset as J0)")
    if fo_accuracy > tolerance:
        reasons.append(f"warning: the FO path's own accuracy ~{fo_accuracy:.0e} exceeds the tolerance")
    return Decision("fo", fo_path, error, 0.0, reasons)


def explain(system, ranges, tolerance: float = 1e-3) -> Decision:
    """Print and return the decision ``lo.overlap(system, ranges, method="auto", tolerance=tolerance)``
    makes, with the estimates behind it."""
    if not isinstance(system, LidarSystem):
        raise ValueError(f"system = {_checks.shown(system)} is invalid: expected a LidarSystem")
    z = _checks.ranges("ranges", ranges)
    decision = decide(system, z, _checks.unit_interval("tolerance", tolerance))
    print(decision)
    return decision
