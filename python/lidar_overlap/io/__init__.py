"""Files: scenario TOML files (a system, ranges and a method) and measured curves.

Files: overlap_curves.py, scenario.py, scenario_schema.py.
"""

__all__ = ["overlap_curves", "scenario", "scenario_schema"]
