"""``method="auto"``: the cheapest model whose error stays within the tolerance, and why.

Ray tracing is exact geometric optics; what it misses is diffraction at the receiver. Its error on G
is estimated per scene from the receiver geometry alone, before anything is computed
(:func:`validity.rt_error_bound`, derived in docs/auto_method.md): at each range, the Airy tail of a
compact image beyond the detector edge, the Fresnel edges of the blur disc and of the obstruction
shadow near or through the detector, and the boundary waves the pupil edges focus on each image
centre, all as fractions of the coupling a lit detector would have.

Its maximum over the ranges, times a safety factor of 1.5, is the model error. The measured |G_RT -
G_FO| never exceeded 1.14 times the unscaled estimate at any range (where it exceeds 1 % of its
maximum) of 51 chosen scenes and 157 of 160 drawn at random (4 um to 3 mm detectors, 355-1064 nm,
0.1-0.4 m telescopes, defocus, obstruction, NA, biaxial, 5-3000 m); in the other three FO's fixed NA
cone or obstruction shadow is itself the approximation. RT is chosen when the model error leaves at
least 1 % of ``tolerance`` for RT's quadrature, which then gets the rest; otherwise Fourier optics:
the radial path for Gaussian beams, whatever their pointing (nominal accuracy 1e-8), the 2-D path
for other fields (1e-6). A field that is not Gaussian always needs Fourier optics.

With receiver aberrations the estimate is first order in the aberrated ray-traced curve: the Airy
tail e_tail G plus the edge blur (λd/D)|∂G/∂r_d|, from two coarse RT curves with the detector radius
r_d(1 ± 1e-2) on at most 16 ranges (their mean stands for G). Field-dependent Seidel terms exist
only in ray tracing.

Through turbulence on both paths (:func:`decide_both_paths`) ray tracing's return path also leaves
out the backscatter enhancement (the bright spots the two paths share); its estimate
(:func:`~.backends.turbulent_return.missed_enhancement`) adds to the diffraction error, and
Fourier optics runs where the two leave the quadrature less than its share of the tolerance, and
where it can run: its grid must sample the receiver's field of view at every plane (the core's rule,
``_core.turbulent_grid``), which for a wide field of view or a long path asks for more samples
than the memory budget holds or than the accuracy gained pays for
(:data:`AUTO_MAX_TURBULENT_GRID`). Then auto takes ray tracing on both paths, says why and warns
that its estimated error exceeds the tolerance: it never chooses a method that would refuse the
scene.

:func:`decide` only chooses, from the geometry: it computes no overlap curve, and the plan it feeds
carries its numbers, so nothing is estimated twice (:mod:`lidar_overlap.forward.planning`). The
aberrated estimate needs two coarse RT curves, so :func:`decide_aberrated` runs when the plan runs
(:func:`lidar_overlap.forward.planning.resolve`), never when it is made.
"""

from __future__ import annotations

import functools
import os
from dataclasses import dataclass, field
from typing import List, Tuple

import numpy as np

from .. import _core
from ..model.field_beam import FieldBeam
from .backends.aberrated import detector_edge_curves
from .backends.fo import FO_2D_ACCURACY, FO_RADIAL_ACCURACY
from .backends.turbulent_return import missed_enhancement
from .validity import rt_diffraction_error, rt_error_bound

