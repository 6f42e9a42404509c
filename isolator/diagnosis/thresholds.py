"""Every threshold that decides a verdict, in one place.

The values in use are read from ``thresholds.json`` beside this module, which
``validation/diagnosis/tune.py`` writes from the *tune* half of the tuning panel only, with
the panel, the half and the score; without the file the defaults below apply.

Scales: ``*_z`` are in standard errors of the summed block differences of the held-out
weighted residual (a block is a half cycle of one test); ``*_explained`` and ``name_min`` are
shares of the weighted excess above noise that a model leaves; ``practical_*`` are RMS force
changes over the RMS force (an effect smaller than that is not worth naming, whatever its
statistical significance); ``none_margin`` is the held-out standardised score above one that
still counts as noise; ``transition_score`` is the mean squared residual over the noise
variance inside the transition windows from which they hold a gap, when its excess energy,
as an RMS over the whole test over the RMS force, is at least ``transition_practical``.
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, fields, replace
from pathlib import Path

THRESHOLDS_FILE = Path(__file__).with_name("thresholds.json")


@dataclass(frozen=True)
class Thresholds:
    """The decision thresholds (see the module docstring for the scales)."""

    z_min: float = 2.5  # an effect on mu or the force earns its keep ...
    explained_min: float = 0.25  # ... closing this share of the excess left ...
    practical_gain: float = 0.01  # ... and at least this RMS force over the RMS force
    name_min: float = 0.6  # the selected effects must close this share to be named
    none_margin: float = 0.15  # a held-out score within 1 + this is noise
    practical_none: float = 0.015  # an excess RMS below this share of the RMS force is none
    practical_remain: float = 0.012  # an excess left above this is a real gap remaining
    second_z: float = 2.5  # a second effect, against the first in its flexible form
    second_explained: float = 0.3
    kinematic_z: float = 3.0  # a play or a lag, judged on every sample
    kinematic_explained: float = 0.3
    kinematic_practical: float = 0.02
    lag_min_samples: float = 2.5  # a lag is named beyond this many samples in all
    backlash_min: float = 1.0e-3  # [m] a play is named from this width on
    flexible_margin: float = 0.1  # the flexible form is reported when it closes this much more
    transition_score: float = 4.0  # inside the transition windows: a residual RMS twice the
    transition_practical: float = 0.03  # noise's, and this excess RMS over the whole test

    @classmethod
    def load(cls, path: str | Path = THRESHOLDS_FILE) -> Thresholds:
        """The thresholds of ``path`` (the defaults when the file is absent)."""
        path = Path(path)
        if not path.is_file():
            return cls()
        data = json.loads(path.read_text())
        known = {f.name for f in fields(cls)}
        values = {k: float(v) for k, v in data.get("thresholds", {}).items() if k in known}
        return replace(cls(), **values)

    def to_dict(self) -> dict[str, float]:
        """The thresholds by name."""
        return asdict(self)


def current() -> Thresholds:
    """The thresholds in use (``thresholds.json``, else the defaults)."""
    return Thresholds.load()
