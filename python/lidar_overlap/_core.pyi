"""Types of lidar_overlap._core, the C++ core (SI units throughout). Kept in step with
bindings/*.cpp by tests/test_core_stub.py (mypy's stubtest)."""

from collections.abc import Callable, Sequence
from typing import Any, SupportsFloat, SupportsIndex, SupportsInt, Union

import numpy
from numpy.typing import ArrayLike, NDArray

_Float = Union[SupportsFloat, SupportsIndex]
_Int = Union[SupportsInt, SupportsIndex]
_Pair = Sequence[_Float]  # (x, y)
_Ranges = Union[
    Sequence[_Float], NDArray[Any]
]  # any 1-D sequence of numbers, NumPy arrays included
_Reals = NDArray[numpy.float64]
_Counts = NDArray[numpy.uint64]
_Flags = NDArray[numpy.bool_]
_Complex = NDArray[numpy.complex128]

class _pybind11_type(
    type
): ...  # the metaclass of every class below (pybind11_builtins.pybind11_type)

class _MadeByTheCore(metaclass=_pybind11_type):
    # Results and reports (and Cn2Profile, made by its static methods): pybind11's __init__ takes
    # anything and raises TypeError ("No constructor defined").
    def __init__(self, *args: Any, **kwargs: Any) -> None: ...

__version__: str

# Limits (bind_limits.cpp)
MIN_LENGTH: float
MIN_TOLERANCE: float
MAX_LENGTH: float
MAX_ANGLE: float
MAX_GRID_SIDE: int

class ParameterError(ValueError):
    parameter: str
    value: Any
    expected: str

def max_memory() -> int: ...
def set_max_memory(bytes: _Int) -> None: ...
def _set_interrupt_requested(on: bool) -> None: ...
def max_threads() -> int: ...

# System model (bind_system.cpp)
class GaussianBeam(metaclass=_pybind11_type):
    def __init__(
        self,
        wavelength: _Float,
        waist_radius: _Float,
        divergence: _Float | None,
        offset: _Pair,
        tilt: _Pair,
        width_law: str,
    ) -> None: ...
    def half_angle_divergence(self) -> float: ...
    def radius(self, z: ArrayLike) -> object: ...

class Telescope(metaclass=_pybind11_type):
    def __init__(
        self,
        diameter: _Float,
        focal_length: _Float,
        obstruction_radius: _Float,
        obstruction_distance: _Float,
    ) -> None: ...

class Detector(metaclass=_pybind11_type):
    def __init__(
        self,
        radius: _Float,
        defocus: _Float,
        offset: _Pair,
        numerical_aperture: _Float | None,
        stop_radius: _Float | None = None,
        stop_distance: _Float = 0.0,
    ) -> None: ...
    @staticmethod
    def from_fov(
        fov: _Float,
        focal_length: _Float,
        defocus: _Float,
        offset: _Pair,
        numerical_aperture: _Float | None,
    ) -> Detector: ...
    @property
    def radius(self) -> float: ...

class LidarSystem(metaclass=_pybind11_type):
    def __init__(self, beam: GaussianBeam, telescope: Telescope, detector: Detector) -> None: ...
    def is_axisymmetric(self) -> bool: ...
    def validate_ranges(self, ranges: _Ranges) -> None: ...

# Ray-tracing overlap (bind_overlap_rt.cpp)
class RtOptions(metaclass=_pybind11_type):
    tolerance: float
    threads: int
    max_segments: int
    def __init__(
        self, *, tolerance: _Float = ..., threads: _Int = ..., max_segments: _Int = ...
    ) -> None: ...
    def __copy__(self) -> RtOptions: ...

class RtOverlap(_MadeByTheCore):
    @property
    def overlap(self) -> _Reals: ...
    @property
    def error_estimate(self) -> _Reals: ...
    @property
    def converged(self) -> _Flags: ...
    @property
    def evaluations(self) -> int: ...
    @property
    def axisymmetric(self) -> bool: ...

def overlap_rt(system: LidarSystem, ranges: _Ranges, options: RtOptions = ...) -> RtOverlap: ...
def overlap_rt_batch(
    systems: Sequence[LidarSystem], ranges: _Ranges, options: RtOptions = ...
) -> RtOverlap: ...
def emitter_coupling_rt(system: LidarSystem, z: _Float, position: _Pair) -> float: ...
def optimal_focus_range(focal_length: _Float, defocus: _Float) -> float: ...

