"""dcfpb.plotting.base.draw: figures drawn in two processes give the same files, in order, and
an error in the forked share is raised in the caller."""

from __future__ import annotations

import os

import pytest

from dcfpb.plotting.base import draw


def _figures(folder, fail=None):
    def writer(name):
        def write():
            if name == fail:
                raise RuntimeError(f"cannot draw {name}")
            (folder / name).write_text(f"{name} drawn by {os.getpid()}")
        return write

    names = ["a.png", "b.png", "c.png", "d.png", "e.png"]
    return [(folder / n, writer(n), w) for n, w in zip(names, (6, 3.5, 3, 2, 1), strict=True)]


@pytest.mark.parametrize("processes", [1, 2])
def test_every_file_is_written_and_returned_in_order(tmp_path, processes):
    figures = _figures(tmp_path)
    assert draw(figures, processes=processes) == [path for path, _, _ in figures]
    drawers = {path.read_text().split()[-1] for path, _, _ in figures}
    assert len(drawers) == (2 if processes == 2 and hasattr(os, "fork") else 1)
    assert str(os.getpid()) in drawers


@pytest.mark.skipif(not hasattr(os, "fork"), reason="no fork on this platform")
def test_an_error_in_the_forked_share_is_raised_here(tmp_path):
    figures = _figures(tmp_path, fail="b.png")  # with a.png (6) here, b.png goes to the copy
    with pytest.raises(RuntimeError, match=r"cannot draw b\.png"):
        draw(figures, processes=2)
    assert (tmp_path / "a.png").exists()
