"""The fits' Jacobian (analysis.sensitivity.jacobian): central differences of ray-traced G, and a
one-sided difference for a parameter one step from the edge of the model's range (a beam at its
diffraction limit has no smaller divergence), checked against differences of independently computed
curves."""

import dataclasses
import math

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap.analysis.sensitivity import jacobian
from lidar_overlap.forward.planning import plan

Z = np.array([80.0, 200.0, 500.0])
TOL = 1e-4  # RT's quadrature tolerance: sets the steps, s (3 TOL)^(1/3), 6.7 % of a divergence
CURVE_TOL = 1e-10  # the independent curves, far tighter than the Jacobian's own
# Both sides difference the same two curves, each within TOL: their quotients agree to 2 TOL / h.
AGREE = 2.0


def at_limit():
    """Table 1 with its beam tilted (so that divergence and tilt both move G) and its divergence
    at the diffraction limit, stated explicitly."""
    table1 = lo.paper_table1()
    beam = table1.beam
    limit = beam.wavelength / (math.pi * beam.waist_radius)
    beam = dataclasses.replace(beam, divergence=limit, tilt=(-2e-4, 0.0))
    return dataclasses.replace(table1, beam=beam), limit


def curve(system, **beam_changes):
    changed = dataclasses.replace(system, beam=dataclasses.replace(system.beam, **beam_changes))
    return lo.overlap(changed, Z, "rt", tolerance=CURVE_TOL).overlap


def test_a_divergence_at_the_diffraction_limit_gets_the_forward_difference():
    system, limit = at_limit()
    with pytest.raises(ValueError, match="divergence"):  # no beam below the limit
        curve(system, divergence=limit * (1.0 - 1e-3))
    j = jacobian(plan(system, Z, "rt", tolerance=TOL), system, ["beam.divergence"], TOL)
    h = limit * (3.0 * TOL) ** (1.0 / 3.0)
    forward = (curve(system, divergence=limit + h) - curve(system)) / h
    assert j.shape == (Z.size, 1) and np.all(np.isfinite(j))
    assert np.max(np.abs(j[:, 0] - forward)) <= AGREE * 2.0 * TOL / h
    assert np.max(np.abs(forward)) * h > 10 * TOL  # and a step moves G by far more than TOL


def test_a_parameter_inside_its_range_keeps_the_central_difference():
    system, _ = at_limit()
    paths = ["beam.divergence", "beam.tilt[0]"]
    j = jacobian(plan(system, Z, "rt", tolerance=TOL), system, paths, TOL)
    h = (0.45e-3) * (3.0 * TOL) ** (1.0 / 3.0)  # the tilt's scale is the half field of view
    central = (curve(system, tilt=(-2e-4 + h, 0.0)) - curve(system, tilt=(-2e-4 - h, 0.0))) / (
        2 * h
    )
    assert np.max(np.abs(j[:, 1] - central)) <= AGREE * TOL / h
