"""The twin's 3-D scene: the geometry of :func:`lidar_overlap.scene` (beam envelope coloured by
G(z), field of view, aperture, obstruction, detector, axis) plus the open sectors of an aperture
mask, built once and then
moved in place as the sliders change: every mesh keeps its points and cells, so a web view sends
    only the
changed coordinates. Range z to scale, x and y times ``exaggeration``, as in
:func:`lidar_overlap.scene`.
"""

from __future__ import annotations

import math

import numpy as np

from ..model.field_beam import FieldBeam
from .headless import use_headless_gl
from .scene import beam_profile

# Fewer samples than lidar_overlap.scene: each update sends the tubes' coordinates to the browser.
N_PHI = 48  # samples around every circle
N_Z = 81  # ranges along the tubes
SECTOR_COLORS = (
    "#e41a1c",
    "#377eb8",
    "#4daf4a",
    "#984ea3",
    "#ff7f00",
    "#a65628",
    "#f781bf",
    "#999999",
)
MISSING = "the interactive view needs its extra: pip install 'lidar-overlap[app]'"
#: The first camera: its direction from the focal point (z across the page, x up, seen from the
#: near side, as lidar_overlap.scene), the narrowest page it must fit (width / height: the scene's
#: column of the page is about 0.8 on a 1500 x 950 window) and the margin left on each side
#: (fraction of the half-width).
VIEW, VIEW_UP, ASPECT, MARGIN = (0.5, 1.0, -1.5), (1.0, 0.0, 0.0), 0.75, 0.06


def pyvista():
    """PyVista, or an ImportError naming the extra to install."""
    try:
        import pyvista as pv
    except ImportError as exc:
        raise ImportError(MISSING) from exc
    return pv


def _tube_faces(nz: int) -> np.ndarray:
    i = (np.arange(nz - 1) * N_PHI)[:, None]
    j = np.arange(N_PHI)[None, :]
    j1 = (j + 1) % N_PHI
    return np.stack(
        np.broadcast_arrays(4, i + j, i + j1, i + N_PHI + j1, i + N_PHI + j), axis=-1
    ).ravel()


def _tube_points(z, center, radius, scale) -> np.ndarray:
    """Circles of ``radius`` (m) about ``center`` ((nz, 2), m) at each z, x and y times
    ``scale``."""
    phi = np.linspace(0.0, 2.0 * np.pi, N_PHI, endpoint=False)
    x = scale * (center[:, :1] + radius[:, None] * np.cos(phi))
    y = scale * (center[:, 1:] + radius[:, None] * np.sin(phi))
    return np.stack([x, y, np.broadcast_to(z[:, None], x.shape)], axis=-1).reshape(-1, 3)


def _disc(pv, center, radius):
    """A filled disc (a fan of N_PHI triangles) of ``radius`` about ``center`` (x, y, z), normal
    z."""
    mesh = pv.PolyData(
        _disc_points(center, radius),
        faces=np.stack(
            np.broadcast_arrays(3, 0, 1 + np.arange(N_PHI), 1 + (np.arange(N_PHI) + 1) % N_PHI),
            axis=-1,
        ).ravel(),
    )
    return mesh


def _disc_points(center, radius) -> np.ndarray:
    phi = np.linspace(0.0, 2.0 * np.pi, N_PHI, endpoint=False)
    ring = np.stack([radius * np.cos(phi), radius * np.sin(phi), 0 * phi], axis=-1)
    return np.asarray(center, float) + np.vstack([[0.0, 0.0, 0.0], ring])


def _sector(pv, sector, aperture_radius, scale, z):
    """An annular sector of the aperture plane as a strip of quads, x and y times ``scale``."""
    outer = aperture_radius if sector.outer_radius is None else sector.outer_radius
    phi = np.linspace(sector.start_angle, sector.stop_angle, 25)
    rings = [
        r * np.stack([np.cos(phi), np.sin(phi)], axis=-1) for r in (sector.inner_radius, outer)
    ]
    points = np.vstack([np.column_stack([scale * p, np.full(len(p), z)]) for p in rings])
    k, n = np.arange(phi.size - 1), phi.size
    return pv.PolyData(
        points, faces=np.stack(np.broadcast_arrays(4, k, k + 1, n + k + 1, n + k), axis=-1).ravel()
    )


