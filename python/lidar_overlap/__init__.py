"""lidar_overlap: the overlap function of atmospheric lidars (SI units throughout).

The package is built in layers, each importing only those below it (docs/architecture.md): ``model``
(value types), ``optics`` (fields and their propagation), ``forward`` (methods, plans, backends,
results), ``analysis`` (maps, sensitivities, fits, telecover, design, signals, studies), ``io``
(scenario files), ``cli`` and ``views`` (plots, 3-D scenes). This namespace re-exports what users
call. Each name's module is imported when the name is first used, so that ``import lidar_overlap``
costs numpy and the compiled core, not every layer (``lo.fit`` loads the fit layer, ``lo.view`` the
browser view).
"""

import importlib
from typing import TYPE_CHECKING

from ._checks import ParameterError, set_max_memory
from ._core import __version__, max_memory, max_threads

#: The public names of each module, imported on first use by :func:`__getattr__`.
_EXPORTS = {
    "analysis.design.alignment": ("alignment_map", "alignment_maps"),
    "analysis.design.autoalign": ("AlignResult", "align"),
    "analysis.design.objectives": ("MaximumOverlapAt", "Objective", "SmallestFieldOfView"),
    "analysis.design.optimize": ("OptimizeResult", "optimize"),
    "analysis.design.realign": ("Realignment", "realign"),
    "analysis.fitting.drift": ("fit_drift",),
    "analysis.fitting.drift_result": ("DriftFitResult",),
    "analysis.fitting.fit": ("fit",),
    "analysis.fitting.global_result": ("GlobalFitResult", "GlobalRelativeFitResult"),
    "analysis.fitting.joint": ("fit_joint",),
    "analysis.fitting.joint_result": ("JointFitResult",),
    "analysis.fitting.relative_result": ("RelativeFitResult",),
    "analysis.fitting.result": ("DegeneracyWarning", "FitResult", "Prediction"),
    "analysis.fitting.verdict": ("FitQualityWarning",),
    "analysis.sensitivity": ("sensitivity",),
    "analysis.studies.empirical_drift": ("EmpiricalDrift", "empirical_drift"),
    "analysis.studies.series": ("fit_series",),
    "analysis.studies.signals": ("CorrectedSignal", "LidarSignal", "correct", "signal"),
    "analysis.studies.telecover": ("TelecoverResult", "telecover"),
    "analysis.studies.telecover_fit": ("fit_telecover",),
    "analysis.studies.tolerance": ("tolerance_study",),
    "analysis.studies.turbulence": ("turbulent_realizations",),
    "forward.compute": ("overlap", "run"),
    "forward.coupling": ("emitter_coupling", "optimal_focus_range"),
    "forward.methods": ("FO", "RT", "Auto", "Turbulent"),
    "forward.planning": ("Plan", "explain", "plan"),
    "forward.result": ("OverlapResult", "TurbulentOverlapResult"),
    "io.overlap_series": ("OverlapSeries", "read_overlap_series"),
    "model.aberrations": (
        "Aberrations",
        "noll_index",
        "seidel_to_zernike",
        "with_aberrations",
        "zernike",
        "zernike_to_seidel",
    ),
    "model.aperture_mask": ("ApertureMask", "Sector"),
    "model.atmosphere": ("Atmosphere",),
    "model.field": ("Field",),
    "model.field_beam": ("FieldBeam",),
    "model.flat_top": ("FlatTopBeam",),
    "model.mixture_beam": ("BeamComponent", "GaussianMixtureBeam"),
    "model.presets": ("paper_table1",),
    "model.system": ("Detector", "GaussianBeam", "LidarSystem", "Telescope"),
    "model.turbulence": ("Turbulence",),
    "optics.beam_fields": ("annular_field", "laguerre_gauss_field", "super_gaussian_field"),
    "optics.detector_image": ("DetectorImage", "detector_image"),
    "optics.imaging": ("point_image",),
    "optics.phase_screen": ("phase_screen",),
    "optics.propagation": ("SamplingWarning", "propagate"),
    "views.scene": ("save_scene", "scene"),
    "views.app": ("view",),
}
#: Public modules of the namespace, imported on first use.
_MODULES = {
    "instruments": "model.instruments",
    "parameters": "model.parameters",
    "plotting": "views.plotting",
}
_HOME = {name: module for module, names in _EXPORTS.items() for name in names}
_HOME.update(_MODULES)

