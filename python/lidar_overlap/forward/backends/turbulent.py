"""Overlap through a turbulent atmosphere (paper Section 3, step 2; the model in
:mod:`lidar_overlap.model.turbulence`): the mean over random draws of the atmosphere, with its
spread.

- Fourier optics: the beam carried through phase screens by split-step Fresnel propagation, one draw
  per realisation of the screens (C++, in parallel).
- Ray tracing: each draw is the short-term beam (radius W_ST) displaced by a random wander from a
  Gaussian whose per-axis variance (W_LT² − W_ST²)/4 makes the short-term beam, averaged over it,
  the long-term beam W_LT. With both paths the return path also tilts the image (correlated with
  the wander) and blurs it (:mod:`.turbulent_return`). All K x N draws are traced in one core call
  (``overlap_rt_batch``).

Both compute any slice of realisations bit for bit as the whole run does (``fo_rows``, ``rt_rows``
with a slice of ``wander``'s offsets): :mod:`lidar_overlap.analysis.studies.turbulence` runs them as
tasks.
"""

from __future__ import annotations

import copy
import dataclasses
import math
from typing import Any, Dict, List, NamedTuple, Optional, cast

import numpy as np

from ... import _checks, _core
from ..result import BAND, MAX_REALIZATIONS, TurbulentOverlapResult
from . import turbulent_return
from ._result import result
from .batch import pairs, warn_rt


class Rows(NamedTuple):
    """Realisations of a turbulent run: ``overlap`` (realisations x ranges); RT's convergence flags
    and error estimates (flat), None for FO; FO's uncorrelated G through both paths (realisations x
    ranges), None otherwise (RT computes their mean exactly, :func:`rt_uncorrelated_mean`)."""

    overlap: np.ndarray
    converged: Optional[np.ndarray]
    error_estimate: Optional[np.ndarray]
    uncorrelated: Optional[np.ndarray]


#: Bytes per draw (realisation x range) of the RT path: the drawn system, its result, and the copies
#: the statistics make.
BYTES_PER_DRAW = 512
#: The core's parameters that the return path through the screens constrains (a grid that samples
#: the receiver's light, no fibre NA): a refusal of either says that paths='transmit' avoids it.
RETURN_PATH_NEEDS = ("beam_grid", "detector.numerical_aperture")


def run_fo(plan) -> TurbulentOverlapResult:
    """The FO draws, all in the core; with both paths also each draw's beam with an independent
    draw's receiver (the uncorrelated paths), for the amplification."""
    g, uncorrelated = fo_rows(plan, 0, plan.turbulence.realizations)
    return statistics(plan, g, uncorrelated)


def fo_rows(plan, first: int, count: int):
    """Realisations ``first .. first + count - 1`` of the FO run of ``plan`` (count x ranges): bit
    for bit those rows of the whole run (the core's ``first_realization``), on
    ``plan.options.threads`` threads; and with both paths the same rows of the uncorrelated G
    (None for transmit only)."""
    part = copy.copy(plan.options)  # the plan's own options stay as they are
    part.realizations, part.first_realization = count, first
    both = part.paths == "both"
    try:
        raw = _core.overlap_fo_turbulent(
            plan.system._native, plan.ranges, plan.turbulence.turbulence._native, part
        )
    except _checks.ParameterError as exc:  # what the return path needs (a finer grid, no fibre NA)
        if both and exc.parameter in RETURN_PATH_NEEDS:
            message = f"{exc}; or paths = 'transmit' (the return path unperturbed)"
            raise _checks.refused(exc.parameter, exc.value, exc.expected, message) from None
        raise
    return np.asarray(raw.overlap), (np.asarray(raw.uncorrelated) if both else None)