# Aperture masks (bind_aperture_mask.cpp)
class ApertureMask(metaclass=_pybind11_type):
    def __init__(self, sectors: Sequence[tuple[_Float, _Float, _Float, _Float | None]]) -> None: ...
    def validate(self, telescope: Telescope) -> None: ...

def overlap_rt_masked(
    system: LidarSystem, ranges: _Ranges, mask: ApertureMask, options: RtOptions = ...
) -> RtOverlap: ...
def overlap_rt_masks(
    system: LidarSystem, ranges: _Ranges, masks: Sequence[ApertureMask], options: RtOptions = ...
) -> list[RtOverlap]: ...

MAX_MASKS: int

def overlap_fo_masked(
    system: LidarSystem, ranges: _Ranges, mask: ApertureMask, options: FoAberratedOptions = ...
) -> FoAberratedOverlap: ...
def emitter_coupling_rt_masked(
    system: LidarSystem, z: _Float, position: _Pair, mask: ApertureMask
) -> float: ...

# Alignment maps (bind_alignment_map.cpp)
MAX_ALIGNMENT_POINTS: int

class AlignmentMap(_MadeByTheCore):
    @property
    def shape(self) -> list[int]: ...
    @property
    def overlap(self) -> _Reals: ...
    @property
    def error_estimate(self) -> _Reals: ...
    @property
    def converged(self) -> _Flags: ...
    @property
    def evaluations(self) -> int: ...
    @property
    def axisymmetric(self) -> bool: ...

def alignment_map(
    system: LidarSystem,
    axes: Sequence[tuple[str, _Ranges]],
    ranges: _Ranges,
    options: RtOptions = ...,
) -> AlignmentMap: ...
def alignment_parameters() -> list[str]: ...

# Fields and propagation (bind_field.cpp, bind_propagate.cpp)
def field_moments(
    values: ArrayLike, spacing: _Float, wavelength: _Float
) -> tuple[float, list[float], float]: ...
def gaussian_field(
    wavelength: _Float, waist_radius: _Float, n: _Int, spacing: _Float, center: _Pair, power: _Float
) -> _Complex: ...

class PropagationReport(_MadeByTheCore):
    @property
    def method(self) -> str: ...
    @property
    def critical_distance(self) -> float: ...
    @property
    def band_limit_loss(self) -> float: ...
    @property
    def input_edge_power(self) -> float: ...
    @property
    def output_edge_power(self) -> float: ...
    @property
    def scaled_output(self) -> bool: ...
    @property
    def chirp_phase_step(self) -> float: ...
    @property
    def fresnel_phase_error(self) -> float: ...
    @property
    def fraunhofer_phase(self) -> float: ...

def propagate(
    values: ArrayLike,
    spacing: _Float,
    wavelength: _Float,
    distance: _Float,
    method: str,
    output_spacing: _Float,
    grid_size: _Int,
) -> tuple[_Complex, float, PropagationReport]: ...
def fft2d_roundtrip(values: ArrayLike) -> _Complex: ...

# Fourier-optics overlap (bind_overlap_fo.cpp)
class FoOptions(metaclass=_pybind11_type):
    beam_grid: int
    beam_window: float
    max_spectrum_grid: int
    threads: int
    def __init__(
        self,
        *,
        beam_grid: _Int = ...,
        beam_window: _Float = ...,
        max_spectrum_grid: _Int = ...,
        threads: _Int = ...,
    ) -> None: ...
    def __copy__(self) -> FoOptions: ...

class RadialFoOptions(metaclass=_pybind11_type):
    periods_per_panel: float
    threads: int
    def __init__(self, *, periods_per_panel: _Float = ..., threads: _Int = ...) -> None: ...
    def __copy__(self) -> RadialFoOptions: ...

class FoOverlap(_MadeByTheCore):
    @property
    def overlap(self) -> _Reals: ...
    @property
    def beam_reports(self) -> list[PropagationReport]: ...
    @property
    def spectrum_grid(self) -> _Counts: ...

class RadialFoOverlap(_MadeByTheCore):
    @property
    def overlap(self) -> _Reals: ...
    @property
    def evaluations(self) -> _Counts: ...

