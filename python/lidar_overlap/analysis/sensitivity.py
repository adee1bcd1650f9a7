"""Sensitivities dG/dp of the overlap to scalars of the system, by central differences of ray-traced
G.

Step rule. The central difference D(h) = (G(p + h) - G(p - h)) / 2h errs by the truncation h² G'''/6
plus the quadrature error of the two values, up to ``tolerance``/h. With G''' ~ 1/s³ for a parameter
whose natural scale is s (G changes by O(1) over s), the sum is smallest at h = s (3
tolerance)^(1/3). The scales are the parameter table's (:mod:`lidar_overlap.model.parameters`).

The error stated for each derivative is measured, not assumed: the truncation from D(h) and D(2h)
(Richardson's leading-order estimate |D(2h) - D(h)| / 3, doubled as a margin for the h⁴ terms, which
can make it short when they oppose the h² term) plus the core's error estimates of the two values
over 2h. All 4 perturbed systems of every parameter go through one ``overlap_rt_batch`` call.
"""

from __future__ import annotations

from typing import Optional

import numpy as np

from .. import _checks
from ..forward.backends import many
from ..forward.planning import plan
from ..model import parameters as _parameters
from .datasets import range_coordinate, xarray
from .method_choice import ray_tracing, requested


def sensitivity(
    system,
    ranges,
    parameters,
    method="rt",
    tolerance: Optional[float] = None,
    *,
    threads: int = 0,
):
    """dG/dp at each range for each parameter path (:mod:`lidar_overlap.model.parameters`; a bare
    pair such as ``"beam.tilt"`` stands for both components), by central differences of ray-traced
    G.

    ranges : m, strictly increasing. method : ``"rt"`` or an :class:`lidar_overlap.RT` (Fourier
    optics is refused: its curves state no error to set the step and the derivative's error from).
    tolerance : RT's absolute tolerance on each G (None: RT's default); the steps follow from it
    (module docstring). threads : OpenMP threads; 0 uses all cores.

    Returns an ``xarray.Dataset`` (``pip install 'lidar-overlap[io]'``) with dims (``parameter``,
    ``range``): ``derivative`` (dG/dp, in 1/unit of the parameter), ``error_estimate`` (its
    estimated absolute error), ``step`` (h per parameter, in its unit), ``value`` (the system's
    value) and ``unit`` (per parameter).
    """
    paths = _parameters.plain_paths(
        parameters,
        "parameters",
        "sensitivities ray trace the plain receiver in one batch call, and the aberrated paths "
        "have none yet",
    )
    xr = xarray("sensitivity")
    model = ray_tracing(
        requested(method, tolerance),
        "for sensitivities: their steps and errors come from ray tracing's error estimates "
        "(Fourier optics states none); use method='rt'",
    )
    p = plan(system, ranges, model, threads=threads)
    if not p.batched:
        raise ValueError(
            f"sensitivity ray traces the plain receiver; this system needs {p.backend!r} (receiver "
            "aberrations), which has no batch call yet"
        )
    values = np.array([_parameters.get(system, path) for path in paths])
    steps, g, e = central_differences(p, system, paths, (1, -1, 2, -2), p.rt_quadrature_tolerance)
    factor = (3.0 * p.rt_quadrature_tolerance) ** (1.0 / 3.0)
    z = p.ranges
    h = steps[:, None]
    d1 = (g[:, 0] - g[:, 1]) / (2 * h)
    d2 = (g[:, 2] - g[:, 3]) / (4 * h)
    error = 2.0 * np.abs(d2 - d1) / 3.0 + (e[:, 0] + e[:, 1]) / (2 * h)
    units = [_parameters.unit(path) for path in paths]
    per_unit = [f"1/{u}" if u != "1" else "1" for u in units]
    dims = ("parameter", "range")
    return xr.Dataset(
        {
            "derivative": (
                dims,
                d1,
                {
                    "long_name": "dG/dp, central difference with step h",
                    "units": "1/(unit of the parameter)",
                },
            ),
            "error_estimate": (
                dims,
                error,
                {
                    "long_name": "estimated absolute error of dG/dp: 2 |D(2h) - D(h)|/3 "
                    "+ quadrature error / h"
                },
            ),
            "step": (
                "parameter",
                steps,
                {"long_name": "central-difference step h, in the parameter's unit"},
            ),
            "value": ("parameter", values, {"long_name": "the system's value of the parameter"}),
            "unit": ("parameter", np.array(units)),
            "derivative_unit": ("parameter", np.array(per_unit)),
        },
        coords={"parameter": ("parameter", np.array(paths)), "range": range_coordinate(z)},
        attrs={
            "method": p.method,
            "tolerance": p.tolerance,
            "step_rule": f"h = s (3 tolerance)^(1/3) = {factor:.4g} s, s the parameter's natural "
            "scale",
        },
    )


