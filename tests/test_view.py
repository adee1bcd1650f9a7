"""The interactive view (lo.view, lidar-overlap view) and the standalone HTML scene.

The twin behind the page is tested on its own (sliders, the systems they make, the saved scenario);
the page
itself in headless Chromium: a slider moved with the keyboard must bring the plotted G(z) to what
    lo.overlap
gives for the moved system, and the scene must draw. Screenshots and the measured slider-to-update
time are kept in build/test-artifacts/ (the time is reported, never asserted)."""

import json
import subprocess
import sys
import time

import numpy as np
import pytest
from _browser import ARTIFACTS, chromium, drawn, pixels, require_browser, served, wait_for

import lidar_overlap as lo

pytest.importorskip("pyvista")
from lidar_overlap.io.scenario import load_scenario  # noqa: E402
from lidar_overlap.views.twin import Twin, sliders_for  # noqa: E402

TABLE1_TOML = """name = "twin"
[beam]
wavelength = 355e-9
waist_radius = 1e-3
[telescope]
diameter = 0.15
focal_length = 1.0
obstruction_radius = 0.0
obstruction_distance = 0.7
[detector]
fov = 0.9e-3
[ranges]
start = 5.0
stop = 1000.0
count = 50
spacing = "log"
[run]
method = "rt"
tolerance = 1e-4
"""


def test_import_loads_no_optional_dependency():
    code = (
        "import sys, lidar_overlap as lo; lo.view; print([m for m in ('trame', 'pyvista', "
        "'matplotlib', 'vtk') if m in sys.modules])"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=120, check=True
    )
    assert out.stdout.strip() == "[]"


@pytest.mark.parametrize(
    "call",
    ["lo.view(lo.paper_table1(), block=False)", "lo.save_scene(lo.paper_table1(), 'scene.html')"],
)
def test_missing_extra_names_it(call, tmp_path):
    code = (
        "import sys; sys.modules['trame'] = sys.modules['trame_vtk'] = None; import lidar_overlap "
        f"as lo\ntry:\n    {call}\nexcept ImportError as exc:\n    print(exc)"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=300, cwd=tmp_path
    )
    assert "pip install 'lidar-overlap[app]'" in out.stdout, out.stderr
    assert not (tmp_path / "scene.html").exists()


def test_sliders_are_exact_multiples_of_their_step():
    system = lo.paper_table1()
    sliders = sliders_for(system)
    assert list(sliders) == [
        "tilt_x",
        "tilt_y",
        "offset_x",
        "offset_y",
        "detector_x",
        "detector_y",
        "defocus",
        "fov",
        "divergence",
    ]
    assert sliders["tilt_x"].step == 1e-5 and sliders["tilt_x"].value(110) == 2e-4
    assert sliders["tilt_x"].value(sliders["tilt_x"].n // 2) == 0.0
    assert (
        sliders["divergence"].low >= system.beam.half_angle_divergence
    )  # never below the diffraction limit
    assert sliders["fov"].low > 0
    for bad in (-1, 181, 1.5, True, "3"):
        with pytest.raises(
            ValueError, match=r"tilt_x = .* expected a slider position, an integer from 0 to 180"
        ):
            sliders["tilt_x"].value(bad)


def test_moved_slider_gives_the_overlap_of_the_moved_system():
    system = lo.paper_table1()
    twin = Twin(system, telecover="quadrants")
    assert twin.system is system and twin.ranges.size == 200
    twin.update({"tilt_x": 120, "fov": 40, "divergence": 10})
    s = twin.sliders
    moved = lo.parameters.replace(
        system,
        {
            "beam.tilt[0]": s["tilt_x"].value(120),
            "detector.radius": 0.5 * s["fov"].value(40),
            "beam.divergence": s["divergence"].value(10),
        },
    )
    assert twin.system == moved
    assert twin.result == lo.overlap(moved, twin.ranges, "rt", tolerance=1e-4)
    assert twin.image.range == twin.ranges[twin.probe]
    assert twin.deviation.overlap.shape == (4, 200)
    twin.update({}, probe=3)
    assert (
        twin.image.range == twin.ranges[3] and twin.system == moved
    )  # unmoved sliders keep their values
    assert twin.warnings == []
    twin.update({"fov": 1})  # a detector of a few Airy radii: said, not raised
    assert any("outside its validity" in w for w in twin.warnings)


def test_twin_refuses_bad_input_naming_it():
    system = lo.paper_table1()
    for kwargs, message in (
        (dict(system=system.beam), "system = .* expected a lidar_overlap.LidarSystem"),
        (dict(system=system, telecover="halves"), "telecover = 'halves' is invalid"),
        (dict(system=system, name="a b"), "name = 'a b' is invalid"),
        (dict(system=system, ranges=[10.0, 5.0]), "ranges"),
    ):
        with pytest.raises(ValueError, match=message):
            Twin(**kwargs)
    twin = Twin(system)
    for positions, probe, message in (
        ({"tilt": 1}, None, "slider 'tilt' is invalid"),
        ({}, 200, r"probe = 200 is invalid: expected an index from 0 to 199"),
    ):
        with pytest.raises(ValueError, match=message):
            twin.update(positions, probe)
    assert twin.system is system


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(port=70000), r"port = 70000 is invalid: .* from 0 to 65535"),
        (dict(timeout=-1), "timeout = -1 is invalid"),
        (dict(host=""), "host = '' is invalid"),
    ],
)
def test_view_refuses_bad_server_options(kwargs, message):
    with pytest.raises(ValueError, match=message):
        lo.view(lo.paper_table1(), block=False, **kwargs)


