"""Files: scenario TOML files (a system, ranges and a method), measured curves and series of them.

Files: overlap_curves.py, overlap_series.py, scenario.py, scenario_schema.py.
"""

__all__ = ["overlap_curves", "overlap_series", "scenario", "scenario_schema"]
