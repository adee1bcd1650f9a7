"""method="auto": on scenes of every kind its error estimate distinguishes (focused, defocused,
obstructed, overfilled fibres, a blur edge through a fibre, biaxial), the chosen model stays within
the tolerance of a converged Fourier-optics reference, reports an error estimate that covers its
error, and explains itself. (The estimate's calibration and its check on 160 random scenes:
docs/auto_method.md; its speed against the
single methods: benchmarks/speed_accuracy.py.)
"""

import dataclasses

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import _core
from lidar_overlap.forward.auto import decide

Z = np.geomspace(10.0, 3000.0, 60)


def reference(system):
    """Converged FO: the radial path (any Gaussian pointing) with 4x its nodes; the 2-D path on a
    finer beam grid agrees with it to 3e-7 on the biaxial scene (tests/test_overlap_fo.py)."""
    return _core.overlap_fo_radial(
        system._native, Z, _core.RadialFoOptions(periods_per_panel=2.0)
    ).overlap


base = lo.paper_table1()
SCENES = {
    "table1": base,
    "obstructed and defocused": lo.paper_table1(obstruction_radius=0.025, defocus=1e-3),
    "near infrared": lo.paper_table1(wavelength=1064e-9),
    "m2 = 2": lo.paper_table1(divergence=2 * 355e-9 / (np.pi * 1e-3)),
    "wide field": dataclasses.replace(base, detector=lo.Detector.from_fov(2e-3, 1.0)),
    "diffraction-limited fibre": dataclasses.replace(base, detector=lo.Detector(radius=5e-6)),
    "large telescope": lo.LidarSystem(
        beam=lo.GaussianBeam(532e-9, 4e-3),
        telescope=lo.Telescope(0.3, 1.5),
        detector=lo.Detector.from_fov(0.6e-3, 1.5),
    ),
    "biaxial tilted": dataclasses.replace(
        base, beam=lo.GaussianBeam(355e-9, 1e-3, offset=(0.12, 0.0), tilt=(-0.1e-3, 0.0))
    ),
    # The beam image (0.34 mm) overfills a 10 um fibre: light crosses its edge both ways, RT errs by
    # 1.8e-5.
    "overfilled fibre": dataclasses.replace(
        lo.paper_table1(wavelength=1064e-9), detector=lo.Detector(radius=10e-6)
    ),
    # The blur disc's edge sweeps through a 25 um fibre (biaxial): RT errs by 2.5e-4 where it
    # crosses.
    "edge through fibre": lo.LidarSystem(
        beam=lo.GaussianBeam(355e-9, 1e-3, offset=(0.08, 0.0), tilt=(-0.16e-3, 0.0)),
        telescope=base.telescope,
        detector=lo.Detector(radius=25e-6),
    ),
}
CROSSING_RT_ERROR = 2e-4  # measured 2.5e-4 (at 530 m): above the 1e-4 tolerance below


@pytest.fixture(scope="module")
def references():
    return {name: reference(s) for name, s in SCENES.items()}


@pytest.mark.parametrize("tolerance", [1e-2, 3e-3, 1e-4])
@pytest.mark.parametrize("name", list(SCENES))
def test_auto_meets_its_tolerance(name, tolerance, references, recwarn):
    res = lo.overlap(SCENES[name], Z, method="auto", tolerance=tolerance)
    error = np.abs(res.overlap - references[name])
    assert error.max() <= tolerance
    assert np.all(error <= res.error_estimate + 1e-9)  # the estimate covers the actual error


