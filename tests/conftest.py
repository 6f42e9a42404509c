"""Shared fixtures: the path of ``../shared`` (skipped with a reason when absent) and OpenSees
(``ops``, skipped with a reason when openseespy cannot be imported)."""

from __future__ import annotations

from pathlib import Path

import pytest

REPO_ROOT = Path(__file__).resolve().parents[1]
SHARED_DIR = REPO_ROOT.parent / "shared"


@pytest.fixture(scope="session")
def shared_dir() -> Path:
    """The project's ``../shared`` folder; tests that need it skip on a user's clone."""
    if not SHARED_DIR.is_dir():
        pytest.skip(f"../shared is absent ({SHARED_DIR}): this test needs the shared data")
    return SHARED_DIR


@pytest.fixture(scope="session")
def ops():
    """The openseespy module (:func:`structures.opensees.runtime.import_opensees`); tests that
    need it skip where it cannot be imported."""
    from structures.opensees.runtime import import_opensees

    try:
        return import_opensees()
    except ImportError as error:
        pytest.skip(f"openseespy cannot be imported: {error}")