__all__ = ["__version__", "ParameterError", "max_memory", "max_threads", "set_max_memory", *_HOME]

# The same names for type checkers and IDEs (tests/test_namespace.py keeps both lists equal).
if TYPE_CHECKING:
    from .analysis.design.alignment import alignment_map, alignment_maps
    from .analysis.design.autoalign import AlignResult, align
    from .analysis.design.objectives import MaximumOverlapAt, Objective, SmallestFieldOfView
    from .analysis.design.optimize import OptimizeResult, optimize
    from .analysis.design.realign import Realignment, realign
    from .analysis.fitting.drift import fit_drift
    from .analysis.fitting.drift_result import DriftFitResult
    from .analysis.fitting.fit import fit
    from .analysis.fitting.global_result import GlobalFitResult, GlobalRelativeFitResult
    from .analysis.fitting.joint import fit_joint
    from .analysis.fitting.joint_result import JointFitResult
    from .analysis.fitting.relative_result import RelativeFitResult
    from .analysis.fitting.result import DegeneracyWarning, FitResult, Prediction
    from .analysis.fitting.verdict import FitQualityWarning
    from .analysis.sensitivity import sensitivity
    from .analysis.studies.empirical_drift import EmpiricalDrift, empirical_drift
    from .analysis.studies.series import fit_series
    from .analysis.studies.signals import CorrectedSignal, LidarSignal, correct, signal
    from .analysis.studies.telecover import TelecoverResult, telecover
    from .analysis.studies.telecover_fit import fit_telecover
    from .analysis.studies.tolerance import tolerance_study
    from .analysis.studies.turbulence import turbulent_realizations
    from .forward.compute import overlap, run
    from .forward.coupling import emitter_coupling, optimal_focus_range
    from .forward.methods import FO, RT, Auto, Turbulent
    from .forward.planning import Plan, explain, plan
    from .forward.result import OverlapResult, TurbulentOverlapResult
    from .io.overlap_series import OverlapSeries, read_overlap_series
    from .model import instruments, parameters
    from .model.aberrations import (
        Aberrations,
        noll_index,
        seidel_to_zernike,
        with_aberrations,
        zernike,
        zernike_to_seidel,
    )
    from .model.aperture_mask import ApertureMask, Sector
    from .model.atmosphere import Atmosphere
    from .model.field import Field
    from .model.field_beam import FieldBeam
    from .model.flat_top import FlatTopBeam
    from .model.mixture_beam import BeamComponent, GaussianMixtureBeam
    from .model.presets import paper_table1
    from .model.system import Detector, GaussianBeam, LidarSystem, Telescope
    from .model.turbulence import Turbulence
    from .optics.beam_fields import annular_field, laguerre_gauss_field, super_gaussian_field
    from .optics.detector_image import DetectorImage, detector_image
    from .optics.imaging import point_image
    from .optics.phase_screen import phase_screen
    from .optics.propagation import SamplingWarning, propagate
    from .views import plotting
    from .views.app import view
    from .views.scene import save_scene, scene


def __getattr__(name: str):
    """The public ``name``, imported from its module on first use and kept in the namespace."""
    module = _HOME.get(name)
    if module is None:
        raise AttributeError(f"module 'lidar_overlap' has no attribute {name!r}")
    imported = importlib.import_module(f"{__name__}.{module}")
    value = imported if name in _MODULES else getattr(imported, name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_HOME))
