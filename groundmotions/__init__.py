"""Ground motions: records, readers, spectra, scaling.

Imports nothing of ours but ``dcfpb.units`` and ``dcfpb.validation``.
"""