#: Safety factor on the estimate: the measured error reached 1.14 times the unscaled estimate.
RT_ESTIMATE_SAFETY = 1.5
#: Least share of the tolerance left to RT's quadrature.
QUADRATURE_SHARE = 0.01
#: Factor on the first-order estimate of aberrated RT's diffraction error (largest measured
#: actual/estimate).
ABERRATED_ESTIMATE_SAFETY = 1.25
#: Ranges on which the aberrated edge term is sampled (it varies smoothly along the curve).
EDGE_SAMPLES = 16
#: Segments per direction of the two edge curves' beam integrals. They share one adaptive layout, so
#: their difference settles long before either curve: 8 segments give it within 0.2 % of 4000
#: segments at a fifth of the time (a field-dependent scene at 20 km where each curve stops ~2e-4
#: short of convergence).
EDGE_MAX_SEGMENTS = 8
#: Largest beam grid auto gives Fourier optics on both paths. Each draw carries 1 + receiver_fields
#: fields of grid² through every plane; 1024² is 16 times the default grid's cost (benchmarks/
#: bench_turbulent_both.py: 8 s a draw at 432² with 8 fields and 20 ranges, so ~50 s at 1024²),
#: and its mean still carries the draws' statistical error (a few % of G for 20 draws): a finer
#: grid does not buy what ray tracing's missed diffraction and enhancement cost.
#: ``lo.FO(beam_grid=...)`` insists.
AUTO_MAX_TURBULENT_GRID = 1024
#: The turbulent FO path's default grid (the core's), which auto raises to what the scene needs.
DEFAULT_TURBULENT_GRID = _core.TurbulenceOptions().beam_grid


@dataclass(frozen=True)
class Decision:
    """What ``method="auto"`` chooses, with the estimates behind the choice (no overlap
    computed)."""

    method: str  # "rt" or "fo"
    fo_path: str  # "radial", "2d", "aberrated" or "" for RT
    rt_model_error: float  # estimated max |G_RT - G_exact| (NaN when RT cannot model the beam)
    rt_quadrature_tolerance: float  # what the model error leaves to RT's quadrature (0 for FO)
    reasons: List[str] = field(default_factory=list)
    warning: str = ""  # said when the plan runs (RT chosen beyond its estimated accuracy)
    # the reasons (among ``reasons``) for the FO path: not said where another path is taken
    fo_path_reasons: Tuple[str, ...] = ()


def rt_model_error(system, ranges: np.ndarray) -> float:
    """Estimated largest |G_RT - G_exact| over ``ranges`` (m), safety factor included (module
    docstring). Remembered for the last 32 (system, ranges): a curve planned again skips the ~50 µs
    estimate."""
    z = np.ascontiguousarray(ranges, dtype=float)
    try:
        return _model_error(system, z.tobytes())
    except TypeError:  # a system that cannot be hashed
        return RT_ESTIMATE_SAFETY * float(np.max(rt_error_bound(system, z)))


@functools.lru_cache(maxsize=32)
def _model_error(system, ranges: bytes) -> float:
    return RT_ESTIMATE_SAFETY * float(np.max(rt_error_bound(system, np.frombuffer(ranges))))


def radial_fo_applies(system) -> bool:
    """True when the radial FO path models the scene: a Gaussian beam (any pointing: the image
    offset enters as J0) following the Gaussian width law."""
    return not isinstance(system.beam, FieldBeam) and system.beam.width_law == "gaussian"


