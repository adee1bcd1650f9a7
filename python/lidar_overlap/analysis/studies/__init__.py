"""Studies on many curves: tolerance and turbulence studies, the telecover test and its fit, lidar
signals and their correction, parameter distributions.

Files: distributions.py, signals.py, telecover.py, telecover_fit.py, tolerance.py, turbulence.py.
"""

__all__ = ["distributions", "signals", "telecover", "telecover_fit", "tolerance", "turbulence"]
