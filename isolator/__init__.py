"""Isolator layer: friction laws, frictional heating, the DCFPB element, bearing tests."""
