"""Overlap function G(z): plan the computation, then run it.

G(z) is the power reaching the detector over the power entering the full, unobstructed aperture,
summed over all scatterers at range z weighted by the beam irradiance (so a central obstruction
lowers the far-range value to 1 - (r_obs/R)²).
"""

from __future__ import annotations

from typing import Optional, Sequence

import numpy as np

from ..model.system import LidarSystem
from . import backends
from .planning import Plan, check, plan, resolve
from .result import OverlapResult


def overlap(
    system: LidarSystem,
    ranges: Sequence[float] | np.ndarray,
    method="rt",
    *,
    threads: int = 0,
    tolerance: Optional[float] = None,
    max_segments: Optional[int] = None,
    fo_path: Optional[str] = None,
    beam_grid: Optional[int] = None,
    beam_window: Optional[float] = None,
    max_spectrum_grid: Optional[int] = None,
    turbulence=None,
    realizations: Optional[int] = None,
    seed: Optional[int] = None,
    screens: Optional[int] = None,
    paths: Optional[str] = None,
) -> OverlapResult:
    """Overlap function of ``system`` at each range: ``run(plan(system, ranges, method, ...))``.

    Parameters
    ----------
    system : the lidar.
    ranges : m, strictly increasing 1-D array; each > 0 and beyond the obstruction distance.
    method : how to compute G, an object of :mod:`lidar_overlap.forward.methods` or a shortcut
        string:

        - ``lo.RT(tolerance=1e-4, max_segments=...)`` / ``"rt"``: paraxial ray tracing (paper
          Appendix B) with exact circle geometry, to an absolute tolerance on G.
        - ``lo.FO(path="auto"|"radial"|"2d", beam_grid=, beam_window=)`` / ``"fo"``: Fourier optics
          (Appendix C), with diffraction at the receiver. A :class:`FieldBeam` or
          :class:`FlatTopBeam` needs it; a Gaussian beam with M² > 1 is taken as a Gaussian
          Schell-model beam.
        - ``lo.Auto(tolerance=...)`` / ``"auto"``: the cheapest model whose error stays within the
          tolerance (:mod:`lidar_overlap.forward.auto`; :func:`explain` says what it chose and why).
        - ``lo.Turbulent(turbulence, method, realizations=, seed=, screens=, paths=)``: through a
          turbulent atmosphere, on the beam's path and (``paths="both"``, the default) the return
          path; the result is a :class:`TurbulentOverlapResult` (mean over the draws, ``std``, a
          5–95 % band and, on both paths, the backscatter amplification).

        With ``system.telescope.aberrations`` set, both models include them (field-dependent Seidel
        terms need ray tracing).
    threads : OpenMP threads across ranges; 0 uses all cores. Results do not depend on it. A caller
        that runs computations from several threads passes 1 (or its share).

    The other keywords are shortcuts, used with a method string only (beside a method object they
    are refused): ``tolerance`` and ``max_segments`` (RT and auto), ``fo_path``, ``beam_grid``,
    ``beam_window``, ``max_spectrum_grid`` (FO), and ``turbulence``, ``realizations``, ``seed``,
    ``screens``, ``paths`` (which make it a :class:`Turbulent` method). Options that do not apply to
    the method's model are ignored.

    Warns (RuntimeWarning) when ray tracing is used outside its validity (a detector within a few
    tens of Airy radii, or ranges so short that paraxial slopes err by more than 1 %; see
    :mod:`lidar_overlap.forward.validity`), and (SamplingWarning) when a Fourier-optics grid clips
    the beam.
    """
    return run(
        plan(
            system,
            ranges,
            method,
            threads=threads,
            tolerance=tolerance,
            max_segments=max_segments,
            fo_path=fo_path,
            beam_grid=beam_grid,
            beam_window=beam_window,
            max_spectrum_grid=max_spectrum_grid,
            turbulence=turbulence,
            realizations=realizations,
            seed=seed,
            screens=screens,
            paths=paths,
        )
    )


def run(plan: Plan) -> OverlapResult:
    """Compute a :class:`Plan` (from :func:`lidar_overlap.plan`): each curve once, on the backend it
    names."""
    if not isinstance(plan, Plan):
        raise ValueError(
            f"plan = {plan!r} is invalid: expected a lidar_overlap.Plan (from lidar_overlap.plan)"
        )
    return backends.run(resolve(check(plan)))
