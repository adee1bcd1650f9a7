"""The telecover test (EARLINET quality assurance; Freudenthaler et al., 2018, Atmos. Meas. Tech.
11, 4713).

The receiver's aperture is covered but for one sector at a time (classically four quadrants); the
range-corrected signals of the sectors are compared through their normalised deviations S_i(z) /
mean_j S_j(z) - 1. The atmosphere is the same for every sector, so the signals differ only through
the overlap: S_i ∝ G_i, and the deviations are ratios of G's. :func:`telecover` computes each
sector's G (one plan per sector; by ray tracing all sectors in one core call sharing their nodes)
and the full-aperture G.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any, Dict, Optional, Tuple

import numpy as np

from ... import _checks, _values
from ..._pickling import ByValue
from ...forward.backends import many
from ...forward.compute import run
from ...forward.planning import plan
from ...forward.result import OverlapResult
from ...model.aperture_mask import ApertureMask
from ...model.parameters import unit
from ...model.system import LidarSystem
from ..datasets import xarray

#: The ``sectors`` strings :func:`telecover` knows.
SECTOR_SETS = ("quadrants",)


@dataclass(frozen=True, eq=False)
class TelecoverResult(ByValue):
    """Per-sector overlaps and their normalised deviations.

    Attributes
    ----------
    ranges : m.
    names : the sectors' names.
    sectors : one :class:`OverlapResult` per sector (G normalised to the full aperture), in the
        order of ``names``.
    full : the full-aperture :class:`OverlapResult`.
    """

    ranges: np.ndarray
    names: Tuple[str, ...]
    sectors: Tuple[OverlapResult, ...]
    full: OverlapResult

    def __post_init__(self) -> None:
        _values.check(self, {"ranges": _values.array(low=0.0)})
        names, sectors = self.names, self.sectors
        if (
            not isinstance(names, tuple)
            or not isinstance(sectors, tuple)
            or len(names) != len(sectors)
            or not all(isinstance(n, str) for n in names)
            or not all(isinstance(r, OverlapResult) for r in (*sectors, self.full))
        ):
            raise ValueError(
                "names, sectors and full are invalid: expected a name and an OverlapResult per "
                "sector, and the full aperture's OverlapResult"
            )
        for r in (*sectors, self.full):
            if not np.array_equal(r.ranges, self.ranges):
                raise ValueError("ranges is invalid: expected the ranges of every sector's result")

    @property
    def overlap(self) -> np.ndarray:
        """G of each sector (sector x range)."""
        return np.array([r.overlap for r in self.sectors])

    @property
    def error_estimate(self) -> np.ndarray:
        """Stated error of each sector's G (sector x range)."""
        return np.array([r.error_estimate for r in self.sectors])

    @property
    def deviation(self) -> np.ndarray:
        """Normalised deviations G_i / mean_j G_j - 1 (sector x range): the telecover's S_i / mean S
        - 1, since
        the sectors see the same atmosphere. NaN where no sector receives anything."""
        return deviations(self.overlap)

    @property
    def method(self) -> str:
        """The model of every curve."""
        return self.full.method

    @property
    def system(self) -> Optional[LidarSystem]:
        """The system without a mask (the full aperture's)."""
        return self.full.system

    def to_xarray(self):
        """An ``xarray.Dataset`` (sector x range): ``overlap``, ``error_estimate``, ``deviation``
        and ``full_overlap`` (range), with units and the method in the attributes (needs the ``io``
        extra)."""
        xr = xarray("TelecoverResult.to_xarray")
        dims = ("sector", "range")
        return xr.Dataset(
            {
                "overlap": (
                    dims,
                    self.overlap,
                    {"long_name": "overlap through the sector (of the full aperture)"},
                ),
                "error_estimate": (
                    dims,
                    self.error_estimate,
                    {"long_name": "stated error of overlap"},
                ),
                "deviation": (
                    dims,
                    self.deviation,
                    {"long_name": "normalised deviation G_i / mean G - 1"},
                ),
                "full_overlap": (
                    ("range",),
                    self.full.overlap,
                    {"long_name": "overlap of the full aperture"},
                ),
            },
            coords={"sector": list(self.names), "range": ("range", self.ranges, {"units": "m"})},
            attrs={
                "method": self.full.method,
                "tolerance": float(self.full.tolerance),
                "reference": "Freudenthaler et al. (2018), Atmos. Meas. Tech. 11, 4713",
            },
        )

    def plot(self, band: float = 0.05, axes=None):
        """The conventional telecover figure: range-corrected signals per sector (∝ G_i) and the
        normalised deviations with the ±``band`` lines. Returns the two Axes (needs ``pip install
        lidar-overlap[plot]``)."""
        from ...views.plotting import plot_telecover

        return plot_telecover(self, band=band, axes=axes)

    def plot_fit(self, fit, fig):
        """A telecover fit's plot (``fit.plot()``, ``fit`` the FitResult whose result this is):
        measured deviations (with error bars) and the fitted ones per sector in %, residuals
        below."""
        t = self
        z, shape = t.ranges, (len(t.names), t.ranges.size)
        measured, residuals = fit.measured.reshape(shape), fit.residuals.reshape(shape)
        err = (
            fit.sigma.reshape(shape)
            if fit.sigma is not None
            else np.full(shape, math.sqrt(fit.reduced_chi_square))
        )
        top, bottom = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": (3, 1)})
        for k, (name, d) in enumerate(zip(t.names, t.deviation)):
            color = f"C{k % 10}"
            top.errorbar(
                z, 100 * measured[k], yerr=100 * err[k], fmt=".", ms=3, lw=0.6, color=color
            )
            top.plot(z, 100 * d, color=color, label=f"{name} (fitted)")
            bottom.plot(z, residuals[k], ".", ms=3, color=color)
        top.axhline(0.0, color="0.5", lw=0.6)
        top.set_xscale("log")
        top.set_ylabel("normalised deviation (%)")
        top.legend(fontsize=8)
        top.set_title(
            "; ".join(
                f"{p} = {v:.4g} ± {fit.uncertainties[p]:.2g} {unit(p)}"
                for p, v in fit.parameters.items()
            ),
            fontsize=8,
        )
        bottom.axhline(0.0, color="0.5", lw=0.6)
        bottom.set_xlabel("range (m)")
        bottom.set_ylabel("residual / sigma" if fit.sigma is not None else "residual")
        return fig


