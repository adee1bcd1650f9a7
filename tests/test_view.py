"""The interactive view (lo.view, lidar-overlap view) and the standalone HTML scene.

The twin behind the page is tested here on its own (sliders, the systems they make, the saved
scenario); the page itself in headless Chromium in test_view_browser.py."""

import json
import subprocess
import sys

import numpy as np
import pytest
from _browser import TABLE1_TOML

import lidar_overlap as lo

pytest.importorskip("pyvista")
from lidar_overlap.io.scenario import load_scenario  # noqa: E402
from lidar_overlap.views.twin import Twin, sliders_for  # noqa: E402


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