def test_view_in_a_running_event_loop_returns_the_app_unstarted(tmp_path):
    pytest.importorskip("trame")

    async def in_a_notebook():  # Jupyter runs cells in an event loop: lo.view must not block it
        return lo.view(lo.paper_table1(), telecover="quadrants", out=tmp_path)

    app = __import__("asyncio").run(in_a_notebook())
    try:
        assert not app.server.running and app.twin.deviation is not None
        assert app.state.curve_figure["data"][0]["y"] == app.twin.result.overlap.tolist()
        app.save()
        assert (tmp_path / "view.toml").exists() and "saved" in app.state.saved
        # What a slider move does on the server (the browser test drives it through the page).
        positions = {**app.twin.positions(), "probe": app.twin.probe}
        app._on_change(**{**positions, "defocus": 150})
        assert app.twin.system.detector.defocus == app.twin.sliders["defocus"].value(150)
        assert app.state.curve_figure["data"][0]["y"] == app.twin.result.overlap.tolist()
        assert app.state.text_defocus == "5 mm" and app.state.timing.startswith("update ")

        def refuse(positions, probe):
            raise ValueError("detector.defocus = 1 is invalid")

        app.twin.update = refuse  # a system the library refuses: the slider goes back
        app._on_change(**{**positions, "defocus": 160})
        assert app.state.error == "detector.defocus = 1 is invalid" and app.state.defocus == 150
    finally:
        app.scene.close()


def test_saved_scenario_reads_back_to_the_same_system_and_curve(tmp_path):
    system = lo.paper_table1(obstruction_radius=0.02)
    twin = Twin(system, np.geomspace(2.0, 800.0, 40), name="saved")
    twin.update({"offset_y": 80, "detector_x": 100, "defocus": 130})
    toml, csv = twin.save(tmp_path / "out")
    scenario = load_scenario(toml)
    assert scenario.system == twin.system and scenario.name == "saved"
    np.testing.assert_array_equal(scenario.ranges, twin.ranges)
    assert scenario.compute() == twin.result
    assert lo.OverlapResult.from_csv(csv) == twin.result


def test_twin_scene_follows_the_system():
    pytest.importorskip("trame")
    from lidar_overlap.views.twin_scene import N_PHI, TwinScene

    twin = Twin(lo.paper_table1(obstruction_radius=0.02), telecover="quadrants")
    scene = TwinScene(twin, exaggeration=50.0)
    try:
        twin.update({"tilt_y": 130, "detector_x": 150, "defocus": 140})
        scene.update()
        system, k = twin.system, 60
        z = scene.z[k]
        ring = scene.meshes["beam"].points[k * N_PHI : (k + 1) * N_PHI]
        np.testing.assert_allclose(
            ring[:, :2].mean(axis=0), 50.0 * np.array(system.beam.center(z)), atol=1e-9
        )
        np.testing.assert_allclose(
            np.linalg.norm(ring[:, :2] - ring[:, :2].mean(axis=0), axis=1),
            50.0 * system.beam.radius(np.array([z]))[0],
            rtol=1e-9,
        )
        # The FOV envelope is the one lo.scene draws (same formula, checked against its mesh).
        reference = lo.scene(system, ranges=scene.z[1:], exaggeration=50.0, off_screen=True)
        mesh = reference.lidar_meshes["fov"]
        reference.close()
        theirs = mesh.points[np.abs(mesh.points[:, 2] - z) <= 1e-9 * z]
        fov_centre = theirs[:, :2].mean(axis=0)
        fov_radius = np.linalg.norm(theirs[0, :2] - fov_centre)
        for ring in (
            mesh.points[np.abs(mesh.points[:, 2] - z) <= 1e-9 * z],
            scene.meshes["fov"].points[k * N_PHI : (k + 1) * N_PHI],
        ):
            centre = ring[:, :2].mean(axis=0)
            radius = np.linalg.norm(ring[:, :2] - centre, axis=1)
            np.testing.assert_allclose(centre, fov_centre, rtol=1e-9, atol=1e-12)
            np.testing.assert_allclose(radius, fov_radius, rtol=1e-9)
        det = scene.meshes["detector"].points
        np.testing.assert_allclose(
            det[0], [50.0 * system.detector.offset[0], 0.0, -system.image_distance]
        )
        assert sum(name.startswith("mask_") for name in scene.meshes) == 4
    finally:
        scene.close()


