"""Rendering of ``studies.kinetostatics``: text, CSV, JSON and plots."""
