"""The interactive view of every beam the library computes: a flat-top, a sampled field and a
mixture get the model auto chooses, computed in the background with the last curve kept on the page;
the first camera frames the instrument and the beam's cone; the tab is titled with the scenario's
name.  Nothing here depends on how fast anything runs: the background computation is awaited with a
generous timeout, and its order (a newer setting supersedes an older one) follows from the event
loop, not from timing. The browser tests drive Debian's headless Chromium (tests/_browser.py);
screenshots are kept in build/test-artifacts/."""

import asyncio
import math
import pathlib

import numpy as np
import pytest
from _browser import ARTIFACTS, chromium, drawn_canvas, require_browser, served, wait_for

import lidar_overlap as lo

pytest.importorskip("pyvista")
from lidar_overlap.io.scenario import load_scenario  # noqa: E402
from lidar_overlap.views.twin import Twin  # noqa: E402

SCENARIOS = pathlib.Path(__file__).resolve().parent.parent / "examples" / "scenarios"
RANGES = np.geomspace(20.0, 1000.0, 8)  # m, few: each Fourier-optics range propagates the field
TOLERANCE = 1e-4
#: The curve in the page against the one lo.run gives: the same plan run in chunks of ranges.
SAME = 1e-12
#: The longest a background curve may take to arrive on a loaded machine (s); never a speed claim.
BACKGROUND_WAIT = 600.0


def _systems():
    table1 = lo.paper_table1()
    return {
        "flat_top": lo.LidarSystem(
            lo.FlatTopBeam(355e-9, 1e-3, 0.36e-3, grid=128), table1.telescope, table1.detector
        ),
        "field": lo.LidarSystem(
            lo.FieldBeam(lo.super_gaussian_field(355e-9, 1e-3, 4.0, 128, 5e-5)),
            table1.telescope,
            table1.detector,
        ),
        "mixture": lo.LidarSystem(
            lo.GaussianMixtureBeam.with_wings(table1.beam, 0.05, 1e-3),
            table1.telescope,
            table1.detector,
        ),
    }


def _auto(system, ranges=RANGES, threads=0):
    return lo.run(lo.plan(system, ranges, "auto", tolerance=TOLERANCE, threads=threads))


@pytest.mark.parametrize("kind", ["flat_top", "field", "mixture"])
def test_twin_computes_what_auto_chooses_for_the_moved_system(kind):
    system = _systems()[kind]
    twin = Twin(system, RANGES, tolerance=TOLERANCE)
    assert twin.background and twin.method == "auto" and "divergence" not in twin.sliders
    np.testing.assert_allclose(twin.result.overlap, _auto(system).overlap, rtol=0, atol=SAME)
    twin.update({"tilt_y": 120, "detector_x": 110})
    s = twin.sliders
    moved = lo.parameters.replace(
        system,
        {"beam.tilt[1]": s["tilt_y"].value(120), "detector.offset[0]": s["detector_x"].value(110)},
    )
    assert twin.system == moved and twin.image.range == RANGES[twin.probe]
    expected = _auto(moved)
    assert twin.result.method == expected.method
    np.testing.assert_allclose(twin.result.overlap, expected.overlap, rtol=0, atol=SAME)


def test_a_gaussian_beam_stays_ray_traced_at_once():
    twin = Twin(lo.paper_table1(), RANGES)
    assert not twin.background and twin.result.method == "rt" and "divergence" in twin.sliders


def test_compute_reports_progress_and_stops_when_superseded():
    system = _systems()["field"]
    twin = Twin(system, RANGES, compute=False)
    assert twin.result is None
    done = []
    outcome = twin.compute(cancelled=lambda: len(done) >= 2, progress=done.append)
    assert outcome is None and done == [0.125, 0.25]  # stopped after two chunks of one range
    assert twin.result is None  # compute changes nothing in the twin
    done.clear()
    outcome = twin.compute(progress=done.append)
    assert done == [(i + 1) / RANGES.size for i in range(RANGES.size)]
    twin.accept(outcome)
    np.testing.assert_allclose(twin.result.overlap, _auto(system).overlap, rtol=0, atol=SAME)


