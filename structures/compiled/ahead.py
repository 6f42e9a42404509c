"""Compile the engine in a second process while the first one gets on with the rest.

Compiling on a cold numba cache takes most of a first run's time and is pure Python work, which
a thread cannot overlap with the caller's work; a process can, on a second core.
:func:`compile_ahead` starts ``python -m structures.compiled.ahead``, which compiles the
engine's loop and its entry from Python, the Newton matrix's pieces and the step's factors, and
writes them to numba's disk cache (:func:`structures.compiled.engine.warm_up_late`), while the
caller compiles the window's moves, the friction, the bearings' trials and commit and the loop's
start (:meth:`CompileAhead.help`), does its own work and waits (:meth:`CompileAhead.wait`)
before its first engine call, which then loads the rest. The two shares do not wait for each
other: the engine calls what the other share compiles as code of its own
(:mod:`isolator.compiled.linking`), bound in the second process to placeholders it never runs.
The caller's stage file (0 started, 1 the window's moves, 2 its share done) tells the second
process that it is helped; without one (no helping caller, or it failed) the second process
compiles the caller's share too. Nothing is started when the cache holds the engine, without
numba (or with ``DCFPB_DISABLE_NUMBA=1``), or with ``DCFPB_COMPILE_AHEAD=0``; if the second
process fails, the caller compiles itself."""

from __future__ import annotations

import contextlib
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from types import TracebackType

__all__ = ["CompileAhead", "compile_ahead", "engine_in_cache"]

WAIT_LIMIT = 600.0
"""Longest wait for the second process [s]; past it, it is stopped and the caller compiles."""
STAGE_VARIABLE = "DCFPB_AHEAD_STAGE"  # the stage file's path, for the second process

_PACKAGE_ROOT = Path(__file__).resolve().parents[2]
_ENGINE_INDEX = "integrator.integrate-*.nbi"  # numba's index file of the engine


def engine_in_cache() -> bool:
    """Whether numba's disk cache seems to hold the engine: its index file under
    ``NUMBA_CACHE_DIR`` when set, else in ``__pycache__`` or the user-wide numba cache. A stale
    entry counts as present (the run then compiles as it would have anyway)."""
    chosen = os.environ.get("NUMBA_CACHE_DIR", "")
    if chosen:
        return any(Path(chosen).glob(f"*/{_ENGINE_INDEX}"))
    if any((_PACKAGE_ROOT / "structures" / "compiled" / "__pycache__").glob(_ENGINE_INDEX)):
        return True
    user_wide = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "numba"
    return user_wide.is_dir() and any(user_wide.glob(f"*/{_ENGINE_INDEX}"))


class CompileAhead:
    """A handle on the compiling process (or on none); leaving its ``with`` block stops it."""

    def __init__(self, process: subprocess.Popen | None, stage: Path | None = None) -> None:
        self.process = process
        self.stage = stage  # the stage file (:func:`write_stage`), in a folder of its own
        self.waited = 0.0  # time spent in :meth:`wait` [s]

    @property
    def started(self) -> bool:
        """Whether a second process was started."""
        return self.process is not None

    def help(self) -> float:
        """Compile the caller's share of the engine here
        (:func:`structures.compiled.engine.warm_up_early`); the time spent [s] (0 when no
        process runs). Call it right after :func:`compile_ahead`, before this process's own
        work."""
        if self.process is None or self.process.poll() is not None:
            return 0.0
        stage = self.stage
        if stage is None:
            from structures.compiled.engine import warm_up_early

            return warm_up_early()
        write_stage(stage, 0)  # at once: the second process now knows it will be helped
        try:
            from structures.compiled.engine import warm_up_early

            spent = warm_up_early(lambda: write_stage(stage, 1))
            write_stage(stage, 2)
        except BaseException:
            stage.unlink(missing_ok=True)  # the second process stops waiting and compiles
            raise
        return spent

    def wait(self) -> bool:
        """Block until the engine is compiled; whether the process succeeded (True at once
        when none was started)."""
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
        """Stop the process if it is still running; remove the stage file."""
        if self.process is not None and self.process.poll() is None:
            self.process.kill()
            self.process.wait()
        if self.stage is not None:
            self.stage.unlink(missing_ok=True)
            with contextlib.suppress(OSError):
                self.stage.parent.rmdir()

    def __enter__(self) -> CompileAhead:
        return self

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        self.stop()


def compile_ahead() -> CompileAhead:
    """Start compiling the engine in a second process when that will help; the handle
    (``started`` False when nothing needed compiling or numba is off)."""
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
        stage = Path(tempfile.mkdtemp(prefix="dcfpb-ahead-")) / "stage"
    except OSError:
        stage = None
    if stage is not None:
        env[STAGE_VARIABLE] = str(stage)
    try:
        process = subprocess.Popen([sys.executable, "-m", "structures.compiled.ahead"], env=env,
                                   stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                   stderr=subprocess.DEVNULL)
    except OSError:
        if stage is not None:
            stage.parent.rmdir()
        return CompileAhead(None)
    return CompileAhead(process, stage)


def write_stage(stage: Path, value: int) -> None:
    """Write how far the caller's share has come (0 started, 1 the window's moves, 2 all of
    it: in the cache) to the file ``stage``, replacing it whole."""
    partial = stage.with_name(stage.name + ".partial")
    partial.write_text(str(value))
    os.replace(partial, stage)


if __name__ == "__main__":  # the second process
    import gc

    gc.set_threshold(50_000, 20, 20)  # fewer collections while numba compiles

    from structures.compiled.engine import warm_up_early, warm_up_late

    STAGE = Path(os.environ[STAGE_VARIABLE]) if os.environ.get(STAGE_VARIABLE) else None
    # the loop while the first process compiles the window's moves, the friction, the trials
    warm_up_late()
    if STAGE is None or not STAGE.exists():  # nobody helps (or it failed): the rest too
        warm_up_early()
    # the cache is written: skip the teardown the first process would otherwise wait for
    os._exit(0)
