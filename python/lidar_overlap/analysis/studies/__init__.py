"""Studies on many curves: tolerance and turbulence studies, the telecover test and its fit, lidar
signals and their correction, parameter distributions, series of curves of one instrument (one fit
per curve; the empirical per-gate temperature model).

Files: distributions.py, empirical_drift.py, series.py, signals.py, telecover.py,
telecover_fit.py, tolerance.py, turbulence.py.
"""

__all__ = [
    "distributions",
    "empirical_drift",
    "series",
    "signals",
    "telecover",
    "telecover_fit",
    "tolerance",
    "turbulence",
]