def test_save_writes_the_curve_of_a_field_beam_and_says_no_scenario(tmp_path):
    twin = Twin(_systems()["field"], RANGES, name="field")
    toml, csv = twin.save(tmp_path)
    assert toml is None and not (tmp_path / "field.toml").exists()
    read = lo.OverlapResult.from_csv(csv)  # a field beam's system is not in the file
    np.testing.assert_array_equal(read.overlap, twin.result.overlap)
    np.testing.assert_array_equal(read.ranges, twin.result.ranges)
    with pytest.raises(ValueError, match="no curve yet"):
        Twin(_systems()["field"], RANGES, compute=False).save(tmp_path)


def test_page_computes_in_the_background_and_keeps_the_last_curve(tmp_path):
    """A slider move returns at once with the old curve on the page and the progress shown; two
    moves in a row compute only the second setting, whose curve then replaces the first."""
    pytest.importorskip("trame")
    system = _systems()["flat_top"]

    async def page():
        app = lo.view(system, RANGES, tolerance=TOLERANCE, name="flat", out=tmp_path, block=False)
        try:
            assert app.twin.result is None and app.state.trame__title.startswith("flat")
            assert app.state.curve_figure["data"] == []  # nothing to show before the first curve
            app._compute_in_background()  # what the running server does when it is ready
            await _until(lambda: app.computed == 1)
            first = app.twin.result
            assert app.state.curve_figure["data"][0]["y"] == first.overlap.tolist()
            assert not app.state.computing and app.state.progress == 100
            positions = {**app.twin.positions(), "probe": app.twin.probe}
            app._on_change(**{**positions, "tilt_x": 100})
            assert app.state.computing and app.twin.result is first  # the move did not wait
            assert app.state.curve_figure["data"][0]["y"] == first.overlap.tolist()
            app._on_change(**{**positions, "tilt_x": 100, "offset_y": 120})  # supersedes it
            await _until(lambda: app.computed == 2 and not app.state.computing)
            await asyncio.sleep(0.5)  # a stale result would be shown now, if ever
            assert app.computed == 2  # the first move's curve was never shown
            s = app.twin.sliders
            moved = lo.parameters.replace(
                system,
                {
                    "beam.tilt[0]": s["tilt_x"].value(100),
                    "beam.offset[1]": s["offset_y"].value(120),
                },
            )
            expected = _auto(moved).overlap
            assert app.twin.system == moved
            np.testing.assert_allclose(app.twin.result.overlap, expected, rtol=0, atol=SAME)
            assert app.state.curve_figure["data"][0]["y"] == app.twin.result.overlap.tolist()
        finally:
            app.close()

    asyncio.run(page())


def test_page_says_why_a_background_curve_failed(tmp_path):
    pytest.importorskip("trame")

    async def page():
        app = lo.view(_systems()["field"], RANGES, out=tmp_path, block=False)
        try:

            def refuse(cancelled=None, progress=None):
                raise RuntimeError("not converged: raise max_segments")

            app.twin.compute = refuse
            app._compute_in_background()
            await _until(lambda: not app.state.computing)
            assert app.state.error == "not converged: raise max_segments"
            assert app.twin.result is None and app.computed == 0
        finally:
            app.close()

    asyncio.run(page())


async def _until(condition, timeout=BACKGROUND_WAIT):
    deadline = asyncio.get_running_loop().time() + timeout
    while not condition():
        if asyncio.get_running_loop().time() > deadline:
            pytest.fail(f"the background computation did not arrive within {timeout:g} s")
        await asyncio.sleep(0.05)


