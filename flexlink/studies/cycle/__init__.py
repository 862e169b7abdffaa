"""Studies over one crank revolution: rigid motion, the modal map, modes tracked by shape and the Campbell bands."""
