"""The registry of public value and result types that tests/test_value_contract.py and
tests/test_value_field_checks.py check against the value contract: one example of each type (a
factory, built once by :func:`example`) and the fields where NaN, an infinity or None is a
documented value (``tolerance`` NaN: none asked for)."""

from __future__ import annotations

import dataclasses
import functools
import math
import warnings
from typing import Any, Callable, Dict, FrozenSet, NamedTuple, Tuple

import numpy as np

import lidar_overlap as lo
from lidar_overlap.analysis.fitting.families import LADDER
from lidar_overlap.analysis.fitting.ladder import FamilyScore, LadderResult, fit_ladder
from lidar_overlap.analysis.fitting.problem import fit_problem
from lidar_overlap.io.noise_profile import NoiseProfile, noise_profile
from lidar_overlap.io.overlap_curves import OverlapCurve

Z = np.array([150.0, 400.0, 1200.0, 3000.0])
SYSTEM = lo.paper_table1()


@dataclasses.dataclass(frozen=True)
class Entry:
    """How to build an example of a type, and the fields where NaN, an infinity or None is a
    documented value."""

    build: Callable[[], Any]
    nan_ok: FrozenSet[str] = frozenset()
    inf_ok: FrozenSet[str] = frozenset()
    none_ok: FrozenSet[str] = frozenset()


def _turbulent() -> lo.TurbulentOverlapResult:
    rows = np.array([[0.1, 0.5, 0.9, 1.0], [0.12, 0.52, 0.92, 1.0]])
    return lo.TurbulentOverlapResult(
        ranges=Z,
        overlap=rows.mean(axis=0),
        method="fo",
        error_estimate=rows.std(axis=0, ddof=1) / math.sqrt(2.0),
        system=SYSTEM,
        tolerance=math.nan,
        error_kind="standard_error",
        realizations=rows,
        std=rows.std(axis=0, ddof=1),
        low=rows.min(axis=0),
        high=rows.max(axis=0),
    )


def _measured() -> Tuple[np.ndarray, np.ndarray]:
    truth = lo.paper_table1(defocus=1e-3)
    g = lo.overlap(truth, Z, "rt", tolerance=1e-6).overlap
    return g, np.full(Z.size, 1e-3)


def _fit(**options) -> Any:
    g, sigma = _measured()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return lo.fit(
            SYSTEM, Z, g, sigma, free=["detector.defocus"], method="rt", tolerance=1e-6, **options
        )


def _fit_entry(build: Callable[[], Any]) -> Entry:
    """A fit: sigma None for unit weights; an infinite covariance and uncertainty, NaN correlations
    and an undefined reduced chi-square (no degree of freedom) are documented values."""
    return Entry(
        build,
        nan_ok=frozenset({"correlation", "reduced_chi_square", "extinction_bias_covariance"}),
        inf_ok=frozenset({"covariance", "reduced_chi_square", "extinction_bias_covariance"}),
        none_ok=frozenset({"sigma"}),
    )


class Also(NamedTuple):
    """A registry key for another example of a registered type (the telecover fit's FitResult)."""

    cls: type
    label: str


def _cls(key: Any) -> type:
    return key.cls if isinstance(key, Also) else key


def _name(key: Any) -> str:
    return f"{key.cls.__name__}[{key.label}]" if isinstance(key, Also) else key.__name__


def _telecover() -> lo.TelecoverResult:
    return lo.telecover(lo.paper_table1(obstruction_radius=0.0), Z, tolerance=1e-5)


def _telecover_fit() -> lo.FitResult:
    s = lo.paper_table1(obstruction_radius=0.0)
    tilted = lo.parameters.replace(s, {"beam.tilt[1]": 5e-5})
    measured = lo.telecover(tilted, Z, tolerance=1e-5).deviation
    return lo.fit_telecover(s, Z, measured, 0.01, free=["beam.tilt[1]"], tolerance=1e-5)


def _ladder() -> LadderResult:
    """The model ladder's first two families, a short search each (its value, not its choice)."""
    z = np.geomspace(150.0, 3000.0, 10)
    g = lo.overlap(lo.paper_table1(defocus=1e-3), z, "rt", tolerance=1e-6).overlap
    problem = fit_problem(
        SYSTEM, z, g, 1e-3, free="auto", method="rt", tolerance=1e-6, generations=2,
        population=5, minima=1, allow_unconverged=True,
    )  # fmt: skip
    return fit_ladder(problem, LADDER[:2])


