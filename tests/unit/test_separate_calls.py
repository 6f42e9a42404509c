"""Calls from compiled code to code compiled apart (isolator.compiled.linking), as the engine
makes them: the caller compiles without the callee, its machine code holds only the call, a
process binds the callee before it compiles or loads the caller, and the numbers are those of
an ordinary call."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from isolator.compiled.kernels import COMPILED

REPO = Path(__file__).resolve().parents[2]

pytestmark = pytest.mark.skipif(not COMPILED, reason="numba is disabled: nothing is linked")

MODULE = '''
import math
from isolator.compiled.kernels import jit_inner, jit_unmanaged
from isolator.compiled.linking import separately


@jit_unmanaged
def norm(values, scale):
    total = 0.0
    for value in values:
        total += value * value
    return math.sqrt(total) * scale, values.shape[0]


NORM = separately(norm, lambda types: types.Tuple((types.float64, types.int64)))


@jit_inner
def inner(values, out):
    size, count = NORM(values, 2.0)
    out[0], out[1] = size, count


INNER = separately(inner, lambda types: types.none)


@jit_unmanaged
def outer(values, out):
    INNER(values, out)
'''

RUN = '''
import json, sys
import numpy as np
from numba import typeof, types
from numba.core import event
sys.path.insert(0, sys.argv[1])
import separate_module as m
from isolator.compiled.linking import bind, bind_placeholder

compiled = []
class Listener(event.Listener):
    def on_start(self, ev):
        pass
    def on_end(self, ev):
        compiled.append(ev.data["dispatcher"].py_func.__name__)
event.register("numba:compile", Listener())
values, out = np.array([3.0, 4.0]), np.zeros(2)
arguments = (typeof(values), typeof(out))
if sys.argv[2] == "compile-only":  # the caller alone, against a placeholder
    bind_placeholder(m.NORM, (typeof(values), types.float64))
    m.inner.compile(arguments)
    print(json.dumps({"compiled": compiled}))
else:
    bind(m.NORM, (typeof(values), types.float64))
    bind(m.INNER, arguments)
    m.outer(values, out)
    print(json.dumps({"compiled": compiled, "out": out.tolist()}))
'''


def _run(folder: Path, cache: Path, mode: str) -> dict:
    import json

    env = {**os.environ, "NUMBA_CACHE_DIR": str(cache),
           "PYTHONPATH": os.pathsep.join((str(REPO), str(folder)))}
    env.pop("DCFPB_DISABLE_NUMBA", None)
    out = subprocess.run([sys.executable, "-c", RUN, str(folder), mode], env=env, check=True,
                         capture_output=True, text=True, timeout=600).stdout
    return json.loads(out.strip().splitlines()[-1])


def test_a_caller_compiles_without_its_callee_and_runs_it_once_bound(tmp_path):
    (tmp_path / "separate_module.py").write_text(textwrap.dedent(MODULE))
    cache = tmp_path / "cache"
    first = _run(tmp_path, cache, "compile-only")
    assert first["compiled"] == ["inner"]  # not the callee: it is not typed for the caller
    second = _run(tmp_path, cache, "run")
    assert second["out"] == [10.0, 2.0]  # 2 * |(3, 4)|, 2 values: the callee's own numbers
    assert "inner" not in second["compiled"]  # loaded from the cache the first process left
    assert set(second["compiled"]) == {"norm", "outer"}


def test_from_python_the_stand_in_calls_the_function():
    from isolator.compiled.kernels import jit_unmanaged
    from isolator.compiled.linking import separately

    @jit_unmanaged
    def twice(x):
        return 2.0 * x

    call = separately(twice, lambda types: types.float64)
    assert call(1.5) == 3.0


def test_the_symbol_names_the_function_and_its_types():
    from numba import types

    from isolator.compiled.linking import symbol_name

    def f(x):
        return x

    one = symbol_name(f, (types.float64,), types.float64)
    assert one.startswith(f"dcfpb.{__name__}.") and "f." in one
    assert one == symbol_name(f, (types.float64,), types.float64)
    assert one != symbol_name(f, (types.int64,), types.float64)
    assert one != symbol_name(f, (types.float64,), types.int64)


def test_binding_a_function_that_returns_another_type_is_refused():
    from numba import types

    from isolator.compiled.kernels import jit_unmanaged
    from isolator.compiled.linking import bind, separately

    @jit_unmanaged
    def half(x):
        return 0.5 * x

    call = separately(half, lambda t: t.int64)
    with pytest.raises(TypeError, match="returns float64"):
        bind(call, (types.float64,))


LOOP = """
import json
from structures.compiled import engine
from structures.compiled import integrator as compiled
engine.compile_loop()  # for the cache only: what it calls apart are placeholders here
result = compiled.integrate.overloads[compiled.integrate.signatures[0]]
print(json.dumps([library.name for library in result.library._linking_libraries]))
"""


def test_the_engine_loop_links_none_of_the_functions_it_calls_apart(tmp_path):
    """The loop compiles before the trials, the commit and the rest that it calls apart, and
    its machine code holds calls to them, not their code (which LLVM would optimise and emit
    again inside it)."""
    import json

    from structures.compiled import engine

    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path), "PYTHONPATH": str(REPO)}
    env.pop("DCFPB_DISABLE_NUMBA", None)
    out = subprocess.run([sys.executable, "-c", LOOP], env=env, check=True, capture_output=True,
                         text=True, timeout=600).stdout
    linked = set(json.loads(out.strip().splitlines()[-1]))
    apart = {call.function.py_func.__name__ for call in engine._separate_calls()}
    assert "set_trials" in apart and "commit_trials" in apart
    assert linked and not linked & apart