def test_html_archive_leaves_the_plotter_as_it_was():
    pytest.importorskip("trame_vtk")
    import zipfile

    from lidar_overlap.views.html_export import scene_archive

    plotter = lo.scene(lo.paper_table1(), off_screen=True, planes=(100.0,))
    try:
        props = plotter.renderer.GetViewProps()
        before = props.GetNumberOfItems()
        archive = scene_archive(plotter)
        assert props.GetNumberOfItems() == before
    finally:
        plotter.close()
    with zipfile.ZipFile(__import__("io").BytesIO(archive)) as z:
        scene = json.loads(z.read("index.json"))
    classes = json.dumps(scene["scene"])
    assert "vtkCubeAxesActor" not in classes and classes.count("vtkScalarBarActor") == 1
    assert len(scene["hashes"]) > 10  # the meshes' arrays are in the file


def test_save_scene_refuses_unknown_format(tmp_path):
    with pytest.raises(ValueError, match="format = 'svg' is invalid"):
        lo.save_scene(lo.paper_table1(), tmp_path / "scene.svg", format="svg")


def test_scenes_render_without_a_display_and_without_x_messages(tmp_path):
    code = (
        "import lidar_overlap as lo; lo.save_scene(lo.paper_table1(), "
        f"{str(tmp_path / 'scene.png')!r}, window_size=(320, 240))"
    )
    env = {
        k: v
        for k, v in __import__("os").environ.items()
        if k not in ("DISPLAY", "WAYLAND_DISPLAY", "VTK_DEFAULT_OPENGL_WINDOW")
    }
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=300, env=env
    )
    assert out.returncode == 0, out.stderr
    assert "X server" not in out.stderr + out.stdout and "WARN" not in out.stderr
    assert (tmp_path / "scene.png").stat().st_size > 1000


def test_cli_view_refuses_bad_options_naming_them(tmp_path, capsys):
    from lidar_overlap.cli import main

    path = tmp_path / "twin.toml"
    path.write_text(TABLE1_TOML)
    assert main(["view", str(path), "--port", "x"]) == 2
    assert main(["view", str(path), "--port", "70000", "--no-browser"]) == 2  # a usage error
    assert "'70000' is invalid: expected a port, an integer from 0 to 65535" in (
        capsys.readouterr().err
    )


# -----------------------------------------------------------------------------------------------
# browser
SLIDER = "tilt_x"
MOVES = 5  # slider steps timed one by one
JS_CURVE = (
    "const p = document.querySelector('#curve .js-plotly-plot'); "
    "return p && p.data ? p.data[0].y : null;"
)
# Stamps (performance.now(), ms) of the key press, of the new figures' arrival (the slider's label
# changes in the same message), of the first frame that shows the new curve (plotly has taken the
# new data: Plotly.react draws 2-D plots synchronously) and of the scene's update counter changing
# (sent after the scene's moved coordinates, on the same socket).
JS_STAMPS = """window.__t = {};
const gd = document.querySelector('#curve .js-plotly-plot'), y0 = gd.data[0].y;
document.addEventListener('keydown', () => {
  window.__t.key = window.__t.key || performance.now();
}, true);
// the time the frame's callbacks run (a frame's own time stamp is when it began)
(function frame() {
  if (window.__t.key && !window.__t.curve && gd.data[0].y !== y0) {
    window.__t.curve = performance.now();
  }
  if (!window.__t.curve) requestAnimationFrame(frame);
})();
const stamp = (name, selector) => new MutationObserver(() => {
  if (window.__t.key && !window.__t[name]) window.__t[name] = performance.now(); }).observe(
  document.querySelector(selector), {childList: true, subtree: true, characterData: true});
stamp('data', '#label-tilt_x');          // the new figures and texts have arrived (one message)
stamp('scene', '#scene-version');"""


