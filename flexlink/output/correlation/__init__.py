"""Renderings of the correlation studies (module for module as ``studies.correlation``)."""
