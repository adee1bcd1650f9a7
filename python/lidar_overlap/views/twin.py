"""The digital twin behind the interactive view: a lidar system whose alignment and receiver are set
by sliders, and what follows from it at each setting (G(z) by ray tracing, the detector-plane image
at one range, the telecover deviations through a mask). Needs NumPy and the library only, no web
framework, so it is tested on its own.

Every slider is an integer position 0..n; its value is ``low + position * step`` in SI units (rad or
m), so the browser never rounds a physical value. A slider the user has not moved keeps the system's
own value.
"""

from __future__ import annotations

import dataclasses
import math
import os
import pathlib
import re
import time
import warnings
from dataclasses import dataclass
from functools import partial
from typing import Any, Dict, Optional, Tuple

import numpy as np

from ..analysis.studies.telecover import telecover
from ..forward.compute import run
from ..forward.planning import plan
from ..io.scenario_writer import scenario_toml
from ..model import parameters
from ..model.aperture_mask import ApertureMask
from ..model.field_beam import FieldBeam
from ..model.mixture_beam import GaussianMixtureBeam
from ..model.system import GaussianBeam, LidarSystem
from ..optics.detector_image import detector_image
from .twin_telecover import centred_shadow_telecover

#: Ranges of the curve when none are given: ray traced, and computed by another model.
N_RANGES, N_RANGES_AUTO = 200, 40
#: Chunks a curve that is not ray traced is computed in (progress, and where a newer setting stops
#: it).
CHUNKS = 10
#: The beams the view computes: ray tracing for a GaussianBeam, what auto chooses for the others.
BEAMS = (GaussianBeam, FieldBeam, GaussianMixtureBeam)
#: Slider positions across each range.
N_STEPS = 200
#: Samples per side of the detector-plane image.
N_IMAGE = 96


@dataclass(frozen=True)
class Slider:
    """One slider: ``path`` is a :mod:`lidar_overlap.parameters` path or ``"fov"`` (the full field
        of view,
    rad, set through the detector radius r_d = fov f / 2). Values ``(start + i) * step``, i =
    0..``n`` (SI), from ``low = start * step``; ``unit`` and ``factor`` are for display only (shown
    value = SI value x factor)."""

    key: str
    path: str
    label: str
    start: int
    step: float
    n: int
    unit: str
    factor: float

    def value(self, position: int) -> float:
        """The SI value at slider ``position`` (an integer 0..n)."""
        if not _is_index(position, self.n):
            raise ValueError(
                f"{self.key} = {position!r} is invalid: expected a slider position, an integer "
                f"from 0 to {self.n}"
            )
        return (self.start + int(position)) * self.step  # an integer times step: 20 * 1e-5 is 2e-4

    @property
    def low(self) -> float:
        return self.start * self.step

    def position(self, value: float) -> int:
        """The slider position nearest to ``value`` (SI), clamped to 0..n."""
        return int(min(self.n, max(0, round((value - self.low) / self.step))))

    def shown(self, value: float) -> str:
        return f"{value * self.factor:.4g} {self.unit}"


def _is_index(value, high: int) -> bool:
    """``value`` is an integer (int or integral float, not bool) from 0 to ``high``."""
    return bool(
        isinstance(value, (int, float, np.integer, np.floating))
        and not isinstance(value, bool)
        and float(value).is_integer()
        and 0 <= value <= high
    )


def _nice(x: float) -> float:
    """The smallest of 1, 2, 5 x 10^k that is >= x (> 0)."""
    k = math.floor(math.log10(x))
    # m / 10**5 is the double nearest m e-5 (10.0**-5 is not, and 10 * 1e-6 is not 1e-5)
    nice = (m * 10**j if j >= 0 else m / 10**-j for j in (k, k + 1) for m in (1, 2, 5))
    return next(v for v in nice if v >= x * (1 - 1e-12))


