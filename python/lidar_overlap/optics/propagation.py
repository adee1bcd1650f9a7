"""Free-space propagation of a sampled field (paper Appendix A; SI units).

:func:`propagate` moves a :class:`~lidar_overlap.Field` by a distance with the angular spectrum
(A1), Fresnel (A5) or Fraunhofer (A7) integral, computed with FFTW in C++, and warns
(:class:`SamplingWarning`) when the result is outside the chosen method's validity.
"""

from __future__ import annotations

import warnings
from typing import Optional, Union

import numpy as np

from .. import _checks, _core
from ..model.field import Field

PROPAGATION_METHODS = ("auto", "angular_spectrum", "fresnel", "fraunhofer")

#: Power fraction allowed in the outer n/16 of a window before the field counts as clipped or
#: wrapped.
EDGE_POWER_LIMIT = 1e-6
#: Power fraction the band-limited angular-spectrum transfer function may remove.
BAND_LIMIT_LOSS_LIMIT = 1e-6
#: Phase (rad) allowed for the terms the Fresnel (A3) and Fraunhofer (A6) approximations neglect.
APPROXIMATION_PHASE_LIMIT = 0.1


class SamplingWarning(RuntimeWarning):
    """A propagation was computed outside its method's validity (aliasing, clipping, or an
    approximation used beyond its region). The message gives the reason and the fix."""


def propagate(
    field: Field,
    distance: float,
    method: str = "auto",
    output_spacing: Optional[float] = None,
    grid_size: Union[None, int, str] = None,
) -> Field:
    """Propagate ``field`` over ``distance`` (m) in free space.

    method : ``"angular_spectrum"`` (A1: exact transfer function, band-limited; output on the input
        grid), ``"fresnel"`` (A5: single FFT with output spacing λz/(n dx), or a scaled chirp-z
        transform when ``output_spacing`` is given), ``"fraunhofer"`` (A7: far field, same grids),
        or ``"auto"``: angular spectrum up to the critical distance n dx²/λ, Fresnel beyond it (and
        whenever another ``output_spacing`` is asked for).
    output_spacing : m, the output grid spacing for Fresnel and Fraunhofer; ``None`` for the natural
        one.
    grid_size : ``None`` keeps the field's n; an even int >= n zero-pads to that size; ``"auto"``
        zero-pads to the smallest power of two for which the result neither wraps around nor is
        clipped (the radius holding all but 1e-7 of the power grows at most as r0 + ``|z|`` θ, θ
        from the field's spectrum), the angular spectrum's band limit keeps the power, and a Fresnel
        output samples the irradiance at its Nyquist rate (the window spans twice the field's
        diameter); with ``method="auto"`` the method is then chosen for the padded grid. Raises
        ValueError above 8192 samples per side.

    Warns :class:`SamplingWarning` with the reason and the fix when the field is clipped by or wraps
    around the window, the angular-spectrum band limit removes power, the Fresnel input chirp is
    undersampled, or the Fresnel (A3) or Fraunhofer (A6) approximation is used outside its region.
    """
    if not isinstance(field, Field):
        raise ValueError(f"field = {_checks.shown(field)} is invalid: expected a Field")
    _checks.choice("method", method, PROPAGATION_METHODS)
    distance = _checks.real("distance", distance)
    spacing_out = (
        0.0 if output_spacing is None else _checks.positive("output_spacing", output_spacing)
    )
    values, spacing, report = _core.propagate(
        field.values,
        field.spacing,
        field.wavelength,
        distance,
        method,
        spacing_out,
        _grid_size_code(grid_size, field.n),
    )
    _warn_outside_validity(report, distance)
    return Field._from_core(values, spacing, field.wavelength)


def _grid_size_code(grid_size: Union[None, int, str], n: int) -> int:
    """0 keeps the grid, -1 asks the core to choose it, n pads to n."""
    if grid_size is None:
        return 0
    if isinstance(grid_size, str):
        _checks.choice("grid_size", grid_size, ("auto",))
        return -1
    size = _checks.count("grid_size", grid_size, n)
    if size % 2 or size > _core.MAX_GRID_SIDE:
        raise ValueError(
            f"grid_size = {size} is invalid: expected an even size from the field's n = {n} to "
            f"{_core.MAX_GRID_SIDE}, or 'auto'"
        )
    return size


def _warn_outside_validity(r: _core.PropagationReport, distance: float) -> None:
    used = r.method
    problems = []
    if r.input_edge_power > EDGE_POWER_LIMIT:
        problems.append(
            f"the input field reaches the window edge ({r.input_edge_power:.2g} of its power in "
            "the outer n/16): enlarge the grid (n) so that the field is not clipped"
        )
    # A scaled (chirp-z) output is a window chosen by the caller: what lies outside it is not
    # computed, nothing wraps around, so it is not a sampling problem.
    if r.output_edge_power > EDGE_POWER_LIMIT and not r.scaled_output:
        if used == "angular_spectrum":
            problems.append(
                f"the propagated field reaches the window edge ({r.output_edge_power:.2g} of its "
                "power in the outer n/16) and wraps around: enlarge the grid (grid_size='auto' "
                "picks it), or use method='fresnel', whose output grid grows with distance"
            )
        else:
            problems.append(
                f"{r.output_edge_power:.2g} of the power lands in the outer n/16 of the output "
                "window λz/dx, which holds the input's spatial frequencies up to its Nyquist "
                "limit: the input is undersampled there and that power is aliased (hard edges do "
                "this); sample the input more finely, soften its edges, or choose output_spacing"
            )
    if used == "angular_spectrum" and r.band_limit_loss > BAND_LIMIT_LOSS_LIMIT:
        problems.append(
            f"the band-limited transfer function removes {r.band_limit_loss:.2g} of the power: "
            f"{abs(distance):.4g} m is too far for this grid (critical distance "
            f"{r.critical_distance:.4g} m); use method='fresnel' or grid_size='auto'"
        )
    if used == "fresnel" and r.chirp_phase_step > np.pi:
        problems.append(
            f"the Fresnel input chirp is undersampled (phase step {r.chirp_phase_step:.3g} rad > π "
            "at the field's edge): the distance is too short for this grid; use "
            "method='angular_spectrum'"
        )
    if used == "fresnel" and r.fresnel_phase_error > APPROXIMATION_PHASE_LIMIT:
        problems.append(
            f"the Fresnel approximation (A3) neglects up to {r.fresnel_phase_error:.3g} rad of "
            "phase at this distance: use method='angular_spectrum'"
        )
    if used == "fraunhofer" and r.fraunhofer_phase > APPROXIMATION_PHASE_LIMIT:
        problems.append(
            "Fraunhofer in the near field: the neglected input phase π a²/(λz) is "
            f"{r.fraunhofer_phase:.3g} rad (A6); use method='fresnel'"
        )
    for p in problems:
        warnings.warn(f"propagate({used}, {distance:.4g} m): {p}", SamplingWarning, stacklevel=3)
