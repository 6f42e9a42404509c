"""Two horizontal components of one recording (and an optional vertical): the pair and its
readers (:mod:`~groundmotions.pairs.pair`: :class:`GroundMotionPair`, :func:`read_pair`,
:func:`read_pair_manifest`, imported here) and its RotD50 / RotD100 spectra
(:mod:`~groundmotions.pairs.rotd`). A suite of pairs is scaled as one of records is
(`groundmotions.scale_suite`, on RotD100); synthetic pairs are drawn by
`groundmotions.synthetic.synthetic_pair`."""

from groundmotions.pairs.pair import (
    MANIFEST_COLUMNS,
    GroundMotionPair,
    read_pair,
    read_pair_manifest,
)

__all__ = ["MANIFEST_COLUMNS", "GroundMotionPair", "read_pair", "read_pair_manifest"]
