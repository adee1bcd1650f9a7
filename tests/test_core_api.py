"""The core's Python API: option classes carry the C++ defaults and are checked by the core; results
are classes with NumPy properties; overlap_rt_batch is the single-system RT call, entry by entry."""

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import _core

OPTIONS = [
    _core.RtOptions,
    _core.FoOptions,
    _core.RadialFoOptions,
    _core.RtAberratedOptions,
    _core.FoAberratedOptions,
    _core.TurbulenceOptions,
]


@pytest.mark.parametrize("cls", OPTIONS)
def test_options_are_keyword_only_and_repr_their_fields(cls):
    o = cls()
    assert repr(o).startswith(cls.__name__ + "(") and repr(cls(**{"threads": 1})) != repr(o)
    with pytest.raises(TypeError):
        cls(1)


def test_options_hold_the_cpp_defaults_python_relied_on():
    assert repr(_core.RtOptions()) == "RtOptions(tolerance=0.0001, threads=0, max_segments=4000)"
    assert _core.RadialFoOptions().periods_per_panel == 8.0
    assert _core.FoAberratedOptions().tail_error == 1e-4
    assert _core.RtAberratedOptions().max_segments == 4000
    assert (_core.RtAberratedOptions().rings, _core.RtAberratedOptions().ring_rays) == (48, 128)


@pytest.mark.parametrize("bad", [-1, 1.5, "4000", None])
def test_counts_of_the_wrong_type_raise_type_error(bad):
    with pytest.raises(TypeError):
        _core.RtOptions(max_segments=bad)
    o = _core.RtOptions()
    with pytest.raises(TypeError):
        o.max_segments = bad
    assert o.max_segments == 4000


def test_invalid_values_are_refused_by_the_core_by_name():
    s = lo.paper_table1()._native
    with pytest.raises(ValueError, match="tolerance"):
        _core.overlap_rt(s, [100.0], _core.RtOptions(tolerance=2.0))
    with pytest.raises(ValueError, match="max_segments"):
        _core.overlap_rt(s, [100.0], _core.RtOptions(max_segments=0))
    with pytest.raises(ValueError, match="beam_grid"):
        _core.overlap_fo(s, [100.0], _core.FoOptions(beam_grid=15))


def test_results_are_numpy_properties():
    s = lo.paper_table1()._native
    rt = _core.overlap_rt(s, [100.0, 500.0])
    assert (
        rt.overlap.dtype == np.float64
        and rt.error_estimate.dtype == np.float64
        and rt.converged.dtype == bool
    )
    assert rt.overlap.shape == (2,) and isinstance(rt.evaluations, int) and rt.axisymmetric is True
    with pytest.raises(AttributeError):
        rt.overlap = np.zeros(2)
    fo = _core.overlap_fo(s, [500.0], _core.FoOptions(beam_grid=64))
    assert isinstance(fo.beam_reports[0], _core.PropagationReport) and fo.beam_reports[
        0
    ].method in ("angular_spectrum", "fresnel")
    assert fo.spectrum_grid.shape == (1,)
    with pytest.raises(TypeError):
        _core.RtOverlap()


def test_batch_entries_are_single_calls_bit_for_bit():
    systems, ranges = [], []
    for tilt, offset in [
        ((0.0, 0.0), (0.0, 0.0)),
        ((0.2e-3, 0.0), (0.05, 0.0)),
        ((-0.1e-3, 0.05e-3), (0.0, -0.02)),
    ]:
        for z in (40.0, 150.0, 900.0):
            systems.append(lo.LidarSystem(beam=lo.GaussianBeam(tilt=tilt, offset=offset)))
            ranges.append(z)
    options = _core.RtOptions(tolerance=1e-6)
    batch = _core.overlap_rt_batch([s._native for s in systems], ranges, options)
    single = [_core.overlap_rt(s._native, [z], options) for s, z in zip(systems, ranges)]
    assert np.array_equal(batch.overlap, [r.overlap[0] for r in single])
    assert np.array_equal(batch.error_estimate, [r.error_estimate[0] for r in single])
    assert batch.evaluations == sum(r.evaluations for r in single) and not batch.axisymmetric


def test_batch_refuses_bad_sizes_and_ranges_by_name():
    s = lo.paper_table1()._native
    with pytest.raises(ValueError, match="ranges"):
        _core.overlap_rt_batch([s, s], [100.0])
    with pytest.raises(ValueError, match=r"ranges\[1\]"):
        _core.overlap_rt_batch([s, s], [100.0, -1.0])
