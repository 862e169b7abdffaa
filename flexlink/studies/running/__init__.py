"""Studies of the running linkage at crank speed: modes at speed, driving torque, Floquet stability, the steady elastic response and the speed-dependent Campbell diagram."""