def decide(system, ranges: np.ndarray, tolerance: float) -> Decision:
    """The model ``method="auto"`` takes for ``system`` (no receiver aberrations: see
    :func:`decide_aberrated`) at ``ranges`` (m, validated by the caller) within ``tolerance``, from
    the geometry alone."""
    system._native.validate_ranges(ranges)
    radial_ok = radial_fo_applies(system)
    fo_path = "radial" if radial_ok else "2d"
    fo_accuracy = FO_RADIAL_ACCURACY if radial_ok else FO_2D_ACCURACY
    if isinstance(system.beam, FieldBeam):
        return Decision(
            "fo",
            fo_path,
            float("nan"),
            0.0,
            [
                f"the beam is a {type(system.beam).__name__}: ray tracing models Gaussian beams "
                "only",
                f"Fourier optics on the field's own grid, numerical accuracy ~{fo_accuracy:.0e}",
            ],
        )
    if system.aberrated:
        raise ValueError(
            "auto.decide takes systems without receiver aberrations: their estimate needs two RT "
            "curves and is made when the plan runs (auto.decide_aberrated)"
        )
    error = rt_model_error(system, ranges)
    reasons = [
        f"diffraction at the receiver: RT misses up to {error:.2g} of G here (Airy tail, Fresnel "
        "edges and boundary waves of the blur disc, estimated from the geometry, x "
        f"{RT_ESTIMATE_SAFETY})"
    ]
    quadrature = tolerance - error
    if quadrature >= QUADRATURE_SHARE * tolerance:
        reasons.append(
            f"{error:.2g} + quadrature {quadrature:.2g} <= tolerance {tolerance:g}: ray tracing "
            f"({'radial' if system.is_axisymmetric else 'two-dimensional'} integrals) is enough"
        )
        return Decision("rt", "", error, quadrature, reasons)
    if not radial_ok:  # a Gaussian beam on the linear width law: Fourier optics cannot model it
        reasons.append(
            f"{error:.2g} > tolerance {tolerance:g}, but width_law 'linear' (the paper's marginal "
            "ray) exists only in ray tracing: RT, whose model error may exceed the tolerance"
        )
        return Decision("rt", "", error, QUADRATURE_SHARE * tolerance, reasons)
    reasons.append(
        f"{error:.2g} > tolerance {tolerance:g}: diffraction matters, Fourier optics is needed"
    )
    radial = (
        "Gaussian beam: the radial FO path (one integral per range, the beam image's offset as J0)"
    )
    reasons.append(radial)
    if fo_accuracy > tolerance:
        reasons.append(
            f"warning: the FO path's own accuracy ~{fo_accuracy:.0e} exceeds the tolerance"
        )
    return Decision("fo", fo_path, error, 0.0, reasons, fo_path_reasons=(radial,))


@dataclass(frozen=True)
class TurbulentFoGrid:
    """The grid Fourier optics on both paths would run on, and whether auto may take it."""

    grid: int  # samples per side auto would use (the FO model's, or the least the scene needs)
    needed: int  # the least the core accepts (_core.turbulent_grid)
    bytes: float  # memory the call would allocate
    refusal: str = ""  # why auto may not take it ("" when it may)


def turbulent_fo_grid(system, z: np.ndarray, turbulence, options, fo_grid, threads: int):
    """The grid of Fourier optics on both paths for ``options`` (a ``_core.TurbulenceOptions``:
    screens, window, receiver fields) and the FO model's ``fo_grid`` (None: the default raised to
    what the scene needs), and why auto may not take it: a given grid below the core's least, a
    grid above :data:`AUTO_MAX_TURBULENT_GRID`, or memory above ``_core.max_memory()``."""
    options = options.__copy__()
    options.paths = "both"
    needed = int(_core.turbulent_grid(system._native, z, turbulence._native, options).min_beam_grid)
    grid = int(fo_grid) if fo_grid is not None else max(DEFAULT_TURBULENT_GRID, needed)
    team = threads if threads > 0 else (os.cpu_count() or 1)
    size = _core.turbulent_both_bytes(grid, options.screens, options.receiver_fields, team)
    refusal = ""
    if grid < needed:
        refusal = (
            f"the FO model's beam_grid {grid} is below the {needed} the core needs here (every "
            "plane must sample the receiver's field of view and λ/r0)"
        )
    elif grid > AUTO_MAX_TURBULENT_GRID:
        refusal = (
            f"Fourier optics on both paths needs a beam grid of {grid} here (every plane must "
            "sample the receiver's field of view and λ/r0), above the "
            f"{AUTO_MAX_TURBULENT_GRID} auto allows (AUTO_MAX_TURBULENT_GRID): "
            f"{(grid / DEFAULT_TURBULENT_GRID) ** 2:.3g} times the default grid's cost per field "
            "and plane"
        )
    elif size > _core.max_memory():
        refusal = (
            f"Fourier optics on both paths on {grid}² would allocate {size / 2**30:.1f} GiB, above "
            f"the memory budget {_core.max_memory() / 2**30:.1f} GiB (max_memory)"
        )
    return TurbulentFoGrid(grid, needed, size, refusal)


