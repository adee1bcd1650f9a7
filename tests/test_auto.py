"""method="auto": on scenes beyond those the estimator was tuned on, the chosen model stays within the
tolerance of a converged Fourier-optics reference, reports an error estimate that covers its error,
and explains itself. (Its speed against the single methods is charted in benchmarks/speed_accuracy.py.)
"""

import dataclasses

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import _core

Z = np.geomspace(10.0, 3000.0, 60)


def reference(system):
    """Converged FO: the radial path with 4x its nodes, or the 2-D path on a finer beam grid."""
    if system.is_axisymmetric:
        return np.asarray(_core.overlap_fo_radial(system._native, Z, 2.0, 0)["overlap"])
    return lo.overlap(system, Z, method="fo", fo_path="2d", beam_grid=512, beam_window=12.0).overlap


base = lo.paper_table1()
SCENES = {
    "table1": base,
    "obstructed and defocused": lo.paper_table1(obstruction_radius=0.025, defocus=1e-3),
    "near infrared": lo.paper_table1(wavelength=1064e-9),
    "m2 = 2": lo.paper_table1(divergence=2 * 355e-9 / (np.pi * 1e-3)),
    "wide field": dataclasses.replace(base, detector=lo.Detector.from_fov(2e-3, 1.0)),
    "diffraction-limited fibre": dataclasses.replace(base, detector=lo.Detector(radius=5e-6)),
    "large telescope": lo.LidarSystem(beam=lo.GaussianBeam(532e-9, 4e-3), telescope=lo.Telescope(0.3, 1.5),
                                      detector=lo.Detector.from_fov(0.6e-3, 1.5)),
    "biaxial tilted": dataclasses.replace(base, beam=lo.GaussianBeam(355e-9, 1e-3, offset=(0.12, 0.0),
                                                                     tilt=(-0.1e-3, 0.0))),
}


@pytest.fixture(scope="module")
def references():
    return {name: reference(s) for name, s in SCENES.items()}


@pytest.mark.parametrize("tolerance", [1e-2, 3e-3, 1e-4])
@pytest.mark.parametrize("name", list(SCENES))
def test_auto_meets_its_tolerance(name, tolerance, references, recwarn):
    res = lo.overlap(SCENES[name], Z, method="auto", tolerance=tolerance)
    error = np.abs(res.overlap - references[name])
    assert error.max() <= tolerance
    assert np.all(error <= res.error_estimate + 1e-9)    # the estimate covers the actual error


def test_decisions_follow_the_physics():
    loose = lo.explain(base, Z, tolerance=2e-2)
    tight = lo.explain(base, Z, tolerance=1e-4)
    assert loose.method == "rt"                     # 1e-2 leaves room for RT's ~5e-3 diffraction error
    assert tight.method == "fo" and tight.fo_path == "radial"
    assert lo.explain(SCENES["biaxial tilted"], Z, tolerance=1e-4).fo_path == "2d"
    # A detector of 1.7 Airy radii: RT misses 10 % of G, which here is at most 0.06 (absolute 6e-3).
    fibre = lo.explain(SCENES["diffraction-limited fibre"], Z, tolerance=1e-3)
    assert fibre.method == "fo" and fibre.rt_model_error > 3e-3
    flat = dataclasses.replace(base, beam=lo.FieldBeam(lo.Field.gaussian(355e-9, 1e-3, 128, 1e-3 / 12)))
    assert lo.explain(flat, Z, tolerance=0.5).method == "fo"


def test_explain_says_why(capsys):
    lo.explain(base, Z, tolerance=1e-4)
    out = capsys.readouterr().out
    assert "Fourier optics (radial path)" in out and "diffraction" in out and "tolerance" in out


def test_auto_result_reports_method_and_tolerance():
    res = lo.overlap(base, Z, method="auto", tolerance=2e-2)
    assert res.method == "rt" and res.tolerance == 2e-2
    assert np.all(res.error_estimate > 0)
