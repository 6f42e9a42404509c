"""dcfpb: time-history analysis of buildings on double concave friction pendulum bearings.

The distribution has four top-level packages:

- ``groundmotions``: records, readers, spectra (imports nothing of ours but the
  foundation modules below);
- ``isolator``: friction laws, frictional heating, the DCFPB element, the virtual test machine;
- ``structures``: shear building, integrators, analyses and workflows;
- ``dcfpb``: the command line (``dcfpb.cli``) and its figures (``dcfpb.plotting``) at the top,
  and at the bottom ``dcfpb.common``, what every layer builds on and which imports nothing of
  ours: errors, units, parameter checks and lazy imports.
"""

__version__ = "0.1.0"
