"""Alignment maps: the overlap G over a grid of misalignments, at chosen ranges.

Each axis (``tilt_x``, ``beam_offset_y``, ``defocus``, ...) is a 1-D array of values **added to the
system's own value** of that scalar (a tilt of 0 on the axis is the system as given). One or two
axes; the whole grid is computed by ray tracing in one parallel call of the C++ core, each grid
point bit for bit what ``lo.overlap(misaligned system, ranges, "rt", tolerance=..., threads=...)``
gives (with ``method="fo"``, one Fourier-optics computation per grid point instead).
"""

from __future__ import annotations

from typing import Optional

import numpy as np

from ... import _checks, _core
from ...forward.backends import many
from ...forward.compute import run
from ...forward.methods import FO
from ...forward.planning import plan
from ...model import parameters
from ...model.system import LidarSystem
from ..datasets import range_coordinate, xarray
from ..engines import engine, run_tasks, workers
from ..method_choice import ray_tracing, requested

#: Each axis keyword: the parameter path it adds to (:mod:`lidar_overlap.model.parameters`) and its
#: unit.
AXES = {
    "tilt_x": ("beam.tilt[0]", "rad"),
    "tilt_y": ("beam.tilt[1]", "rad"),
    "beam_offset_x": ("beam.offset[0]", "m"),
    "beam_offset_y": ("beam.offset[1]", "m"),
    "detector_offset_x": ("detector.offset[0]", "m"),
    "detector_offset_y": ("detector.offset[1]", "m"),
    "defocus": ("detector.defocus", "m"),
}
#: Most grid points one map takes (the product of the axis sizes), the core's cap.
MAX_POINTS = _core.MAX_ALIGNMENT_POINTS
#: Most grid points with method="fo": each is a separate FO computation (~5 ms a range on the radial
#: path).
MAX_FO_POINTS = 2500


