"""Compile the engine in a second process while the first one gets on with the rest.

On a cold numba cache the compiled engine (:mod:`structures.compiled.integrator`) takes most of a
first run's time to compile, while the run itself needs a fraction of a second. The compilation is
pure Python work in numba, which a thread cannot overlap with the caller's own Python work
(imports, reading the record, the fixed-base reference, spectra); a process can, on a second
core. :func:`compile_ahead` starts ``python -m structures.compiled.ahead``, which compiles the
engine's callees but the bearings' trials (:func:`structures.compiled.engine.warm_up_late`),
then the engine exactly as the first run would (:func:`structures.compiled.engine.warm_up`),
and writes numba's disk cache. Meanwhile the caller compiles the bearings' trials
(:meth:`CompileAhead.help`, :func:`structures.compiled.engine.warm_up_early`), which that
process then finds in the cache, does its own work, and waits
(:meth:`CompileAhead.wait`) before its first engine call, which then loads the machine code
from the cache. What is computed does
not change: the cached code is the code the caller would have compiled itself.

Nothing is started when the cache already holds the engine, without numba (or with
``DCFPB_DISABLE_NUMBA=1``), or with ``DCFPB_COMPILE_AHEAD=0``. If the second process fails,
the caller compiles as it always did.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path
from types import TracebackType

__all__ = ["CompileAhead", "compile_ahead", "engine_in_cache"]

WAIT_LIMIT = 600.0
"""Longest wait for the second process [s]; past it, it is stopped and the caller compiles."""

_PACKAGE_ROOT = Path(__file__).resolve().parents[2]
_ENGINE_INDEX = "integrator.integrate-*.nbi"  # numba's index file of the engine


def engine_in_cache() -> bool:
    """Whether numba's disk cache seems to hold the engine already.

    Looks for the engine's index file where numba keeps it: under ``NUMBA_CACHE_DIR`` when
    that is set, else beside the source (``__pycache__``) or in the user-wide numba cache.
    A stale entry (the source changed since) counts as present: the run then compiles as it
    would have anyway.
    """
    chosen = os.environ.get("NUMBA_CACHE_DIR", "")
    if chosen:
        return any(Path(chosen).glob(f"*/{_ENGINE_INDEX}"))
    if any((_PACKAGE_ROOT / "structures" / "compiled" / "__pycache__").glob(_ENGINE_INDEX)):
        return True
    user_wide = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "numba"
    return user_wide.is_dir() and any(user_wide.glob(f"*/{_ENGINE_INDEX}"))


class CompileAhead:
    """A handle on the compiling process (or on none); a context manager.

    Leaving the ``with`` block stops the process if it is still running.
    """

    def __init__(self, process: subprocess.Popen | None) -> None:
        self.process = process
        self.waited = 0.0  # time spent in :meth:`wait` [s]

    @property
    def started(self) -> bool:
        """Whether a second process was started."""
        return self.process is not None

    def help(self) -> float:
        """Compile here, meanwhile, the bearings' trials
        (:func:`structures.compiled.engine.warm_up_early`), which the second process needs
        only once it has compiled the rest of the engine's callees, so that it finds them in
        the cache; return the time spent [s] (0 when no process was started).

        Call it right after :func:`compile_ahead`, before this process's own work: both then
        compile on their own core, and the second one sooner reaches the end.
        """
        if self.process is None or self.process.poll() is not None:
            return 0.0
        from structures.compiled.engine import warm_up_early

        return warm_up_early()

    def wait(self) -> bool:
        """Block until the engine is compiled; return whether the process succeeded.

        Returns True at once when no process was started.
        """
        if self.process is None:
            return True
        start = time.perf_counter()
        try:
            status = self.process.wait(timeout=WAIT_LIMIT)
        except subprocess.TimeoutExpired:
            self.stop()
            status = -1
        self.waited += time.perf_counter() - start
        return status == 0

    def stop(self) -> None:
        """Stop the process if it is still running."""
        if self.process is not None and self.process.poll() is None:
            self.process.kill()
            self.process.wait()

    def __enter__(self) -> CompileAhead:
        return self

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        self.stop()


def compile_ahead() -> CompileAhead:
    """Start compiling the engine in a second process when that will help.

    Returns
    -------
    CompileAhead
        The handle; ``started`` is False when nothing needed compiling or numba is off.
    """
    if os.environ.get("DCFPB_COMPILE_AHEAD", "1") == "0":
        return CompileAhead(None)
    if os.environ.get("DCFPB_DISABLE_NUMBA", "") not in ("", "0") or engine_in_cache():
        return CompileAhead(None)
    try:
        import importlib.util

        if importlib.util.find_spec("numba") is None:
            return CompileAhead(None)
    except (ImportError, ValueError):
        return CompileAhead(None)
    path = os.environ.get("PYTHONPATH", "")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(p for p in (str(_PACKAGE_ROOT), path) if p)}
    try:
        process = subprocess.Popen([sys.executable, "-m", "structures.compiled.ahead"], env=env,
                                   stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                   stderr=subprocess.DEVNULL)
    except OSError:
        return CompileAhead(None)
    return CompileAhead(process)


if __name__ == "__main__":  # the second process
    import gc

    gc.set_threshold(50_000, 20, 20)  # numba's compilation: 1.5 -> 0.4 s of collections

    from structures.compiled.engine import warm_up, warm_up_late

    warm_up_late()  # while the first process compiles the bearings' trials
    warm_up()
    # numba's cache is written and its files closed: leave without the interpreter's teardown
    # (its last collection and module cleanup: 0.1 to 0.5 s the first process would wait for)
    os._exit(0)
