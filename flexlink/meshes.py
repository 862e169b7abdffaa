"""Default meshes [elements per link] where none is named and the mesh rule (``analysis.mesh``,
which commands use) is not run. Measured on the Table II cases against 128 elements per link,
largest relative error over the first four frequencies: 16 elements 1.6e-5, 8 elements 2.6e-4.
"""

# library calls that name no mesh, the sensitivity study of assumed inputs and the stability
# checks: their spreads and tolerances are far above 1.6e-5
DEFAULT_ELEMENTS = 16

# every evaluation of a calibration fit (thousands of models): 2.6e-4 is far below the
# per-cent residuals the fits minimise
FIT_ELEMENTS = 8
