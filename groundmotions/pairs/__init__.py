"""Two horizontal components of one recording and an optional vertical: `GroundMotionPair`
and its readers (`groundmotions.pairs.pair`), its RotD50 / RotD100 spectra
(`groundmotions.pairs.rotd`). A suite of pairs is scaled on RotD100 by
`groundmotions.scale_suite`; synthetic pairs come from `groundmotions.synthetic.synthetic_pair`."""

from groundmotions.pairs.pair import (
    MANIFEST_COLUMNS,
    GroundMotionPair,
    read_pair,
    read_pair_manifest,
)

__all__ = ["MANIFEST_COLUMNS", "GroundMotionPair", "read_pair", "read_pair_manifest"]