def alignment_map(
    system,
    ranges,
    *,
    tilt_x=None,
    tilt_y=None,
    beam_offset_x=None,
    beam_offset_y=None,
    detector_offset_x=None,
    detector_offset_y=None,
    defocus=None,
    method="rt",
    tolerance: Optional[float] = None,
    threads: int = 0,
):
    """G of ``system`` over a grid of one or two misalignment axes, at each range.

    Parameters
    ----------
    system : the lidar (a Gaussian beam, no receiver aberrations: the map is ray traced).
    ranges : m, strictly increasing, each > 0 and beyond the obstruction.
    tilt_x, tilt_y : rad, added to ``beam.tilt``; beam_offset_x, beam_offset_y : m, added to
        ``beam.offset``; detector_offset_x, detector_offset_y : m, added to ``detector.offset``;
        defocus : m, added to ``detector.defocus``. Give one or two, each a non-empty, strictly
        increasing 1-D array of finite values; at most :data:`MAX_POINTS` grid points.
    method : ``"rt"`` or an :class:`lidar_overlap.RT`: the whole grid in one parallel core call.
        ``"fo"`` or an :class:`lidar_overlap.FO`: one Fourier-optics computation per grid point
        (each ``lo.overlap``, run from Python: at most :data:`MAX_FO_POINTS` points). Auto is
        refused: it could pick another model at each grid point.
    tolerance : absolute error allowed on G at each grid point and range (RT's quadrature), used
        with ``"rt"``; None: :class:`lidar_overlap.RT`'s default.
    threads : OpenMP threads over all grid points and ranges; 0 uses all cores.

    Returns an ``xarray.Dataset`` (needs ``pip install 'lidar-overlap[io]'``) with dims (the axes in
    the order of the keywords above, ``range``), coordinates with ``units`` (and the system's own
    value of each axis as its ``system_value`` attribute), variables ``overlap`` and
    ``error_estimate`` (its estimated absolute error), and attributes ``method``, ``fo_path``,
    ``tolerance`` and ``error_kind`` (as :class:`lidar_overlap.OverlapResult` states them).
    """
    given = dict(
        tilt_x=tilt_x,
        tilt_y=tilt_y,
        beam_offset_x=beam_offset_x,
        beam_offset_y=beam_offset_y,
        detector_offset_x=detector_offset_x,
        detector_offset_y=detector_offset_y,
        defocus=defocus,
    )
    axes = [(name, _axis(name, values)) for name, values in given.items() if values is not None]
    if not 1 <= len(axes) <= 2:
        raise ValueError(
            f"alignment_map takes one or two axes, {len(axes)} given "
            f"({', '.join(n for n, _ in axes) or 'none'}): choose among {', '.join(AXES)}"
        )
    points = int(np.prod([a.size for _, a in axes], dtype=float))
    if points > MAX_POINTS:
        shape = " x ".join(f"{n} ({a.size})" for n, a in axes)
        raise ValueError(
            f"{shape} = {points} grid points is too many: expected at most {MAX_POINTS}"
        )
    xr = xarray("alignment_map")
    model = requested(method, tolerance)
    if isinstance(model, FO):
        p, g, error = _fo_map(system, ranges, axes, points, model, threads)
    else:
        p = plan(
            system,
            ranges,
            ray_tracing(
                model,
                "for alignment maps: use 'rt' (one parallel core call) or 'fo' (one computation "
                "per grid point); auto could choose another model at each grid point",
            ),
            threads=threads,
        )
        if not p.batched:
            raise ValueError(
                f"alignment_map ray traces the plain receiver; this system needs {p.backend!r} "
                "(receiver aberrations): compute lo.overlap per misaligned system instead"
            )
        _checks.check_memory(
            "ranges",
            p.ranges.size,
            32.0 * points * p.ranges.size,
            "use fewer grid points or ranges",
        )
        curves = many.grid(p, axes)
        g, error = curves.overlap, curves.error_estimate

    dims = tuple(n for n, _ in axes) + ("range",)
    coords = {
        n: (
            n,
            a,
            {
                "units": AXES[n][1],
                "long_name": f"{AXES[n][0]} added to the system's value",
                "system_value": parameters.get(system, AXES[n][0]),
            },
        )
        for n, a in axes
    }
    coords["range"] = range_coordinate(p.ranges)
    return xr.Dataset(
        {
            "overlap": (dims, g, {"units": "1", "long_name": "lidar overlap function"}),
            "error_estimate": (
                dims,
                error,
                {"units": "1", "long_name": "estimated absolute error of the overlap"},
            ),
        },
        coords=coords,
        attrs={
            "method": p.method,
            "fo_path": p.fo_path,
            "tolerance": p.tolerance,
            "error_kind": p.error_kind,
            "axes": ", ".join(f"{n}: {AXES[n][0]}" for n, _ in axes),
        },
    )


def misaligned(system, **offsets):
    """``system`` with each axis keyword's value added to its scalar (what one grid point of a map
    computes)."""
    for name in offsets:
        _checks.choice("axis", name, tuple(AXES))
    return parameters.replace(
        system,
        {
            AXES[n][0]: parameters.get(system, AXES[n][0]) + _checks.real(n, v)
            for n, v in offsets.items()
        },
    )


def _fo_map(system, ranges, axes, points, model: FO, threads):
    """The FO map: one plan and run per grid point (FO has no grid call), each what lo.overlap
    gives."""
    if points > MAX_FO_POINTS:
        raise ValueError(
            f"{' x '.join(n for n, _ in axes)} = {points} grid points is too many for method='fo' "
            f"(one FO computation each): expected at most {MAX_FO_POINTS}, or use method='rt'"
        )
    grid = np.meshgrid(*(a for _, a in axes), indexing="ij")
    results = [
        run(
            plan(
                misaligned(system, **{n: float(v[i]) for (n, _), v in zip(axes, grid)}),
                ranges,
                model,
                threads=threads,
            )
        )
        for i in np.ndindex(grid[0].shape)
    ]
    shape = grid[0].shape + (results[0].ranges.size,)
    first = plan(system, ranges, model, threads=threads)
    return (
        first,
        np.array([r.overlap for r in results]).reshape(shape),
        np.array([r.error_estimate for r in results]).reshape(shape),
    )


