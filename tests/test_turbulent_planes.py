"""The turbulent FO path's planes (cpp/src/atmosphere/segment_plan.hpp): ranges in any order,
repeated, on a screen's plane or just past it, through the core's own interface (the Python API
asks for increasing ranges; instrument software calling the core may not)."""

from __future__ import annotations

import numpy as np

import lidar_overlap as lo
from lidar_overlap import _core

# A range on a screen's plane is read from the field arriving there (the screen's phase does not
# change the irradiance); one a nanometre past it from the field leaving it: the two agree to the
# propagation over 1 nm and rounding.
SCREEN_PLANE_ATOL = 1e-10

# Table 1 to 2000 m with 10 screens: screens at 100, 300, ..., 1900 m.
RANGES = np.array([2000.0, 100.0, 300.0, 300.0, 50.0, 1000.0])


def _draws(ranges, **options):
    o = dict(realizations=4, screens=10, seed=2, beam_grid=128, beam_window=8.0, threads=0)
    return np.array(
        _core.overlap_fo_turbulent(
            lo.paper_table1()._native,
            [float(z) for z in ranges],
            lo.Turbulence(1e-14)._native,
            _core.TurbulenceOptions(**(o | options)),
        ).overlap
    )


def test_order_and_repeats_do_not_change_a_draw():
    g = _draws(RANGES)
    order = np.argsort(RANGES, kind="stable")
    assert np.array_equal(g[:, order], _draws(RANGES[order]))
    assert np.array_equal(g[:, 2], g[:, 3])  # 300 m twice
    assert np.array_equal(g, _draws(RANGES, threads=1))
    assert np.all((g > 0) & (g <= 1 + 1e-9)) and np.ptp(g[:, 0]) > 0  # draws differ at 2000 m


def test_a_range_on_a_screen_plane_is_continuous():
    g = _draws(RANGES)
    past = _draws([2000.0, 100.0 + 1e-9, 300.0 + 1e-9, 300.0, 50.0, 1000.0])
    assert np.max(np.abs(past - g)) < SCREEN_PLANE_ATOL