def test_decisions_follow_the_physics():
    loose = lo.explain(base, Z, tolerance=2e-2)
    tight = lo.explain(base, Z, tolerance=1e-4)
    assert loose.method == "rt"  # 1e-2 leaves room for RT's ~5e-3 diffraction error
    assert tight.method == "fo" and tight.fo_path == "radial"
    assert (
        lo.explain(SCENES["biaxial tilted"], Z, tolerance=1e-4).fo_path == "radial"
    )  # offset as J0
    linear = lo.paper_table1(width_law="linear")  # the marginal-ray law exists only in RT
    assert lo.explain(linear, Z, tolerance=1e-4).method == "rt"
    # A detector of 1.7 Airy radii overfilled by the beam image: diffraction moves light across its
    # edge both ways, so RT errs by 3.4e-5 (0.9 % of G <= 3.7e-3), not by the 10 % of G a focused
    # point would lose.
    fibre = lo.explain(SCENES["diffraction-limited fibre"], Z, tolerance=1e-3)
    assert fibre.method == "rt" and fibre.rt_model_error < 1e-3 / 3
    assert lo.explain(SCENES["overfilled fibre"], Z, tolerance=1e-4).method == "rt"
    flat = dataclasses.replace(
        base, beam=lo.FieldBeam(lo.Field.gaussian(355e-9, 1e-3, 128, 1e-3 / 12))
    )
    assert (
        lo.explain(flat, Z, tolerance=0.5).method == "fo"
        and lo.explain(flat, Z, tolerance=0.5).fo_path == "2d"
    )


@pytest.mark.filterwarnings("ignore:ray tracing outside its validity")
def test_edge_through_the_detector_refuses_rt(references):
    """Where the blur disc's edge crosses a small detector, diffraction shifts that edge: RT is
    refused at a tolerance below its error there, and accepted above it."""
    system = SCENES["edge through fibre"]
    rt = lo.overlap(system, Z, method="rt", tolerance=1e-8).overlap
    assert np.max(np.abs(rt - references["edge through fibre"])) > CROSSING_RT_ERROR
    tight = lo.explain(system, Z, tolerance=1e-4)
    assert (
        tight.method == "fo"
        and tight.fo_path == "radial"
        and tight.rt_model_error > CROSSING_RT_ERROR
    )
    assert lo.explain(system, Z, tolerance=1e-2).method == "rt"


def test_explain_says_why(capsys):
    lo.explain(base, Z, tolerance=1e-4)
    out = capsys.readouterr().out
    assert "Fourier optics (radial path)" in out and "diffraction" in out and "tolerance" in out


def test_auto_result_reports_method_and_tolerance():
    res = lo.overlap(base, Z, method="auto", tolerance=2e-2)
    assert res.method == "rt" and res.tolerance == 2e-2
    assert np.all(res.error_estimate > 0)


# --------------------------------------------------------------------------------- hostile input
OBSTRUCTED = lo.paper_table1(obstruction_radius=0.02, obstruction_distance=0.7)


@pytest.mark.parametrize(
    "system, ranges, index",
    [
        (base, [-0.0], 0),
        (base, [0.0], 0),
        (base, [5e-324], 0),
        (base, [1e-300, 1.0], 0),
        (base, [1.0, 1e11], 1),
        (base, [1e300], 0),
        (OBSTRUCTED, [0.5, 1.0], 0),
        (OBSTRUCTED, [0.7, 1.0], 0),
    ],
)
def test_explain_refuses_the_ranges_overlap_refuses(system, ranges, index):
    """explain and auto's decision validate the ranges as the overlap paths do, instead of
    estimating NaN."""
    message = rf"^ranges\[{index}\] = .* is invalid"
    with pytest.raises(ValueError, match=message):
        lo.explain(system, ranges)
    with pytest.raises(ValueError, match=message):
        decide(system, np.asarray(ranges, dtype=float), 1e-3)
    with pytest.raises(ValueError, match=message):
        lo.overlap(system, ranges, "rt")


@pytest.mark.parametrize("ranges", [[1e-10], [1e10], [1e-10, 1.0, 1e10]])
def test_explain_at_the_ends_of_the_ranges_gives_a_finite_estimate(ranges, capsys):
    d = lo.explain(base, ranges)
    assert d.method in ("rt", "fo") and np.isfinite(d.rt_model_error) and d.rt_model_error >= 0


@pytest.mark.parametrize("ranges", [[None], [[1.0]], [], [2**63, 1.0], 10**400, "ranges"])
def test_explain_refuses_ranges_that_are_not_numbers_by_name(ranges):
    with pytest.raises(ValueError, match="^ranges"):
        lo.explain(base, ranges)


@pytest.mark.parametrize("system", [None, base.beam, "paper_table1", 1.0])
def test_explain_refuses_a_system_of_the_wrong_kind_by_name(system):
    with pytest.raises(ValueError, match="^system = "):
        lo.explain(system, [100.0])
