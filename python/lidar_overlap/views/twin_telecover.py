"""The twin's telecover panel when a central obstruction makes the exact sectors slow.

Through a sector mask, an obstruction's shadow on the aperture moves with each scatterer (centre
-P z_obs / (z - z_obs), radius r_obs z / (z - z_obs)), and ray tracing must intersect the sector
with the detector's disc less that moving disc at every node of the beam integral: about 30 ms a
range on one core, 6 s for 200 ranges, against 6 ms for all 200 without the obstruction. The
estimate here keeps the shadow's size and leaves out its motion: at each range the shadow becomes
the sectors' inner radius, centred, which ray tracing integrates as fast as an unobstructed mask.
What it leaves out is the shift of the shadow by the scatterers' distance from the axis times
z_obs / (z - z_obs): for a beam centred on the axis the shifts cancel to first order (|ΔG| 3e-5 on
Table 1 with a 20 mm obstruction); a beam tilted by 0.2 mrad or set 50 mm off the axis moved G by
up to 6e-4 and the deviations G_i / mean G - 1 by up to 0.012 where mean G > 1e-3
(tests/test_view_every_beam.py holds it to the exact curves).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..analysis.telecover import TelecoverResult, sector_curves, sector_mask, with_mask
from ..forward.compute import run
from ..forward.planning import plan
from ..model.aperture_mask import ApertureMask


def centred_shadow_telecover(
    system, ranges, sectors="quadrants", *, tolerance=None, threads: int = 1
) -> TelecoverResult:
    """The telecover of ``system`` (with a central obstruction) at ``ranges`` (m) by ray tracing to
    ``tolerance``, each sector's obstruction shadow centred on the aperture (see the module's
    note): the sectors' G are estimates, ``full`` is the exact full-aperture curve."""
    mask = sector_mask(system, sectors)
    full = run(plan(system, ranges, "rt", tolerance=tolerance, threads=threads))
    tel = system.telescope
    clear = dataclasses.replace(system, telescope=dataclasses.replace(tel, obstruction_radius=0.0))
    parts = mask.split()
    overlap = np.zeros((len(parts), full.ranges.size))
    error = np.zeros_like(overlap)
    first = None
    for j, z in enumerate(full.ranges):
        shadow = tel.obstruction_radius * z / (z - tel.obstruction_distance)
        open_ = [i for i, p in enumerate(parts) if _outer(p, tel) > shadow]
        if not open_:
            continue  # every sector lies in the shadow: G = 0
        plans = [
            plan(
                with_mask(clear, _outside(parts[i], shadow, tel)),
                [z],
                "rt",
                tolerance=tolerance,
                threads=threads,
            )
            for i in open_
        ]
        for i, result in zip(open_, sector_curves(plans)):
            overlap[i, j], error[i, j] = result.overlap[0], result.error_estimate[0]
            first = first or result
    base = first or full
    return TelecoverResult(
        ranges=full.ranges,
        names=mask.names,
        sectors=tuple(
            dataclasses.replace(
                base, ranges=full.ranges.copy(), overlap=overlap[i], error_estimate=error[i]
            )
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