def run_rt(plan) -> TurbulentOverlapResult:
    """The RT draws: one wandering beam per realisation and range, in one batched core call; with
    both paths also the return path's image tilt and blur, and the same draws with independent
    tilts (the uncorrelated paths), in the same call (:mod:`.turbulent_return`). A range where the
    turbulent beam leaves the paraxial model (it spreads or wanders beyond its angles or lengths) is
    refused naming ``ranges[i]`` and the turbulence."""
    check_work(plan.ranges, plan.turbulence.realizations)
    spreads = radii(plan)
    beam_radii, offsets = draws(plan, spreads)
    g, converged, error, _ = rt_rows(plan, beam_radii, offsets)
    if plan.turbulence.paths != "both":
        warn_rt(plan, converged, error, np.tile(plan.ranges, g.shape[0]))
        return statistics(plan, g)
    uncorrelated, more_converged, more_error = rt_uncorrelated_mean(plan, spreads)
    warn_rt(
        plan,
        np.concatenate([converged, more_converged]),
        np.concatenate([error, more_error]),
        np.tile(plan.ranges, g.shape[0] + 1),
    )
    warn_return_path(plan, spreads)
    return statistics(plan, g, uncorrelated_mean=uncorrelated)


def rt_uncorrelated_mean(plan, spreads=None):
    """The mean G over draws with uncorrelated paths at each range, exactly (one trace per range of
    the beam :func:`turbulent_return.uncorrelated_radius` gives), and that call's convergence flags
    and error estimates."""
    short_term, sigma = radii(plan) if spreads is None else spreads
    radius = turbulent_return.uncorrelated_radius(plan, short_term, sigma)
    g, converged, error, _ = rt_rows(plan, radius, np.zeros((1, plan.ranges.size, 2)))
    return g[0], converged, error


def warn_return_path(plan, spreads=None) -> None:
    """The RT return path's regime warning (:func:`turbulent_return.warn_outside_regime`), with the
    long-term beam radius from ``spreads`` (:func:`radii`, computed when None)."""
    short_term, sigma = radii(plan) if spreads is None else spreads
    turbulent_return.warn_outside_regime(plan, np.sqrt(short_term**2 + 4.0 * sigma**2))


def draws(plan, spreads=None):
    """What every RT draw of ``plan`` is traced with, drawn up front: :func:`wander` for the
    transmitted beam alone; with both paths :func:`turbulent_return.return_draws` of it (the beam
    radius blurred by the image's spread, and the offsets of the image's tilt added to the wander,
    realisations x ranges x 2). ``spreads``: :func:`radii` (computed when None)."""
    spreads = radii(plan) if spreads is None else spreads
    short_term, offsets = wander(plan, spreads)
    if plan.turbulence.paths != "both":
        return short_term, offsets
    blurred, both = turbulent_return.return_draws(plan, short_term, offsets, spreads[1])
    for i, zi in enumerate(plan.ranges):
        angle = spread(plan.system.beam, zi, blurred[i])
        if angle > _core.MAX_ANGLE:
            raise ValueError(
                f"{_where(plan, i)} is invalid: the short-term beam blurred by the image's spread "
                f"there ({blurred[i]:.4g} m) spreads at {angle:.4g} rad, beyond the paraxial "
                f"model's {_core.MAX_ANGLE:g} rad; expected weaker turbulence (cn2) or shorter "
                "ranges"
            )
    return blurred, both


def wander(plan, spreads=None):
    """The short-term beam radius W_ST at each range (m) and the wander offsets of every draw (m,
    realisations x ranges x 2): drawn from ``numpy.random.default_rng(seed)``, range after range,
    all realisations of a range (x, y) at a time, with per-axis sd sqrt(W_LT² − W_ST²) / 2
    (``spreads``: :func:`radii`, computed when None). A range where the short-term beam spreads
    beyond the paraxial model is refused by name."""
    system, z, request = plan.system, plan.ranges, plan.turbulence
    short_term, sigma = radii(plan) if spreads is None else spreads
    for i, zi in enumerate(z):
        if spread(system.beam, zi, short_term[i]) > _core.MAX_ANGLE:
            raise ValueError(
                f"{_where(plan, i)} is invalid: the short-term beam there ({short_term[i]:.4g} m) "
                f"spreads at {spread(system.beam, zi, short_term[i]):.4g} rad, beyond the "
                f"paraxial model's {_core.MAX_ANGLE:g} rad; expected weaker turbulence (cn2) or "
                "shorter ranges"
            )
    # 0 + sigma z: numpy's normal(0, sigma) for each draw, bit for bit, in the same order of the one
    # stream
    drawn = 0.0 + sigma[:, None, None] * np.random.default_rng(request.seed).standard_normal(
        (z.size, request.realizations, 2)
    )
    return short_term, drawn.transpose(1, 0, 2)


