"""The 3-D scene (lidar_overlap.scene): geometry of its meshes, the rendered picture, errors.

Mesh vertices are placed exactly on circles at sampled ranges, so radii and centres are checked to
rounding (REL); the detector-plane image is a sampled convolution, checked against G(z) to
IMAGE_ABS."""

import dataclasses
import re
import subprocess
import sys

import numpy as np
import pytest

import lidar_overlap as lo

pv = pytest.importorskip("pyvista")
from lidar_overlap.views.scene import save_scene, scene  # noqa: E402

REL = 1e-9  # vertices are computed in float64 at exact ranges: rounding only
IMAGE_ABS = 0.01  # detector image power inside the detector vs G: 192² pixels, disc edges
RANGES = np.geomspace(1.0, 500.0, 60)


def build(system, **kwargs):
    kwargs.setdefault("ranges", RANGES)
    plotter = scene(system, off_screen=True, **kwargs)
    meshes = plotter.lidar_meshes
    plotter.close()
    return meshes


def ring(mesh, z):
    """Vertices of a tube at range z (m): their (x, y) centre and mean distance from it."""
    pts = mesh.points[np.abs(mesh.points[:, 2] - z) <= 1e-12 * max(z, 1.0)]
    assert len(pts) >= 16, f"no ring of vertices at z = {z}"
    centre = pts[:, :2].mean(axis=0)
    r = np.linalg.norm(pts[:, :2] - centre, axis=1)
    assert np.ptp(r) <= REL * r.mean() + 1e-12
    return centre, r.mean()


def with_beam(system, **changes):
    return dataclasses.replace(system, beam=dataclasses.replace(system.beam, **changes))


def test_picture_is_not_blank(tmp_path):
    system = lo.paper_table1(obstruction_radius=0.02)
    path = save_scene(
        system,
        tmp_path / "scene.png",
        ranges=RANGES,
        planes=(60.0, 300.0),
        color_by="overlap",
        window_size=(600, 400),
    )
    assert path == tmp_path / "scene.png" and path.stat().st_size > 10_000
    image = pv.read(path)
    rgb = np.asarray(image.point_data[image.point_data.keys()[0]])[:, :3].astype(float)
    assert rgb.shape[0] == 600 * 400
    background = np.median(rgb, axis=0)
    assert (
        np.mean(np.any(np.abs(rgb - background) > 30, axis=1)) > 0.05
    )  # > 5 % of the pixels drawn
    assert len(np.unique(rgb.astype(np.uint8), axis=0)) > 200  # shaded, coloured, textured
    assert rgb.std() > 20


@pytest.mark.parametrize("exaggeration", [1.0, 50.0])
def test_beam_tube_radius_is_exaggerated_w(exaggeration):
    system = lo.paper_table1()
    meshes = build(system, exaggeration=exaggeration)
    for z in (0.0, RANGES[20], RANGES[-1]):
        centre, r = ring(meshes["beam"], z)
        assert r == pytest.approx(exaggeration * system.beam.radius(np.array([z]))[0], rel=REL)
        assert np.allclose(centre, 0.0, atol=REL * r)


def test_field_beam_tube_uses_propagated_second_moment_radius():
    field = lo.Field.gaussian(355e-9, 1e-3, n=64, spacing=2.5e-4)
    system = dataclasses.replace(lo.paper_table1(), beam=lo.FieldBeam(field))
    ranges = np.geomspace(20.0, 200.0, 6)
    meshes = build(system, ranges=ranges, exaggeration=100.0, planes=(50.0,))
    for z, expected in ((0.0, field.beam_radius), (200.0, lo.propagate(field, 200.0).beam_radius)):
        assert ring(meshes["beam"], z)[1] == pytest.approx(100.0 * expected, rel=REL)
    assert meshes["plane_50"].n_points == meshes["detector_image_50"].n_points > 0


def test_fov_cone_half_angle_is_rd_over_f():
    system = lo.paper_table1()
    scale = 100.0
    meshes = build(system, exaggeration=scale)
    z = RANGES[::7]
    radii = np.array([ring(meshes["fov"], zi)[1] for zi in z]) / scale
    slope, intercept = np.polyfit(z, radii, 1)
    assert slope == pytest.approx(system.detector.radius / system.telescope.focal_length, rel=1e-9)
    assert intercept == pytest.approx(0.5 * system.telescope.diameter, rel=1e-9)
    rim = np.linalg.norm(meshes["aperture"].points[:, :2], axis=1).max()  # a float32 disc
    assert rim == pytest.approx(scale * 0.5 * system.telescope.diameter, rel=1e-6)


def test_fov_cone_with_defocus_narrows_to_the_detector_at_the_focus_range():
    """At z_opt the circle of confusion vanishes: the FOV radius is the back-projected detector r_d
    z/d."""
    system = lo.paper_table1(defocus=2e-3)
    f, d = 1.0, 1.0 + 2e-3
    z_opt = lo.optimal_focus_range(f, 2e-3)
    meshes = build(system, ranges=np.sort(np.r_[RANGES, z_opt]), exaggeration=1.0)
    assert ring(meshes["fov"], z_opt)[1] == pytest.approx(
        system.detector.radius * z_opt / d, rel=1e-7
    )
    assert meshes["detector"].center[2] == pytest.approx(-d)


