"""The command line ``lidar-overlap`` (run, demo, fit, telecover)."""

from .commands import main

__all__ = ["main"]