def test_first_camera_frames_the_lidar_and_the_cone():
    """Every point of the instrument and of the beam and FOV tubes to the image range projects,
    through VTK's own camera transform at the narrowest page aspect, inside the picture less its
    margin, and the picture is filled to that margin on one axis (the fit is tight)."""
    pytest.importorskip("trame")
    from lidar_overlap.views.twin_scene import ASPECT, MARGIN, N_PHI, TwinScene

    twin = Twin(lo.paper_table1(obstruction_radius=0.02), telecover="quadrants")
    scene = TwinScene(twin)
    try:
        scene.plotter.render()  # the camera as the first frame has it
        z_image = twin.ranges[twin.probe]
        n = int(np.searchsorted(scene.z, z_image, side="right")) * N_PHI
        points = np.vstack(
            [scene.meshes["beam"].points[:n], scene.meshes["fov"].points[:n]]
            + [scene.meshes[k].points for k in ("aperture", "obstruction", "detector")]
        )
        for aspect in (ASPECT, 1.6):  # a wider page leaves room on the sides, never cuts
            matrix = scene.plotter.camera.GetCompositeProjectionTransformMatrix(aspect, -1, 1)
            m = np.array([[matrix.GetElement(i, j) for j in range(4)] for i in range(4)])
            h = np.c_[points, np.ones(len(points))] @ m.T
            ndc = h[:, :2] / h[:, 3:]
            assert np.all(h[:, 3] > 0)  # in front of the camera
            assert np.max(np.abs(ndc)) <= 1 - MARGIN + 1e-6
            if aspect == ASPECT:
                assert max(np.max(np.abs(ndc[:, k])) for k in (0, 1)) >= 1 - MARGIN - 1e-3
    finally:
        scene.close()


# -----------------------------------------------------------------------------------------------
# browser
JS_CURVE = (
    "const p = document.querySelector('#curve .js-plotly-plot'); "
    "return p && p.data && p.data.length ? p.data[0].y : null;"
)


@pytest.mark.parametrize("scenario", ["biaxial_flat_top.toml", "super_gaussian.toml"])
def test_view_shows_the_curve_of_a_field_beam_scenario(scenario, tmp_path):
    require_browser()
    loaded = load_scenario(SCENARIOS / scenario)
    ranges = np.geomspace(loaded.ranges[0], loaded.ranges[-1], 40)  # the view's ranges
    tolerance = loaded.options["tolerance"] if "tolerance" in loaded.options else 1e-4
    with served([SCENARIOS / scenario], tmp_path) as url, chromium() as page:
        page.get(url)
        wait_for(lambda: page.title.startswith(loaded.name), "the tab titled with the name")
        # the progress bar is up until the curve arrives, or the curve is already there
        wait_for(
            lambda: page.execute_script(
                "const p = document.querySelector('#progress'); "
                "return (p && p.offsetParent !== null) || "
                "document.querySelector('#curve-version').textContent.trim() === '1';"
            ),
            "the progress bar or the curve",
        )
        curve = np.array(
            wait_for(lambda: page.execute_script(JS_CURVE), "the curve", timeout=BACKGROUND_WAIT),
            dtype=float,
        )
        page.save_screenshot(str(_artifact(f"view_{loaded.name}.png")))
    expected = lo.run(lo.plan(loaded.system, ranges, "auto", tolerance=tolerance)).overlap
    np.testing.assert_allclose(curve, expected, rtol=0, atol=1e-9)
    assert curve[-1] > 0.5  # the curve of a lidar that reaches overlap, not an empty plot


def _artifact(name: str) -> pathlib.Path:
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    return ARTIFACTS / name


def _colour_fraction(rgb, colour, tolerance=40.0) -> float:
    return float(np.mean(np.all(np.abs(rgb - np.array(colour, float)) < tolerance, axis=-1)))