class TwinScene:
    """The meshes of a :class:`~lidar_overlap.views.twin.Twin`'s system in a PyVista ``plotter``
    (off-screen), updated by :meth:`update`. The scene runs from the detector plane to ``zmax`` (m):
    twice the first system's full-overlap range, or its last range if G does not level off."""

    def __init__(self, twin, exaggeration: float = 100.0):
        pv = pyvista()
        use_headless_gl()  # before the plotter makes its render window
        self.twin, self.scale = twin, float(exaggeration)
        result, z = twin.result, twin.ranges
        # A curve still to come (computed in the background): the scene runs to the last range.
        z_full = (
            result.full_overlap_range()
            if result is not None and result.reaches_far_range()
            else float("nan")
        )
        self.zmax = float(min(2 * z_full, z[-1]) if np.isfinite(z_full) else z[-1])
        self.z = np.linspace(0.0, self.zmax, N_Z)
        # A field beam's width, from its propagated field (the sliders only move it), else w(z).
        self._field_width = (
            beam_profile(twin.system, self.zmax)[0]
            if isinstance(twin.system.beam, FieldBeam)
            else None
        )
        self.plotter = pv.Plotter(off_screen=True, window_size=(900, 640))
        faces = _tube_faces(N_Z)
        zeros = np.zeros((N_Z * N_PHI, 3))
        self.meshes = {
            "beam": pv.PolyData(zeros.copy(), faces=faces),
            "fov": pv.PolyData(zeros.copy(), faces=faces),
        }
        tel, scale = twin.system.telescope, self.scale
        self.meshes["aperture"] = _disc(pv, (0.0, 0.0, 0.0), scale * 0.5 * tel.diameter)
        if tel.obstruction_radius > 0:
            self.meshes["obstruction"] = _disc(
                pv, (0.0, 0.0, tel.obstruction_distance), scale * tel.obstruction_radius
            )
        self.meshes["detector"] = _disc(pv, (0.0, 0.0, 0.0), 1.0)
        self.meshes["axis"] = pv.Line((0.0, 0.0, -1.0), (0.0, 0.0, self.zmax))
        self.meshes["beam"].point_data["G"] = np.zeros(N_Z * N_PHI)
        self.update()
        add = self.plotter.add_mesh
        add(
            self.meshes["beam"],
            name="beam",
            scalars="G",
            cmap="viridis",
            clim=(0.0, 1.0),
            nan_color="lightgrey",
            show_scalar_bar=False,
        )
        add(self.meshes["fov"], name="fov", color="lightskyblue", opacity=0.25)
        add(self.meshes["aperture"], name="aperture", color="silver", opacity=0.6)
        if "obstruction" in self.meshes:
            add(self.meshes["obstruction"], name="obstruction", color="black")
        add(self.meshes["detector"], name="detector", color="orange")
        add(self.meshes["axis"], name="axis", color="grey", line_width=1)
        mask = twin.mask
        if mask is not None:  # open sectors just in front of the aperture, one colour each
            for i, sector in enumerate(mask.sectors):
                key = f"mask_{i}"
                self.meshes[key] = _sector(pv, sector, 0.5 * tel.diameter, scale, 1e-3 * self.zmax)
                add(
                    self.meshes[key],
                    name=key,
                    color=SECTOR_COLORS[i % len(SECTOR_COLORS)],
                    opacity=0.8,
                )
        self.fit_camera()

    def fit_camera(self) -> None:
        """Point the camera (from :data:`VIEW`) so that the whole instrument (detector, aperture,
        obstruction) and the beam and field of view up to the detector image's range fill a page of
        width / height :data:`ASPECT` or wider, within :data:`MARGIN`."""
        z_image = min(float(self.twin.ranges[self.twin.probe]), self.zmax)
        n = int(np.searchsorted(self.z, z_image, side="right")) * N_PHI
        points = np.vstack(
            [self.meshes["beam"].points[:n], self.meshes["fov"].points[:n]]
            + [
                self.meshes[k].points
                for k in ("aperture", "obstruction", "detector")
                if k in self.meshes
            ]
        )
        angle = float(self.plotter.camera.view_angle)
        # through camera_position: the plotter then keeps it at its first render
        self.plotter.camera_position = fitted_camera(points, VIEW, VIEW_UP, angle, ASPECT, MARGIN)
        self.plotter.renderer.reset_camera_clipping_range()

    def update(self) -> None:
        """Move the meshes to the twin's current system and colour the beam by its G(z)."""
        system, result, z, scale = self.twin.system, self.twin.result, self.z, self.scale
        beam, det = system.beam, system.detector
        d, f, radius = (
            system.image_distance,
            system.telescope.focal_length,
            0.5 * system.telescope.diameter,
        )
        centers = np.asarray(beam.offset) + np.outer(z, beam.tilt)
        width = self._field_width(z) if self._field_width is not None else beam.radius(z)
        self.meshes["beam"].points = _tube_points(z, centers, np.asarray(width), scale)
        g = (
            np.interp(z, result.ranges, result.overlap, left=np.nan, right=np.nan)
            if result is not None
            else np.full(z.shape, np.nan)  # grey until the first curve arrives
        )
        self.meshes["beam"].point_data["G"] = np.repeat(g, N_PHI)
        # The receiver's field of view: scatterers P with |P + o_d z/d| < R|1 + z(1/d - 1/f)| + r_d
        # z/d.
        fov_center = -np.outer(z, det.offset) / d
        fov_radius = radius * np.abs(1.0 + z * (1.0 / d - 1.0 / f)) + det.radius * z / d
        self.meshes["fov"].points = _tube_points(z, fov_center, fov_radius, scale)
        self.meshes["detector"].points = _disc_points(
            (scale * det.offset[0], scale * det.offset[1], -d), scale * det.radius
        )
        self.meshes["axis"].points = np.array([[0.0, 0.0, -d], [0.0, 0.0, self.zmax]])

    def close(self) -> None:
        self.plotter.close()