def radii(plan):
    """W_ST (m) at each range and the per-axis sd (m) of the beam's wander, sqrt(W_LT² − W_ST²) / 2
    (per axis W_LT² / 4 = W_ST² / 4 + sd²)."""
    beam, z, turbulence = plan.system.beam, plan.ranges, plan.turbulence.turbulence
    lam = beam.wavelength
    short_term, sigma = np.empty(z.size), np.empty(z.size)
    for i, zi in enumerate(z):
        st = turbulence.short_term_radius(
            wavelength=lam, waist_radius=beam.waist_radius, path_length=zi
        )
        lt = turbulence.long_term_radius(
            wavelength=lam, waist_radius=beam.waist_radius, path_length=zi
        )
        short_term[i] = st
        sigma[i] = 0.5 * math.sqrt(max(lt**2 - st**2, 0.0))
    return short_term, sigma


def rt_rows(plan, short_term: np.ndarray, offsets: np.ndarray):
    """G of the RT draws whose offsets are ``offsets`` (a slice of :func:`draws`'s: realisations x
    ranges x 2, m), the beam of radius ``short_term`` at each range, in one batched core call on
    ``plan.options.threads`` threads: G (realisations x ranges), the core's convergence flags and
    error estimates (flat), and None (the place of FO's uncorrelated rows: RT computes their mean
    exactly, :func:`rt_uncorrelated_mean`). Each draw's G depends on its offset alone, so the rows
    of a slice are those of the whole run, bit for bit."""
    system, z = plan.system, plan.ranges
    beam, telescope, detector = system.beam, system.telescope._native, system.detector._native
    count = offsets.shape[0]
    draws: List[Any] = [None] * (count * z.size)  # realisation-major: G reshapes to (count, ranges)
    for i, zi in enumerate(z):  # range by range: an invalid draw is named by its first range
        for r in range(count):
            try:
                draws[r * z.size + i] = _core.LidarSystem(
                    native_beam_for(beam, zi, short_term[i], offsets[r, i]), telescope, detector
                )
            except ValueError as exc:  # the drawn beam's offset or divergence beyond the core's
                raise ValueError(
                    f"{_where(plan, i)} is invalid: ray tracing cannot model the wandering beam "
                    f"there ({exc}); its axis (offset + tilt x range) and wander must stay within "
                    "the model's lengths and angles: expected shorter ranges, a smaller tilt or "
                    "weaker turbulence (cn2)"
                ) from None
    rows = pairs(plan, draws, np.tile(z, count), warn=False)
    return Rows(rows.overlap.reshape(count, z.size), rows.converged, rows.error_estimate, None)


def _where(plan, i: int) -> str:
    z, turbulence = float(plan.ranges[i]), plan.turbulence.turbulence
    return f"ranges[{i}] = {z!r} m with turbulence = {turbulence!r}"


def without_turbulence(plan, plain) -> TurbulentOverlapResult:
    """A path without turbulence: every draw is the plain curve, the spread zero; on both paths the
    amplification 1 (NaN where no light comes back)."""
    zero = np.zeros(plan.ranges.size)
    samples = np.tile(plain.overlap, (plan.turbulence.realizations, 1))
    extra: Dict[str, Any] = {"paths": plan.turbulence.paths}
    if plan.turbulence.paths == "both":
        extra["amplification"] = np.where(plain.overlap > 0, 1.0, np.nan)
    out = result(
        plan,
        plain.overlap,
        zero,
        TurbulentOverlapResult,
        realizations=samples,
        std=zero.copy(),
        low=plain.overlap.copy(),
        high=plain.overlap.copy(),
        **extra,
    )
    return cast(TurbulentOverlapResult, out)


