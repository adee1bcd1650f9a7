"""free="auto": the model ladder chooses by BIC the family the data need (a defocused truth gets the
family that frees the defocus; an in-focus truth the simpler one, at the rate BIC's penalty
gives), says when no family reaches the noise, and its runs test against known sign sequences."""

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import parameters
from lidar_overlap.analysis.fitting.families import Family
from lidar_overlap.analysis.fitting.ladder import fit_ladder, runs_p_value
from lidar_overlap.analysis.fitting.problem import fit_problem

pytest.importorskip("scipy")

BIAXIAL = parameters.replace(lo.paper_table1(), {"beam.offset[0]": 0.15})
Z = np.geomspace(100.0, 3000.0, 16)
SIGMA = 0.01
TILT = Family("tilt", ("beam.tilt[0]",), "pointing")
TILT_FOCUS = Family("tilt + focus", ("beam.tilt[0]", "detector.defocus"), "pointing, focus")
BOUNDS = {"beam.tilt[0]": (-1e-3, 1e-3), "detector.defocus": (-0.01, 0.02)}
START = {"beam.tilt[0]": 2e-4, "detector.defocus": 0.5e-3}
#: An in-focus truth: the larger family wins only when its chi-square gain exceeds ln(16) + 2
#: (the penalty plus the tie rule), chance 2.9% per draw (chi-square, 1 dof): 4 of 5 draws or more
#: fail with probability 0.8%.
N_DRAWS, SIMPLE_AT_LEAST = 5, 4


def _ladder(truth, seed, families=(TILT, TILT_FOCUS)):
    g = lo.overlap(parameters.replace(BIAXIAL, truth), Z, "rt", tolerance=1e-8).overlap
    y = g + np.random.default_rng(seed).normal(0.0, SIGMA, Z.size)
    return fit_ladder(
        fit_problem(
            parameters.replace(BIAXIAL, START),
            Z,
            y,
            SIGMA,
            free="auto",
            bounds=BOUNDS,
            method="rt",
            tolerance=1e-5,
            threads=1,
            seed=seed,
        ),
        families=families,
    )


def test_defocused_truth_chooses_the_family_with_the_defocus():
    r = _ladder({"beam.tilt[0]": -1e-4, "detector.defocus": 4e-3}, 0)
    assert r.chosen_family is TILT_FOCUS and r.criterion == "BIC"
    assert r.scores[1].reaches_noise and not r.scores[0].reaches_noise
    assert r.chosen.parameters["detector.defocus"] == pytest.approx(
        4e-3, abs=4 * r.chosen.uncertainties["detector.defocus"]
    )
    assert r.note is None and "chosen 'tilt + focus'" in str(r)


def test_in_focus_truth_chooses_the_simpler_family_in_most_draws():
    simple = sum(
        _ladder({"beam.tilt[0]": -1e-4, "detector.defocus": 0.5e-3}, seed).chosen_family is TILT
        for seed in range(N_DRAWS)
    )
    assert simple >= SIMPLE_AT_LEAST


def test_says_when_no_family_reaches_the_noise():
    r = _ladder({"beam.tilt[0]": -1e-4, "detector.defocus": 4e-3}, 1, families=(TILT,))
    assert r.note is not None and "no family reaches the noise" in r.note


def test_auto_needs_sigma():
    with pytest.raises(ValueError, match="free = 'auto' needs sigma"):
        lo.fit(BIAXIAL, Z, np.ones(Z.size), free="auto", method="rt")


@pytest.mark.parametrize(
    "signs, low",
    [
        ([1] * 10 + [-1] * 10, True),  # 2 runs of 20: structure
        ([1, -1] * 10, False),  # 20 runs: as many as can be
    ],
)
def test_runs_test_on_known_sequences(signs, low):
    p = runs_p_value(np.array(signs, dtype=float))
    assert (p < 1e-3) if low else (p > 0.5)


def test_runs_test_on_random_signs_has_its_false_alarm_rate():
    rng = np.random.default_rng(2)
    #: one-sided 1% test over 400 random sequences: 4 expected, 12 or more has chance < 0.1%.
    alarms = sum(runs_p_value(rng.normal(size=60)) < 0.01 for _ in range(400))
    assert alarms < 12
