"""Receivers with aberrations (:class:`lidar_overlap.Aberrations` on the telescope),
docs/aberrations.md.

- Ray tracing: rays through the pupil displaced by d ∇W on the detector plane. For Zernike terms and
  W040 (the same for every scatterer) with no NA cone and no obstruction in front of the aperture, G
  is one smooth pupil integral of the share of the Gaussian beam image each ray leaves on the
  detector; otherwise each scatterer sends a ray fan whose detector-edge crossings are interpolated.
- Fourier optics: the aberrated pupil sampled and its OTF computed by FFT at each range; G is the
  aberration-free radial result plus the Parseval sum of the OTF's change. Field-dependent Seidel
  terms need ray tracing; near ranges whose defocus blur needs a transform beyond
  ``max_spectrum_grid`` are refused.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ... import _core
from ..validity import warn_if_rt_invalid, warn_if_rt_unconverged
from ._result import result

#: Accuracy of the aberrated FO path at its default tail_error, measured against finer sampling
#: (docs/aberrations.md).
FO_ABERRATED_ACCURACY = 5e-6


def run_rt(plan):
    """G by aberrated ray tracing; error: the beam integral's plus auto's model error (if any)."""
    system, z = plan.system, plan.ranges
    raw = _core.overlap_rt_aberrated(
        system._native, system.telescope.aberrations._native, z, plan.options
    )
    warn_if_rt_invalid(system, z, diffraction=plan.rt_diffraction_warning)
    warn_if_rt_unconverged(raw, z, plan.rt_quadrature_tolerance, "loosen the tolerance")
    return result(plan, raw.overlap, raw.error_estimate + plan.rt_model_error)


def run_fo(plan):
    """G by Fourier optics through the sampled aberrated pupil."""
    system = plan.system
    raw = _core.overlap_fo_aberrated(
        system._native, system.telescope.aberrations._native, plan.ranges, plan.options
    )
    return result(plan, raw.overlap, FO_ABERRATED_ACCURACY)


def detector_edge_curves(system, ranges, options, step: float):
    """Aberrated RT G of ``system`` with the detector radius r_d + step and r_d - step (m) at
    ``ranges`` (m), on ``options`` (``_core.RtAberratedOptions``): the two curves whose difference
    auto's aberrated estimate takes (:func:`lidar_overlap.forward.auto.aberrated_rt_error`)."""
    ab = system.telescope.aberrations._native
    curves = []
    for s in (step, -step):
        detector = dataclasses.replace(system.detector, radius=system.detector.radius + s)
        shifted = dataclasses.replace(system, detector=detector)
        curves.append(
            np.asarray(_core.overlap_rt_aberrated(shifted._native, ab, ranges, options).overlap)
        )
    return curves[0], curves[1]
