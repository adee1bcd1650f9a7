"""Fourier optics (paper Appendix C) of a plan: the radial path, the 2-D path of a Gaussian beam,
and the 2-D path of any transmitted field on its own grid."""

from __future__ import annotations

from ... import _checks, _core
from ...optics.propagation import EDGE_POWER_LIMIT, SamplingWarning
from ..validity import warn_if_fo_stop_moves
from ._result import result

#: Nominal accuracy of the radial path, stated as its error estimate: it agrees to 2e-10 with 8x its
#: nodes and to 4e-9 with a direct quadrature of single scatterers (docs/auto_method.md).
FO_RADIAL_ACCURACY = 1e-8
#: Nominal accuracy of the 2-D path (measured: 5.5e-7 against finer grids).
FO_2D_ACCURACY = 1e-6


def run_radial(plan):
    """One Gauss–Legendre integral per range (Gaussian beams of any pointing)."""
    raw = _core.overlap_fo_radial(plan.system._native, plan.ranges, plan.options)
    warn_if_fo_stop_moves(plan.system, plan.ranges)
    return result(plan, raw.overlap, FO_RADIAL_ACCURACY)


def run_2d(plan):
    """The sampled TEM00 (or Gaussian Schell-model) beam propagated to each range with FFTW."""
    raw = _core.overlap_fo(plan.system._native, plan.ranges, plan.options)
    _warn_if_clipped(plan, raw, "enlarge beam_window or beam_grid")
    warn_if_fo_stop_moves(plan.system, plan.ranges)
    return result(plan, raw.overlap, FO_2D_ACCURACY)


def run_field(plan):
    """Any transmitted field (flat-top, annular, vortex, ...) propagated on its own grid."""
    f = plan.system.beam.field
    raw = _core.overlap_fo_field(
        plan.system._native, plan.ranges, f.values, f.spacing, f.wavelength, plan.options
    )
    _warn_if_clipped(plan, raw, "enlarge the field's grid (zero-pad it)")
    warn_if_fo_stop_moves(plan.system, plan.ranges)
    return result(plan, raw.overlap, FO_2D_ACCURACY)


def _warn_if_clipped(plan, raw, fix: str) -> None:
    """SamplingWarning where the transmitted field loses more than EDGE_POWER_LIMIT of its power to
    the window edge or the band limit on its way to a range."""
    for z, report in zip(plan.ranges, raw.beam_reports):
        worst = max(report.output_edge_power, report.input_edge_power, report.band_limit_loss)
        if worst > EDGE_POWER_LIMIT:
            _checks.warn(
                f"overlap(fo): the transmitted field at {z:.4g} m loses {worst:.2g} of its power "
                f"to the window edge or the band limit; {fix}",
                SamplingWarning,
            )
