"""Renderings of the calibration studies (module for module as ``studies.calibration.fit``)."""
