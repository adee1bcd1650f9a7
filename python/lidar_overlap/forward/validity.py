"""Where the ray-tracing model stops describing the physics, and by how much.

RT (paper Appendix B) is paraxial geometric optics. Two things break it:
- diffraction at the receiver: a point scatterer images to an Airy pattern (in focus) or to a blur
  disc with Fresnel edges and a boundary wave focused on its centre (defocused), not to a uniform
  disc. For a centred in-focus image the lost fraction is 1 - EE(v) with v = π D r_d / (λ f); its
  large-v asymptote 2/(π v) = 2 λ f / (π² D r_d) is the RT model error at full overlap.
  :func:`rt_error_bound` estimates the error for any geometry (docs/auto_method.md derives it).
  Fourier optics (method "fo") includes it.
- the paraxial approximation: ray slopes of about R / z must stay small; the error grows like
  slope².
"""

from __future__ import annotations

import math

import numpy as np

from .._checks import warn

#: Model errors above this fraction of G trigger a RuntimeWarning from the RT path.
RT_MODEL_ERROR_LIMIT = 0.01


def rt_diffraction_error(system) -> float:
    """Fraction of a focused point image's power that diffraction moves beyond the detector edge, 2
    λ f / (π² D r_d): the geometric-optics error of RT where the overlap is full."""
    return 2.0 * system.diffraction_blur / (math.pi**2 * system.detector.radius)


def _arc_inside(p, c, rho):
    """Length (m) of the circle of radius c centred at distance p > 0 from the origin inside the
    disc of radius rho."""
    cos_half = (p * p + c * c - rho * rho) / np.maximum(2.0 * p * c, 1e-300)
    return 2.0 * c * np.arccos(np.minimum(np.maximum(cos_half, -1.0), 1.0))


def _edge_gap(p, c, rd):
    """Distance (m) between the circle of radius c centred at distance p and the detector edge (0 if
    they cross)."""
    return np.maximum(np.maximum(p - c - rd, np.abs(c - rd) - p), 0.0)