def test_page_slider_moves_curve_to_lo_overlap(tmp_path):
    require_browser()
    from selenium.webdriver.common.by import By
    from selenium.webdriver.common.keys import Keys

    (tmp_path / "twin.toml").write_text(TABLE1_TOML)
    scenario = load_scenario(tmp_path / "twin.toml")
    ranges = np.geomspace(5.0, 1000.0, 200)
    slider = sliders_for(scenario.system)[SLIDER]
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    with served(["twin.toml", "--out", tmp_path / "saved"], tmp_path) as url, chromium() as page:
        page.get(url)
        before = np.array(
            wait_for(lambda: page.execute_script(JS_CURVE), "the G(z) plot"), dtype=float
        )
        np.testing.assert_allclose(
            before, lo.overlap(scenario.system, ranges, "rt").overlap, rtol=0, atol=1e-12
        )
        thumb = page.find_element(By.CSS_SELECTOR, f"#slider-{SLIDER} .v-slider-thumb")
        start = int(thumb.get_attribute("aria-valuenow"))
        wait_for(
            lambda: page.execute_script("return document.querySelector('#scene canvas') !== null"),
            "the 3-D scene's canvas",
        )
        time.sleep(1.0)  # the first scene and figures settle
        runs = []
        for _ in range(MOVES):  # one key press at a time, each waited for
            page.execute_script(JS_STAMPS)
            thumb.send_keys(Keys.ARROW_RIGHT)
            runs.append(
                wait_for(
                    lambda: (lambda t: t if t and {"curve", "scene", "data"} <= set(t) else None)(
                        page.execute_script("return window.__t")
                    ),
                    "the update's time stamps",
                )
            )
            runs[-1]["server"] = page.find_element(
                By.CSS_SELECTOR, "#timing"
            ).text  # sent with the scene's counter
            time.sleep(0.3)
        position = start + MOVES
        after = np.array(page.execute_script(JS_CURVE), dtype=float)
        assert int(thumb.get_attribute("aria-valuenow")) == position
        moved = lo.parameters.replace(scenario.system, {"beam.tilt[0]": slider.value(position)})
        expected = lo.overlap(moved, ranges, "rt", tolerance=1e-4).overlap
        np.testing.assert_allclose(after, expected, rtol=0, atol=1e-12)
        assert np.max(np.abs(after - before)) > 1e-6
        time.sleep(0.5)  # vtk.js draws the moved scene on its next frame
        page.save_screenshot(str(ARTIFACTS / "view.png"))
        scene = pixels(page.find_element(By.CSS_SELECTOR, "#scene").screenshot_as_png)
        assert drawn(scene) > 0.01  # the beam and FOV cones are drawn
        page.find_element(By.CSS_SELECTOR, "#save").click()
        wait_for(lambda: (tmp_path / "saved" / "twin.toml").exists(), "the saved scenario")
        assert load_scenario(tmp_path / "saved" / "twin.toml").system == moved
    timing = {
        f"key_to_{name}_ms": [round(t[name] - t["key"], 1) for t in runs]
        for name in ("data", "curve", "scene")
    }
    timing.update(
        {
            f"median_key_to_{name}_ms": float(np.median(timing[f"key_to_{name}_ms"]))
            for name in ("data", "curve", "scene")
        }
    )
    timing["server"] = [t["server"] for t in runs]
    (ARTIFACTS / "view_timing.json").write_text(json.dumps(timing, indent=1))
    print(f"slider to updated curve and scene: {timing}")


def test_html_scene_draws_in_the_browser(tmp_path):
    require_browser()
    from selenium.webdriver.common.by import By

    path = lo.save_scene(
        lo.paper_table1(obstruction_radius=0.02),
        tmp_path / "scene.html",
        planes=(100.0,),
        color_by="overlap",
    )
    text = path.read_text(encoding="utf-8")
    assert "kitware.github.io/vtk-js/icon" not in text and "<script" in text
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    with chromium(1000, 700) as page:
        page.get(path.as_uri())
        canvas = wait_for(
            lambda: page.find_elements(By.CSS_SELECTOR, "canvas"), "the vtk.js canvas"
        )[0]
        rgb = wait_for(
            lambda: (lambda p: p if drawn(p) > 0.01 else None)(pixels(canvas.screenshot_as_png)),
            "the scene to be drawn",
        )
        page.save_screenshot(str(ARTIFACTS / "scene_html.png"))
        errors = [e for e in page.get_log("browser") if e["level"] == "SEVERE"]
    assert rgb.shape[0] > 100 and len(np.unique(rgb.reshape(-1, 3), axis=0)) > 50
    assert errors == []  # nothing failed to load: no network needed
