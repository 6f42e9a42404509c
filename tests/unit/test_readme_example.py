"""The README's Python example of a building run, executed as written."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

README = Path(__file__).resolve().parents[2] / "README.md"


def _building_example() -> str:
    blocks = re.findall(r"```python\n(.*?)```", README.read_text(encoding="utf-8"), re.S)
    chosen = [block for block in blocks if "structures.run(" in block]
    assert len(chosen) == 1, "the README has one Python example of a building run"
    return chosen[0]


def test_the_readme_building_example_runs(monkeypatch, capsys):
    monkeypatch.chdir(README.parent)
    namespace: dict = {}
    exec(compile(_building_example(), "README.md", "exec"), namespace)
    printed = float(capsys.readouterr().out.split()[0])
    assert 0.05 < printed < 0.5  # [m] the isolator's peak under El Centro
    result = namespace["result"]
    assert result.attrs["success"]
    assert result.attrs["compile_time"] >= 0.0 and result.attrs["wall_time"] > 0.0
    assert result.attrs["dt"] == pytest.approx(0.005)  # the default step: 0.02 s / 4
    assert np.isfinite(result["bearing_displacement"]).all()
    assert len(_building_example().strip().splitlines()) <= 12
