"""Shared by the amplification tests: the backscatter amplification Fourier optics measures on both
paths through the core, with its paired standard error."""

import math

import numpy as np

import lidar_overlap as lo
from lidar_overlap import _core


def fo_amplification(system, z, cn2, draws, fields, seed):
    """Mean G over mean uncorrelated G of ``system`` at range z (m) through ``lo.Turbulence(cn2)``
    on both paths (10 screens), on the least grid the core accepts: (amplification, its standard
    error from the paired rows by the delta method, mean G)."""
    air = lo.Turbulence(cn2)._native
    options = _core.TurbulenceOptions(
        paths="both", realizations=draws, screens=10, receiver_fields=fields, seed=seed
    )
    options.beam_grid = _core.turbulent_grid(system._native, [z], air, options).min_beam_grid
    raw = _core.overlap_fo_turbulent(system._native, [z], air, options)
    g, u = raw.overlap[:, 0], raw.uncorrelated[:, 0]
    ratio = g.mean() / u.mean()
    error = np.std(g - ratio * u, ddof=1) / math.sqrt(g.size) / u.mean()
    return float(ratio), float(error), float(g.mean())