def _signal() -> lo.LidarSignal:
    return lo.signal(
        lo.overlap(SYSTEM, Z, "rt"),
        pulse_energy=0.1,
        receiver_efficiency=0.3,
        range_resolution=7.5,
    )


def _first_g(result: lo.OverlapResult) -> float:
    """An objective's function (module level: a value holding it pickles)."""
    return float(result.overlap[0])


REGISTRY: Dict[type, Entry] = {
    lo.Aberrations: Entry(lambda: lo.Aberrations(zernike={4: 1e-7}, w222=1e-7, field_radius=1e-3)),
    lo.ApertureMask: Entry(lambda: lo.ApertureMask.quadrants()),
    lo.Sector: Entry(lambda: lo.ApertureMask.quadrants().sectors[0]),
    lo.Atmosphere: Entry(lambda: lo.Atmosphere()),
    lo.BeamComponent: Entry(lambda: lo.BeamComponent(0.5, 1e-3, 2e-3)),
    lo.GaussianMixtureBeam: Entry(
        lambda: lo.GaussianMixtureBeam.with_wings(SYSTEM.beam, 0.1, 2e-3)
    ),
    lo.GaussianBeam: Entry(lambda: lo.paper_table1().beam),
    lo.Telescope: Entry(lambda: lo.paper_table1().telescope),
    lo.Detector: Entry(lambda: lo.paper_table1().detector),
    lo.LidarSystem: Entry(lambda: lo.instruments.chm15k()),  # with fit_bounds
    lo.Field: Entry(lambda: lo.Field.gaussian(532e-9, 1e-3, n=32, spacing=2e-4)),
    lo.FieldBeam: Entry(
        lambda: lo.FieldBeam(lo.Field.gaussian(355e-9, 1e-3, n=32, spacing=2e-4), tilt=(1e-5, 0))
    ),
    lo.FlatTopBeam: Entry(lambda: lo.FlatTopBeam(355e-9, 1e-3, 0.5e-3, grid=128, max_iterations=5)),
    lo.Turbulence: Entry(
        lambda: lo.Turbulence(1e-14, inner_scale=0.01), inf_ok=frozenset({"outer_scale"})
    ),
    lo.RT: Entry(lambda: lo.RT(1e-4)),
    lo.FO: Entry(lambda: lo.FO()),
    lo.Auto: Entry(lambda: lo.Auto(tolerance=1e-3)),
    lo.Turbulent: Entry(lambda: lo.Turbulent(lo.Turbulence(1e-14), lo.RT(1e-3))),
    lo.Plan: Entry(
        lambda: lo.plan(SYSTEM, Z, "rt"), nan_ok=frozenset({"tolerance", "rt_model_error"})
    ),
    lo.OverlapResult: Entry(
        lambda: lo.overlap(SYSTEM, Z, "rt"), nan_ok=frozenset({"tolerance", "error_estimate"})
    ),
    lo.TurbulentOverlapResult: Entry(_turbulent, nan_ok=frozenset({"tolerance", "error_estimate"})),
    lo.DetectorImage: Entry(lambda: lo.detector_image(SYSTEM, 300.0, n=32)),
    OverlapCurve: Entry(
        lambda: OverlapCurve(Z, [0.1, 0.5, 0.9, 1.0], [0.01] * 4, ("h",), "m"),
        none_ok=frozenset({"sigma"}),
    ),
    NoiseProfile: Entry(
        lambda: noise_profile(
            np.arange(500.0, 800.0, 7.5), np.cos(np.arange(40.0) ** 2), (500.0, 800.0)
        )
    ),
    lo.OverlapSeries: Entry(
        lambda: lo.OverlapSeries(
            Z,
            [[0.1, 0.5, 0.9, 1.0], [0.12, 0.52, 0.92, 1.0]],
            np.array(["2014-01-01", "2014-01-02"], dtype="datetime64[D]"),
            {"temperature_K": [290.0, math.nan]},
            "s",
        )
    ),
    lo.EmpiricalDrift: Entry(
        lambda: lo.empirical_drift(
            Z,
            [[0.1, 0.5, 0.9, 1.0], [0.12, 0.52, 0.92, 1.0], [0.13, 0.5, 0.95, 1.0]],
            [280.0, 290.0, 300.0],
            [0.11, 0.5, 0.9, 1.0],
        )
    ),
    lo.FitResult: _fit_entry(_fit),
    lo.Prediction: Entry(
        lambda: _fit().predict(Z), nan_ok=frozenset({"sigma"}), inf_ok=frozenset({"sigma"})
    ),
    lo.RelativeFitResult: _fit_entry(lambda: _fit(normalize=(1000.0, 3000.0))),
    lo.GlobalFitResult: _fit_entry(lambda: _fit(search="global", seed=1, max_evaluations=40)),
    lo.GlobalRelativeFitResult: _fit_entry(
        lambda: _fit(search="global", seed=1, max_evaluations=40, normalize=(1000.0, 3000.0))
    ),
    lo.JointFitResult: _fit_entry(
        lambda: lo.fit_joint(
            [SYSTEM, SYSTEM],
            [Z, Z],
            [_measured()[0]] * 2,
            sigma=[1e-3, 1e-3],
            shared=["detector.defocus"],
            method="rt",
            tolerance=1e-6,
        )  # fmt: skip
    ),
    lo.DriftFitResult: _fit_entry(
        lambda: lo.fit_drift(
            SYSTEM,
            Z,
            [_measured()[0]] * 2,
            [290.0, 300.0],
            sigma=1e-3,
            free=["detector.defocus"],
            drifting=["detector.defocus"],
            method="rt",
            tolerance=1e-6,
        )  # fmt: skip
    ),
    Also(lo.DriftFitResult, "spline drift"): _fit_entry(
        lambda: lo.fit_drift(
            SYSTEM,
            Z,
            [_measured()[0]] * 3,
            [290.0, 295.0, 300.0],
            sigma=1e-3,
            free=["detector.defocus"],
            drifting={"detector.defocus": "spline"},
            spline_knots=3,
            method="rt",
            tolerance=1e-6,
        )  # fmt: skip
    ),
    lo.TelecoverResult: Entry(_telecover),
    Also(lo.FitResult, "telecover fit"): _fit_entry(_telecover_fit),
    LadderResult: Entry(_ladder),
    FamilyScore: Entry(
        lambda: dataclasses.replace(example(LadderResult).scores[0]),
        nan_ok=frozenset({"chi2_dof"}),
        inf_ok=frozenset({"chi2_dof"}),
    ),
    lo.LidarSignal: Entry(_signal),
    lo.CorrectedSignal: Entry(
        lambda: lo.correct(Z, _signal().range_corrected, lo.overlap(SYSTEM, Z, "rt"))
    ),
    lo.MaximumOverlapAt: Entry(lambda: lo.MaximumOverlapAt(300.0)),
    lo.SmallestFieldOfView: Entry(lambda: lo.SmallestFieldOfView(full_overlap_range=500.0)),
    lo.Objective: Entry(lambda: lo.Objective(_first_g, ranges=(300.0,))),
    lo.Realignment: Entry(
        lambda: lo.realign(lo.paper_table1(obstruction_radius=0.0), 300.0)["beam.tilt[0]"]
    ),
    lo.AlignResult: Entry(
        lambda: lo.align(
            SYSTEM,
            500.0,
            box=2e-4,
            resolution=5e-5,
            shots_per_step=10,
            signal=dict(pulse_energy=1e-3, receiver_efficiency=0.3, range_resolution=7.5),
        )
    ),
    lo.OptimizeResult: Entry(
        lambda: lo.optimize(
            SYSTEM,
            lo.MaximumOverlapAt(300.0),
            ["detector.defocus"],
            {"detector.defocus": (-1e-3, 1e-3)},
        )
    ),
}


@functools.lru_cache(maxsize=None)
def example(cls: type) -> Any:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return REGISTRY[cls].build()


TYPES = sorted(REGISTRY, key=_name)
IDS = [_name(c) for c in TYPES]
