"""Renderings of the cycle studies (module for module as ``studies.cycle.modal_map``)."""
