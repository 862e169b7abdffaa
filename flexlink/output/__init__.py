"""Outputs: tables and CSV (``report``), VTK files, pictures and plots, the calibration report."""