def statistics(
    plan, samples: np.ndarray, uncorrelated=None, uncorrelated_mean=None
) -> TurbulentOverlapResult:
    """Mean, standard error, standard deviation and the BAND percentiles of the K x N ``samples``
    (C-contiguous: the reductions then sum in one order, whoever computed the rows); with both
    paths, the amplification: the mean over the mean of the ``uncorrelated`` rows (FO), or over
    ``uncorrelated_mean`` (N: RT's exact mean)."""
    samples = np.ascontiguousarray(samples)
    low, high = np.percentile(samples, BAND, axis=0)
    k = samples.shape[0]
    std = samples.std(axis=0, ddof=1) if k > 1 else np.zeros(plan.ranges.size)
    extra: Dict[str, Any] = {"paths": plan.turbulence.paths}
    if uncorrelated is not None:
        uncorrelated = np.ascontiguousarray(uncorrelated)
        mean_u = uncorrelated.mean(axis=0)
        ratio = np.divide(
            samples.mean(axis=0), mean_u, out=np.full(mean_u.shape, np.nan), where=mean_u > 0
        )
        extra.update(uncorrelated=uncorrelated, amplification=ratio)
    elif uncorrelated_mean is not None:
        mean_u = np.asarray(uncorrelated_mean)
        ratio = np.divide(
            samples.mean(axis=0), mean_u, out=np.full(mean_u.shape, np.nan), where=mean_u > 0
        )
        extra.update(amplification=ratio)
    out = result(
        plan,
        samples.mean(axis=0),
        std / math.sqrt(k),
        TurbulentOverlapResult,
        realizations=samples,
        std=std,
        low=low,
        high=high,
        **extra,
    )
    return cast(TurbulentOverlapResult, out)


def spread(beam, z: float, radius: float) -> float:
    """Far-field half-angle (rad) of a beam from ``beam``'s waist, on its width law, whose 1/e²
    radius at range z (m) is ``radius``."""
    w0 = beam.waist_radius
    if beam.width_law == "linear":  # w = w0 + θz
        return max(radius - w0, 0.0) / z
    return math.sqrt(max(radius**2 - w0**2, 0.0)) / z  # w² = w0² + (θz)²


def beam_for(beam, z: float, radius: float, center=(0.0, 0.0)):
    """A Gaussian beam whose 1/e² radius at range z is ``radius`` and whose centre there is
    ``beam``'s axis moved by ``center`` (m): the short-term beam of one draw."""
    divergence, offset = _drawn(beam, z, radius, center)
    return dataclasses.replace(beam, divergence=divergence, offset=offset, tilt=(0.0, 0.0))


def native_beam_for(beam, z: float, radius: float, center=(0.0, 0.0)) -> _core.GaussianBeam:
    """:func:`beam_for`'s beam built in the core directly (which validates it): a draw's beam needs
    none of the model's checks of a caller's input, which would cost most of a run's time."""
    divergence, offset = _drawn(beam, z, radius, center)
    return _core.GaussianBeam(
        beam.wavelength, beam.waist_radius, divergence, offset, (0.0, 0.0), beam.width_law
    )


def _drawn(beam, z: float, radius: float, center):
    axis = beam.center(z)
    offset = (axis[0] + float(center[0]), axis[1] + float(center[1]))
    return max(spread(beam, z, radius), beam.half_angle_divergence), offset


def check_work(z: np.ndarray, realizations: int) -> None:
    """Refuse, naming ``realizations``, more draws than the FO path allows or draws beyond the
    memory budget (RT: the drawn systems and their results; a study of either path: the rows it
    gathers)."""
    if realizations > MAX_REALIZATIONS:
        raise ValueError(
            f"realizations = {realizations} is invalid: expected a count from 1 to "
            f"{MAX_REALIZATIONS}"
        )
    _checks.check_memory(
        "realizations",
        realizations,
        BYTES_PER_DRAW * realizations * z.size,
        "lower realizations or the number of ranges",
    )
