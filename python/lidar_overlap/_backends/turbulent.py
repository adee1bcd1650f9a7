"""Overlap through a turbulent atmosphere (paper Section 3, step 2; the model in
:mod:`lidar_overlap.turbulence`): the mean over random draws of the atmosphere, with its spread.

- Fourier optics: the beam carried through phase screens by split-step Fresnel propagation, one draw per
  realisation of the screens (C++, in parallel).
- Ray tracing: each draw is the short-term beam (radius W_ST) displaced by a random wander from a Gaussian
  whose per-axis variance (W_LT² − W_ST²)/4 makes the short-term beam, averaged over it, the long-term beam
  W_LT. All K x N draws are traced in one core call (``overlap_rt_batch``).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from .. import _checks, _core
from ..turbulence import TurbulentOverlapResult
from ..validity import warn_if_rt_invalid, warn_if_rt_unconverged
from ._result import result

#: Percentiles of the spread band reported per range.
BAND = (5.0, 95.0)
#: Realisations one turbulent overlap may draw (the core's bound on the FO path).
MAX_REALIZATIONS = 1_000_000
#: Bytes per draw (realisation x range) of the RT path: the drawn system, its result, and the copies the
#: statistics make.
BYTES_PER_DRAW = 512


def run_fo(plan) -> TurbulentOverlapResult:
    """The FO draws, all in the core."""
    raw = _core.overlap_fo_turbulent(plan.system._native, plan.ranges, plan.turbulence.turbulence._native,
                                     plan.options)
    return _statistics(plan, np.asarray(raw.overlap))


def run_rt(plan) -> TurbulentOverlapResult:
    """The RT draws: one wandering beam per realisation and range, in one batched core call. A range where the
    turbulent beam leaves the paraxial model (it spreads or wanders beyond its angles or lengths) is refused
    naming ``ranges[i]`` and the turbulence."""
    system, z, request = plan.system, plan.ranges, plan.turbulence
    k = request.realizations
    _check_rt_work(z, k)
    beam, lam, turbulence = system.beam, system.beam.wavelength, request.turbulence
    telescope, detector = system.telescope._native, system.detector._native
    rng = np.random.default_rng(request.seed)
    draws = []
    for i, zi in enumerate(z):
        where = f"ranges[{i}] = {float(zi)!r} m with turbulence = {turbulence!r}"
        st = turbulence.short_term_radius(wavelength=lam, waist_radius=beam.waist_radius, path_length=zi)
        lt = turbulence.long_term_radius(wavelength=lam, waist_radius=beam.waist_radius, path_length=zi)
        if spread(beam, zi, st) > _core.MAX_ANGLE:
            raise ValueError(f"{where} is invalid: the short-term beam there ({st:.4g} m) spreads at "
                             f"{spread(beam, zi, st):.4g} rad, beyond the paraxial model's {_core.MAX_ANGLE:g} rad; "
                             "expected weaker turbulence (cn2) or shorter ranges")
        sigma = 0.5 * math.sqrt(max(lt**2 - st**2, 0.0))   # per axis: W_LT^2 / 4 = W_ST^2 / 4 + sigma^2
        for _ in range(k):
            try:
                draws.append(_core.LidarSystem(beam_for(beam, zi, st, rng.normal(0.0, sigma, 2))._native, telescope,
                                               detector))
            except ValueError as exc:       # the drawn beam's offset or divergence beyond the core's scales
                raise ValueError(f"{where} is invalid: ray tracing cannot model the wandering beam there "
                                 f"({exc}); its axis (offset + tilt x range) and wander must stay within the model's "
                                 "lengths and angles: expected shorter ranges, a smaller tilt or weaker turbulence "
                                 "(cn2)") from None
    raw = _core.overlap_rt_batch(draws, np.repeat(z, k), plan.options)
    warn_if_rt_invalid(system, z)
    warn_if_rt_unconverged(raw, np.repeat(z, k), plan.rt_quadrature_tolerance, "loosen the tolerance")
    return _statistics(plan, np.asarray(raw.overlap).reshape(z.size, k).T)


def without_turbulence(plan, plain) -> TurbulentOverlapResult:
    """A path without turbulence: every draw is the plain curve, the spread zero."""
    zero = np.zeros(plan.ranges.size)
    samples = np.tile(plain.overlap, (plan.turbulence.realizations, 1))
    return result(plan, plain.overlap, zero, TurbulentOverlapResult, realizations=samples, std=zero.copy(),
                  low=plain.overlap.copy(), high=plain.overlap.copy())


def _statistics(plan, samples: np.ndarray) -> TurbulentOverlapResult:
    """Mean, standard error, standard deviation and the BAND percentiles of the K x N ``samples``."""
    low, high = np.percentile(samples, BAND, axis=0)
    k = samples.shape[0]
    std = samples.std(axis=0, ddof=1) if k > 1 else np.zeros(plan.ranges.size)
    return result(plan, samples.mean(axis=0), std / math.sqrt(k), TurbulentOverlapResult, realizations=samples,
                  std=std, low=low, high=high)


def spread(beam, z: float, radius: float) -> float:
    """Far-field half-angle (rad) of a beam from ``beam``'s waist, on its width law, whose 1/e² radius at range
    z (m) is ``radius``."""
    w0 = beam.waist_radius
    if beam.width_law == "linear":                          # w = w0 + θz
        return max(radius - w0, 0.0) / z
    return math.sqrt(max(radius**2 - w0**2, 0.0)) / z      # w² = w0² + (θz)²


def beam_for(beam, z: float, radius: float, center=(0.0, 0.0)):
    """A Gaussian beam whose 1/e² radius at range z is ``radius`` and whose centre there is ``beam``'s axis moved
    by ``center`` (m): the short-term beam of one draw."""
    axis = beam.center(z)
    offset = (axis[0] + float(center[0]), axis[1] + float(center[1]))
    return dataclasses.replace(beam, divergence=max(spread(beam, z, radius), beam.half_angle_divergence),
                               offset=offset, tilt=(0.0, 0.0))


def _check_rt_work(z: np.ndarray, realizations: int) -> None:
    """Refuse, naming ``realizations``, more draws than the FO path allows or draws beyond the memory budget."""
    if realizations > MAX_REALIZATIONS:
        raise ValueError(f"realizations = {realizations} is invalid: expected a count from 1 to {MAX_REALIZATIONS}")
    _checks.check_memory("realizations", realizations, BYTES_PER_DRAW * realizations * z.size,
                         "lower realizations or the number of ranges")
