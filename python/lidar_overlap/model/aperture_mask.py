"""Aperture masks: the parts of the receiver's aperture stop that the telecover test leaves open.

A :class:`Sector` is an annular sector of the aperture plane (angles from +x towards +y, radii about
the aperture centre, the frame of the beam's ``offset`` and ``tilt``); an :class:`ApertureMask` is a
union of disjoint sectors, attached to a receiver as ``Telescope(..., mask=mask)``. The overlap
through a mask stays normalised to the full, unobstructed aperture, so the G's of the parts of a
partition add up to the full G. Ray tracing computes it exactly per scatterer, Fourier optics
through the sampled pupil cut to the mask (``docs/telecover.md``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Optional, Sequence, Tuple

from .. import _checks, _core
from .._pickling import ByArguments

#: Names of the four quadrants, in the order of :meth:`ApertureMask.quadrants`.
QUADRANTS = ("north", "east", "south", "west")


def _finite(name: str, value) -> float:
    v = _checks.real(name, value)
    if not math.isfinite(v):
        raise ValueError(f"{name} = {v!r} is invalid: expected a finite number")
    return v


@dataclass(frozen=True)
class Sector(ByArguments):
    """Aperture points at angle in [start_angle, stop_angle] (rad, from +x towards +y) and radius in
    [inner_radius, outer_radius] (m). ``outer_radius=None``: the aperture's edge. The radii are
    checked against the aperture (and the obstruction: a sector wholly inside it leaves nothing)
    when the mask joins a :class:`Telescope`."""

    start_angle: float
    stop_angle: float
    inner_radius: float = 0.0
    outer_radius: Optional[float] = None

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        for name in ("start_angle", "stop_angle", "inner_radius"):
            set_(self, name, _finite(f"sector.{name}", getattr(self, name)))
        set_(self, "outer_radius", _checks.optional_real("sector.outer_radius", self.outer_radius))
        span = self.stop_angle - self.start_angle
        if not (0.0 < span <= 2.0 * math.pi * (1.0 + 1e-12)):
            raise ValueError(
                f"sector.stop_angle = {self.stop_angle!r} is invalid: expected an angle beyond "
                f"start_angle = {self.start_angle!r} by at most 2 pi (rad)"
            )
        if self.inner_radius < 0.0:
            raise ValueError(
                f"sector.inner_radius = {self.inner_radius!r} is invalid: expected a radius >= 0 "
                "(m)"
            )
        if self.outer_radius is not None and not (
            self.outer_radius > self.inner_radius and math.isfinite(self.outer_radius)
        ):
            raise ValueError(
                f"sector.outer_radius = {self.outer_radius!r} is invalid: expected a finite radius "
                f"beyond inner_radius = {self.inner_radius!r} (m), or None for the aperture's edge"
            )

    @property
    def span(self) -> float:
        """Angular width (rad)."""
        return self.stop_angle - self.start_angle


@dataclass(frozen=True)
class ApertureMask(ByArguments):
    """A union of disjoint :class:`Sector` s (touching is allowed). Empty masks and overlapping
    sectors are refused, naming the sectors. ``names`` labels the sectors (the helpers fill it)."""

    sectors: Tuple[Sector, ...]
    names: Tuple[str, ...] = ()
    _native: _core.ApertureMask = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        sectors = self.sectors
        if isinstance(sectors, Sector) or not isinstance(sectors, Sequence):
            raise ValueError(
                f"mask.sectors = {_checks.shown(sectors)} is invalid: expected a tuple of Sector"
            )
        sectors = tuple(sectors)
        if not sectors:
            raise ValueError(
                "mask.sectors = () is invalid: expected at least one Sector (an empty mask leaves "
                "nothing of the aperture)"
            )
        for i, s in enumerate(sectors):
            if not isinstance(s, Sector):
                raise ValueError(
                    f"mask.sectors[{i}] = {_checks.shown(s)} is invalid: expected a Sector"
                )
        names = tuple(str(n) for n in self.names) or tuple(
            f"sector {i}" for i in range(len(sectors))
        )
        if len(names) != len(sectors):
            raise ValueError(
                f"mask.names has {len(names)} entries: expected one per sector ({len(sectors)})"
            )
        object.__setattr__(self, "sectors", sectors)
        object.__setattr__(self, "names", names)
        native = _core.ApertureMask(
            [(s.start_angle, s.stop_angle, s.inner_radius, s.outer_radius) for s in sectors]
        )
        # Overlaps need no aperture: checked against one twice as wide as every radius given.
        reach = (
            max([s.outer_radius or 0.0 for s in sectors] + [s.inner_radius for s in sectors]) or 1.0
        )
        native.validate(_core.Telescope(4.0 * reach, 1.0, 0.0, 0.0))
        object.__setattr__(self, "_native", native)

    def validate(self, diameter: float, obstruction_radius: float = 0.0) -> None:
        """Checks the radii against an aperture of ``diameter`` (m) and its obstruction (ValueError
        naming ``mask.sectors[i]``)."""
        self._native.validate(_core.Telescope(diameter, 1.0, obstruction_radius, 0.0))

    def split(self) -> Tuple["ApertureMask", ...]:
        """One mask per sector, with its name."""
        return tuple(ApertureMask((s,), (n,)) for s, n in zip(self.sectors, self.names))

    @classmethod
    def quadrants(cls, rotation: float = 0.0) -> "ApertureMask":
        """The telecover's quadrants north, east, south, west, with north = +y and east = +x of the
        aperture plane (as seen looking along the beam, towards the sky): north spans 45°-135° from
        +x, east -45°-45°, and so on; ``rotation`` (rad) turns all four from +x towards +y."""
        rotation = _finite("rotation", rotation)
        centres = {"north": 0.5 * math.pi, "east": 0.0, "south": -0.5 * math.pi, "west": math.pi}
        return cls(
            tuple(
                Sector(
                    rotation + centres[n] - 0.25 * math.pi, rotation + centres[n] + 0.25 * math.pi
                )
                for n in QUADRANTS
            ),
            QUADRANTS,
        )

    @classmethod
    def rings(cls, radii: Sequence[float]) -> "ApertureMask":
        """Full rings between increasing ``radii`` (m): rings([0, 0.04, 0.075]) is a disc and an
        annulus. The last radius may be None for the aperture's edge."""
        radii = list(radii)
        if len(radii) < 2:
            raise ValueError(
                f"radii = {_checks.shown(radii)} is invalid: expected at least two radii (m), "
                "increasing"
            )
        return cls(
            tuple(
                Sector(0.0, 2.0 * math.pi, radii[k], radii[k + 1]) for k in range(len(radii) - 1)
            ),
            tuple(f"ring {k}" for k in range(len(radii) - 1)),
        )


def equal_sectors(n: int, rotation: float = 0.0) -> ApertureMask:
    """``n`` equal sectors, the first from ``rotation`` (rad from +x towards +y) onwards."""
    n = _checks.count("n", n, 1, 64)  # the core takes at most 64 sectors per mask
    rotation = _finite("rotation", rotation)
    step = 2.0 * math.pi / n
    return ApertureMask(
        tuple(Sector(rotation + k * step, rotation + (k + 1) * step) for k in range(n)),
        tuple(f"sector {k}" for k in range(n)),
    )


class _SectorsAttribute:
    """``ApertureMask.sectors(n, rotation)`` on the class makes n equal sectors; ``mask.sectors`` on
    a mask is its tuple of sectors (the instance's own attribute wins over this non-data
    descriptor)."""

    def __get__(self, obj, owner=None):
        return equal_sectors


# set after the dataclass is made, so that the instances keep their own tuple of sectors
ApertureMask.sectors = _SectorsAttribute()  # type: ignore[assignment]