def telecover(
    system: LidarSystem,
    ranges,
    sectors="quadrants",
    method="rt",
    tolerance: Optional[float] = None,
    *,
    threads: int = 0,
) -> TelecoverResult:
    """The telecover test of ``system`` at ``ranges`` (m). ``sectors``: ``"quadrants"`` (north = +y,
    east = +x: :meth:`ApertureMask.quadrants`) or an :class:`ApertureMask` whose sectors are
    measured one at a time. ``method``: ``"rt"``, ``"fo"``, ``"auto"`` or a method object;
    ``tolerance`` applies to ``"rt"`` and ``"auto"`` (None: RT's default). G of each sector stays
    normalised to the full
    aperture: by ray tracing the sectors of a partition add up to the full G; in Fourier optics
    diffraction at the sectors' edges makes their sum fall short of it by about RT's diffraction
    error (1e-3 on Table 1)."""
    mask = sector_mask(system, sectors)
    options: Dict[str, Any] = dict(threads=threads)
    if isinstance(method, str) and method != "fo":
        options["tolerance"] = tolerance
    full = run(plan(system, ranges, method, **options))
    plans = [plan(with_mask(system, part), full.ranges, method, **options) for part in mask.split()]
    return TelecoverResult(
        ranges=full.ranges, names=mask.names, sectors=sector_curves(plans), full=full
    )


def sector_curves(plans) -> tuple:
    """The result of each sector's plan: ray tracing of one system through all the masks in one core
    call (they share the beam integral's nodes) where the plans allow it, else one run each."""
    if many.one_call(plans):
        return tuple(many.through_masks(plans))
    return tuple(run(p) for p in plans)


def deviations(g: np.ndarray) -> np.ndarray:
    """G_i / mean_j G_j - 1 of G (sector x ...); NaN where every sector's G is 0."""
    mean = g.mean(axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(mean > 0.0, g / np.where(mean > 0.0, mean, 1.0) - 1.0, np.nan)


def with_mask(system: LidarSystem, mask: ApertureMask) -> LidarSystem:
    """``system`` with ``mask`` on its receiver's aperture."""
    return dataclasses.replace(system, telescope=dataclasses.replace(system.telescope, mask=mask))


def sector_mask(system, sectors) -> ApertureMask:
    """The mask of :func:`telecover`'s ``sectors`` (``"quadrants"`` or an :class:`ApertureMask`),
    checked against ``system`` (a LidarSystem without a mask)."""
    if not isinstance(system, LidarSystem):
        raise ValueError(f"system = {_checks.shown(system)} is invalid: expected a LidarSystem")
    if system.telescope.mask is not None:
        raise ValueError(
            "system.telescope.mask is invalid for telecover: expected None (telecover sets each "
            "sector's mask itself; pass the mask as sectors=)"
        )
    if isinstance(sectors, str):
        _checks.choice("sectors", sectors, SECTOR_SETS)
        mask = ApertureMask.quadrants()
    elif isinstance(sectors, ApertureMask):
        mask = sectors
    else:
        raise ValueError(
            f"sectors = {_checks.shown(sectors)} is invalid: expected 'quadrants' or an "
            "ApertureMask"
        )
    mask.validate(system.telescope.diameter, system.telescope.obstruction_radius)
    return mask
