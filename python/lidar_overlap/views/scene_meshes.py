"""The meshes of :func:`lidar_overlap.scene`, made from arrays: tubes of circles along z (the beam's
envelope, the field of view), rings (outlines) and textured planes (the panels), every circle
sampled at :data:`N_PHI` points. Coordinates are the scene's displayed ones: range z to scale, x
and y times its exaggeration (``tube`` multiplies them itself, by ``scale``). PyVista is passed in
by the caller, which imports it only when a scene is built."""

from __future__ import annotations

import numpy as np

N_PHI = 72  # samples around every circle
PLANE_SCALARS = "panels:\nrelative\nirradiance"


def tube(pv, z, center, radius, scale):
    """Surface made of circles of ``radius`` (m) about ``center`` ((nz, 2), m) at each z; x, y
    scaled."""
    phi = np.linspace(0.0, 2.0 * np.pi, N_PHI, endpoint=False)
    x = scale * (center[:, :1] + radius[:, None] * np.cos(phi))
    y = scale * (center[:, 1:] + radius[:, None] * np.sin(phi))
    points = np.stack([x, y, np.broadcast_to(z[:, None], x.shape)], axis=-1).reshape(-1, 3)
    i = (np.arange(z.size - 1) * N_PHI)[:, None]
    j = np.arange(N_PHI)[None, :]
    j1 = (j + 1) % N_PHI
    quads = np.stack(np.broadcast_arrays(4, i + j, i + j1, i + N_PHI + j1, i + N_PHI + j), axis=-1)
    return pv.PolyData(points, faces=quads.reshape(-1))


def ring(pv, center, radius):
    phi = np.linspace(0.0, 2.0 * np.pi, N_PHI, endpoint=False)
    points = np.asarray(center, float) + radius * np.stack(
        [np.cos(phi), np.sin(phi), 0 * phi], axis=-1
    )
    return pv.PolyData(points, lines=np.r_[N_PHI + 1, np.arange(N_PHI), 0])


def textured_plane(pv, values, origin, spacing):
    """A textured plane (normal z) from a (ny, nx) array; ``origin`` is the (x, y, z) of values[0,
    0]."""
    mesh = pv.ImageData(
        dimensions=(values.shape[1], values.shape[0], 1),
        spacing=(spacing, spacing, 1.0),
        origin=origin,
    )
    mesh.point_data[PLANE_SCALARS] = values.ravel()
    return mesh
