"""What every figure of the command line shares: pyplot on the Agg backend, PNG options, fixed
margins and the colours of the friction models. matplotlib is imported on first use
(:func:`pyplot`), so the library runs without it."""

from __future__ import annotations

import os
import sys
from collections.abc import Callable, Sequence
from pathlib import Path


def pyplot():
    """matplotlib's pyplot on the Agg backend, imported on first use (it is slow to import)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


PNG_OPTIONS = {"pil_kwargs": {"compress_level": 1}}
"""A fast zlib level for the PNGs: quicker to write than the default, files a little larger."""


def save_figure(fig, path: str | os.PathLike, **options) -> Path:
    """Save ``fig`` to ``path`` atomically (:func:`dcfpb.common.files.atomic_output`): a failed
    or interrupted write leaves the file there before whole. The format is the suffix of
    ``path`` (none: PNG); ``options`` go to ``savefig`` (``pil_kwargs`` only for a PNG)."""
    from dcfpb.common.files import atomic_output

    path = Path(path)
    kind = path.suffix.lower().lstrip(".") or "png"
    if kind != "png":
        options.pop("pil_kwargs", None)
    with atomic_output(path) as temporary:
        fig.savefig(temporary, format=kind, **options)
    return path


def finish(fig, path: str | os.PathLike, *, title: str = "", dpi: int = 120,
           **options) -> Path:
    """Save ``fig`` to ``path`` (:func:`save_figure` at ``dpi`` with ``options``) under
    ``title`` (when given: 12 pt on a figure wider than 7 in, else 9, wrapped) and close it."""
    if title:
        fig.suptitle(title, fontsize=12 if fig.get_figwidth() > 7.0 else 9, wrap=True)
    path = save_figure(fig, path, dpi=dpi, **options)
    pyplot().close(fig)
    return path


def margins(fig, *, left: float = 0.85, right: float = 0.2, bottom: float = 0.6,
             top: float = 0.85, **spacing: float) -> None:
    """Fixed margins in inches (quicker to draw than a constrained layout)."""
    width, height = fig.get_size_inches()
    fig.subplots_adjust(left=left / width, right=1.0 - right / width, bottom=bottom / height,
                        top=1.0 - top / height, **spacing)


MODEL_COLOURS = {"precise": "tab:red", "simplified": "tab:orange", "constant": "tab:blue",
                 "ptv-no-heating": "tab:green", "opensees": "black"}


def colour(name: str, index: int) -> str:
    """The colour of a run's label: its friction model's, else matplotlib's ``index``-th."""
    return MODEL_COLOURS.get(name, f"C{index}")


def corner_bearing(result) -> int:
    """The bearing position of a run that moved farthest (largest resultant displacement): in
    plan the corner bearing that torsion loads most; in one direction the one group."""
    import numpy as np

    reach = np.sqrt((result["bearing_displacement"].values ** 2).sum(axis=-1))
    return int(np.argmax(reach.max(axis=0)))


def draw(figures: Sequence[tuple[Path, Callable[[], object], float]], *,
         processes: int = 1) -> list[Path]:
    """Draw figures and return their files, in the order given.

    ``figures`` are (file, function, weight): the function draws the figure and saves it to the
    file; the weight is its share of the drawing time (any unit). With ``processes=2`` (and
    ``os.fork``, so not on Windows) they are split in two shares of about equal weight, one drawn
    by a forked copy of this process on a second core (matplotlib's drawing and PNG compression
    hold the GIL, so a thread would not overlap them). The files are those drawn one after the
    other. Should the copy fail, this process draws its share again, so that the error is raised
    here.
    """
    if processes < 2 or len(figures) < 2 or not hasattr(os, "fork"):
        for _, function, _ in figures:
            function()
        return [path for path, _, _ in figures]
    shares: tuple[list[int], list[int]] = ([], [])
    load = [0.0, 0.0]
    for index in sorted(range(len(figures)), key=lambda i: -figures[i][2]):
        side = 0 if load[0] <= load[1] else 1
        shares[side].append(index)
        load[side] += figures[index][2]
    mine, theirs = shares
    sys.stdout.flush()  # nothing buffered is copied into the child (it would print it twice)
    sys.stderr.flush()
    pid = os.fork()
    if pid == 0:  # the copy: draw its share and leave at once, without the parent's cleanup
        status = 1
        try:
            for index in sorted(theirs):
                figures[index][1]()
            status = 0
        finally:
            os._exit(status)
    try:
        for index in sorted(mine):
            figures[index][1]()
    finally:
        _, status = os.waitpid(pid, 0)
    if status != 0:
        for index in sorted(theirs):
            figures[index][1]()
    return [path for path, _, _ in figures]
