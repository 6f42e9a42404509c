"""numba's disk cache of our compiled functions is stale once any module they import changes
(isolator.compiled.freshness): shown on a two-module package in a folder of its own. With
numba 0.68's own locators alone, the second run below loads the stale constant (1, measured
when this test was written); with ours it compiles the new one."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from isolator.compiled.freshness import dependency_closure, dependency_stamp

REPO = Path(__file__).resolve().parents[2]
FRESHNESS = REPO / "isolator" / "compiled" / "freshness.py"

RUN = textwrap.dedent("""
    import importlib.util, sys
    root, install = sys.argv[1], sys.argv[2] == "1"
    sys.path.insert(0, root)  # this isolator/ shadows ours: load the locator by its file
    if install:
        spec = importlib.util.spec_from_file_location("freshness", sys.argv[3])
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        assert module.install()
    from isolator.user import value
    print(value())
""")


def test_the_engine_depends_on_its_layouts_and_callees_not_on_the_rest():
    closure = {p.relative_to(REPO).as_posix()
               for p in dependency_closure(str(REPO / "structures/compiled/integrator.py"))}
    assert {"structures/compiled/workspace.py", "structures/compiled/lapack.py",
            "isolator/compiled/element.py", "isolator/compiled/plate.py",
            "isolator/compiled/kernels.py",
            "isolator/compiled/layout.py", "isolator/heating.py"} <= closure
    assert not closure & {"structures/analysis.py", "structures/results.py",
                          "structures/__init__.py", "isolator/__init__.py"}


def test_the_engine_is_stamped_with_its_closure():
    numba = pytest.importorskip("numba")
    del numba
    from structures.compiled import integrator

    if not hasattr(integrator.integrate, "_cache"):
        pytest.skip("numba disabled (DCFPB_DISABLE_NUMBA)")
    locator = integrator.integrate._cache._impl._locator
    assert type(locator).__name__ == "DependencyStampLocator"
    assert locator.get_source_stamp() == dependency_stamp(integrator.__file__)


def _value(root: Path, cache: Path, install: bool) -> int:
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache))
    env.pop("DCFPB_DISABLE_NUMBA", None)
    out = subprocess.run([sys.executable, "-c", RUN, str(root), str(int(install)),
                          str(FRESHNESS)], env=env, capture_output=True, text=True, check=True)
    return int(out.stdout.split()[-1])


def test_an_edited_dependency_is_compiled_afresh(tmp_path):
    pytest.importorskip("numba")
    package = tmp_path / "src" / "isolator"
    package.mkdir(parents=True)
    (package / "__init__.py").write_text("")
    (package / "dep.py").write_text("CONST = 1\n")
    (package / "user.py").write_text(
        "import numba\nfrom isolator.dep import CONST\n\n\n@numba.njit(cache=True)\n"
        "def value():\n    return CONST\n")
    cache = tmp_path / "cache"
    assert _value(package.parent, cache, True) == 1  # compiled and cached
    (package / "dep.py").write_text("CONST = 2\n")  # user.py itself unchanged
    # numba alone keys the cache on user.py and loads the stale 1; ours sees dep.py change
    assert _value(package.parent, cache, True) == 2
