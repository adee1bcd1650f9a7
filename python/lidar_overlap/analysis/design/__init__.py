"""Designing and aligning a lidar: alignment maps, objectives, design optimisation, the smallest
field of view, automatic alignment and realignment.

Files: alignment.py, autoalign.py, objectives.py, optimize.py, realign.py, search.py,
smallest_fov.py.
"""

__all__ = ["alignment", "autoalign", "objectives", "optimize", "realign", "search", "smallest_fov"]