def decide_both_paths(
    system, z: np.ndarray, tolerance: float, turbulence, fo_grid: TurbulentFoGrid | None = None
) -> Decision:
    """The model ``method="auto"`` takes through ``turbulence`` on both paths: :func:`decide`'s
    choice, and ray tracing only where its diffraction error plus what its return path leaves out
    (the backscatter enhancement, :func:`~.backends.turbulent_return.missed_enhancement`) leave
    its quadrature a share of the tolerance; otherwise Fourier optics through the phase screens,
    unless ``fo_grid`` (:func:`turbulent_fo_grid`) refuses it: then ray tracing, with a warning."""
    d = decide(system, z, tolerance)
    if d.method == "fo" and fo_grid is not None and radial_fo_applies(system):
        if fo_grid.refusal:
            return _rt_instead(
                system, z, tolerance, turbulence, d.rt_model_error, fo_grid, d.reasons[:1]
            )
        return Decision("fo", "2d", d.rt_model_error, 0.0, d.reasons[:2] + [_on_grid(fo_grid)])
    if d.method != "rt" or not radial_fo_applies(system):  # the linear width law is RT's alone
        return d
    missed = float(np.max(missed_enhancement(system, turbulence, z)))
    reasons = d.reasons[:1] + [
        "turbulence on both paths: ray tracing tilts and blurs the image of the scattering volume "
        f"but leaves out the backscatter enhancement, estimated up to {missed:.2g} of G (spherical-"
        "wave Rytov variance x aperture averaging x the paths' tilt correlation)"
    ]
    quadrature = tolerance - d.rt_model_error - missed
    if quadrature >= QUADRATURE_SHARE * tolerance:
        reasons.append(
            f"{d.rt_model_error:.2g} + {missed:.2g} + quadrature {quadrature:.2g} <= tolerance "
            f"{tolerance:g}: ray tracing on both paths is enough"
        )
        return Decision("rt", "", d.rt_model_error + missed, quadrature, reasons)
    if fo_grid is not None and fo_grid.refusal:
        return _rt_instead(system, z, tolerance, turbulence, d.rt_model_error, fo_grid, reasons[:1])
    reasons.append(
        f"{d.rt_model_error:.2g} + {missed:.2g} > tolerance {tolerance:g}: Fourier optics through "
        "the phase screens on both paths"
    )
    if fo_grid is not None:
        reasons.append(_on_grid(fo_grid))
    return Decision("fo", "2d", d.rt_model_error + missed, 0.0, reasons)


def _on_grid(fo_grid: TurbulentFoGrid) -> str:
    return (
        f"Fourier optics on both paths on a beam grid of {fo_grid.grid} (the least the core "
        f"accepts here: {fo_grid.needed}; {fo_grid.bytes / 2**30:.2g} GiB)"
    )


def _rt_instead(system, z, tolerance, turbulence, error, fo_grid, reasons) -> Decision:
    """Ray tracing on both paths where Fourier optics would be needed but cannot run
    (``fo_grid.refusal``): its estimated error exceeds ``tolerance``, which the plan warns about."""
    missed = float(np.max(missed_enhancement(system, turbulence, z)))
    total = error + missed
    reasons = list(reasons) + [
        f"turbulence on both paths: ray tracing misses up to {error:.2g} (diffraction) + "
        f"{missed:.2g} (backscatter enhancement) of G, above tolerance {tolerance:g}",
        f"but {fo_grid.refusal}: ray tracing on both paths, whose model error may exceed the "
        "tolerance (pass method=lo.FO(beam_grid=...) to insist on Fourier optics)",
    ]
    warning = (
        f"Fourier optics on both paths cannot run here ({fo_grid.refusal}); ray tracing's "
        f"estimated error {total:.2g} exceeds tolerance {tolerance:g}"
    )
    return Decision("rt", "", total, QUADRATURE_SHARE * tolerance, reasons, warning=warning)


