"""The code that computes a :class:`lidar_overlap.forward.planning.Plan`: one module per family of
paths, each runner taking a plan and returning an :class:`OverlapResult`, and :mod:`.many` for one
plan over many variants (systems, masks, alignment grids). These modules are the only callers of
the core's compute functions; none calls a public entry point or plans anything.

:data:`BACKENDS` is the one registry: each :class:`Backend` (what a plan names by its key) says what
it computes, the model and Fourier-optics path it stands for, what it models (masks, aberrations,
turbulence, mixtures), how it runs one plan (``run``) and many variants of one (``run_many``), and
how a turbulent one runs in parts (``draws``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Optional

from ... import _checks, _core
from ..result import OverlapResult
from . import aberrated, batch, fo, masked, mixture, rt, turbulent, turbulent_parts


@dataclass(frozen=True)
class Backend:
    """One way to compute G.

    description : for plans. model : ``"rt"``, ``"fo"`` or ``"auto"`` (decided when the plan runs).
    fo_path : ``""`` for RT. error_kind : of the results (``"bound"``, ``"nominal"``,
    ``"standard_error"``). run : plan -> result (None where the plan is resolved first). run_many :
    (plan, variants, warn) -> :class:`~.batch.Curves` of many systems in one batched core call, or
    None where this plan cannot batch them (None: every backend runs them one by one). masks,
    aberrations, turbulence, mixture : what it models (an aperture mask, receiver aberrations, draws
    of a turbulent atmosphere, incoherent beam components). batched : plain-receiver ray tracing,
    whose variants and alignment grids run in one parallel core call. draws : how a turbulent
    backend runs in parts (:mod:`.turbulent_parts`), None otherwise.
    """

    description: str
    model: str
    fo_path: str
    error_kind: str
    run: Optional[Callable]
    run_many: Optional[Callable] = None
    masks: bool = False
    aberrations: bool = False
    turbulence: bool = False
    mixture: bool = False
    batched: bool = False
    draws: Optional[turbulent_parts.Draws] = None

    @property
    def plain_rt(self) -> bool:
        """Ray tracing of the plain receiver (no mask, aberrations or turbulence), of one beam or
        of each incoherent component: the quadrature's tolerance sets its accuracy."""
        return self.model == "rt" and not (self.masks or self.aberrations or self.turbulence)

    @property
    def geometric_rt(self) -> bool:
        """Ray tracing of one Gaussian beam whose diffraction error auto estimates from the
        geometry alone (with or without an aperture mask): at other ranges the estimate is made
        again (:meth:`lidar_overlap.Plan.at`)."""
        return self.model == "rt" and not (self.aberrations or self.turbulence or self.mixture)


_BOUND, _NOMINAL = "bound", "nominal"

BACKENDS = {
    "rt": Backend("ray tracing", "rt", "", _BOUND, rt.run, run_many=batch.systems, batched=True),
    "rt_aberrated": Backend(
        "ray tracing through the aberrated pupil",
        "rt",
        "",
        _BOUND,
        aberrated.run_rt,
        aberrations=True,
    ),
    "rt_masked": Backend(
        "ray tracing through the aperture mask", "rt", "", _BOUND, masked.run, masks=True
    ),
    "fo_masked": Backend(
        "Fourier optics through the aperture mask (sampled pupil)",
        "fo",
        "masked",
        _NOMINAL,
        masked.run_fo,
        masks=True,
    ),
    "fo_radial": Backend("Fourier optics (radial path)", "fo", "radial", _NOMINAL, fo.run_radial),
    "fo_2d": Backend("Fourier optics (2d path)", "fo", "2d", _NOMINAL, fo.run_2d),
    "fo_field": Backend(
        "Fourier optics (2d path, the field's own grid)", "fo", "2d", _NOMINAL, fo.run_field
    ),
    "fo_aberrated": Backend(
        "Fourier optics (aberrated path)",
        "fo",
        "aberrated",
        _NOMINAL,
        aberrated.run_fo,
        aberrations=True,
    ),
    "auto_aberrated": Backend(
        "auto through the aberrated pupil: ray tracing or Fourier optics, decided when run",
        "auto",
        "",
        _BOUND,
        None,
        aberrations=True,
    ),
    "rt_mixture": Backend(
        "ray tracing of each incoherent beam component, G their power-weighted sum",
        "rt",
        "",
        _BOUND,
        lambda plan: _run_mixture(plan),
        run_many=mixture.systems,
        mixture=True,
    ),
    "fo_mixture": Backend(
        "Fourier optics of each incoherent beam component, G their power-weighted sum",
        "fo",
        "mixture",
        _NOMINAL,
        lambda plan: _run_mixture(plan),
        mixture=True,
    ),
    "auto_mixture": Backend(
        "auto for each incoherent beam component (with aberrations: decided when run), G their "
        "power-weighted sum",
        "auto",
        "",
        _BOUND,
        None,
        mixture=True,
    ),
    "rt_turbulent": Backend(
        "ray tracing of the wandering short-term beam (all draws in one core call)",
        "rt",
        "",
        "standard_error",
        turbulent.run_rt,
        turbulence=True,
        draws=turbulent_parts.RT,
    ),
    "fo_turbulent": Backend(
        "Fourier optics through phase screens",
        "fo",
        "2d",
        "standard_error",
        turbulent.run_fo,
        turbulence=True,
        draws=turbulent_parts.FO,
    ),
}


def backend(key: str) -> Backend:
    """The registry entry of ``key``; a key no plan makes is refused by name."""
    if key not in BACKENDS:  # a Plan built by hand
        raise ValueError(
            f"plan.backend = {_checks.shown(key)} is invalid: expected one of "
            f"{', '.join(map(repr, BACKENDS))} (make plans with lidar_overlap.plan)"
        )
    return BACKENDS[key]


def run(plan) -> OverlapResult:
    """Compute ``plan`` (resolved: see :func:`lidar_overlap.forward.planning.resolve`): its
    warnings, then its backend (a turbulent plan along a path without turbulence runs the plain
    backend and repeats its curve for every draw)."""
    entry = backend(plan.backend)
    if entry.run is None:
        raise ValueError(
            f"plan.backend = {plan.backend!r} is decided when the plan runs: pass the plan to "
            "lidar_overlap.run"
        )
    for message in plan.warnings:
        _checks.warn(message)
    try:
        result = entry.run(plan)
    except MemoryError as exc:  # the core's std::bad_alloc: a budget above the machine's memory
        raise _out_of_memory(plan, exc) from None
    if plan.turbulence is not None and not entry.turbulence:
        return turbulent.without_turbulence(plan, result)
    return result


def _out_of_memory(plan, exc: MemoryError) -> MemoryError:
    """``exc`` of the core, said with the grid that asked for the memory and the budget that let
    it try."""
    grid = getattr(plan.options, "beam_grid", None)
    sized = f" on a beam grid of {grid}² samples" if grid is not None else ""
    budget = _core.max_memory() / 2**30
    return MemoryError(
        f"the {plan.backend} run{sized} for {plan.ranges.size} ranges could not allocate its "
        f"arrays ({exc}): the memory budget, {budget:.6g} GiB (set_max_memory), is above what this "
        "machine can give; lower beam_grid or the ranges, or call set_max_memory(0) to restore "
        "the default budget (a quarter of the physical memory), under which the call is refused "
        "before it starts"
    )


def _run_mixture(plan) -> OverlapResult:
    """A mixture plan: each component's plan run (its own warnings said), then combined."""
    return mixture.combine(plan, [run(part) for part in plan.component_plans()])
