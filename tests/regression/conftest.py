"""Fixtures shared by the regression tests: the diagnosis of the real friction-damper data."""

from __future__ import annotations

import pytest

NOMINAL_AXIAL_LOAD = 1.0e5  # [N] a friction damper has none; mu is then force / 100 kN
NOMINAL_DIAMETER = 0.05  # [m]


@pytest.fixture(scope="session")
def friction_damper_diagnosis(shared_dir):
    """The diagnosis (constant baseline) of the compact friction-damper dataset-2 files of
    ``../shared/realdata/friction-damper/compact``, run once for the tests that read it."""
    from isolator.diagnosis import diagnose, load_campaign

    folder = shared_dir / "realdata" / "friction-damper" / "compact"
    files = sorted(folder.glob("dataset-2_*.csv.gz"))
    if len(files) < 3:
        pytest.skip(f"the compact friction-damper files are absent from {folder}")
    campaign = load_campaign(files, effective_radius=float("inf"),
                             slider_diameter=NOMINAL_DIAMETER, axial_load=NOMINAL_AXIAL_LOAD)
    return diagnose(campaign, "constant")
