"""What benchmarks/bench_aberrations.py measures lo's point image of an aberrated pupil against: the
scene (the Table 1 telescope, the detector in the image plane, the image and pupil sampling, the
Noll terms), closed forms independent of every code compared (Zernike wavefronts, the exact Strehl
ratio, a code's wavefront error against them) and the peer libraries poppy, hcipy and LightPipes,
each imported only when its point image is asked for. SI units."""

from __future__ import annotations

import math

import numpy as np

WAVELENGTH, D, F, DEFOCUS = 355e-9, 0.15, 1.0, 1e-3
R, DIST = D / 2, F + DEFOCUS  # pupil radius; lens-detector distance d
N, ACROSS = 512, 256  # image samples per side; pupil samples across D
SPACING = (
    WAVELENGTH * DIST / (2 * D)
)  # m on the detector: lambda d / (n delta) with delta = D / 256
C = N // 2  # index of the axis (every code here puts 0 there)
PSF_TERMS = {6: 0.05e-6, 8: 0.03e-6, 11: 0.05e-6}  # Noll j: m RMS


# ---- closed forms (independent of every code compared) ----


def noll_nm(j):
    n = int(math.sqrt(2 * j - 1) + 0.5) - 1
    m = (
        2 * ((2 * j + 1 - n * (n + 1)) // 4)
        if n % 2 == 0
        else 2 * ((2 * (j + 1) - n * (n + 1)) // 4) - 1
    )
    return n, (m if j % 2 == 0 else -m)  # Noll: even j cos, odd j sin


def wavefront(terms, x, y):
    """W (m) of Noll Zernike terms (unit RMS) at normalised pupil points."""
    rho, theta = np.hypot(x, y), np.arctan2(y, x)
    w = np.zeros_like(rho)
    for j, c in terms.items():
        n, m = noll_nm(j)
        k = (n - abs(m)) // 2
        radial = sum(
            (-1) ** s
            * math.factorial(n - s)
            / (math.factorial(s) * math.factorial(n - k - s) * math.factorial(k - s))
            * rho ** (n - 2 * s)
            for s in range(k + 1)
        )
        ang = 1.0 if m == 0 else math.sqrt(2) * (np.cos(m * theta) if m > 0 else np.sin(-m * theta))
        w += c * math.sqrt(n + 1) * radial * ang
    return w


def exact_strehl(terms, n_rho=64, n_theta=128):
    """|<exp(2 pi i W / lambda)>|^2 over the disc: Gauss-Legendre in rho^2, trapezoid in theta."""
    u, wt = np.polynomial.legendre.leggauss(n_rho)
    rho, theta = np.sqrt(0.5 * (u + 1)), 2 * np.pi * np.arange(n_theta) / n_theta
    rr, tt = np.meshgrid(rho, theta, indexing="ij")
    w = wavefront(terms, rr * np.cos(tt), rr * np.sin(tt))
    return abs(np.sum(0.5 * wt[:, None] / n_theta * np.exp(2j * np.pi * w / WAVELENGTH))) ** 2


def convention_error(w_peer, x, y, terms):
    """Largest |W_peer - W| (m) on the peer's samples with centre inside the pupil (x, y in m)."""
    inside = np.hypot(x, y) < R
    return float(np.max(np.abs(w_peer - wavefront(terms, x / R, y / R))[inside]))


# ---- the point image by each peer: (ideal PSF, aberrated PSF builder, W check) ----


def poppy_psf(hard_edge):
    import astropy.units as u
    import poppy

    # poppy's OPD has the opposite sign (+Z2 images at -x, its documented convention): it gets -c.
    coeffs = np.zeros(max(PSF_TERMS))
    for j, c in PSF_TERMS.items():
        coeffs[j - 1] = -c
    pixelscale = math.degrees(WAVELENGTH / (2 * D)) * 3600 * u.arcsec / u.pix  # = SPACING / d

    def build(c):
        osys = poppy.OpticalSystem(npix=ACROSS, pupil_diameter=D * u.m, verbose=False)
        if not hard_edge:
            osys.add_pupil(
                poppy.CircularAperture(radius=R * u.m)
            )  # gray (area-weighted) edge pixels
        zwfe = osys.add_pupil(
            poppy.ZernikeWFE(coefficients=c * u.m, radius=R * u.m, aperture_stop=hard_edge)
        )
        osys.add_detector(
            pixelscale=pixelscale, fov_pixels=N + 1, oversample=1
        )  # odd: a pixel on the axis
        return osys, zwfe

    def psf(osys):
        return osys.calc_psf(wavelength=WAVELENGTH)[0].data[:N, :N]  # rows/cols -256 .. 255 like lo

    ideal, _ = build(np.zeros_like(coeffs))
    osys, zwfe = build(coeffs)
    wave = osys.input_wavefront(wavelength=WAVELENGTH * u.m)
    y, x = wave.coordinates()
    return psf(ideal), lambda: psf(osys), convention_error(-zwfe.get_opd(wave), x, y, PSF_TERMS)


def hcipy_psf():
    import hcipy

    pupil_grid = hcipy.make_pupil_grid(ACROSS, D)
    focal_grid = hcipy.make_uniform_grid([N, N], N * SPACING, has_center=True)
    aperture = hcipy.evaluate_supersampled(
        hcipy.make_circular_aperture(D), pupil_grid, 8
    )  # as lo's 8 x 8 edges
    # radial_cutoff=False: edge pixels whose centre is outside R keep the polynomial's value, as in
    # lo.
    basis = hcipy.make_zernike_basis(max(PSF_TERMS), D, pupil_grid, 1, radial_cutoff=False)
    prop = hcipy.FraunhoferPropagator(pupil_grid, focal_grid, focal_length=DIST)
    coeffs = np.array([PSF_TERMS.get(j, 0.0) for j in range(1, max(PSF_TERMS) + 1)])

    def psf(c):
        w = basis.linear_combination(c)
        return prop(
            hcipy.Wavefront(aperture * np.exp(2j * np.pi * w / WAVELENGTH), WAVELENGTH)
        ).power.shaped

    w = np.asarray(basis.linear_combination(coeffs))
    return (
        psf(0 * coeffs),
        lambda: psf(coeffs),
        convention_error(w, pupil_grid.x, pupil_grid.y, PSF_TERMS),
    )


def lightpipes_psf():
    import LightPipes as lp

    # LightPipes' Zernike multiplies by exp(-2 pi i A Z / lambda) with theta = atan2(y, x) + pi,
    # which flips odd-m terms: A = -c for even m, +c for odd m gives lo's exp(+2 pi i W / lambda).
    def pupil(terms):
        f = lp.Begin(N * D / ACROSS, WAVELENGTH, N)
        for j, c in terms.items():
            n, m = lp.noll_to_zern(j)
            f = lp.Zernike(f, n, m, R, c if m % 2 else -c, norm=True, units="opd")
        return f

    def psf(terms):
        f = lp.PipFFT(
            lp.CircAperture(pupil(terms), R)
        )  # hard edge; output spacing lambda d / (N delta)
        return np.abs(f.field) ** 2

    f = pupil(PSF_TERMS)
    y, x = f.mgrid_cartesian
    phase = np.angle(
        f.field * np.exp(-2j * np.pi * wavefront(PSF_TERMS, x / R, y / R) / WAVELENGTH)
    )
    inside = np.hypot(x, y) < R
    return (
        psf({}),
        lambda: psf(PSF_TERMS),
        float(np.max(np.abs(phase[inside]))) * WAVELENGTH / (2 * np.pi),
    )


PEERS = {
    "poppy": lambda: poppy_psf(False),
    "poppy (hard edge)": lambda: poppy_psf(True),
    "hcipy": hcipy_psf,
    "LightPipes": lightpipes_psf,
}
