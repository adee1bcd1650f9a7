"""lidar_overlap: the overlap function of atmospheric lidars (SI units throughout).

The package is built in layers, each importing only those below it (docs/architecture.md): ``model``
(value types), ``optics`` (fields and their propagation), ``forward`` (methods, plans, backends,
results), ``analysis`` (maps, sensitivities, fits, telecover, design, signals, studies), ``io``
(scenario files), ``cli`` and ``views`` (plots, 3-D scenes). This namespace re-exports what users
call.
"""

from ._checks import ParameterError, set_max_memory
from ._core import __version__, max_memory, max_threads
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
from .views.scene import save_scene, scene

__all__ = [
    "__version__",
    "Aberrations",
    "ApertureMask",
    "Atmosphere",
    "BeamComponent",
    "CorrectedSignal",
    "LidarSignal",
    "Auto",
    "FO",
    "ParameterError",
    "Plan",
    "RT",
    "Turbulent",
    "alignment_map",
    "alignment_maps",
    "fit",
    "fit_drift",
    "fit_joint",
    "fit_telecover",
    "DriftFitResult",
    "JointFitResult",
    "DegeneracyWarning",
    "FitQualityWarning",
    "FitResult",
    "GlobalFitResult",
    "GlobalRelativeFitResult",
    "RelativeFitResult",
    "Prediction",
    "AlignResult",
    "align",
    "MaximumOverlapAt",
    "Objective",
    "OptimizeResult",
    "SmallestFieldOfView",
    "optimize",
    "realign",
    "Realignment",
    "sensitivity",
    "plan",
    "run",
    "with_aberrations",
    "annular_field",
    "laguerre_gauss_field",
    "noll_index",
    "point_image",
    "seidel_to_zernike",
    "zernike",
    "zernike_to_seidel",
    "super_gaussian_field",
    "Detector",
    "DetectorImage",
    "Field",
    "FieldBeam",
    "FlatTopBeam",
    "GaussianBeam",
    "GaussianMixtureBeam",
    "LidarSystem",
    "OverlapResult",
    "SamplingWarning",
    "Sector",
    "Telescope",
    "TelecoverResult",
    "Turbulence",
    "TurbulentOverlapResult",
    "detector_image",
    "emitter_coupling",
    "explain",
    "optimal_focus_range",
    "overlap",
    "paper_table1",
    "parameters",
    "instruments",
    "plotting",
    "phase_screen",
    "max_memory",
    "max_threads",
    "set_max_memory",
    "telecover",
    "tolerance_study",
    "turbulent_realizations",
    "view",
    "propagate",
    "save_scene",
    "scene",
    "correct",
    "signal",
]


def __getattr__(name: str):
    """``view`` is imported when first used: the browser view loads asyncio and trame's pieces,
    which ``import lidar_overlap`` alone should not pay for."""
    if name == "view":
        from .views.app import view

        globals()["view"] = view
        return view
    raise AttributeError(f"module 'lidar_overlap' has no attribute {name!r}")
