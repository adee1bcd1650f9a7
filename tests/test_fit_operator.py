"""What an operator takes from a fit: the alignment change that moves full overlap to a target
range (checked by recomputing G there), and lo.correct with a fitted curve and its band (an
absolute fit's curve as predicted, a relative fit's divided by its far-range limit)."""

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import parameters
from lidar_overlap.analysis.design.realign import FAR_FACTOR, realign

pytest.importorskip("scipy")

BIAXIAL = parameters.replace(lo.paper_table1(), {"beam.offset[0]": 0.15})
FAST = dict(method="rt", tolerance=1e-6, threads=1)
#: The root is found to 1e-6 of the bounds' span; G's ratio then meets the threshold to this.
RATIO_TOL = 1e-4
TRUE = {"beam.tilt[0]": -1e-4, "detector.defocus": 2e-3}
Z = np.geomspace(100.0, 3000.0, 16)
SIGMA = 0.01


@pytest.mark.parametrize(
    "target, paths",
    [(400.0, ("beam.tilt[0]", "beam.offset[0]")), (1500.0, ("beam.tilt[0]",))],
)  # an offset within +-D cannot delay full overlap to 1500 m in this lidar
def test_realignment_puts_full_overlap_at_the_target(target, paths):
    changes = realign(BIAXIAL, target, paths, threads=1)
    assert set(changes) == set(paths)
    for path, r in changes.items():
        moved = parameters.replace(BIAXIAL, {path: r.value})
        g = lo.overlap(moved, np.array([target, FAR_FACTOR * target]), "rt", tolerance=1e-7)
        assert g.overlap[0] / g.overlap[1] == pytest.approx(0.99, abs=RATIO_TOL)
        assert r.change == pytest.approx(r.value - parameters.get(BIAXIAL, path))


def test_unreachable_target_names_the_path():
    with pytest.raises(ValueError, match=r"beam.tilt\[0\]: no value in"):
        realign(BIAXIAL, 5.0, paths=["beam.tilt[0]"], bounds={"beam.tilt[0]": (0.0, 1e-5)})


def _fit(normalize=None, scale=1.0):
    g = lo.overlap(parameters.replace(BIAXIAL, TRUE), Z, "rt", tolerance=1e-8).overlap
    y = scale * (g + np.random.default_rng(4).normal(0.0, SIGMA, Z.size))
    start = parameters.replace(BIAXIAL, {"beam.tilt[0]": -2e-4, "detector.defocus": 1e-3})
    return lo.fit(start, Z, y, scale * SIGMA, free=list(TRUE), normalize=normalize, **FAST)


def test_correct_with_an_absolute_fit_uses_its_curve_and_band():
    f = _fit()
    signal = np.linspace(5.0, 1.0, Z.size)
    c = lo.correct(Z, signal, f)
    pred = f.predict(Z)
    ref = lo.correct(Z, signal, pred.overlap, overlap_std=pred.sigma)
    assert np.array_equal(c.mask, ref.mask)
    np.testing.assert_allclose(c.values[~c.mask], ref.values[~ref.mask], rtol=1e-12)
    np.testing.assert_allclose(c.std[~c.mask], ref.std[~ref.mask], rtol=1e-12)


def test_correct_with_a_relative_fit_recovers_the_profile_to_its_band():
    f = _fit(normalize=(1000.0, 3000.0), scale=0.8)
    truth = parameters.replace(BIAXIAL, TRUE)
    g = lo.overlap(truth, np.append(Z, FAR_FACTOR * Z[-1]), "rt", tolerance=1e-8).overlap
    profile = np.exp(-Z / 2000.0)
    c = lo.correct(Z, profile * g[:-1] / g[-1], f, min_overlap=0.3)
    use = ~c.mask
    assert use.sum() >= 8
    # The fitted curve differs from the truth by its parameters' error (within 4 of its bands),
    # and this defocused curve peaks above its far limit, so it is divided by the peak: the
    # corrected signal is low by peak / far limit (stated by fitting/correction.py), 1e-5 here.
    a = f.absolute(np.append(Z, FAR_FACTOR * Z[-1])).overlap
    excess = a[:-1].max() / a[-1] - 1.0
    assert 0.0 <= excess < 1e-4
    assert np.all(np.abs(c.values[use] - profile[use]) <= 4 * c.std[use] + excess * profile[use])
