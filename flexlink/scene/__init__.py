"""Scene files: the declared schema, loading (with base files and overrides) and the one
scene contract every command uses."""
