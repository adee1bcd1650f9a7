"""How G is computed: method objects, each holding the options of one model and nothing else.

``lo.overlap(system, ranges, method)`` takes one of these (or the shortcuts ``"rt"``, ``"fo"``,
``"auto"``):

- :class:`RT`: paraxial ray tracing (paper Appendix B) to an absolute tolerance on G;
- :class:`FO`: Fourier optics (Appendix C), on the radial path (Gaussian beams, one integral per
  range) or the 2-D path (the transmitted field sampled and propagated with FFTW);
- :class:`Auto`: the cheapest model whose error fits a tolerance
  (:mod:`lidar_overlap.forward.auto`);
- :class:`Turbulent`: any of these through a turbulent atmosphere, as the mean over random draws.

Every default comes from the C++ core's option structs (``_core.RtOptions`` and its kin); ``None``
means "the core's default for the path that runs" (the 2-D FO window is 10 waist radii without
turbulence and 8 long-term radii with it). Objects are immutable and validated on construction,
naming the option.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Dict, Optional, Union

from .. import _checks, _core
from ..model.turbulence import Turbulence

_RT, _FAN, _FO = _core.RtOptions(), _core.RtAberratedOptions(), _core.FoOptions()
_TURBULENCE = _core.TurbulenceOptions()
FO_PATHS = ("auto", "radial", "2d")
#: Which paths cross the turbulence: the beam's, or the beam's and the return path's
#: (docs/turbulence.md).
TURBULENT_PATHS = ("transmit", "both")
SHORTCUTS = ("rt", "fo", "auto")
#: The fewest and most random-phase fields of the detector (``Turbulent.receiver_fields``).
RECEIVER_FIELDS = (1, 1000)


@dataclass(frozen=True)
class RT:
    """Ray tracing.

    Parameters
    ----------
    tolerance : absolute error allowed on G at each range, in [1e-14, 1); the adaptive beam integral
        stops below it.
    max_segments : cap on adaptive subdivisions per integral; reaching it warns (RuntimeWarning).
    rings, ring_rays : the ray fan each scatterer sends through an aberrated receiver (rings equally
        spaced in area x rays per ring); used only where the aberrations need a fan.
    """

    tolerance: float = _RT.tolerance
    max_segments: int = _RT.max_segments
    rings: int = _FAN.rings
    ring_rays: int = _FAN.ring_rays

    def __post_init__(self) -> None:
        object.__setattr__(self, "tolerance", _checks.tolerance("tolerance", self.tolerance))
        object.__setattr__(
            self, "max_segments", _checks.count("max_segments", self.max_segments, 1)
        )
        object.__setattr__(self, "rings", _checks.count("rings", self.rings, 1))
        object.__setattr__(self, "ring_rays", _checks.count("ring_rays", self.ring_rays, 3))


@dataclass(frozen=True)
class FO:
    """Fourier optics.

    path : ``"radial"`` (Gaussian beams of any pointing: one integral per range, the beam image's
        offset as J0, no grids), ``"2d"`` (the sampled beam propagated on a grid) or ``"auto"``
        (radial where it applies).
    beam_grid, beam_window : 2-D path with a Gaussian beam: samples per side of the transmitted
        field and its window (waist radii; long-term radii with turbulence). ``None``: the core's
        default. A FieldBeam brings its own grid.
    max_spectrum_grid : cap on the zero-padded beam spectrum (with aberrations, on the pupil
        transform); a range that needs more is refused naming it (use ray tracing there).
    """

    path: str = "auto"
    beam_grid: Optional[int] = None
    beam_window: Optional[float] = None
    max_spectrum_grid: int = _FO.max_spectrum_grid

    def __post_init__(self) -> None:
        _checks.choice("path", self.path, FO_PATHS)
        if self.beam_grid is not None:
            object.__setattr__(self, "beam_grid", _checks.count("beam_grid", self.beam_grid, 16))
        if self.beam_window is not None:
            object.__setattr__(self, "beam_window", _checks.real("beam_window", self.beam_window))
        object.__setattr__(
            self,
            "max_spectrum_grid",
            _checks.count("max_spectrum_grid", self.max_spectrum_grid, 16),
        )
        if self.path == "radial" and (self.beam_grid is not None or self.beam_window is not None):
            raise ValueError(
                "beam_grid and beam_window apply to the 2-D FO path only; use fo_path='2d'"
            )


@dataclass(frozen=True)
class Auto:
    """The cheapest model whose error on G stays within ``tolerance`` (absolute, in [1e-14, 1)): ray
    tracing when its estimated diffraction error leaves room for its quadrature, else Fourier
    optics. ``rt`` and ``fo`` set the models it may run (RT's tolerance is the share the model error
    leaves; FO's path is auto's choice, and its beam_grid and beam_window apply where that is the
    2-D path)."""

    tolerance: float = _RT.tolerance
    rt: RT = RT()
    fo: FO = FO()

    def __post_init__(self) -> None:
        object.__setattr__(self, "tolerance", _checks.tolerance("tolerance", self.tolerance))
        for name, kind in (("rt", RT), ("fo", FO)):
            if not isinstance(getattr(self, name), kind):
                raise ValueError(
                    f"{name} = {_checks.shown(getattr(self, name))} is invalid: expected a "
                    f"lidar_overlap.{kind.__name__}"
                )


Model = Union[RT, FO, Auto]


@dataclass(frozen=True)
class Turbulent:
    """``method`` through ``turbulence``: the mean G over ``realizations`` random draws of the
    atmosphere (reproducible with ``seed``), with its spread. Fourier optics carries the beam
    through ``screens`` phase screens; ray tracing displaces the short-term beam by the random
    wander (all draws in one core call). ``paths="both"`` (the default) also perturbs the return
    path: Fourier optics carries it through the same screens, the detector standing as
    ``receiver_fields`` random-phase fields; ray tracing tilts the image of the scattering volume
    by the return path's angle of arrival, correlated with the beam's wander, and blurs it.
    ``"transmit"`` takes the return path as unperturbed (docs/turbulence.md).

    ``receiver_fields`` (M, default 1): the detector's sensitivity is the mean over M random-phase
    fields, unbiased for every M; their speckle is an independent noise per draw, which the mean
    over ``realizations`` averages with the atmosphere's spread. A draw costs about 1 + M
    propagations, and at equal CPU time the standard error of the mean G hardly depends on M
    (measured at 1000 m on the 5 cm, 0.28 mrad lidar of docs/turbulence.md, a detector of few
    coherence cells: SE x sqrt(CPU s) 0.213, 0.205, 0.187, 0.202 for M = 1, 2, 4, 8; a wide field
    of view averages the speckle under the beam). So the default spends the time on draws; raise
    ``realizations`` for a smaller error, or M (about 4) for a detector only a few diffraction
    spots wide."""

    turbulence: Turbulence
    method: Model = Auto()
    realizations: int = _TURBULENCE.realizations
    seed: int = _TURBULENCE.seed
    screens: int = _TURBULENCE.screens
    paths: str = "both"
    receiver_fields: int = _TURBULENCE.receiver_fields

    def __post_init__(self) -> None:
        if not isinstance(self.turbulence, Turbulence):
            raise ValueError(
                f"turbulence = {_checks.shown(self.turbulence)} is invalid: expected a "
                "lidar_overlap.Turbulence or None"
            )
        object.__setattr__(self, "method", model(self.method))
        object.__setattr__(
            self, "realizations", _checks.count("realizations", self.realizations, 1)
        )
        object.__setattr__(self, "seed", _checks.count("seed", self.seed, 0, 2**64 - 1))
        object.__setattr__(self, "screens", _checks.count("screens", self.screens, 1))
        _checks.choice("paths", self.paths, TURBULENT_PATHS)
        fields = _checks.count("receiver_fields", self.receiver_fields, *RECEIVER_FIELDS)
        object.__setattr__(self, "receiver_fields", fields)


Method = Union[RT, FO, Auto, Turbulent]


def model(method) -> Model:
    """``method`` as an RT, FO or Auto object (a shortcut string becomes the object with its
    defaults)."""
    if isinstance(method, (RT, FO, Auto)):
        return method
    if isinstance(method, str):
        _checks.choice("method", method, SHORTCUTS)
        return {"rt": RT, "fo": FO, "auto": Auto}[method]()
    raise ValueError(
        f"method = {_checks.shown(method)} is invalid: expected one of 'rt', 'fo', 'auto' or a "
        "lidar_overlap.RT, FO, Auto or Turbulent"
    )


def from_shortcuts(
    method,
    *,
    tolerance=None,
    max_segments=None,
    fo_path=None,
    beam_grid=None,
    beam_window=None,
    max_spectrum_grid=None,
    turbulence=None,
    realizations=None,
    seed=None,
    screens=None,
    paths=None,
) -> Method:
    """The method object for ``overlap(system, ranges, method, **options)``: a method object passes
    unchanged (options given beside it are refused: they belong on the object); a shortcut string
    takes the options that apply to its model (the others are ignored, so one set of options can
    serve every method)."""
    given = {
        k: v
        for k, v in dict(
            tolerance=tolerance,
            max_segments=max_segments,
            fo_path=fo_path,
            beam_grid=beam_grid,
            beam_window=beam_window,
            max_spectrum_grid=max_spectrum_grid,
            turbulence=turbulence,
            realizations=realizations,
            seed=seed,
            screens=screens,
            paths=paths,
        ).items()
        if v is not None
    }
    if not isinstance(method, str):
        if given:
            raise ValueError(
                f"{', '.join(given)} given beside method = {_checks.shown(method)}: set them on "
                "the method object (lidar_overlap.RT, FO, Auto, Turbulent)"
            )
        return method if isinstance(method, Turbulent) else model(method)
    _checks.choice("method", method, SHORTCUTS)
    if fo_path is not None:
        _checks.choice("fo_path", fo_path, FO_PATHS)  # named as the caller named it
    rt = RT(**_only(given, tolerance="tolerance", max_segments="max_segments"))
    fo = FO(
        **_only(
            given,
            path="fo_path",
            beam_grid="beam_grid",
            beam_window="beam_window",
            max_spectrum_grid="max_spectrum_grid",
        )
    )
    models: Dict[str, Model] = {
        "rt": rt,
        "fo": fo,
        "auto": Auto(tolerance=rt.tolerance, rt=rt, fo=fo),
    }
    chosen = models[method]
    if turbulence is None:
        return chosen
    return Turbulent(
        turbulence,
        chosen,
        **_only(given, realizations="realizations", seed="seed", screens="screens", paths="paths"),
    )


def _only(given: Dict[str, Any], **names: str) -> Dict[str, Any]:
    """The options in ``given`` under their method-object names (``names``: object name -> shortcut
    name)."""
    return {field: given[shortcut] for field, shortcut in names.items() if shortcut in given}
