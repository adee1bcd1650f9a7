"""The twin's telecover panel when a central obstruction makes the exact sectors slow.

Through a sector mask, an obstruction's shadow on the aperture moves with each scatterer (centre
-P z_obs / (z - z_obs), radius r_obs z / (z - z_obs)), and ray tracing must intersect the sector
with the detector's disc less that moving disc at every node of the beam integral: about 30 ms a
range on one core, 6 s for 200 ranges, against 6 ms for all 200 without the obstruction. The
estimate here keeps the shadow's size and leaves out its motion: at each range the shadow becomes
the sectors' inner radius, centred, which ray tracing integrates as fast as an unobstructed mask
(0.63 s for 200 ranges against 35.9 s exact in one run on a loaded machine, bench_view.py).
What it leaves out is the shift of the shadow by the scatterers' distance from the axis times
z_obs / (z - z_obs): for a beam centred on the axis the shifts cancel to first order (|ΔG| 3e-5 on
Table 1 with a 20 mm obstruction); a beam tilted by 0.2 mrad or set 50 mm off the axis moved G by
up to 6e-4 and the deviations G_i / mean G - 1 by up to 0.012 where mean G > 1e-3
(tests/test_view_every_beam.py holds it to the exact curves).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..analysis.studies.telecover import TelecoverResult, sector_curves, sector_mask, with_mask
from ..forward.compute import run
from ..forward.planning import plan
from ..model.aperture_mask import ApertureMask

#: Shadow radii at which the sectors are ray traced: those of this many ranges, evenly spaced in
#: index, and the obstruction's own (the far field's); between them G is interpolated in r².
LEVELS = 8


def centred_shadow_telecover(
    system, ranges, sectors="quadrants", *, tolerance=None, threads: int = 1
) -> TelecoverResult:
    """The telecover of ``system`` (with a central obstruction) at ``ranges`` (m) by ray tracing to
    ``tolerance``, each sector's obstruction shadow centred on the aperture (see the module's
    note): the sectors' G are estimates, ``full`` is the exact full-aperture curve.

    The centred shadow's radius r_s(z) = r_obs z / (z - z_obs) differs at every range; each sector
    is ray traced at all ranges through a few fixed radii (:data:`LEVELS`: those of evenly spaced
    ranges, so every range lies between two close ones) and G interpolated linearly in r_s², a
    blocked area (1e-5 from tracing each range through its own radius, on Table 1)."""
    mask = sector_mask(system, sectors)
    full = run(plan(system, ranges, "rt", tolerance=tolerance, threads=threads))
    z, tel = full.ranges, system.telescope
    clear = dataclasses.replace(system, telescope=dataclasses.replace(tel, obstruction_radius=0.0))
    parts = mask.split()
    shadow = tel.obstruction_radius * z / (z - tel.obstruction_distance)
    index = np.unique(np.round(np.linspace(0, z.size - 1, LEVELS)).astype(int))
    levels = np.unique(np.r_[shadow[index], tel.obstruction_radius])
    traced = np.zeros((levels.size, len(parts), z.size))  # G through each level's sectors
    errors = np.zeros_like(traced)
    for k, radius in enumerate(levels):
        open_ = [i for i, p in enumerate(parts) if _outer(p, tel) > radius]
        plans = [
            plan(
                with_mask(clear, _outside(parts[i], radius, tel)),
                z,
                "rt",
                tolerance=tolerance,
                threads=threads,
            )
            for i in open_
        ]
        for i, result in zip(open_, sector_curves(plans) if plans else ()):
            traced[k, i], errors[k, i] = result.overlap, result.error_estimate
    # each range between the two levels around its shadow radius, linear in r²
    upper = np.clip(np.searchsorted(levels, shadow), 1, max(1, levels.size - 1))
    lower = upper - 1 if levels.size > 1 else upper * 0
    span = levels[upper] ** 2 - levels[lower] ** 2
    t = np.where(span > 0, (shadow**2 - levels[lower] ** 2) / np.where(span > 0, span, 1.0), 0.0)
    columns = np.arange(z.size)
    overlap = (1 - t) * traced[lower, :, columns].T + t * traced[upper, :, columns].T
    error = np.maximum(errors[lower, :, columns].T, errors[upper, :, columns].T)
    return TelecoverResult(
        ranges=z,
        names=mask.names,
        sectors=tuple(
            dataclasses.replace(full, overlap=overlap[i], error_estimate=error[i])
            for i in range(len(parts))
        ),
        full=full,
    )


def _outer(part: ApertureMask, telescope) -> float:
    """The largest radius (m) of ``part``'s sectors."""
    edge = 0.5 * telescope.diameter
    return max(edge if s.outer_radius is None else s.outer_radius for s in part.sectors)


def _outside(part: ApertureMask, radius: float, telescope) -> ApertureMask:
    """``part`` less the centred disc of ``radius`` (m): each sector's inner radius raised to it,
    the sectors wholly inside it left out."""
    edge = 0.5 * telescope.diameter
    kept = [
        (dataclasses.replace(s, inner_radius=max(s.inner_radius, radius)), name)
        for s, name in zip(part.sectors, part.names)
        if (edge if s.outer_radius is None else s.outer_radius) > radius
    ]
    return ApertureMask(tuple(s for s, _ in kept), tuple(n for _, n in kept))