def test_beam_offset_and_tilt_move_the_beam_only():
    scale = 100.0
    base = lo.paper_table1()
    moved = with_beam(base, offset=(0.1, -0.05), tilt=(-2e-4, 1e-4))
    a, b = build(base, exaggeration=scale), build(moved, exaggeration=scale)
    for z in (0.0, RANGES[30], RANGES[-1]):
        centre, _ = ring(b["beam"], z)
        expected = scale * (np.array([0.1, -0.05]) + np.array([-2e-4, 1e-4]) * z)
        assert np.allclose(centre, expected, rtol=0, atol=REL * scale)
    for name in ("fov", "aperture", "detector"):
        assert np.array_equal(a[name].points, b[name].points), name


def test_detector_offset_moves_the_fov_and_detector_only():
    scale = 100.0
    base = lo.paper_table1()
    offset = (1e-4, -5e-5)
    moved = dataclasses.replace(base, detector=dataclasses.replace(base.detector, offset=offset))
    a, b = build(base, exaggeration=scale), build(moved, exaggeration=scale)
    for z in (0.0, RANGES[30], RANGES[-1]):  # line of sight: angle -o_d/f (in focus, d = f)
        assert np.allclose(
            ring(b["fov"], z)[0],
            -scale * np.array(offset) * z,
            rtol=0,
            atol=REL * scale * z + 1e-12,
        )
    assert np.allclose(b["detector"].center, (scale * offset[0], scale * offset[1], -1.0))
    assert np.array_equal(a["beam"].points, b["beam"].points)


@pytest.mark.parametrize(
    "offset, tilt, z",
    [
        ((0.0, 0.0), (0.0, 0.0), 60.0),
        ((0.05, 0.02), (0.0, 0.0), 100.0),
        ((0.2, 0.0), (-0.4e-3, 0.0), 150.0),
    ],
)
def test_detector_image_inside_the_detector_holds_g(offset, tilt, z):
    """Without obstruction or NA, the image's power inside the detector outline over its total is
    G(z)."""
    system = with_beam(lo.paper_table1(), offset=offset, tilt=tilt)
    meshes = build(system, planes=(z,))
    image, outline = meshes[f"detector_image_{z:g}"], meshes[f"detector_outline_{z:g}"]
    centre = outline.points.mean(axis=0)
    radius = np.linalg.norm(outline.points[0] - centre)
    values = np.asarray(image.point_data[image.point_data.keys()[0]])
    inside = np.hypot(*(image.points[:, :2] - centre[:2]).T) < radius
    g = lo.overlap(system, [z]).overlap[0]
    assert values[inside].sum() / values.sum() == pytest.approx(g, abs=IMAGE_ABS)


def test_full_overlap_is_marked_and_obstruction_drawn():
    system = lo.paper_table1(obstruction_radius=0.02)
    result = lo.overlap(system, RANGES)
    plotter = scene(system, result=result, off_screen=True, color_by="overlap")
    meshes = plotter.lidar_meshes
    assert {"beam", "fov", "aperture", "obstruction", "detector", "full_overlap"} <= set(
        plotter.actors
    )
    plotter.close()
    assert ring(meshes["full_overlap"], result.full_overlap_range())[1] > 0
    assert meshes["obstruction"].center[2] == pytest.approx(system.telescope.obstruction_distance)
    g = meshes["beam"].point_data[meshes["beam"].point_data.keys()[0]]
    assert np.nanmax(g) == pytest.approx(result.overlap.max(), rel=1e-12)


def test_default_ranges_end_at_twice_the_full_overlap_range():
    system = lo.paper_table1()
    z_full = lo.overlap(system, np.geomspace(1.0, 1000.0, 200)).full_overlap_range()
    plotter = scene(system, off_screen=True)
    assert plotter.lidar_meshes["beam"].points[:, 2].max() == pytest.approx(2 * z_full, rel=1e-12)
    plotter.close()


def test_package_imports_without_pyvista():
    code = (
        "import sys; sys.modules['pyvista'] = None; import lidar_overlap, lidar_overlap.views.scene"
    )
    assert subprocess.run([sys.executable, "-c", code], capture_output=True).returncode == 0


def test_without_pyvista_both_functions_say_how_to_install(monkeypatch, tmp_path):
    monkeypatch.setitem(sys.modules, "pyvista", None)
    message = re.escape(
        "the 3-D scene (lo.scene, lo.save_scene) needs PyVista: pip install 'lidar-overlap[viz]' "
        "(or pip install pyvista)"
    )
    with pytest.raises(ImportError, match=message):
        scene(lo.paper_table1())
    with pytest.raises(ImportError, match=message):
        save_scene(lo.paper_table1(), tmp_path / "x.png")


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(exaggeration=0.0), "exaggeration"),
        (dict(exaggeration=-5.0), "exaggeration"),
        (dict(color_by="power"), "color_by"),
        (dict(planes=(600.0,)), "planes"),
        (dict(planes=(-1.0,)), "planes"),
        (dict(planes=("far",)), "planes"),
        (dict(ranges=[-1.0, 2.0]), "ranges"),
        (dict(result="G"), "result"),
    ],
)
def test_bad_input_names_the_parameter(kwargs, name):
    kwargs.setdefault("ranges", RANGES)
    with pytest.raises(ValueError, match=name):
        scene(lo.paper_table1(), off_screen=True, **kwargs)


def test_bad_system_and_window_size(tmp_path):
    with pytest.raises(ValueError, match="system"):
        scene("lidar", off_screen=True)
    with pytest.raises(ValueError, match="window_size"):
        save_scene(lo.paper_table1(), tmp_path / "x.png", window_size=(0, 10))
