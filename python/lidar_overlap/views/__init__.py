"""Pictures: matplotlib figures of results and PyVista 3-D scenes (optional dependencies, imported
when used)."""
