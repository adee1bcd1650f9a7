"""Fitting misalignment to a measured telecover test: the free scalars of a system such that its
sectors' normalised deviations G_i / mean G - 1 (:func:`.telecover`) match the measured ones, by the
least-squares driver of :mod:`lidar_overlap.analysis.fitting.solve` (:func:`.solve.solve`:
optimiser, covariance, degeneracy warnings, convergence error).

Model. Ray tracing through each sector's mask, planned once per sector on the start (RT at
``tolerance``); the vector is the deviations, sector-major (sector x range, flattened). Jacobian:
central differences of the deviations, from :func:`.sensitivity.central_differences` of each
sector's G (the same steps for every sector).

Constraint. The deviations of a range sum to zero over the sectors, so a range carries (sectors - 1)
independent points: the measured deviations are centred per range (a no-op on deviations computed
from signals, the projection of independent noise otherwise), and the degrees of freedom are
(sectors - 1) x ranges - free parameters.
"""

from __future__ import annotations

from typing import Optional

import numpy as np

from ...forward.compute import run
from ..fitting import inputs as fit_inputs
from ..fitting.problem import fit_settings, free_paths, with_system_bounds
from ..fitting.result import FitResult, step_tolerance
from ..fitting.solve import Model, fit_plan, solve
from ..sensitivity import central_differences
from .telecover import TelecoverResult, deviations, sector_curves, sector_mask, with_mask


def fit_telecover(
    system,
    ranges,
    measured_deviation,
    sigma=None,
    free=("beam.tilt",),
    sectors="quadrants",
    *,
    bounds=None,
    tolerance: Optional[float] = None,
    loss: str = "linear",
    max_evaluations: int = 200,
    method="rt",
    allow_unconverged: bool = False,
    threads: int = 0,
) -> FitResult:
    """Fit the ``free`` scalars of ``system`` (the start) to the telecover deviations
    ``measured_deviation``.

    The deviations are ratios of the sectors' G: they constrain what breaks the symmetry between the
    sectors (beam tilt, beam and detector offsets: north = +y, east = +x, so a beam tilted north
    fits as tilt[1] > 0), not the absolute level of G (an overall scale, a symmetric defocus or
    field of view are weakly or not at all constrained: expect degeneracy warnings). Unlike G, the
    deviations are odd in a tilt, so a start at tilt 0 is fine.

    ranges : m, strictly increasing. measured_deviation : array (sector x range) in the order of
    the sectors' names, or a :class:`TelecoverResult` (its deviations, at the same sectors and
    ranges). sigma : 1-sigma error of each deviation: a number, one per range or one per (sector,
    range), > 0; None: unit weights and the covariance scaled by the reduced chi-square. sectors :
    ``"quadrants"`` or an :class:`ApertureMask` (as in :func:`.telecover`). method : each sector's
    model, ``"rt"`` (its sectors in one core call), ``"fo"``, ``"auto"`` or a method object, planned
    once on the start. tolerance : RT's absolute tolerance on each sector's G (None: RT's default).
    bounds : {path: (low, high)} (SI units) over the start's ``fit_bounds`` (an instrument
    preset's), as in :func:`.fit`. Other arguments as in :func:`.fit`. Returns a
    :class:`FitResult` whose ``result`` is the fitted :class:`TelecoverResult` and whose
    ``measured``, ``sigma`` and ``residuals`` are sector-major (sector x range, flattened);
    ``predict`` gives the full aperture's G. Needs scipy.
    """
    paths = tuple(free_paths(free))
    problem = fit_settings(
        system, free=paths, bounds=with_system_bounds(system, bounds, paths), method=method,
        tolerance=tolerance, loss=loss, max_evaluations=max_evaluations,
        allow_unconverged=allow_unconverged, threads=threads,
    )  # fmt: skip
    mask = sector_mask(system, sectors)
    if len(mask.names) < 2:
        raise ValueError(
            f"sectors has {len(mask.names)} sector: expected at least two (a deviation compares "
            "sectors)"
        )
    full = fit_plan(problem, system, ranges)
    z = full.ranges
    parts = mask.split()
    plans = [fit_plan(problem, with_mask(system, part), z) for part in parts]
    y = _measured(measured_deviation, mask.names, z)
    w = _sigma(sigma, y.shape, mask.names)
    h = step_tolerance(plans[0], problem.tolerance)

    def sector_g(trial):
        return sector_curves(
            [p.with_system(with_mask(trial, part)) for p, part in zip(plans, parts)]
        )

    def result(trial):
        t = TelecoverResult(z, mask.names, sector_g(trial), run(full.with_system(trial)))
        return t, t.deviation.ravel()

    def jacobian(trial):
        g = []
        for p, part in zip(plans, parts):
            steps, shifted, _ = central_differences(p, with_mask(trial, part), paths, (1, -1), h)
            g.append(shifted)  # (path, +-, range)
        d = deviations(np.array(g))  # (sector, path, +-, range)
        return (
            ((d[:, :, 0] - d[:, :, 1]) / (2.0 * steps[:, None]))
            .transpose(0, 2, 1)
            .reshape(-1, len(paths))
        )

    start_g = np.array([c.overlap for c in sector_g(system)])
    dark = ~(start_g.mean(axis=0) > 0)
    if dark.any():
        i = int(np.argmax(dark))
        raise ValueError(
            f"ranges[{i}] = {z[i]:g} m is invalid for a telecover fit: no sector receives light "
            "there (G = 0), so the deviations are undefined; start the ranges farther out"
        )
    # the model's error on a deviation: G's tolerance relative to a sector's typical (median) mean G
    model = Model(
        evaluate=lambda trial: deviations(np.array([c.overlap for c in sector_g(trial)])).ravel(),
        jacobian=jacobian,
        result=result,
        target=(y - y.mean(axis=0)).ravel(),
        weights=w.ravel(),
        sigma_given=sigma is not None,
        plan=full,
        step_tolerance=h,
        tolerance=problem.tolerance / float(np.median(start_g.mean(axis=0))),
        independent=(len(parts) - 1) * z.size,
    )
    return solve(problem, model)


