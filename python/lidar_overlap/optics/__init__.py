"""Optics of sampled fields: free-space propagation, beam fields, phase screens, point and
detector-plane images.

Files: beam_fields.py, detector_image.py, imaging.py, phase_screen.py, propagation.py.
"""

__all__ = ["beam_fields", "detector_image", "imaging", "phase_screen", "propagation"]
