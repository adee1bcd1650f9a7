"""Backends are objects that say what they model and how they run (forward.backends.Backend): a
plan's capabilities are read from them, many variants run through their run_many (or one by one),
a turbulent plan runs in parts through their draws, and Plan.at moves a plan to other ranges with
auto's model error estimated again."""

import dataclasses

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap.forward import auto
from lidar_overlap.forward.backends import BACKENDS, many
from lidar_overlap.forward.backends.turbulent import Rows

Z = np.geomspace(50.0, 2000.0, 6)
BASE = lo.paper_table1()
MASKED = dataclasses.replace(
    BASE, telescope=dataclasses.replace(BASE.telescope, mask=lo.ApertureMask.quadrants())
)


def _mixture(system):
    beam = system.beam
    return dataclasses.replace(
        system,
        beam=lo.GaussianMixtureBeam(
            (
                lo.BeamComponent(0.8, beam.waist_radius),
                lo.BeamComponent(0.2, 3 * beam.waist_radius),
            ),
            beam.wavelength,
        ),
    )


def test_every_backend_states_what_it_models_consistently_with_its_key():
    for key, b in BACKENDS.items():
        assert b.model == key.split("_")[0]
        assert b.masks == ("masked" in key) and b.turbulence == ("turbulent" in key)
        assert b.mixture == ("mixture" in key) and b.aberrations == ("aberrated" in key)
        assert (b.draws is not None) == b.turbulence
        assert b.batched == (key == "rt") and (b.run is None) == (b.model == "auto")
    assert [k for k, b in BACKENDS.items() if b.plain_rt] == ["rt", "rt_mixture"]


@pytest.mark.parametrize(
    "system, method, batched, plain_rt",
    [
        (BASE, "rt", True, True),
        (BASE, "fo", False, False),
        (_mixture(BASE), "rt", False, True),
        (MASKED, "rt", False, False),
        (MASKED, "fo", False, False),
    ],
)
def test_plans_answer_their_capabilities(system, method, batched, plain_rt):
    p = lo.plan(system, Z, method)
    assert (p.batched, p.plain_rt) == (batched, plain_rt)
    assert p.engine is BACKENDS[p.backend]


def test_a_mixture_of_ray_traced_components_runs_its_variants_in_one_call_bit_for_bit():
    system = _mixture(BASE)
    p = lo.plan(system, Z, "rt")
    variants = [
        dataclasses.replace(system, detector=dataclasses.replace(system.detector, radius=r))
        for r in (0.9e-3, 1.1e-3)
    ]
    batched = many.systems(p, variants)
    for v, g in zip(variants, batched.overlap):
        assert np.array_equal(g, lo.run(p.with_system(v)).overlap)


def test_fourier_optics_variants_run_one_by_one_as_single_runs():
    p = lo.plan(BASE, Z, "fo")
    variants = [
        dataclasses.replace(BASE, detector=dataclasses.replace(BASE.detector, radius=r))
        for r in (0.9e-3, 1.1e-3)
    ]
    curves = many.systems(p, variants)
    assert curves.converged.all()
    for v, g in zip(variants, curves.overlap):
        assert np.array_equal(g, lo.run(p.with_system(v)).overlap)


def test_a_turbulent_run_in_two_parts_is_the_whole_run_bit_for_bit():
    method = lo.Turbulent(
        lo.Turbulence(1e-14), lo.RT(tolerance=1e-4), realizations=6, seed=5, paths="transmit"
    )
    p = lo.plan(BASE, Z[2:], method)
    assert many.turbulent(p)
    drawn = many.turbulent_draws(p)
    parts = [many.turbulent_rows(p, 0, 4, drawn), many.turbulent_rows(p, 4, 2, drawn)]
    assert all(isinstance(part, Rows) and part.uncorrelated is None for part in parts)
    whole = lo.run(p)
    split = many.turbulent_result(p, parts)
    assert np.array_equal(split.overlap, whole.overlap) and np.array_equal(split.std, whole.std)


def test_a_plain_plan_has_no_draws_to_run_in_parts():
    with pytest.raises(ValueError, match="draws no turbulent atmosphere"):
        many.turbulent_draws(lo.plan(BASE, Z, "rt"))


def test_plan_at_estimates_auto_s_model_error_again_for_the_new_ranges():
    p = lo.plan(BASE, Z, "auto", tolerance=1e-2)
    assert p.method == "rt" and p.rt_model_error > 0
    near = np.geomspace(20.0, 60.0, 4)
    moved = p.at(near)
    assert moved.rt_model_error == auto.rt_model_error(BASE, near)
    assert moved.rt_model_error != p.rt_model_error
    assert dataclasses.replace(p, ranges=near).rt_model_error == p.rt_model_error
    # the same decisions: the quadrature keeps its tolerance; the stated error, the new estimate
    assert moved.options.tolerance == p.options.tolerance and moved.backend == p.backend
    assert np.all(lo.run(moved).error_estimate >= moved.rt_model_error)