def overlap_fo(system: LidarSystem, ranges: _Ranges, options: FoOptions = ...) -> FoOverlap: ...
def overlap_fo_field(
    system: LidarSystem,
    ranges: _Ranges,
    values: ArrayLike,
    spacing: _Float,
    wavelength: _Float,
    options: FoOptions = ...,
) -> FoOverlap: ...
def overlap_fo_radial(
    system: LidarSystem, ranges: _Ranges, options: RadialFoOptions = ...
) -> RadialFoOverlap: ...
def emitter_coupling_fo(system: LidarSystem, z: _Float, position: _Pair) -> float: ...

# Flat-top plates (bind_flat_top.cpp)
class FlatTopDesign(_MadeByTheCore):
    @property
    def field(self) -> _Complex: ...
    @property
    def spacing(self) -> float: ...
    @property
    def phase(self) -> _Reals: ...
    @property
    def target(self) -> _Reals: ...
    @property
    def far_field(self) -> _Reals: ...
    @property
    def angular_spacing(self) -> float: ...
    @property
    def edge_width_target(self) -> float: ...
    @property
    def history(self) -> _Reals: ...
    @property
    def stop(self) -> str: ...
    @property
    def monotone(self) -> bool: ...
    @property
    def efficiency(self) -> float: ...
    @property
    def uniformity_rms(self) -> float: ...
    @property
    def uniformity_pv(self) -> float: ...
    @property
    def edge_width(self) -> float: ...

def design_flat_top(
    wavelength: _Float,
    waist_radius: _Float,
    angular_diameter: _Float,
    grid: _Int,
    samples_per_waist: _Float,
    edge_width: _Float,
    max_iterations: _Int,
    tolerance: _Float,
    max_error: _Float,
    power: _Float,
) -> FlatTopDesign: ...

# Turbulence (bind_turbulence.cpp)
class Cn2Profile(_MadeByTheCore):
    elevation: float
    altitude: float
    inner_scale: float
    outer_scale: float
    @staticmethod
    def constant(cn2: _Float) -> Cn2Profile: ...
    @staticmethod
    def hufnagel_valley(ground: _Float, wind: _Float) -> Cn2Profile: ...
    @staticmethod
    def custom(cn2_of_height: Callable[[float], _Float]) -> Cn2Profile: ...
    def validate(self) -> None: ...
    def cn2_at_range(self, range: _Float) -> float: ...
    def cn2_at_height(self, height: _Float) -> float: ...
    def fried_parameter_plane(self, wavelength: _Float, path_length: _Float) -> float: ...
    def fried_parameter_spherical(self, wavelength: _Float, path_length: _Float) -> float: ...
    def rytov_variance(self, wavelength: _Float, path_length: _Float) -> float: ...
    def isoplanatic_angle(self, wavelength: _Float, path_length: _Float) -> float: ...
    def beam_wander_variance(
        self, waist_radius: _Float, wavelength: _Float, path_length: _Float
    ) -> float: ...
    def long_term_radius(
        self, waist_radius: _Float, wavelength: _Float, path_length: _Float
    ) -> float: ...
    def short_term_radius(
        self, waist_radius: _Float, wavelength: _Float, path_length: _Float
    ) -> float: ...

class TurbulenceOptions(metaclass=_pybind11_type):
    realizations: int
    first_realization: int
    screens: int
    seed: int
    beam_grid: int
    beam_window: float
    max_spectrum_grid: int
    threads: int
    paths: str
    receiver_fields: int
    def __init__(
        self,
        *,
        realizations: _Int = ...,
        first_realization: _Int = ...,
        screens: _Int = ...,
        seed: _Int = ...,
        beam_grid: _Int = ...,
        beam_window: _Float = ...,
        max_spectrum_grid: _Int = ...,
        threads: _Int = ...,
        paths: str = ...,
        receiver_fields: _Int = ...,
    ) -> None: ...
    def __copy__(self) -> TurbulenceOptions: ...

class TurbulentOverlap(_MadeByTheCore):
    @property
    def overlap(self) -> _Reals: ...  # realisations (from first_realization) x ranges
    @property
    def wander_x(self) -> _Reals: ...
    @property
    def wander_y(self) -> _Reals: ...
    @property
    def radius_last(self) -> _Reals: ...
    @property
    def uncorrelated(
        self,
    ) -> _Reals: ...  # paths = both: a draw's beam with an independent draw's receiver
    @property
    def receiver_error(self) -> _Reals: ...
    @property
    def receiver_x(
        self,
    ) -> _Reals: ...  # paths = both: the sensitivity's centroid at the last range
    @property
    def receiver_y(self) -> _Reals: ...
    @property
    def screen_range(self) -> _Reals: ...
    @property
    def screen_spacing(self) -> _Reals: ...
    @property
    def screen_r0(self) -> _Reals: ...

