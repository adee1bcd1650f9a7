"""What benchmarks/bench_fo.py measures lo.propagate against: the scene (a TEM00 beam on a square
window), the accuracy of a returned irradiance against Eq. (D1), the transforms of the same size
(the floors) and the peer libraries, each skipped with the reason when it does not import. SI
units."""

from __future__ import annotations

import os
import time
import warnings

import numpy as np

import lidar_overlap as lo
from lidar_overlap import _core

WAVELENGTH = 355e-9  # m
WAIST = 5e-3  # m, w0
HALF_WINDOW = 5.0  # window +- HALF_WINDOW w0
THREADS = int(
    os.environ.get("OMP_NUM_THREADS", os.cpu_count())
)  # the team lo uses, and the floor's
FLOOR_NAMES = {1: "one", 2: "pair"}


def d1_radius(z):
    """Eq. (D1) in vacuum."""
    return WAIST * np.sqrt(1.0 + (WAVELENGTH * z / (np.pi * WAIST**2)) ** 2)


def second_moment_radius(intensity, x, y):
    """sqrt(2 (var x + var y)) of an irradiance on the grid x (columns) by y (rows), about its
    centroid: the 1/e^2 radius of a TEM00 beam."""
    i = np.asarray(intensity, dtype=float)
    total = i.sum()
    px, py = i.sum(axis=0), i.sum(axis=1)
    cx, cy = (px * x).sum() / total, (py * y).sum() / total
    return float(np.sqrt(2.0 * (((x - cx) ** 2 * px).sum() + ((y - cy) ** 2 * py).sum()) / total))


def d1_error(intensity, x, y, z):
    return abs(1.0 - d1_radius(z) / second_moment_radius(intensity, x, y))


def pyfftw_floors(n):
    """pyFFTW's FFTW, FFTW_MEASURE for THREADS threads, out of place on aligned arrays: {"one":
    timed forward, "pair": timed forward and backward}, each returning its own seconds; {} with
    the reason printed once where pyFFTW does not import."""
    try:
        import pyfftw
    except ImportError as e:
        if not getattr(pyfftw_floors, "reported", False):
            print(f"floor pyFFTW: not installed ({e}); floors without it")
            pyfftw_floors.reported = True
        return {}
    a = pyfftw.empty_aligned((n, n), dtype="complex128")
    b = pyfftw.empty_aligned((n, n), dtype="complex128")
    flags = ("FFTW_MEASURE",)
    forward = pyfftw.FFTW(a, b, axes=(0, 1), direction="FFTW_FORWARD", flags=flags, threads=THREADS)
    backward = pyfftw.FFTW(
        b, a, axes=(0, 1), direction="FFTW_BACKWARD", flags=flags, threads=THREADS
    )
    a[:] = 1.0 + 0.5j  # planning by timing overwrote the arrays

    def one():
        t0 = time.perf_counter()
        forward.execute()
        return time.perf_counter() - t0

    def pair():
        t0 = time.perf_counter()
        forward.execute()
        backward.execute()
        t = time.perf_counter() - t0
        a[:] = 1.0 + 0.5j  # bounded values (FFTW may reuse an out-of-place input as scratch)
        return t

    return {"one": one, "pair": pair}


def floor_rounds(n):
    """The transforms lo is timed against, each returning its own time (s) of one call:
    {(source, "one" | "pair"): callable}, source = "own" (the library's deterministic transforms),
    "fftw" (the system FFTW, measured plan, THREADS threads), "pyfftw" (where installed)."""
    rounds = {}
    for k, name in FLOOR_NAMES.items():
        rounds[("own", name)] = lambda k=k: _core._fft_pair_seconds(n, 1, True, k)
        rounds[("fftw", name)] = lambda k=k: _core._fft_pair_seconds(n, 1, False, k, THREADS)
    for name, fn in pyfftw_floors(n).items():
        rounds[("pyfftw", name)] = fn
    return rounds