def _symmetric(key, path, label, half, unit, factor) -> Slider:
    step = _nice(2 * half / N_STEPS)
    n = 2 * math.ceil(half / step)
    return Slider(key, path, label, -(n // 2), step, n, unit, factor)


def sliders_for(system) -> Dict[str, Slider]:
    """The sliders of ``system``, their spans set by its size: beam tilt (± the full FOV or 4x the
    tilt), beam offset (± the aperture's diameter, or 2x the offset), detector offset (± 2 detector
    radii), defocus (± 1 % of f or 2x the defocus), FOV (0 to 4x) and, for a GaussianBeam,
    divergence (the diffraction limit to 5x)."""
    beam, tel, det = system.beam, system.telescope, system.detector
    f, fov = tel.focal_length, system.fov
    tilt = max(fov, 4 * max(map(abs, beam.tilt)))
    offset = max(tel.diameter, 2 * max(map(abs, beam.offset)))
    shift = max(2 * det.radius, 2 * max(map(abs, det.offset)))
    out = {}
    for axis, i in (("x", 0), ("y", 1)):
        out[f"tilt_{axis}"] = _symmetric(
            f"tilt_{axis}", f"beam.tilt[{i}]", f"beam tilt {axis}", tilt, "mrad", 1e3
        )
    for axis, i in (("x", 0), ("y", 1)):
        out[f"offset_{axis}"] = _symmetric(
            f"offset_{axis}", f"beam.offset[{i}]", f"beam offset {axis}", offset, "mm", 1e3
        )
    for axis, i in (("x", 0), ("y", 1)):
        out[f"detector_{axis}"] = _symmetric(
            f"detector_{axis}", f"detector.offset[{i}]", f"detector offset {axis}", shift, "mm", 1e3
        )
    out["defocus"] = _symmetric(
        "defocus", "detector.defocus", "defocus", max(0.01 * f, 2 * abs(det.defocus)), "mm", 1e3
    )
    step = _nice(4 * fov / N_STEPS)
    out["fov"] = Slider(
        "fov", "fov", "field of view (full)", 1, step, math.ceil(4 * fov / step) - 1, "mrad", 1e3
    )
    if not isinstance(beam, GaussianBeam):  # a field is given; a mixture's widths are its own
        return out
    limit = beam.wavelength / (math.pi * beam.waist_radius)
    top = 5 * max(limit, beam.half_angle_divergence)
    step = _nice((top - limit) / N_STEPS)
    start = math.ceil(limit / step * (1 - 1e-12))  # at or above the diffraction limit
    start += start * step < limit
    out["divergence"] = Slider(
        "divergence",
        "beam.divergence",
        "divergence (half-angle)",
        start,
        step,
        math.floor(top / step) - start,
        "mrad",
        1e3,
    )
    return out


@dataclass(frozen=True)
class Outcome:
    """What one setting of the sliders gives: the curve (an OverlapResult), the detector-plane image
    at the probe range, the telecover deviations (a TelecoverResult, or None), the warnings said
    on the way and the time of each part (s)."""

    result: Any
    image: Any
    deviation: Any
    warnings: list
    timing: Dict[str, float]


class Twin:
    """A lidar ``system`` at ``ranges`` (m, default 200 log-spaced, as :func:`lidar_overlap.scene`;
    40 when the curve is not ray traced), with ``telecover`` (None, ``"quadrants"`` or an
    ApertureMask). A GaussianBeam is ray traced (``method`` "rt", to ``tolerance``); any other beam
    the library computes (a FieldBeam, a FlatTopBeam, a GaussianMixtureBeam) gets the model
    ``lo.plan(system, ranges, "auto", tolerance=tolerance)`` chooses (``method`` "auto"), which may
    take seconds: :attr:`background` says the page computes it away from its sliders. ``threads``:
    default 1 for ray tracing (a curve of 200 ranges takes about a millisecond on one core, less
    than waking an OpenMP team costs on a busy machine), 0 (all cores) otherwise. ``name`` names
    the saved files. ``compute=False`` leaves the first curve to :meth:`compute` (the page's
    background); :meth:`update` sets slider positions and recomputes at once."""

    def __init__(
        self,
        system,
        ranges=None,
        *,
        telecover=None,
        tolerance: float = 1e-4,
        threads: Optional[int] = None,
        name: str = "view",
        compute: bool = True,
    ):
        if not isinstance(system, LidarSystem):
            raise ValueError(
                f"system = {system!r} is invalid: expected a lidar_overlap.LidarSystem"
            )
        if not isinstance(system.beam, BEAMS):
            raise ValueError(
                f"system.beam = {type(system.beam).__name__} is invalid for the view: expected a "
                "GaussianBeam, FieldBeam, FlatTopBeam or GaussianMixtureBeam"
            )
        if telecover is not None and not (
            telecover == "quadrants" or isinstance(telecover, ApertureMask)
        ):
            raise ValueError(
                f"telecover = {telecover!r} is invalid: expected None, 'quadrants' or an "
                "ApertureMask"
            )
        if not isinstance(name, str) or not re.fullmatch(r"[A-Za-z0-9][A-Za-z0-9_.+-]{0,99}", name):
            raise ValueError(
                f"name = {name!r} is invalid: expected 1 to 100 letters, digits and _ . + - (it "
                "names the saved files)"
            )
        self.method = "rt" if isinstance(system.beam, GaussianBeam) else "auto"
        if ranges is None:
            z_obs = system.telescope.obstruction_distance
            count = N_RANGES if self.method == "rt" else N_RANGES_AUTO
            ranges = np.geomspace(1.0 if z_obs < 1.0 else 1.5 * z_obs, 1000.0, count)
        self.base = system
        self.name = name
        self.telecover = telecover
        self.tolerance = tolerance
        self.threads = (1 if self.method == "rt" else 0) if threads is None else threads
        self.sliders = sliders_for(system)
        self.values: Dict[str, float] = {}  # moved sliders only: SI value by key
        self.plan = self._plan(system, ranges)  # checks ranges, tolerance and threads
        self.ranges = self.plan.ranges
        self.probe = int(np.searchsorted(self.ranges, min(300.0, self.ranges[-1])))
        self.system = system
        self.result: Any = None  # the OverlapResult of the last computed setting
        self.timing: Dict[str, float] = {}
        self.warnings: list = []  # the last update's warnings (validity of ray tracing)
        self.image: Any = None  # a DetectorImage once computed
        self.deviation: Any = None  # a TelecoverResult, with a mask
        if compute:
            self.update({})

    @property
    def telecover_estimated(self) -> bool:
        """Whether the telecover panel shows the centred-shadow estimate
        (:mod:`.twin_telecover`): ray tracing through a central obstruction."""
        return self.method == "rt" and self.base.telescope.obstruction_radius > 0.0

    @property
    def background(self) -> bool:
        """Whether the curve takes long enough to be computed away from the sliders (any model
        but ray tracing)."""
        return self.method != "rt"

    def _plan(self, system, ranges):
        return plan(system, ranges, self.method, tolerance=self.tolerance, threads=self.threads)

    def positions(self) -> Dict[str, int]:
        """The slider positions of the current system."""
        return {key: s.position(self.value(key)) for key, s in self.sliders.items()}

    def value(self, key: str) -> float:
        """The current SI value of slider ``key`` (moved or the system's own)."""
        if key in self.values:
            return self.values[key]
        path = self.sliders[key].path
        return self.base.fov if path == "fov" else parameters.get(self.base, path)

    def system_for(self, values: Dict[str, float]):
        """The base system with the slider values ``values`` (key -> SI value) applied."""
        f = self.base.telescope.focal_length
        changes = {
            ("detector.radius" if self.sliders[k].path == "fov" else self.sliders[k].path): (
                0.5 * v * f if self.sliders[k].path == "fov" else v
            )
            for k, v in values.items()
        }
        return parameters.replace(self.base, changes) if changes else self.base

    def move(self, positions: Dict[str, int], probe: Optional[int] = None) -> None:
        """Move the sliders in ``positions`` (key -> integer position) and the probe range (an index
        into ``ranges``) and plan the moved system's curve (:attr:`plan`), computing nothing: the
        curve, image and deviations stay those of the last :meth:`compute`. A position that makes
        an invalid system raises ValueError and leaves the twin as it was."""
        for key in positions:
            if key not in self.sliders:
                raise ValueError(
                    f"slider {key!r} is invalid: expected one of {', '.join(self.sliders)}"
                )
        values = {**self.values, **{k: self.sliders[k].value(p) for k, p in positions.items()}}
        if probe is not None and not _is_index(probe, self.ranges.size - 1):
            raise ValueError(
                f"probe = {probe!r} is invalid: expected an index from 0 to {self.ranges.size - 1}"
            )
        system = self.system_for(values)
        self.plan = self._plan(system, self.ranges)
        self.values, self.system = values, system
        if probe is not None:
            self.probe = int(probe)

    def compute(self, cancelled=None, progress=None) -> Optional[Outcome]:
        """The curve, image and deviations of the current :attr:`plan` and probe, without changing
        the twin (safe in another thread while the sliders move on). The curve runs in chunks of
        ranges; after each ``progress(fraction done)`` is called and ``cancelled()`` asked: True
        stops the computation and returns None (a newer setting supersedes it)."""
        the_plan, probe, z = self.plan, self.probe, self.ranges
        chunk = z.size if self.method == "rt" else max(1, math.ceil(z.size / CHUNKS))
        t0 = time.perf_counter()
        with warnings.catch_warnings(record=True) as caught:  # said on the page, not in the log
            warnings.simplefilter("always")
            parts = []
            for start in range(0, z.size, chunk):
                if cancelled is not None and cancelled():
                    return None
                parts.append(run(the_plan.subset(slice(start, start + chunk))))
                if progress is not None:
                    progress(min(start + chunk, z.size) / z.size)
            result = parts[0] if len(parts) == 1 else _joined(parts, z)
            t1 = time.perf_counter()
            image = detector_image(the_plan.system, float(z[probe]), n=N_IMAGE)
            t2 = time.perf_counter()
            deviation = None
            if self.telecover is not None and not (cancelled is not None and cancelled()):
                deviation = (
                    centred_shadow_telecover  # the exact sectors take seconds (its module says)
                    if self.telecover_estimated
                    else partial(telecover, method=self.method)
                )(
                    the_plan.system,
                    z,
                    self.telecover,
                    tolerance=self.tolerance,
                    threads=self.threads,
                )
            t3 = time.perf_counter()
        return Outcome(
            result,
            image,
            deviation,
            list(dict.fromkeys(str(w.message) for w in caught)),
            {"overlap": t1 - t0, "image": t2 - t1, "telecover": t3 - t2},
        )

    def accept(self, outcome: Outcome) -> None:
        """Show ``outcome`` (from :meth:`compute`) as the twin's curve, image and deviations."""
        self.result, self.image, self.deviation = outcome.result, outcome.image, outcome.deviation
        self.warnings, self.timing = outcome.warnings, outcome.timing

    def update(self, positions: Dict[str, int], probe: Optional[int] = None) -> None:
        """Move the sliders in ``positions`` and the probe range (:meth:`move`), then recompute G,
        the detector image and the telecover deviations at once (:meth:`compute`). A position that
        makes an invalid system raises ValueError and leaves the twin as it was."""
        before = (self.values, self.system, self.plan, self.probe)
        self.move(positions, probe)
        try:
            outcome = self.compute()
        except ValueError:
            self.values, self.system, self.plan, self.probe = before
            raise
        assert outcome is not None  # nothing cancels it
        self.accept(outcome)

    @property
    def mask(self):
        """The aperture mask shown on the aperture: the telecover's, else the system's own, else
        None."""
        if self.telecover == "quadrants":
            return ApertureMask.quadrants()
        return self.telecover if self.telecover is not None else self.system.telescope.mask

    def save(self, directory=".") -> Tuple[Optional[pathlib.Path], pathlib.Path]:
        """Write the scenario as it stands (``<name>.toml``, readable by ``lidar-overlap run``; a
        Gaussian beam only, None otherwise: the scenario writer knows no other beam) and its curve
        (``<name>.csv``, :meth:`OverlapResult.to_csv`) to ``directory``; returns both paths."""
        if self.result is None:
            raise ValueError("the twin has no curve yet: nothing to save before it is computed")
        directory = pathlib.Path(directory)
        directory.mkdir(parents=True, exist_ok=True)
        toml, csv = directory / f"{self.name}.toml", directory / f"{self.name}.csv"
        if isinstance(self.system.beam, GaussianBeam):
            text = scenario_toml(self.system, self.ranges, self.name, self.tolerance)
            temporary = toml.with_name(f".{toml.name}.part")
            temporary.write_text(text, encoding="utf-8")
            os.replace(temporary, toml)  # the file appears only once complete
        self.result.to_csv(csv, {"scenario": self.name})
        return (toml if isinstance(self.system.beam, GaussianBeam) else None), csv


def _joined(parts, ranges):
    """One OverlapResult from the results of consecutive chunks of ``ranges`` (one plan's)."""
    return dataclasses.replace(
        parts[0],
        ranges=ranges.copy(),
        overlap=np.concatenate([q.overlap for q in parts]),
        error_estimate=np.concatenate([q.error_estimate for q in parts]),
    )
