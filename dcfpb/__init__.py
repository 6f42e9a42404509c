"""dcfpb: time-history analysis of buildings on double concave friction pendulum bearings.

The distribution has four packages: ``groundmotions`` (records, readers, spectra), ``isolator``
(friction laws, frictional heating, the DCFPB element, the virtual test machine),
``structures`` (shear building, integrators, analyses, workflows) and ``dcfpb``: the command
line (``dcfpb.cli``) and its figures (``dcfpb.plotting``) on top, and ``dcfpb.common`` (errors,
units, parameter checks, lazy imports) at the bottom, which imports nothing of the project.
"""

__version__ = "0.1.0"