def test_first_frame_shows_the_lidar_and_the_cone(tmp_path):
    """The Table 1 scenario's first frame: the drawing stays clear of the picture's left, top and
    bottom edges (the cone runs on past the image range to the right), spans most of its width,
    shows the aperture (neutral grey) at its left end and the beam (coloured by G) along it."""
    require_browser()

    with served([SCENARIOS / "table1.toml"], tmp_path) as url, chromium() as page:
        page.get(url)
        wait_for(lambda: page.title.startswith("table1"), "the tab titled with the name")
        canvas, rgb = drawn_canvas(page, "#scene canvas", "the scene's canvas", 0.02)
        page.save_screenshot(str(_artifact("view_first_frame.png")))
        _artifact("view_first_frame_scene.png").write_bytes(canvas.screenshot_as_png)
    rgb = rgb[10:-10, 3:-3]  # the toolbar's shadow above, the page's footer line below
    flat = rgb.reshape(-1, 3).astype(np.uint8)
    values, counts = np.unique(flat, axis=0, return_counts=True)
    content = np.any(np.abs(rgb - values[np.argmax(counts)]) > 30, axis=-1)
    edge = max(2, math.ceil(0.01 * min(content.shape)))
    assert not content[:, :edge].any(), "the scene is cut at the left edge"
    assert not content[:edge, :].any() and not content[-edge:, :].any()
    columns = np.flatnonzero(content.any(axis=0))
    assert columns[-1] - columns[0] > 0.6 * content.shape[1]  # the cone at a readable scale
    left = slice(columns[0], columns[0] + max(3, (columns[-1] - columns[0]) // 10))
    r, g, b = (rgb[:, left, k] for k in range(3))
    grey = content[:, left] & (np.abs(r - b) < 12) & (np.abs(r - g) < 12) & (r < 235)
    assert grey.sum() > 20, "no aperture at the lidar's end"
    green = content & (rgb[..., 1] > rgb[..., 2] + 40) & (rgb[..., 1] > rgb[..., 0])
    assert green.sum() > 50, "no beam coloured by G"


@pytest.mark.parametrize(
    "changes, g_error, deviation_error",
    [
        ({}, 1e-4, 1e-4),  # a beam on the axis: the shadow's shifts cancel to first order
        ({"beam.tilt[0]": 2e-4}, 1e-3, 0.02),
        ({"beam.offset[0]": 0.05}, 1e-3, 0.02),
    ],
)
def test_obstructed_telecover_estimate_against_the_exact_sectors(changes, g_error, deviation_error):
    """The twin's telecover of an obstructed system (the shadow centred in each sector) against
    lo.telecover's exact masked ray tracing: G of each sector within ``g_error``, the deviations
    within ``deviation_error`` where the mean G exceeds 1e-3 (the panel's ±5 % band is 0.05)."""
    from lidar_overlap.views.twin_telecover import centred_shadow_telecover

    system = lo.parameters.replace(lo.paper_table1(obstruction_radius=0.02), changes)
    ranges = np.geomspace(1.05, 1000.0, 30)
    estimate = centred_shadow_telecover(system, ranges, tolerance=TOLERANCE)
    exact = lo.telecover(system, ranges, tolerance=TOLERANCE)
    assert estimate.full == exact.full and estimate.names == exact.names
    np.testing.assert_allclose(estimate.overlap, exact.overlap, rtol=0, atol=g_error)
    seen = exact.full.overlap > 1e-3
    np.testing.assert_allclose(
        estimate.deviation[:, seen], exact.deviation[:, seen], rtol=0, atol=deviation_error
    )
    twin = Twin(system, ranges, telecover="quadrants")
    assert twin.telecover_estimated
    np.testing.assert_array_equal(twin.deviation.overlap, estimate.overlap)


def test_super_gaussian_scenario_is_checked_naming_the_key(tmp_path):
    text = (SCENARIOS / "super_gaussian.toml").read_text()
    scenario = load_scenario(SCENARIOS / "super_gaussian.toml")
    field = lo.super_gaussian_field(355e-9, 1e-3, 4.0, 256, 2.5e-5)
    np.testing.assert_array_equal(scenario.system.beam.field.values, field.values)
    for old, new, message in (
        ("order = 4.0", "order = 0.5", "order = 0.5 is invalid"),
        ("order = 4.0", "order = nan", "order"),
        ("grid = 256", "grid = 255", "n = 255 is invalid"),
        ("grid = 256", "grid = 4294967296", "grid"),
        ("spacing = 2.5e-5", "spacing = 1e-300", "spacing"),
        ('method = "auto"', 'method = "rt"', "ray tracing models Gaussian beams only"),
    ):
        path = tmp_path / "bad.toml"
        path.write_text(text.replace(old, new))
        with pytest.raises(ValueError, match=message):
            load_scenario(path)
