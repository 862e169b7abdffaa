"""Renderings of the running-linkage studies (module for module as ``studies.running``)."""
