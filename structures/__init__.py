"""Structures layer: shear building, integrators, analyses and workflows."""