def _axis(name: str, values) -> np.ndarray:
    """A non-empty, strictly increasing 1-D array of finite values (the core checks each grid
    point's system)."""
    try:
        raw = np.asarray(values) if not isinstance(values, (str, bytes)) else np.asarray([values])
    except (TypeError, ValueError, OverflowError) as exc:
        raise ValueError(
            f"{name} is invalid: expected a 1-D array of values in {AXES[name][1]} ({exc})"
        ) from None
    if raw.dtype.kind not in "iuf":
        raise ValueError(
            f"{name} = {_checks.shown(values)} is invalid: expected a 1-D array of real numbers in "
            f"{AXES[name][1]}"
        )
    arr = raw.astype(float)
    if arr.ndim != 1 or arr.size == 0:
        raise ValueError(
            f"{name} has shape {arr.shape}: expected a non-empty 1-D array of values in "
            f"{AXES[name][1]}"
        )
    bad = ~np.isfinite(arr)
    if bad.any():
        i = int(np.argmax(bad))
        raise ValueError(
            f"{name}[{i}] = {arr[i]} is invalid: expected a finite value in {AXES[name][1]}"
        )
    if arr.size > 1 and not np.all(np.diff(arr) > 0):
        i = int(np.argmax(~(np.diff(arr) > 0))) + 1
        raise ValueError(
            f"{name} must be strictly increasing: {name}[{i}] = {arr[i]} follows {arr[i - 1]}"
        )
    return arr


def alignment_maps(systems, ranges, *, client=None, threads: int = 0, **axes_and_options):
    """:func:`alignment_map` of each system in ``systems`` (a sequence of LidarSystems: a fleet of
    lidars, the members of a study, design variants), one task per system, through Dask: on
    ``client`` (a ``dask.distributed.Client``), else in dask's threaded scheduler here (``threads``
    maps at once, each with one core thread), else in a loop (dask not installed; then ``threads``
    go to each map). The other keywords are :func:`alignment_map`'s (the axes, ``method``,
    ``tolerance``). Each map is bit for bit the single call's.

    Returns an ``xarray.Dataset`` with a leading ``system`` dimension (index into ``systems``):
    ``overlap`` and ``error_estimate`` (system, axes..., range), ``system_value_<axis>`` (system:
    each system's own value of the axis; the axis coordinates are offsets from it), and the
    attributes of the maps plus ``engine``.
    """
    try:
        systems = [] if isinstance(systems, (LidarSystem, str)) else list(systems)
    except TypeError:
        systems = []
    if not systems or not all(isinstance(s, LidarSystem) for s in systems):
        raise ValueError("systems is invalid: expected a non-empty sequence of LidarSystem")
    unknown = sorted(set(axes_and_options) - set(AXES) - {"method", "tolerance"})
    if unknown:
        raise ValueError(
            f"{', '.join(unknown)} is invalid: expected the axes {', '.join(AXES)}, method or "
            "tolerance"
        )
    threads = _checks.threads(threads)
    xr = xarray("alignment_maps")
    kind = engine(client)
    first = alignment_map(
        systems[0], ranges, threads=threads, **axes_and_options
    )  # checks every argument once
    one = threads if kind == "loop" else 1
    rest = run_tasks(
        kind,
        client,
        _map_of,
        None,
        [(s, ranges, one, axes_and_options) for s in systems[1:]],
        workers(client, threads),
    )
    maps = [first] + rest
    names = [d for d in first["overlap"].dims if d != "range"]
    values = {
        f"system_value_{n}": (
            "system",
            [m[n].attrs["system_value"] for m in maps],
            {"units": first[n].attrs["units"], "long_name": f"each system's own {AXES[n][0]}"},
        )
        for n in names
    }
    out = xr.concat([m.drop_vars(names + ["range"]) for m in maps], dim="system")
    out = out.assign_coords({n: first[n] for n in names + ["range"]}).assign(values)
    for n in names:
        out[n].attrs.pop("system_value", None)
    out = out.assign_coords(system=np.arange(len(maps)))
    out.attrs.update(first.attrs, engine=kind)
    return out


def _map_of(_, system, ranges, threads, options):
    """One system's map (the task of :func:`alignment_maps`)."""
    return alignment_map(system, ranges, threads=threads, **options)
