"""3-D view of a lidar's geometry with PyVista (optional: ``pip install 'lidar-overlap[viz]'``).

The range z runs along the telescope axis, to scale; the transverse axes x, y are multiplied by
``exaggeration`` (default 100), because a lidar is millimetres to decimetres wide and hundreds of
metres long. Everything transverse is scaled alike: beam, field of view, aperture, obstruction,
detector. The axes are labelled with true (unexaggerated) coordinates in m. PyVista is imported only
inside the functions, so the rest of the package works without it.
"""

from __future__ import annotations

import os
import pathlib
import sys

import numpy as np

from .. import _checks
from ..forward.compute import overlap
from ..forward.result import OverlapResult
from ..model.field_beam import FieldBeam
from ..model.system import LidarSystem
from ..optics.detector_image import beam_image, blurred, fov_cone, window_about
from ..optics.propagation import propagate
from .headless import use_headless_gl
from .html_export import require, write_scene_html
from .scene_meshes import N_PHI, PLANE_SCALARS, ring, textured_plane, tube

COLOR_BY = ("irradiance", "overlap")
FORMATS = ("png", "html")
N_IMAGE = 192  # samples per side of the plane textures
VIEW, ZOOM = (0.5, 1.0, -1.2), 1.4  # default camera: direction from the focal point, zoom
BAR = dict(
    vertical=True,
    position_y=0.25,
    width=0.06,
    height=0.5,
    title_font_size=14,
    label_font_size=12,
    fmt="%.3g",
    n_labels=5,
)
_MISSING = (
    "the 3-D scene (lo.scene, lo.save_scene) needs PyVista: pip install 'lidar-overlap[viz]' (or "
    "pip install pyvista)"
)


def _pyvista():
    try:
        import pyvista
    except ImportError as exc:
        raise ImportError(_MISSING) from exc
    use_headless_gl()  # without a display: EGL or OSMesa, not an X window that fails with a message
    return pyvista


def beam_profile(system, zmax):
    """w(z) (m, 1/e²) and on-axis peak irradiance (W/m² for P = 1 W) as functions of z.

    Gaussian beam: w(z) of the beam, peak 2/(π w²). Field beam: the second-moment radius and the
    peak of the propagated field at z = 0 and 11 ranges up to ``zmax`` (geometric), interpolated."""
    beam = system.beam
    if not isinstance(beam, FieldBeam):
        width = lambda z: np.asarray(beam.radius(np.asarray(z, dtype=float)))  # noqa: E731
        return width, lambda z: 2.0 / (np.pi * width(z) ** 2)
    zs = np.concatenate(([0.0], np.geomspace(zmax * 1e-3, zmax, 11)))
    fields = [beam.field] + [propagate(beam.field, zi) for zi in zs[1:]]
    w = np.array([f.beam_radius for f in fields])
    log_peak = np.log([f.intensity.max() / beam.field.power for f in fields])
    return lambda z: np.interp(z, zs, w), lambda z: np.exp(np.interp(z, zs, log_peak))


