"""Pictures: matplotlib figures of results, PyVista 3-D scenes and the interactive digital twin in
the browser (:mod:`.app`); optional dependencies, imported when used."""