def fitted_camera(points, direction, up, view_angle: float, aspect: float, margin: float):
    """(position, focal point, view up) of a perspective camera that looks along ``-direction``
    (from the focal point to the camera) with vertical ``view_angle`` (deg) and shows every one
    of ``points`` ((n, 3), scene coordinates) inside ``1 - margin`` of the half-width and
    half-height of a picture of width / height ``aspect``, the points' picture centred. A point
    at depth t in front of the camera, a and b off its axis (right and up), is inside when |a|
    <= t tx and |b| <= t ty: each gives the least distance of the camera from the focal point,
    the largest of them is taken; then the focal point moves to centre the picture, and again (a
    few passes converge)."""
    points = np.asarray(points, dtype=float)
    v = np.asarray(direction, dtype=float)
    v = v / np.linalg.norm(v)
    u = np.asarray(up, dtype=float) - np.dot(up, v) * v
    u = u / np.linalg.norm(u)
    r = np.cross(u, v)
    ty = math.tan(math.radians(view_angle) / 2) * (1.0 - margin)
    tx = ty * aspect
    focus = 0.5 * (points.min(axis=0) + points.max(axis=0))
    for _ in range(40):
        rel = points - focus
        c, a, b = rel @ v, rel @ r, rel @ u
        distance = float(np.max(c + np.maximum(np.abs(a) / tx, np.abs(b) / ty)))
        depth = distance - c
        xs, ys = a / depth, b / depth
        dx, dy = 0.5 * (xs.max() + xs.min()), 0.5 * (ys.max() + ys.min())
        if max(abs(dx) / tx, abs(dy) / ty) < 1e-4:
            break
        focus = focus + distance * (dx * r + dy * u)
    return tuple(focus + distance * v), tuple(focus), tuple(u)