def _planes(pv, plotter, meshes, system, planes, result, scale, width):
    """Scattering-plane irradiance and detector-plane image at each range in ``planes``, as two
    panels stacked above the FOV cone (+x) at that range."""
    det, d = system.detector, system.image_distance
    n = N_IMAGE
    grid = np.arange(n) - n / 2 + 0.5
    for z in planes:
        key, c, w = f"{z:g}", np.array(system.beam.center(z)), float(width(z))
        s, fov_r = (a[0] for a in fov_cone(system, np.array([z])))
        # Scattering plane: the beam to 2.5 w and the FOV section, at the scene's scale, lifted by
        # `lift`.
        mid, half = window_about([(c, 2.5 * w), (s, fov_r)])
        x, y = (mid[k] + grid * 2 * half / n for k in (0, 1))
        g = propagate(system.beam.field, z) if isinstance(system.beam, FieldBeam) else None
        e = beam_image(system, z, x, y, g)
        lift = np.array([max(c[0] + 2.5 * w, s[0] + fov_r) + 1.15 * half - mid[0], 0.0])
        meshes[f"plane_{key}"] = textured_plane(
            pv, e / e.max(), (scale * (x[0] + lift[0]), scale * y[0], z), scale * 2 * half / n
        )
        meshes[f"fov_outline_{key}"] = ring(pv, (*(scale * (s + lift)), z), scale * fov_r)
        # Detector plane, computed back-projected into the scattering plane (u = −x d/z): the beam
        # convolved with the circle of confusion (radius R|m|, less the on-axis obstruction shadow).
        blur, shadow = system.confusion_radius(z) * z / d, system.shadow_radius(z) * z / d
        o_back, r_back = -np.asarray(det.offset) * z / d, det.radius * z / d
        dmid, dhalf = window_about([(c, 2.5 * w + blur), (o_back, r_back)])
        h = 2 * dhalf / n
        xd, yd = (dmid[k] + grid * h for k in (0, 1))
        img = blurred(beam_image(system, z, xd, yd, g), h, blur, min(shadow, blur))[
            ::-1, ::-1
        ]  # flip: u = −x d/z
        # Shown above the plane, the same size, at its own scale k (its width in the detector plane
        # labelled).
        k, centre = half / dhalf, mid + lift + np.array([2.6 * half, 0.0])
        origin = (*(scale * (centre - half + h * k / 2)), z)
        meshes[f"detector_image_{key}"] = textured_plane(
            pv, img / max(img.max(), 1e-300), origin, scale * h * k
        )
        # Detector-plane point u sits at centre + k (u − u_mid) z/d, u_mid = −dmid d/z at the panel
        # centre.
        outline_c = scale * (centre + k * (np.asarray(det.offset) * z / d + dmid))
        meshes[f"detector_outline_{key}"] = ring(pv, (*outline_c, z), scale * k * r_back)
        g = np.interp(z, result.ranges, result.overlap, left=np.nan, right=np.nan)
        for name in (f"plane_{key}", f"detector_image_{key}"):
            plotter.add_mesh(
                meshes[name],
                name=name,
                scalars=PLANE_SCALARS,
                cmap="inferno",
                clim=(0, 1),
                scalar_bar_args=dict(BAR, title=PLANE_SCALARS, position_x=0.9),
            )
        for name in (f"fov_outline_{key}", f"detector_outline_{key}"):
            plotter.add_mesh(meshes[name], name=name, color="cyan", line_width=2)
        tops = scale * np.array(
            [
                [mid[0] + lift[0] + half, mid[1] - half, z / scale],
                [centre[0] + half, centre[1] - half, z / scale],
            ]
        )
        texts = [
            f"z = {z:g} m, G = {np.round(g, 2) + 0.0:.2f}",
            f"detector plane {2e3 * dhalf * d / z:.3g} mm",
        ]
        plotter.add_point_labels(
            tops, texts, name=f"labels_{key}", font_size=11, shape_opacity=0.4, always_visible=True
        )