def rt_error_bound(system, ranges: np.ndarray) -> np.ndarray:
    """Estimate of |G_RT - G_exact| at each range (m) from the receiver geometry alone, before any
    safety factor.

    In the detector plane a scatterer at range z images to a blur disc of radius c = R m (m = |1 +
    d/z - d/f|, d = f + defocus) with an obstruction shadow of radius c_i; the beam spreads these
    over its image of 1/e² radius w_i = w(z) d / z, centred p0 from the detector centre. Diffraction
    changes the coupling by four mechanisms, each a fraction of the lit coupling G_lit = π r_d² x
    peak image irradiance (all lengths m): the Airy tail of a compact image beyond the detector
    edge; the Fresnel edges of the blur disc and of the shadow, near or through the detector, over
    the edge width l = sqrt(w_i² + λ d m / 4 + (λ d / D)²); and the boundary waves the pupil edges
    focus on each image centre (the Poisson spot in a shadow). docs/auto_method.md derives the terms
    and lists the scenes that calibrate them."""
    beam, tel, det = system.beam, system.telescope, system.detector
    z = np.asarray(ranges, dtype=float)
    lam, f, rd = beam.wavelength, tel.focal_length, det.radius
    d = system.image_distance
    radius = 0.5 * tel.diameter
    dz = d / z
    m = np.abs(dz + (1.0 - d / f))
    wi = np.asarray(beam.radius(z)) * dz
    outer = radius  # pupil radii as the FO path sees them: the NA cone, the projected obstruction
    if det.numerical_aperture:
        na = det.numerical_aperture
        outer = np.minimum(
            radius, na / math.sqrt(1.0 - na * na) / np.maximum(np.abs(1.0 / z - 1.0 / f), 1e-300)
        )
    obstructed = tel.obstruction_radius > 0.0
    inner = tel.obstruction_radius * z / (z - tel.obstruction_distance) if obstructed else 0.0
    lit = (
        outer > inner if obstructed and det.numerical_aperture else None
    )  # else nothing passes: G = 0
    width = np.maximum(outer - inner, 1e-300) if lit is not None else outer - inner
    lam_d = lam * d
    c_full = radius * m
    c = c_full if det.numerical_aperture is None else outer * m
    rd2, wi2, c2 = rd * rd, wi * wi, c * c
    s = lam_d / (2.0 * outer)  # diffraction blur lambda d / D
    fresnel2 = lam_d * m  # squared Fresnel width of the blur disc's edges
    edge2 = wi2 + 0.25 * fresnel2 + s * s
    edge = np.sqrt(edge2)
    # Peak irradiance of the image (Gaussian beam image (x) uniform blur disc) and the coupling it
    # gives.
    x = np.maximum(2.0 * (c_full * c_full) / wi2, 1e-300)
    g_lit = np.minimum((2.0 * rd2) * -np.expm1(-x) / (x * wi2), 1.0)
    axisymmetric = system.is_axisymmetric
    if axisymmetric:
        p0, g_up, g_out = 0.0, g_lit, np.abs(c - rd)
    else:
        p0 = np.hypot(
            (beam.offset[0] + beam.tilt[0] * z) * dz + det.offset[0],
            (beam.offset[1] + beam.tilt[1] * z) * dz + det.offset[1],
        )
        reach = (
            np.maximum(p0 - rd - c_full, 0.0) / wi
        )  # G itself: irradiance nearest the image centre
        g_up = np.minimum(
            g_lit,
            rd2
            * np.minimum(2.0 / wi2, 1.0 / np.maximum(c_full * c_full, 1e-300))
            * np.exp(-2.0 * reach * reach),
        )
        g_out = _edge_gap(p0, c, rd)
    # 1. Airy tail of a compact image (a Gaussian of radius sqrt(w_i² + c²)), covering the in-focus
    # model.
    xa2 = (wi2 + c2) * (1.0 / rd2)
    tail = (
        (lam_d / (math.pi**2 * rd))
        / width
        * g_up
        * (1.0 + 1.2 * xa2)
        / (1.0 + 0.48 * xa2 * np.sqrt(xa2))
    )
    # 2. Light moved across the detector edge by a Fresnel edge at distance g: ~ lambda d / (pi² rho
    # g).
    near = (lam_d / math.pi**2) / outer * g_lit / np.sqrt(g_out * g_out + edge2)
    # 3. An edge through (or within l of) the detector shifts by ~ Fresnel² / (2 pi² l) along its
    # length inside.
    cross_scale = g_lit * fresnel2 * edge / (2.0 * math.pi**2)
    if axisymmetric:  # concentric circles: all of the edge is as near as its gap
        cross = cross_scale * np.minimum(2.0 * c / rd2, 2.0 / edge) / (g_out * g_out + edge2)
    else:
        cross = (
            cross_scale
            * np.minimum(_arc_inside(p0, c, rd + g_out + 0.5 * edge) / (math.pi * rd2), 2.0 / edge)
            / (g_out * g_out + edge2)
        )
    bound = np.maximum(np.maximum(tail, near), cross)
    edges = 1.0 / outer
    if obstructed:
        ci = inner * m
        g_in = np.abs(ci - rd) if axisymmetric else _edge_gap(p0, ci, rd)
        length = 2.0 * math.pi * ci if axisymmetric else _arc_inside(p0, ci, rd + g_in + 0.5 * edge)
        bound = bound + cross_scale * np.minimum(length / (math.pi * rd2), 2.0 / edge) / (
            g_in * g_in + edge2
        )
        in_shadow = np.minimum((ci + p0) / rd, 1.0) ** 2
        bound = (
            bound + (lam_d / math.pi**2) / inner * g_lit / np.sqrt(g_in * g_in + edge2) * in_shadow
        )
        edges = edges + in_shadow / inner
    # 4. Boundary waves focused on the image centres, mean intensity I0 lambda d / (2 pi² rho y) at
    # distance y.
    spread = rd * np.minimum(1.0, c / wi) / np.sqrt(rd2 + 0.64 * wi2 + 4.0 * p0 * p0)
    inside = np.minimum(
        c / rd if axisymmetric else np.maximum(c - p0, 0.0) / rd, 1.0
    )  # detector in the discs
    bound = bound + g_lit * np.minimum(1.0, (lam_d / (math.pi**2 * rd)) * edges * spread) * inside
    return bound if lit is None else np.where(lit, bound, 0.0)


def rt_paraxial_error(system, ranges: np.ndarray) -> float:
    """Relative error of the paraxial slope tan u ≈ u at the steepest ray: (R / z_min)² / 3."""
    slope = 0.5 * system.telescope.diameter / float(np.min(ranges))
    return slope**2 / 3.0


