"""Two horizontal components of one recording (and an optional vertical): the pair and its
readers (:mod:`~groundmotions.pairs.pair`: :class:`GroundMotionPair`, :func:`read_pair`,
:func:`read_pair_manifest`, imported here), the RotD50 / RotD100 spectra
(:mod:`~groundmotions.pairs.rotd`), the ASCE 7-16 scaling of a suite of pairs on RotD100
(:mod:`~groundmotions.pairs.scaling`) and synthetic pairs
(:mod:`~groundmotions.pairs.synthetic`)."""

from groundmotions.pairs.pair import (
    MANIFEST_COLUMNS,
    GroundMotionPair,
    read_pair,
    read_pair_manifest,
)

__all__ = ["MANIFEST_COLUMNS", "GroundMotionPair", "read_pair", "read_pair_manifest"]