def phase_screen(
    n: _Int,
    spacing: _Float,
    r0: _Float,
    outer_scale: _Float,
    inner_scale: _Float,
    seed: _Int,
    index: _Int,
) -> _Reals: ...
def overlap_fo_turbulent(
    system: LidarSystem, ranges: _Ranges, atmosphere: Cn2Profile, options: TurbulenceOptions = ...
) -> TurbulentOverlap: ...

class TurbulentGrid(_MadeByTheCore):
    @property
    def plane_range(self) -> _Reals: ...
    @property
    def window(self) -> _Reals: ...
    @property
    def pupil_window(self) -> float: ...
    @property
    def min_beam_grid(self) -> int: ...

def turbulent_grid(
    system: LidarSystem, ranges: _Ranges, atmosphere: Cn2Profile, options: TurbulenceOptions = ...
) -> TurbulentGrid: ...
def turbulent_both_bytes(
    beam_grid: _Int, screens: _Int, receiver_fields: _Int, threads: _Int
) -> float: ...

# Receiver aberrations (bind_aberrations.cpp)
def noll_index(j: _Int) -> list[int]: ...
def zernike(j: _Int, x: ArrayLike, y: ArrayLike) -> _Reals: ...

class Aberrations(metaclass=_pybind11_type):
    def __init__(
        self,
        zernike: Sequence[_Float],
        w040: _Float,
        w131: _Float,
        w222: _Float,
        w220: _Float,
        w311: _Float,
        field_radius: _Float,
    ) -> None: ...
    def wavefront(self, x: ArrayLike, y: ArrayLike, field: _Pair) -> _Reals: ...
    def gradient(self, x: ArrayLike, y: ArrayLike, field: _Pair) -> tuple[_Reals, _Reals]: ...
    def max_gradient(self, field: _Pair) -> float: ...
    def field_dependent(self) -> bool: ...
    def none(self) -> bool: ...

class FoAberratedOptions(metaclass=_pybind11_type):
    max_grid: int
    tail_error: float
    threads: int
    def __init__(
        self, *, max_grid: _Int = ..., tail_error: _Float = ..., threads: _Int = ...
    ) -> None: ...
    def __copy__(self) -> FoAberratedOptions: ...

class RtAberratedOptions(metaclass=_pybind11_type):
    rings: int
    ring_rays: int
    tolerance: float
    directions: int
    threads: int
    max_segments: int
    def __init__(
        self,
        *,
        rings: _Int = ...,
        ring_rays: _Int = ...,
        tolerance: _Float = ...,
        directions: _Int = ...,
        threads: _Int = ...,
        max_segments: _Int = ...,
    ) -> None: ...
    def __copy__(self) -> RtAberratedOptions: ...

class FoAberratedOverlap(_MadeByTheCore):
    @property
    def overlap(self) -> _Reals: ...
    @property
    def grid(self) -> _Counts: ...

class RtAberratedOverlap(_MadeByTheCore):
    @property
    def overlap(self) -> _Reals: ...
    @property
    def error_estimate(self) -> _Reals: ...
    @property
    def converged(self) -> _Flags: ...
    @property
    def rotationally_symmetric(self) -> bool: ...
    @property
    def pupil_form(self) -> bool: ...

def overlap_fo_aberrated(
    system: LidarSystem,
    aberrations: Aberrations,
    ranges: _Ranges,
    options: FoAberratedOptions = ...,
) -> FoAberratedOverlap: ...
def overlap_rt_aberrated(
    system: LidarSystem,
    aberrations: Aberrations,
    ranges: _Ranges,
    options: RtAberratedOptions = ...,
) -> RtAberratedOverlap: ...
def emitter_coupling_rt_aberrated(
    system: LidarSystem,
    aberrations: Aberrations,
    z: _Float,
    position: _Pair,
    options: RtAberratedOptions = ...,
) -> float: ...
def point_image(
    system: LidarSystem, aberrations: Aberrations, z: _Float, n: _Int, spacing: _Float
) -> _Complex: ...
