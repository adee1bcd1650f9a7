"""``method="auto"`` through turbulence on both paths weighs whether Fourier optics can run: its
grid must sample the receiver's field of view and λ/r0 at every plane (the core's rule,
``_core.turbulent_grid``, the one ``overlap_fo_turbulent`` refuses by). Auto never chooses a
method that then refuses the scene: where FO would need a grid above ``AUTO_MAX_TURBULENT_GRID``
or the memory budget, it takes ray tracing, says why and warns that ray tracing's estimated error
exceeds the tolerance; where FO can run it gets the grid the scene needs."""

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import _core
from lidar_overlap.forward import auto

TABLE1_RANGES = np.geomspace(100.0, 1000.0, 40)


def small_lidar(detector_radius=300e-6):
    """D = 5 cm, f = 0.5 m at 1064 nm: a field of view of 1.2 mrad whose return path needs a grid
    between the default 256 and 1024 through Cn² = 1e-14 over 300 m."""
    return lo.LidarSystem(
        beam=lo.GaussianBeam(1064e-9, 5e-3),
        telescope=lo.Telescope(0.05, 0.5),
        detector=lo.Detector(radius=detector_radius),
    )


def least_grid(system, z, turbulence, **options):
    o = _core.TurbulenceOptions(paths="both", **options)
    return _core.turbulent_grid(system._native, z, turbulence._native, o).min_beam_grid


def test_table1_at_1e3_takes_ray_tracing_and_says_why(capsys):
    """Table 1 (0.9 mrad, 15 cm at 355 nm) at 1e-3: RT's diffraction error (0.0077) exceeds the
    tolerance, but FO on both paths would need a grid of thousands: RT, with the reason and a
    warning, and the run gives a curve instead of a refusal."""
    system, air = lo.paper_table1(), lo.Turbulence(1e-15)
    needed = least_grid(system, TABLE1_RANGES, air)
    assert needed > auto.AUTO_MAX_TURBULENT_GRID
    request = lo.Turbulent(air, lo.Auto(1e-3), realizations=4)
    p = lo.plan(system, TABLE1_RANGES, request)
    text = str(p)
    assert p.backend == "rt_turbulent"
    assert f"beam grid of {needed}" in text and "AUTO_MAX_TURBULENT_GRID" in text
    assert len(p.warnings) == 1 and "exceeds tolerance 0.001" in p.warnings[0]
    assert lo.explain(system, TABLE1_RANGES, request).backend == "rt_turbulent"
    assert f"beam grid of {needed}" in capsys.readouterr().out
    with pytest.warns(RuntimeWarning, match="Fourier optics on both paths cannot run here"):
        res = lo.overlap(system, TABLE1_RANGES[::8], request)
    assert res.paths == "both" and np.all(np.isfinite(res.overlap))
    # transmit only: auto's FO needs no receiver grid, and is chosen as before
    only = lo.plan(system, TABLE1_RANGES, lo.Turbulent(air, lo.Auto(1e-3), paths="transmit"))
    assert only.backend == "fo_turbulent"


def test_auto_gives_fourier_optics_the_grid_the_scene_needs():
    """A field of view that needs more than the default grid but less than the cap: FO, on the
    least grid the core accepts, and that run is accepted (one draw)."""
    system, air, z = small_lidar(), lo.Turbulence(1e-14), np.array([150.0, 300.0])
    needed = least_grid(system, z, air, screens=2)
    assert auto.DEFAULT_TURBULENT_GRID < needed <= auto.AUTO_MAX_TURBULENT_GRID
    request = lo.Turbulent(air, lo.Auto(1e-3), realizations=1, screens=2, receiver_fields=1)
    p = lo.plan(system, z, request)
    assert p.backend == "fo_turbulent" and p.options.beam_grid == needed
    assert f"beam grid of {needed}" in str(p)
    res = lo.overlap(system, z, request)
    assert np.all(np.isfinite(res.overlap))
    # an FO without a grid takes the same least grid; a grid below it is refused, naming that size
    explicit = lo.plan(system, z, lo.Turbulent(air, lo.FO(), realizations=1, screens=2))
    assert explicit.options.beam_grid == needed
    too_small = lo.FO(beam_grid=auto.DEFAULT_TURBULENT_GRID)
    with pytest.raises(ValueError, match=f"beam_grid.*>= {needed}"):
        lo.overlap(system, z, lo.Turbulent(air, too_small, realizations=1, screens=2))


def test_memory_budget_and_a_given_grid_also_send_auto_to_ray_tracing():
    system, air, z = small_lidar(), lo.Turbulence(1e-14), np.array([150.0, 300.0])
    request = lo.Turbulent(air, lo.Auto(1e-3), realizations=1, screens=2, receiver_fields=1)
    previous = lo.max_memory()
    lo.set_max_memory(1 << 20)
    try:
        p = lo.plan(system, z, request)
    finally:
        lo.set_max_memory(previous)
    assert p.backend == "rt_turbulent" and "max_memory" in str(p)
    coarse = lo.Turbulent(air, lo.Auto(1e-3, fo=lo.FO(beam_grid=64)), realizations=1, screens=2)
    p = lo.plan(system, z, coarse)
    assert p.backend == "rt_turbulent" and "beam_grid 64 is below" in str(p)


def test_the_grid_rule_refuses_bad_input_by_name():
    system, air = small_lidar(), lo.Turbulence(1e-14)
    for options, name in (
        (dict(screens=0), "screens"),
        (dict(beam_window=float("nan")), "beam_window"),
        (dict(beam_window=1.0), "beam_window"),
    ):
        with pytest.raises(ValueError, match=name):
            least_grid(system, [300.0], air, **options)
    for z in ([float("nan")], [-1.0], [1e300]):
        with pytest.raises(ValueError, match=r"ranges\[0\]"):
            least_grid(system, z, air)
    assert least_grid(system, [], air) == 32
    g = _core.turbulent_grid(
        system._native, [150.0, 300.0], air._native, _core.TurbulenceOptions(screens=2)
    )
    assert g.min_beam_grid == 32  # transmit only: the floor
    assert np.all(np.diff(g.window) >= 0) and g.window[0] >= g.pupil_window
