"""The diagnosis on real measurements: a banded rotary friction damper with backlash.

Data: ``../shared/realdata/friction-damper/compact`` (Coble, Huggins, Cao, Ricles, Downey
2022, *Dataset-Friction-Damper-with-Backlash*, ARTS-Lab, CC BY-SA 4.0; see its NOTES.md),
dataset-2 at 36 lb band tension: ten sine tests (0.25-2 Hz, 0.5-1.5 in) and four
earthquake-displacement profiles, 256 Hz, SI units. There is no pendulum (R_eff = inf) and no
normal load: the axial load is a nominal 100 kN (mu is friction force over 100 kN) and the
"slider diameter" a nominal 50 mm (it only scales the displacement bands and the heating).
Files in name order (the run order is not known).

Measured (dataset-2, all 14 tests, held out in 6 groups of tests): constant-model force
NRMSE 0.43 over all samples against a noise level of 0.006. The verdict names ``backlash``:
a play of 4.7 mm (the dead band the earlier residual report measured: about 4.9 mm) with a
pre-sliding stiffness of its own (u_y 2.2 mm), judged on every sample (z 10.7, 65 % of the
excess closed), followed by ``unexplained``: direction-dependent friction
(mu(+) / mu(-) = 0.74, the band brake's self-energising direction) closes about half of what
is left on the sliding phase but not enough to be named, and an oscillation of the rig
remains. On the sliding phase the held-out gap shrinks from 0.27 to 0.19 with the play.
About 15 s.
"""

from __future__ import annotations

import pytest

pytestmark = pytest.mark.shared


@pytest.fixture(scope="module")
def summary(friction_damper_diagnosis):
    """The diagnosis of the files (tests/regression/conftest.py) as JSON."""
    return friction_damper_diagnosis.to_json()


def test_the_play_is_named_with_its_width(summary):
    assert summary["verdict"][0] == "backlash", summary["verdict"]
    assert summary["verdict"][-1] == "unexplained"  # more is going on than a play
    backlash = next(e for e in summary["effects"] if e["name"] == "backlash")
    assert backlash["role"] == "selected"
    assert backlash["parameters"]["width"] == pytest.approx(4.9e-3, abs=1.0e-3)
    chosen = summary["chosen"]
    assert chosen["shrink"] > 0.2 and chosen["gap_after"] < chosen["gap_before"]
    assert summary["gap"]["value"] > 20.0 * summary["gap"]["noise"]


def test_friction_differs_with_direction(summary):
    """The loops reach about +14 kN and -20 kN: mu(+) / mu(-) well below one."""
    asymmetry = next(e for e in summary["effects"] if e["name"] == "asymmetry")
    assert 0.5 < asymmetry["parameters"]["direction_ratio"] < 0.8
    assert asymmetry["earns_keep"]
