"""A result names the fitted divergences that end at the diffraction limit λ/(π w0) (within 6 %: the
default lower bound lies 5 % above it), for single, joint and drift fits: a diffraction-limited
beam's curve drives its fit there, a beam twice as divergent does not."""

import math
import warnings

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap.analysis.fitting.diffraction import AT_LIMIT, at_diffraction_limit
from lidar_overlap.model.instruments import chm15k, chm15k_bounds

pytest.importorskip("scipy")

FAST = dict(method="rt", tolerance=1e-5, threads=1)
Z = np.geomspace(60.0, 3000.0, 16)
SIGMA = 1e-3
PATH = "beam.divergence"


def _limit(wavelength: float, waist: float = 1e-3) -> float:
    return wavelength / (math.pi * waist)


def _curve(wavelength: float, factor: float):
    """G of the paper's Table 1 lidar with a divergence ``factor`` x the diffraction limit."""
    truth = lo.paper_table1(wavelength=wavelength, divergence=factor * _limit(wavelength))
    return lo.overlap(truth, Z, "rt", tolerance=1e-7).overlap


def _start(wavelength: float):
    return lo.paper_table1(wavelength=wavelength, divergence=3.0 * _limit(wavelength))


def _quiet(call, *args, **options):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return call(*args, **options, **FAST)


def test_a_single_fit_names_a_divergence_at_the_limit_and_not_one_twice_it():
    at = _quiet(lo.fit, _start(355e-9), Z, _curve(355e-9, 1.0), SIGMA, free=[PATH])
    # the data ask for the limit itself: the fit stops on the default bound, 1.05 x the limit
    assert at.parameters[PATH] == pytest.approx(1.05 * _limit(355e-9), rel=1e-6)
    assert at.at_diffraction_limit == (PATH,) and at.at_bounds == (PATH,)
    assert "at the diffraction limit: beam.divergence" in at.summary()
    away = _quiet(lo.fit, _start(355e-9), Z, _curve(355e-9, 2.0), SIGMA, free=[PATH])
    assert away.parameters[PATH] == pytest.approx(2.0 * _limit(355e-9), rel=1e-3)
    assert away.at_diffraction_limit == () and "diffraction" not in away.summary()


def test_joint_and_drift_results_name_the_curve_and_parameter_at_the_limit():
    joint = _quiet(
        lo.fit_joint, [_start(355e-9), _start(532e-9)], [Z, Z],
        [_curve(355e-9, 1.0), _curve(532e-9, 2.0)], sigma=[SIGMA, SIGMA], shared=[],
        per_curve=[PATH],
    )  # fmt: skip
    assert joint.at_diffraction_limit == (f"{PATH}@0",)
    assert f"at the diffraction limit: {PATH}@0" in joint.summary()
    curves = np.array([_curve(355e-9, 1.0)] * 3)
    drift = _quiet(
        lo.fit_drift, _start(355e-9), Z, curves, [280.0, 290.0, 300.0], sigma=SIGMA, free=[PATH],
        drifting=[],
    )  # fmt: skip
    assert drift.at_diffraction_limit == (PATH,)


def test_the_verdict_holds_a_value_the_optimiser_leaves_just_above_a_bound():
    """On the Payerne median curve the ladder left the CHM15k's divergence 2.5e-7 (relative) above
    its preset's lower bound, 1.05 x the limit: at the limit; 1.1 x the limit is not."""
    low = chm15k_bounds()[PATH][0]
    limit = _limit(1064e-9, 45e-3)
    assert low == pytest.approx(1.05 * limit, rel=1e-12)
    for value, expected in ((low * (1 + 2.5e-7), (PATH,)), (AT_LIMIT * limit, (PATH,))):
        system = lo.parameters.replace(chm15k(), {PATH: value})
        assert at_diffraction_limit(system, [PATH, "beam.tilt[0]"]) == expected
    system = lo.parameters.replace(chm15k(), {PATH: 1.1 * limit})
    assert at_diffraction_limit(system, [PATH]) == ()