def scene(
    system: LidarSystem,
    ranges=None,
    *,
    result: OverlapResult | None = None,
    exaggeration: float = 100.0,
    color_by: str = "irradiance",
    planes=(),
    method: str | None = None,
    off_screen: bool | None = None,
):
    """A 3-D PyVista view of ``system``, to scale in range z, transverse x, y times
    ``exaggeration``.

    Shown (actor names in quotes; the same meshes, in displayed coordinates, are in the dict
    ``plotter.lidar_meshes``):

    - "beam": the transmitted beam's 1/e² envelope, a tube of radius w(z) about beam.center(z) =
      offset + tilt·z from z = 0 (a field beam: second-moment radius of the propagated field at 12
      ranges, interpolated). Coloured by the on-axis peak irradiance (W/m² for 1 W; 2/(π w²) for a
      Gaussian) or by G(z) (``color_by="overlap"``; grey outside the computed ranges).
    - "fov": the receiver's full field of view, translucent: the paraxial envelope of the scatterers
      that send some light to the detector, radius R|1 + z(1/d − 1/f)| + r_d z/d about the line of
      sight −o_d z/d (d = f + defocus; in focus: R + z r_d/f, half-angle r_d/f).
    - "aperture" (disc of radius R = D/2 at z = 0, the thin lens), "obstruction" (disc of radius
      r_obs at z = +obstruction_distance, in front of the aperture, when r_obs > 0), "detector"
      (disc of radius r_d at detector.offset, at z = −(f + defocus), behind the lens), "axis" (the
      telescope axis).
    - "full_overlap": a ring around the FOV at result.full_overlap_range(), labelled.
    - for each z in ``planes``, two panels stacked above the FOV cone (displaced along +x so the
      beam tube does not hide them; labelled with z and G(z)): "plane_<z>" (z formatted with
      ``:g``), the beam irradiance in the scattering plane at the scene's scale (a Gaussian averaged
      exactly over each pixel; a field beam: ``propagate(field, z)``, interpolated), with
      "fov_outline_<z>", the FOV section; above it "detector_image_<z>", the geometric-optics image
      on the detector plane: the irradiance scaled by −d/z (flipped) and convolved (FFT) with the
      uniform circle of confusion of radius R|1 + d/z − d/f|, less the obstruction's shadow taken
      for an on-axis scatterer (exact on axis; the shadow's shift with the scatterer's position and
      any fibre NA are ignored), at its own scale (its width in mm is labelled), with
      "detector_outline_<z>", the detector. Without obstruction or NA, the image's power inside the
      outline over its total is G(z). Panels are normalised to their peak.

    Parameters
    ----------
    exaggeration : factor (> 0) on x and y; 1.0 is true scale.
    color_by : "irradiance" or "overlap", the beam's colours.
    planes : ranges (m) in (0, end of the scene] for the panels.
    ranges : m, increasing; default ``result.ranges``, else 200 ranges (40 for Fourier optics) from
        1 m (1.5 z_obs if the obstruction is farther) to 1000 m, with the scene cut at twice the
        full-overlap range. The scene extends from the detector plane to the last range.
    result : an OverlapResult for the colours and the full-overlap marker; default ``overlap(system,
        ranges, method)``.
    method : "rt" or "fo"; default "rt" for a Gaussian beam, "fo" for a field beam.
    off_screen : default PyVista's setting, or off-screen when there is no display.
    Returns the ``pyvista.Plotter`` (not shown).
    """
    pv = _pyvista()
    if not isinstance(system, LidarSystem):
        raise ValueError(f"system = {system!r} is invalid: expected a LidarSystem")
    scale = _checks.positive("exaggeration", exaggeration)
    _checks.choice("color_by", color_by, COLOR_BY)
    if result is not None and not isinstance(result, OverlapResult):
        raise ValueError(f"result = {result!r} is invalid: expected an OverlapResult or None")
    planes = tuple(
        _checks.positive(f"planes[{i}]", p)
        for i, p in enumerate(np.atleast_1d(() if planes is None else planes).tolist())
    )
    if method is None:
        method = "fo" if isinstance(system.beam, FieldBeam) else "rt"
    cut, z_obs = ranges is None and result is None, system.telescope.obstruction_distance
    if ranges is None:
        ranges = (
            result.ranges
            if result is not None
            else np.geomspace(
                1.0 if z_obs < 1.0 else 1.5 * z_obs, 1000.0, 40 if method == "fo" else 200
            )
        )
    z = _checks.ranges("ranges", ranges)
    if z[0] <= 0:
        raise ValueError(f"ranges[0] = {z[0]} is invalid: expected ranges > 0 m")
    if result is None:
        result = overlap(system, z, method=method)
    # No full-overlap ring for a curve still rising at its last range: its "full overlap" would be a
    # guess.
    z_full = result.full_overlap_range() if result.reaches_far_range() else float("nan")
    zmax = float(z[-1])
    if cut and np.isfinite(z_full) and 2 * z_full < zmax:
        zmax = 2 * z_full
    for i, p in enumerate(planes):
        if p > zmax:
            raise ValueError(
                f"planes[{i}] = {p} is invalid: expected a range in (0, {zmax:g}] m, the scene's "
                "extent"
            )

    if off_screen is None:
        off_screen = bool(pv.OFF_SCREEN) or (
            sys.platform.startswith("linux")
            and not os.environ.get("DISPLAY")
            and not os.environ.get("WAYLAND_DISPLAY")
        )
    plotter = pv.Plotter(off_screen=off_screen)
    tel, det = system.telescope, system.detector
    radius, d = 0.5 * tel.diameter, system.image_distance
    extra = [z_full] if np.isfinite(z_full) and z_full <= zmax else []
    zt = np.unique(
        np.concatenate(([0.0], z[z <= zmax], np.linspace(0.0, zmax, 121), planes, extra))
    )
    width, peak = beam_profile(system, zmax)
    centers = np.array(system.beam.offset) + np.outer(zt, system.beam.tilt)
    meshes = {"beam": tube(pv, zt, centers, width(zt), scale)}
    if color_by == "overlap":
        label, values, log = (
            "beam:\noverlap G(z)",
            np.interp(zt, result.ranges, result.overlap, np.nan, np.nan),
            False,
        )
    else:
        label, values, log = "beam: on-axis\nirradiance\n(W/m^2, 1 W)", peak(zt), True
    meshes["beam"].point_data[label] = np.repeat(values, N_PHI)
    fov_c, fov_r = fov_cone(system, zt)
    meshes["fov"] = tube(pv, zt, fov_c, fov_r, scale)
    meshes["aperture"] = pv.Disc(center=(0, 0, 0), inner=0.0, outer=scale * radius, c_res=N_PHI)
    if tel.obstruction_radius > 0:
        meshes["obstruction"] = pv.Disc(
            center=(0, 0, tel.obstruction_distance),
            inner=0.0,
            outer=scale * tel.obstruction_radius,
            c_res=N_PHI,
        )
    meshes["detector"] = pv.Disc(
        center=(scale * det.offset[0], scale * det.offset[1], -d),
        inner=0.0,
        outer=scale * det.radius,
        c_res=N_PHI,
    )
    meshes["axis"] = pv.Line((0, 0, -d), (0, 0, zmax))

    plotter.add_mesh(
        meshes["beam"],
        name="beam",
        scalars=label,
        cmap="viridis" if color_by == "overlap" else "plasma",
        clim=(0, 1) if color_by == "overlap" else None,
        log_scale=log,
        nan_color="lightgrey",
        scalar_bar_args=dict(BAR, title=label, position_x=0.02),
    )
    plotter.add_mesh(meshes["fov"], name="fov", color="lightskyblue", opacity=0.25)
    plotter.add_mesh(meshes["aperture"], name="aperture", color="silver", opacity=0.6)
    if "obstruction" in meshes:
        plotter.add_mesh(meshes["obstruction"], name="obstruction", color="black")
    plotter.add_mesh(meshes["detector"], name="detector", color="orange")
    plotter.add_mesh(meshes["axis"], name="axis", color="grey", line_width=1)
    if extra:
        i = int(np.searchsorted(zt, z_full))
        ring_r = scale * fov_r[i] * 1.05
        meshes["full_overlap"] = ring(
            pv, (scale * fov_c[i, 0], scale * fov_c[i, 1], z_full), ring_r
        )
        plotter.add_mesh(meshes["full_overlap"], name="full_overlap", color="red", line_width=4)
        plotter.add_point_labels(
            np.array([[scale * fov_c[i, 0] + ring_r, scale * fov_c[i, 1], z_full]]),
            [f"full overlap {z_full:.4g} m"],
            name="full_overlap_label",
            font_size=12,
            text_color="red",
            shape_opacity=0.4,
            always_visible=True,
        )
    bounds = np.array(plotter.bounds).reshape(3, 2)  # the physical scene, without the panels
    _planes(pv, plotter, meshes, system, planes, result, scale, width)
    true = bounds / np.array([[scale], [scale], [1.0]])
    plotter.show_bounds(
        bounds=bounds.ravel(),
        axes_ranges=true.ravel(),
        xtitle="x (m)",
        ytitle="y (m)",
        ztitle="range z (m)",
        location="outer",
        font_size=10,
    )
    note = (
        f"transverse x, y exaggerated x{scale:g} (range z to scale); beam: 1/e^2 envelope; blue: "
        "receiver field of view"
    )
    if planes:
        note += (
            "\npanels above the cone at each range: beam irradiance in the scattering plane (cyan: "
            "FOV), above it its image on the detector plane (cyan: detector)"
        )
    plotter.add_text(note, position="upper_left", font_size=9)
    plotter.view_vector(VIEW, viewup=(1.0, 0.0, 0.0))  # z across, x up, from the near side
    plotter.reset_camera()
    plotter.camera.zoom(ZOOM)
    (pv.set_new_attribute if hasattr(pv, "set_new_attribute") else setattr)(
        plotter, "lidar_meshes", meshes
    )
    return plotter


