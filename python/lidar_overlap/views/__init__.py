"""Views of a lidar: the interactive digital twin in the browser (:mod:`.app`) and its pieces."""