def central_differences(p, system, paths, multiples, tolerance: float):
    """G of ``system`` with each path shifted by k h for each k in ``multiples``, on the model of
    plan ``p`` (its backend, options and ranges): (steps h, G and its error estimate, each (path, k,
    range)).

    h = s (3 tolerance)^(1/3) (the module's step rule, s the path's scale in ``system``). The
    shifted systems run through :func:`lidar_overlap.forward.backends.many.systems` (one core call
    on ray tracing; on another backend a run of ``p`` re-targeted at each)."""
    steps = _steps(system, paths, tolerance)
    shifted = [
        _shifted(system, path, _parameters.get(system, path), h, k)
        for path, h in zip(paths, steps)
        for k in multiples
    ]
    return (steps, *_curves(p, system, paths, shifted))


def jacobian(p, system, paths, tolerance: float) -> np.ndarray:
    """dG/dp of ``system`` on plan ``p``'s model and ranges, shape (range, path): central
    differences with the steps of :func:`central_differences`, all in one core call on ray tracing.
    A path one step from the edge of the model's range (a divergence within a step of the
    diffraction limit, a weight within a step of 1) gets the one-sided difference on the side that
    stays inside: first order, where the central one has no second point."""
    shifted, widths = difference_systems(system, paths, tolerance)
    g, _ = _curves(p, system, paths, shifted)
    return ((g[:, 0] - g[:, 1]) / widths[:, None]).T


def difference_systems(system, paths, tolerance: float):
    """(the 2 k shifted systems of :func:`jacobian`'s differences, path by path: above, then below;
    their distances (k,) in each path's unit): what a caller batching several systems' Jacobians
    into one core call runs itself."""
    steps = _steps(system, paths, tolerance)
    pairs, widths = zip(*(_difference(system, path, h) for path, h in zip(paths, steps)))
    return [s for pair in pairs for s in pair], np.array(widths)


def _steps(system, paths, tolerance: float) -> np.ndarray:
    """The step h = s (3 tolerance)^(1/3) of each path (the module's step rule)."""
    factor = (3.0 * tolerance) ** (1.0 / 3.0)
    return np.array([_parameters.step_scale(system, path) * factor for path in paths])


def _curves(p, system, paths, shifted):
    """G and its error estimate, each (path, point, range), of the ``shifted`` systems (the same
    number per path, path by path), in one run of plan ``p``'s model."""
    z = p.ranges
    shape = (len(paths), len(shifted) // len(paths), z.size)
    _checks.check_memory(
        "parameters", paths, 64.0 * len(shifted) * z.size, "vary fewer parameters or ranges"
    )
    curves = many.systems(p.with_system(system), shifted)
    return curves.overlap.reshape(shape), curves.error_estimate.reshape(shape)


def _difference(system, path: str, step: float):
    """((``system`` at p + h, at p - h), their distance 2h) for ``path``'s difference; where one
    side leaves the model's range ``system`` itself stands for it, at distance h (both leaving it is
    the central error, naming the parameter and the step)."""
    value = _parameters.get(system, path)
    try:
        above = _shifted(system, path, value, step, 1)
    except ValueError:
        above = None
    try:
        below = _shifted(system, path, value, step, -1)
    except ValueError:
        if above is None:
            raise
        return (above, system), step
    if above is None:
        return (system, below), step
    return (above, below), 2.0 * step


def _shifted(system, path: str, value: float, step: float, k: int):
    """``system`` with ``path`` at value + k step; refused naming the parameter when that leaves the
    model."""
    try:
        return _parameters.replace(system, {path: float(value + k * step)})
    except ValueError as exc:
        raise ValueError(
            f"parameters: {path} = {value:g} {'+' if k > 0 else '-'} {abs(k)} x step {step:.3g}, a "
            f"point of the central difference, leaves the model's range ({exc})"
        ) from None
