"""The model ladder's families beyond the Gaussian receiver (a beam with wings, a second stop):
curves made by a model outside a fitted family, plus noise, choose the family that can make them and
are recovered in shape to within the noise; a multimode (M²) beam computed by Fourier optics is
recovered by the plain beam family on ray tracing.

Measured over 10 noise draws each (seeds 0-9, these 16 ranges, sigma 0.01): the two-component truth
chose the wings family 10 of 10 times, the second-stop truth the stop family 10 of 10, the plain
truth the plain family 10 of 10; the chosen fit's RMS distance to the noise-free truth was at most
0.81 sigma. The test runs fewer draws (cost) and asks for most of them.
"""

import dataclasses

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import parameters
from lidar_overlap.analysis.fitting.families import (
    LADDER,
    Family,
    stop_bounds,
    wing_bounds,
    with_stop,
    with_wing,
)
from lidar_overlap.analysis.fitting.ladder import fit_ladder
from lidar_overlap.analysis.fitting.problem import fit_problem

pytest.importorskip("scipy")
# a stop's radius and distance trade against each other, and so do a wing's share and divergence:
# the chosen family says so, as it should
pytestmark = pytest.mark.filterwarnings("ignore::lidar_overlap.DegeneracyWarning")

_TABLE1 = lo.paper_table1()
THETA = _TABLE1.beam.half_angle_divergence
BIAXIAL = parameters.replace(_TABLE1, {"beam.offset[0]": 0.15, "beam.divergence": 1.5 * THETA})
Z = np.geomspace(100.0, 3000.0, 16)
SIGMA = 0.01
#: The fitted curve's RMS distance from the noise-free truth, in sigma: with k of n points free
#: it is about sqrt(k / n) = 0.5 sigma; this allows for the draws' spread.
SHAPE_SIGMAS = 1.2
PLAIN = ("beam.tilt[0]", "beam.divergence")
BEAM = Family("beam", PLAIN, "pointing and divergence")
WINGS = Family(
    "beam + wings",
    PLAIN + ("beam.components[1].weight", "beam.components[1].divergence"),
    "a beam with wings",
    extend=with_wing,
    start_from="beam",
    bounds=wing_bounds,
)
STOP = Family(
    "beam + stop",
    PLAIN + ("detector.stop_radius", "detector.stop_distance"),
    "a second stop",
    extend=with_stop,
    start_from="beam",
    bounds=stop_bounds,
)
TILTED = parameters.replace(BIAXIAL, {"beam.tilt[0]": -1e-4})
TRUTHS = {
    "plain": parameters.replace(TILTED, {"beam.divergence": 1.2 * THETA}),
    "wings": dataclasses.replace(
        TILTED, beam=lo.GaussianMixtureBeam.with_wings(TILTED.beam, 0.15, 5 * THETA)
    ),
    "stop": dataclasses.replace(
        TILTED,
        detector=dataclasses.replace(TILTED.detector, stop_radius=0.03, stop_distance=0.5),
    ),
}
START = parameters.replace(BIAXIAL, {"beam.tilt[0]": 2e-4})


def _ladder(g, seed):
    y = g + np.random.default_rng(seed).normal(0.0, SIGMA, Z.size)
    return fit_ladder(
        fit_problem(
            START,
            Z,
            y,
            SIGMA,
            free="auto",
            bounds={"beam.tilt[0]": (-1e-3, 1e-3)},
            method="rt",
            tolerance=1e-5,
            allow_unconverged=True,
            threads=1,
            seed=seed,
        ),
        families=(BEAM, WINGS, STOP),
    )


@pytest.mark.parametrize(
    "truth, family, draws, at_least",
    [("wings", WINGS, 4, 3), ("stop", STOP, 4, 3), ("plain", BEAM, 3, 2)],
)
def test_out_of_family_truth_chooses_its_family(truth, family, draws, at_least):
    g = lo.overlap(TRUTHS[truth], Z, "rt", tolerance=1e-8).overlap
    right = 0
    for seed in range(draws):
        r = _ladder(g, seed)
        right += r.chosen_family is family
        rms = np.sqrt(np.mean((r.chosen.result.overlap - g) ** 2))
        assert rms <= SHAPE_SIGMAS * SIGMA, (truth, seed, rms / SIGMA)
    assert right >= at_least, (truth, right)
    # the plain family alone cannot make the wings' or the stop's curve
    if truth != "plain":
        plain = next(s for s in r.scores if s.family is BEAM)
        assert not plain.reaches_noise


def test_m_squared_beam_in_fourier_optics_is_recovered_by_ray_tracing():
    m2 = 2.5
    beam = lo.GaussianBeam.from_m_squared(
        TILTED.beam.wavelength,
        TILTED.beam.waist_radius,
        m2,
        offset=TILTED.beam.offset,
        tilt=TILTED.beam.tilt,
    )
    g = lo.overlap(dataclasses.replace(TILTED, beam=beam), Z, "fo").overlap
    r = _ladder(g, 3)
    assert r.chosen_family is BEAM and r.scores[0].reaches_noise
    rms = np.sqrt(np.mean((r.chosen.result.overlap - g) ** 2))
    assert rms <= SHAPE_SIGMAS * SIGMA
    fitted = r.chosen.parameters["beam.divergence"]
    assert fitted == pytest.approx(
        beam.divergence, abs=4 * r.chosen.uncertainties["beam.divergence"]
    )


def test_extensions_add_once_and_the_default_ladder_has_them():
    s = with_wing(BIAXIAL)
    assert isinstance(s.beam, lo.GaussianMixtureBeam) and with_wing(s) is s
    assert s.beam.components[0].divergence == BIAXIAL.beam.divergence
    t = with_stop(BIAXIAL)
    assert t.detector.stop_radius is not None and with_stop(t) is t
    # the added stop just vignettes the far-range pupil (STOP_CUT of its radius)
    far = lo.overlap(t, [1e6]).overlap[0] / lo.overlap(BIAXIAL, [1e6]).overlap[0]
    assert 0.8 < far < 0.95
    names = [f.name for f in LADDER]
    assert "alignment + beam + focus + wings" in names
    assert "alignment + beam + focus + second stop" in names
