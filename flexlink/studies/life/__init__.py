"""Stress over the crank turn and the fatigue life of every link."""