def warn_if_rt_unconverged(raw, ranges: np.ndarray, tolerance: float, fix: str) -> None:
    """Warn when RT's adaptive quadrature (a core result with ``converged`` and ``error_estimate``)
    stopped short of ``tolerance`` at some ranges; ``fix`` says what to change."""
    converged = np.asarray(raw.converged, dtype=bool)
    if not converged.all():
        worst = float(np.max(np.asarray(raw.error_estimate)[~converged]))
        missed = int((~converged).sum())
        # A map or a batch holds several values per range: count them, not the ranges.
        where = (
            f"{missed} of {ranges.size} ranges"
            if converged.size == ranges.size
            else f"{missed} of {converged.size} values (grid points or systems x {ranges.size} "
            "ranges)"
        )
        warn(
            f"overlap: tolerance {tolerance:g} not reached at {where} (largest error estimate "
            f"{worst:.3g}); {fix}"
        )


def warn_if_rt_invalid(system, ranges: np.ndarray, diffraction: bool = True) -> None:
    """Warn when RT is used where its model error exceeds RT_MODEL_ERROR_LIMIT (diffraction=False:
    only the paraxial check, for callers that have bounded the diffraction error themselves)."""
    airy_tail = rt_diffraction_error(system)
    if diffraction and airy_tail > RT_MODEL_ERROR_LIMIT:
        warn(
            "ray tracing outside its validity: the detector radius is "
            f"{system.detector.radius / system.airy_radius:.3g} Airy radii, and diffraction moves "
            f"about {airy_tail:.2%} of the image power across its edge; geometric optics ignores "
            "this. Use Fourier optics (method='fo') for this receiver."
        )
    outside = rt_ranges_outside(system, ranges)
    if outside:
        warn(outside)


def rt_ranges_outside(system, ranges: np.ndarray) -> str:
    """Why ``ranges`` (m) lie outside ray tracing's validity (its paraxial error above
    RT_MODEL_ERROR_LIMIT at the nearest), or "" when they do not."""
    paraxial = rt_paraxial_error(system, ranges)
    if not paraxial > RT_MODEL_ERROR_LIMIT:
        return ""
    return (
        f"ray tracing outside its validity: at {float(np.min(ranges)):.3g} m the aperture is "
        f"seen under slopes whose paraxial error is about {paraxial:.2%}; start the ranges "
        "farther away."
    )


#: Fourier optics warns where a second stop's pupil disc moves by more than this fraction of its
#: radius across the beam (docs/receiver_stop.md).
FO_STOP_MOTION_LIMIT = 0.05


def fo_stop_motion(system, ranges: np.ndarray) -> np.ndarray:
    """How far a second stop's pupil disc moves across the beam at each range (m), as a fraction of
    its radius: (|c| + 2 w) s / (z r_s), c the beam centre and w its 1/e² radius; 0 where the stop
    cuts no ray of an on-axis point (its pupil disc r_s / |1 + s/z - s/f| holds the aperture). The
    Fourier-optics paths neglect this motion."""
    det, beam = system.detector, system.beam
    z = np.asarray(ranges, dtype=float)
    if det.stop_radius is None:
        return np.zeros_like(z)
    s, f = det.stop_distance, system.telescope.focal_length
    cuts = det.stop_radius < 0.5 * system.telescope.diameter * np.abs(1.0 + s / z - s / f)
    centre = np.hypot(beam.offset[0] + beam.tilt[0] * z, beam.offset[1] + beam.tilt[1] * z)
    motion = (centre + 2.0 * np.asarray(beam.radius(z))) * s / (z * det.stop_radius)
    return np.where(cuts, motion, 0.0)


def warn_if_fo_stop_moves(system, ranges: np.ndarray) -> None:
    """RuntimeWarning where :func:`fo_stop_motion` exceeds FO_STOP_MOTION_LIMIT."""
    motion = fo_stop_motion(system, ranges)
    if motion.size and motion.max() > FO_STOP_MOTION_LIMIT:
        i = int(np.argmax(motion))
        warn(
            f"overlap(fo): the second stop's pupil disc moves by {motion[i]:.2g} of its radius "
            f"across the beam at {ranges[i]:.4g} m, which Fourier optics neglects (exact on the "
            "axis); method='rt' traces it exactly"
        )