def save_scene(
    system: LidarSystem, filename, *, window_size=(1200, 800), format: str | None = None, **kwargs
) -> pathlib.Path:
    """Build :func:`scene` off-screen (keywords passed on), write it to ``filename`` and return its
    path.

    format : "png", a picture of ``window_size`` (width, height) pixels, or "html", a standalone
        interactive page (vtk.js: turn and zoom in any browser, no server, no network; needs ``pip
        install 'lidar-overlap[app]'``) with the meshes, colours, camera and the first colour bar,
        without the axes grid (vtk.js would label it in exaggerated coordinates) and 2-D text.
        Default: "html" for a name ending in .html or .htm, else "png"."""
    if "off_screen" in kwargs:
        raise ValueError("off_screen is invalid for save_scene: it always renders off-screen")
    path = pathlib.Path(filename)
    if format is None:
        format = "html" if path.suffix.lower() in (".html", ".htm") else "png"
    _checks.choice("format", format, FORMATS)
    if np.ndim(window_size) != 1 or len(window_size) != 2:
        raise ValueError(
            f"window_size = {window_size!r} is invalid: expected (width, height) in pixels"
        )
    size = tuple(_checks.count(f"window_size[{i}]", v, 16) for i, v in enumerate(window_size))
    if format == "html":
        require()  # the ImportError naming the extra comes before the scene is built
    plotter = scene(system, off_screen=True, **kwargs)
    try:
        plotter.window_size = size
        if format == "html":
            write_scene_html(plotter, path)
        else:
            plotter.screenshot(str(path))
    finally:
        plotter.close()
    return path