# ---------------------------------------------------------------------------------------------
# Peers. Each factory returns (version, variants); a variant is (peer, routine, settings, prepare,
# methods it is run for), and prepare(n, distance) -> (call, setup or None, intensity_and_grid),
# where intensity_and_grid(result) -> (irradiance, x of the columns, y of the rows).
# ---------------------------------------------------------------------------------------------
def lightpipes_variants():
    import LightPipes as lp
    from LightPipes import config as lp_config

    fields = {}

    def field(n):
        if n not in fields:
            fields.clear()  # one grid at a time
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                fields[n] = lp.GaussBeam(lp.Begin(2 * HALF_WINDOW * WAIST, WAVELENGTH, n), WAIST)
        return fields[n]

    def make(routine):
        def prepare(n, distance):
            f = field(n)
            return (
                (lambda: routine(f, distance)),
                None,
                (lambda g: (lp.Intensity(g, 0), g.xvalues, g.yvalues)),
            )

        return prepare

    settings = f"numpy FFT (pyFFTW {'on' if lp_config._USE_PYFFTW else 'off'})"
    return lp.__version__, [
        ("LightPipes", "Forvard", settings, make(lp.Forvard), ("angular_spectrum", "fresnel")),
        ("LightPipes", "Fresnel", settings + ", 2N grid", make(lp.Fresnel), ("fresnel",)),
    ]


def hcipy_variants():
    import hcipy

    def make(cls, oversampling):
        def prepare(n, distance):
            grid = hcipy.make_pupil_grid(n, 2 * HALF_WINDOW * WAIST)
            amplitude = np.exp(-(grid.x**2 + grid.y**2) / WAIST**2).astype(complex)
            wf = hcipy.Wavefront(hcipy.Field(amplitude, grid), WAVELENGTH)
            prop = cls(grid, distance, num_oversampling=oversampling)
            x, y = grid.x.reshape(n, n)[0], grid.y.reshape(n, n)[:, 0]
            return (
                (lambda: prop.forward(wf)),
                None,
                (lambda out: (np.asarray(out.intensity.shaped), x, y)),
            )

        return prepare

    try:  # hcipy tries mkl_fft first, then scipy.fft (all cores from 256^2 samples on)
        import mkl_fft  # noqa: F401

        backend = "mkl_fft"
    except ImportError:
        backend = "scipy.fft"
    variants = []
    for method, cls in (
        ("angular_spectrum", hcipy.AngularSpectrumPropagator),
        ("fresnel", hcipy.FresnelPropagator),
    ):
        for oversampling in (2, 1):
            variants.append(
                (
                    "hcipy",
                    f"{cls.__name__}",
                    f"num_oversampling={oversampling}"
                    + (" (default)" if oversampling == 2 else "")
                    + f", 2N zero padding, {backend}",
                    make(cls, oversampling),
                    (method,),
                )
            )
    return hcipy.__version__, variants


def poppy_variants():
    import astropy.units as u
    import poppy
    from poppy import accel_math

    def prepare(n, distance):
        values = lo.Field.gaussian(WAVELENGTH, WAIST, n, 2 * HALF_WINDOW * WAIST / n).values

        def setup():
            # Window 2 * HALF_WINDOW * w0 = npix * oversample pixels of spacing 2 beam_radius /
            # npix.
            wf = poppy.FresnelWavefront(
                beam_radius=HALF_WINDOW * WAIST / 2 * u.m,
                wavelength=WAVELENGTH * u.m,
                npix=n // 2,
                oversample=2,
            )
            wf.wavefront = values.copy()
            return wf

        def call(wf):
            wf.propagate_fresnel(distance * u.m)
            return wf

        def intensity_and_grid(wf):
            yy, xx = wf.coordinates()
            return wf.intensity, xx[0], yy[:, 0]

        return call, setup, intensity_and_grid

    backends = (
        ", ".join(
            k[5:].lower()
            for k in ("_USE_FFTW", "_USE_MKL", "_USE_NUMEXPR", "_USE_CUPY")
            if getattr(accel_math, k, False)
        )
        or "numpy"
    )
    return poppy.__version__, [
        (
            "poppy",
            "FresnelWavefront.propagate_fresnel",
            f"oversample=2, npix=N/2; accelerators: {backends}",
            prepare,
            ("angular_spectrum", "fresnel"),
        )
    ]


PEERS = {"LightPipes": lightpipes_variants, "hcipy": hcipy_variants, "poppy": poppy_variants}


def load_peers():
    status, variants = {}, []
    for name, factory in PEERS.items():
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                version, v = factory()
        except ImportError as e:
            status[name] = {"installed": False, "version": None, "reason": f"not installed ({e})"}
            continue
        except Exception as e:  # imports but cannot be set up: record why
            status[name] = {
                "installed": True,
                "version": None,
                "reason": f"{type(e).__name__}: {e}",
            }
            continue
        status[name] = {"installed": True, "version": version, "reason": None}
        variants += v
    return status, variants
