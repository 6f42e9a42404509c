"""dcfpb: time-history analysis of buildings on double concave friction pendulum bearings.

The distribution has four top-level packages:

- ``groundmotions``: records, readers, spectra (imports nothing of ours but the
  foundation modules below);
- ``isolator``: friction laws, frictional heating, the DCFPB element, the virtual test machine;
- ``structures``: shear building, integrators, analyses and workflows;
- ``dcfpb``: the command line (``dcfpb.cli``) and two foundation modules that import nothing:
  ``dcfpb.units`` (physical constants and unit factors) and ``dcfpb.validation``
  (the one error template for bad parameters).
"""

__version__ = "0.1.0"
