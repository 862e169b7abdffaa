"""Renderings of the verification studies (module for module as ``studies.verification``)."""
