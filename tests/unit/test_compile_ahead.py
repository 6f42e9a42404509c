"""Compiling the engine in a second process (structures.compiled.ahead): when, and to what end.

The point of the second process is the disk cache it leaves: a run that follows must find
every function it calls compiled already, and compute the very same numbers.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from isolator.compiled.kernels import COMPILED
from structures.compiled import ahead

REPO = Path(__file__).resolve().parents[2]

RUN_AFTER = """
import json, sys
from numba.core import event
compiled = []
class Listener(event.Listener):
    def on_start(self, ev):
        pass
    def on_end(self, ev):
        compiled.append(getattr(getattr(ev.data.get("dispatcher"), "py_func", None),
                                "__qualname__", "?"))
event.register("numba:compile", Listener())
import numpy as np
from groundmotions.bundled import load_bundled
from structures.analysis import run
from structures.config import load_config
config = load_config(sys.argv[1])
motion = load_bundled("elcentro").truncated(4.0)
arrays = {}
for model in ("precise", "simplified", "constant"):
    result = run(config.building, config.bearing(model), motion, config.integrator,
                 n_bearings=config.n_bearings, dt=config.dt)
    arrays[model] = result["absolute_acceleration"].values
    arrays[model + "_temperature"] = result["temperature"].values
np.savez(sys.argv[2], **arrays)
print(json.dumps(compiled))
"""


def test_nothing_starts_when_switched_off_or_without_numba(monkeypatch):
    monkeypatch.setenv("DCFPB_COMPILE_AHEAD", "0")
    with ahead.compile_ahead() as handle:
        assert not handle.started and handle.help() == 0.0 and handle.wait()
    monkeypatch.delenv("DCFPB_COMPILE_AHEAD")
    monkeypatch.setenv("DCFPB_DISABLE_NUMBA", "1")
    with ahead.compile_ahead() as handle:
        assert not handle.started


def test_the_cache_is_looked_for_under_numba_cache_dir(tmp_path, monkeypatch):
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    assert not ahead.engine_in_cache()
    folder = tmp_path / "structures_0123abcd"
    folder.mkdir()
    (folder / "integrator.integrate-230.py311.nbi").write_bytes(b"")
    assert ahead.engine_in_cache()
    monkeypatch.setenv("DCFPB_COMPILE_AHEAD", "1")
    with ahead.compile_ahead() as handle:
        assert not handle.started  # present: nothing to do


@pytest.mark.slow
@pytest.mark.skipif(not COMPILED, reason="numba is disabled: nothing is compiled")
def test_a_run_after_the_second_process_compiles_nothing_and_computes_the_same(tmp_path):
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "cache"), "PYTHONPATH": str(REPO),
           "DCFPB_COMPILE_AHEAD": "1"}
    env.pop("DCFPB_DISABLE_NUMBA", None)
    start = ("from structures.compiled.ahead import compile_ahead\n"
             "handle = compile_ahead()\n"
             "assert handle.started, 'nothing was started on an empty cache'\n"
             "assert handle.help() > 0.0, 'this process compiled nothing meanwhile'\n"
             "assert handle.wait(), 'the second process failed'\n")
    subprocess.run([sys.executable, "-c", start], env=env, check=True, timeout=900)
    out = subprocess.run([sys.executable, "-c", RUN_AFTER, str(REPO / "examples" /
                          "five_storey.toml"), str(tmp_path / "after.npz")], env=env,
                         check=True, timeout=900, capture_output=True, text=True).stdout
    assert json.loads(out.strip().splitlines()[-1]) == []  # everything came from the cache

    from groundmotions.bundled import load_bundled
    from structures.analysis import run
    from structures.config import load_config

    config = load_config(REPO / "examples" / "five_storey.toml")
    motion = load_bundled("elcentro").truncated(4.0)
    after = np.load(tmp_path / "after.npz")
    for model in ("precise", "simplified", "constant"):
        result = run(config.building, config.bearing(model), motion, config.integrator,
                     n_bearings=config.n_bearings, dt=config.dt)
        assert np.array_equal(after[model], result["absolute_acceleration"].values), model
        assert np.array_equal(after[model + "_temperature"], result["temperature"].values)
