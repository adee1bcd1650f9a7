"""Optics of sampled fields: free-space propagation, beam fields, phase screens, point and
detector-plane images."""
