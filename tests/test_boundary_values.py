"""The public boundary in the library's words: every refusal names the caller's parameter, and the
value types that travel to processes (masks, masked systems, telecover and fit results) pickle and
compare by value."""

from __future__ import annotations

import dataclasses
import pickle

import numpy as np
import pytest

import lidar_overlap as lo

TABLE1 = lo.paper_table1()
Z = np.geomspace(150.0, 3000.0, 8)


def _masked(system=TABLE1):
    mask = lo.ApertureMask.sectors(4)
    return dataclasses.replace(system, telescope=dataclasses.replace(system.telescope, mask=mask))


@pytest.mark.parametrize("value", [-1, 1.5, "1", True, 2**64])
def test_set_max_memory_refuses_by_name(value):
    before = lo.max_memory()
    with pytest.raises(ValueError, match="bytes"):
        lo.set_max_memory(value)
    assert lo.max_memory() == before


def test_align_names_its_parameters():
    signal = dict(pulse_energy=1e-3)
    with pytest.raises(ValueError, match="system = None is invalid"):
        lo.align(None, 1000.0, signal=signal)
    with pytest.raises(ValueError, match="box"):
        lo.align(TABLE1, 1000.0, box=10.0, signal=signal)
    for seed, match in ((1.5, "seed"), ("0", "seed"), (True, "seed")):
        with pytest.raises(ValueError, match=match):
            lo.align(TABLE1, 1000.0, seed=seed, signal=signal)


def test_field_beams_compare_by_value():
    field = lo.Field.gaussian(532e-9, 2e-3, 64, 2e-4)
    a, b = lo.FieldBeam(field), lo.FieldBeam(lo.Field(np.array(field.values), 2e-4, 532e-9))
    assert a == b and hash(a) == hash(b) and a is not b
    assert a != lo.FieldBeam(field, tilt=(1e-4, 0.0))
    assert pickle.loads(pickle.dumps(a)) == a


def test_masked_systems_telecover_and_fit_results_pickle():
    masked = _masked()
    assert pickle.loads(pickle.dumps(masked)) == masked
    t = lo.telecover(TABLE1, Z, tolerance=1e-4, threads=1)
    back = pickle.loads(pickle.dumps(t))
    assert back.names == t.names and np.array_equal(back.deviation, t.deviation, equal_nan=True)
    pytest.importorskip("scipy")
    g = lo.overlap(TABLE1, Z, "rt", tolerance=1e-6).overlap
    noisy = g + np.random.default_rng(0).normal(0.0, 0.01, Z.size)
    f = lo.fit(TABLE1, Z, noisy, sigma=0.01, free=["detector.defocus"], method="rt", tolerance=1e-5)
    copy = pickle.loads(pickle.dumps(f))
    assert copy.parameters == f.parameters and copy.result == f.result
    assert copy.predict(Z).overlap.tolist() == f.predict(Z).overlap.tolist()
