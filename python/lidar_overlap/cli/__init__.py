"""The command line ``lidar-overlap`` (run, demo, fit, telecover).

Files: __main__.py, commands.py, fit.py, output.py, run.py, telecover.py.
"""

from .commands import main

__all__ = ["main"]