def _measured(measured, names, z) -> np.ndarray:
    if isinstance(measured, TelecoverResult):
        if measured.names != names:
            raise ValueError(
                f"measured_deviation has sectors {', '.join(measured.names)}: expected "
                f"{', '.join(names)} (those of sectors=)"
            )
        if measured.ranges.shape != z.shape or not np.allclose(
            measured.ranges, z, rtol=1e-12, atol=0.0
        ):
            raise ValueError(
                "measured_deviation is a TelecoverResult at other ranges: expected the ranges given"
            )
        measured = measured.deviation
    y = fit_inputs.measured_array(
        "measured_deviation", measured, "an array (sector x range) of deviations"
    )
    if y.shape != (len(names), z.size):
        raise ValueError(
            f"measured_deviation has shape {y.shape}: expected {(len(names), z.size)}, one row per "
            f"sector ({', '.join(names)}) and one column per range"
        )
    _first_bad(
        "measured_deviation",
        y,
        ~np.isfinite(y) | (y < -1.0),
        names,
        z,
        "a finite deviation >= -1 (G_i / mean G - 1); drop that range instead",
    )
    return y


def _sigma(sigma, shape, names) -> np.ndarray:
    if sigma is None:
        return np.ones(shape)
    w = fit_inputs.sigma_array(
        sigma, shape, f"one value per range or one per sector and range (shape {shape})"
    )
    _first_bad("sigma", w, fit_inputs.bad_sigma(w), names, None, fit_inputs.SIGMA_EXPECTED)
    return w


def _first_bad(name, values, bad, names, z, expected) -> None:
    if bad.any():
        i, j = np.unravel_index(int(np.argmax(bad)), bad.shape)
        where = f" ({names[i]}" + (f", {z[j]:g} m)" if z is not None else ")")
        raise ValueError(
            f"{name}[{i}, {j}] = {values[i, j]}{where} is invalid: expected {expected}"
        )
