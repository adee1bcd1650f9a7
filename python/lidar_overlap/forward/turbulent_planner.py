"""How a request through turbulence is planned (:class:`~.methods.Turbulent`): the combinations no
path models refused, auto's choice through the turbulence (on both paths with the grid Fourier
optics would need), a calm path planned as the plain receiver, and the turbulent RT and FO plans."""

from __future__ import annotations

import dataclasses
from typing import Tuple

from .. import _checks, _core
from ..model.field_beam import FieldBeam
from . import auto
from .methods import FO, RT, Auto, Turbulent
from .planners import Scene, plain, rt_options
from .plans import Plan, base_fields

#: The 2-D path of the turbulent FO overlap needs this many samples per side at least.
MIN_TURBULENT_GRID = 32


def turbulent(system, z, request: Turbulent, threads) -> Plan:
    if system.telescope.mask is not None:
        raise ValueError(
            "turbulence with telescope.mask is not modelled: set telescope.mask or turbulence to "
            "None"
        )
    if system.aberrated:
        raise ValueError(
            "turbulence with receiver aberrations is not modelled yet: set telescope.aberrations "
            "to None or turbulence to None"
        )
    if isinstance(system.beam, FieldBeam):
        raise ValueError("turbulence with a FieldBeam is not modelled yet: expected a GaussianBeam")
    if system.detector.stop_radius is not None and request.paths == "both":
        raise ValueError(
            "detector.stop_radius with paths = 'both' is not modelled: the return path's receiver "
            "fields fill the aperture; expected paths = 'transmit' or detector.stop_radius None"
        )
    model = request.method
    tolerance = getattr(model, "tolerance", float("nan"))  # FO states none
    chosen: Tuple[str, ...] = ()  # auto's reasons, said before the plan's own
    warned: Tuple[str, ...] = ()
    calm = request.turbulence.rytov_variance(system.beam.wavelength, float(z[-1])) == 0.0
    if isinstance(model, Auto):
        model, chosen, warned = turbulent_auto(system, z, request, model, calm, threads)
    if calm:  # no turbulence at all
        p = plain(system, z, model, request, threads)
        return dataclasses.replace(
            p,
            tolerance=tolerance if p.method == "rt" else p.tolerance,
            reasons=p.reasons
            + ("the turbulence is zero along the path: every draw is the turbulence-free curve",),
        )
    scene = Scene(system, z, base_fields(system, z, request), threads)
    if isinstance(model, RT):
        return turbulent_rt(scene, request, model, chosen, warned)
    return turbulent_fo(scene, request, model, chosen)


def turbulent_auto(system, z, request: Turbulent, model: Auto, calm: bool, threads):
    """Auto through turbulence: (the model it chose, its reasons, its warning). Through turbulence
    Fourier optics is always the 2-D path through the screens; on both paths only on a grid the core
    accepts and auto allows (:func:`auto.turbulent_fo_grid`)."""
    if request.paths == "both" and not calm:
        grid = auto.turbulent_fo_grid(
            system,
            z,
            request.turbulence,
            fo_options(request, model.fo, threads),
            model.fo.beam_grid,
            threads,
        )
        d = auto.decide_both_paths(system, z, model.tolerance, request.turbulence, grid)
    else:
        d = auto.decide(system, z, model.tolerance)
    chosen = tuple(r for r in d.reasons if r not in d.fo_path_reasons)
    warned = (f"overlap(auto): {d.warning}",) if d.warning else ()
    if d.method == "rt":
        return dataclasses.replace(model.rt, tolerance=model.tolerance), chosen, warned
    if request.paths == "both" and not calm:
        return dataclasses.replace(model.fo, beam_grid=grid.grid), chosen, warned
    return model.fo, chosen, warned


def turbulent_rt(scene: Scene, request: Turbulent, model: RT, chosen, warned) -> Plan:
    both = (
        "; the return path's image tilted (correlated with the wander) and blurred, and the "
        "mean with independent tilts computed exactly for the amplification"
        if request.paths == "both"
        else ""
    )
    return Plan(
        **scene.base,
        backend="rt_turbulent",
        tolerance=model.tolerance,
        options=rt_options(model, model.tolerance, scene.threads),
        warnings=warned,
        reasons=chosen
        + (
            f"{request.realizations} draws of the beam wander{both}, ray traced to "
            f"{model.tolerance:g}",
        ),
    )


def turbulent_fo(scene: Scene, request: Turbulent, model: FO, chosen) -> Plan:
    options = fo_options(request, model, scene.threads)
    if request.paths == "both" and model.beam_grid is None:
        # a grid left to the library: the default raised to the least the core accepts, as auto
        options.beam_grid = auto.turbulent_fo_grid(
            scene.system, scene.z, request.turbulence, options, None, scene.threads
        ).grid
    both = (
        f"; the return path through the same screens ({request.receiver_fields} random-phase "
        "receiver fields)"
        if request.paths == "both"
        else ""
    )
    return Plan(
        **scene.base,
        backend="fo_turbulent",
        tolerance=float("nan"),
        options=options,
        reasons=chosen
        + (
            f"{request.realizations} draws of {request.screens} phase screens, the beam on "
            f"{options.beam_grid}^2{both}",
        ),
    )


def fo_options(request: Turbulent, model: FO, threads: int):
    """The core's options of the turbulent FO path for ``request`` and the FO ``model``."""
    options = _core.TurbulenceOptions()
    options.realizations, options.screens = request.realizations, request.screens
    options.seed = request.seed
    if model.beam_grid is not None:
        options.beam_grid = _checks.count("beam_grid", model.beam_grid, MIN_TURBULENT_GRID)
    if model.beam_window is not None:
        options.beam_window = model.beam_window
    options.max_spectrum_grid, options.threads = model.max_spectrum_grid, threads
    options.paths, options.receiver_fields = request.paths, request.receiver_fields
    return options
