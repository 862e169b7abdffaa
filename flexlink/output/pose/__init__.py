"""Renderings of the pose studies (module for module as ``studies.pose``)."""
