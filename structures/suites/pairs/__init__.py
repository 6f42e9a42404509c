"""Suites of pairs of records on a building in plan: the runs (:mod:`~structures.suites.pairs.runs`:
one pair, scale, friction model and modifier, its id and its row of plan peaks) and the suite
(:mod:`~structures.suites.pairs.suite`: the manifest, the RotD100 scaling, the Dask run through
the machinery of the single-record suites)."""