def decide_aberrated(system, z: np.ndarray, tolerance: float, rt_options=None) -> Decision:
    """The model ``method="auto"`` takes for a receiver with aberrations, from two coarse RT
    curves (:func:`aberrated_rt_error`): computed when the plan runs. ``rt_options`` (a
    :class:`lidar_overlap.RT`) sets the ray fan of the estimate."""
    # Field-dependent Seidel terms take RT whatever its model error: a quadrature far below the
    # tolerance would only make the ray fan (the slow RT form) slower.
    field_dependent = system.telescope.aberrations.field_dependent
    quadrature = (0.1 if field_dependent else 0.01) * tolerance
    error = aberrated_rt_error(system, z, tolerance, rt_options)
    reasons = [
        "receiver aberrations: ray tracing displaces each ray by d grad W; its diffraction error "
        f"here is up to {error:.2g} (Airy tail plus edge blur from two coarse aberrated RT curves, "
        f"x {ABERRATED_ESTIMATE_SAFETY})"
    ]
    if error + quadrature <= tolerance:
        reasons.append(
            f"{error:.2g} + quadrature {quadrature:.1g} <= tolerance {tolerance:g}: ray tracing is "
            "enough"
        )
        return Decision("rt", "", error, quadrature, reasons)
    if field_dependent:
        reasons.append(
            "field-dependent Seidel terms exist only in ray tracing: RT, whose model error may "
            "exceed the tolerance"
        )
        return Decision(
            "rt",
            "",
            error,
            quadrature,
            reasons,
            warning="field-dependent Seidel terms need ray tracing, whose diffraction error here "
            f"may reach {error:.2g} > tolerance {tolerance:g}",
        )
    reasons.append(
        f"{error:.2g} > tolerance {tolerance:g}: Fourier optics with the sampled aberrated pupil"
    )
    return Decision("fo", "aberrated", error, 0.0, reasons)


def aberrated_rt_error(system, z: np.ndarray, tolerance: float = 1e-3, rt_options=None) -> float:
    """Largest |G_RT - G_FO| expected of aberrated ray tracing over ``z`` (m): the Airy tail beyond
    the detector edge, e_tail G, plus the edge blur (λd/D)|∂G/∂r_d|, times
    ABERRATED_ESTIMATE_SAFETY. Diffraction spreads each point image by λd/D whatever the
    aberrations; this first-order bound covers the measured RT-FO difference (docs/aberrations.md).
    G and its derivative come from two RT curves at r_d (1 ± 1e-2) on EDGE_SAMPLES ranges.

    The two curves are computed to 1e-3 x ``tolerance`` (1e-6 at most): their difference over 2 % of
    r_d then errs by far less than the tolerance, and a loose tolerance does not pay for a tight
    derivative."""
    zs = z if z.size <= EDGE_SAMPLES else np.geomspace(z[0], z[-1], EDGE_SAMPLES)
    h = 1e-2 * system.detector.radius
    options = _core.RtAberratedOptions()
    if rt_options is not None:
        options.rings, options.ring_rays = rt_options.rings, rt_options.ring_rays
    options.tolerance, options.max_segments = max(1e-6, 1e-3 * tolerance), EDGE_MAX_SEGMENTS
    up, down = detector_edge_curves(system, zs, options, h)
    blur = system.diffraction_blur
    log_z, log_zs = np.log(z), np.log(zs)
    edge = np.interp(log_z, log_zs, blur * np.abs(up - down) / (2.0 * h))
    g = np.interp(log_z, log_zs, 0.5 * (up + down))
    return ABERRATED_ESTIMATE_SAFETY * float(np.max(rt_diffraction_error(system) * g + edge))
