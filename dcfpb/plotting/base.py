"""What every figure of the command line shares: pyplot on the Agg backend, PNG options,
fixed margins and the colours of the friction models.

matplotlib is imported on first use (:func:`pyplot`), so the library runs without it.
"""

from __future__ import annotations


def pyplot():
    """matplotlib's pyplot on the Agg backend (imported on first use: about 1 s)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


PNG_OPTIONS = {"pil_kwargs": {"compress_level": 1}}
"""A fast zlib level for the PNGs: about 0.03 s less a figure than level 6, files ~25 % larger."""


def margins(fig, *, left: float = 0.85, right: float = 0.2, bottom: float = 0.6,
             top: float = 0.85, **spacing: float) -> None:
    """Fixed margins in inches (a constrained layout costs about 0.25 s per figure)."""
    width, height = fig.get_size_inches()
    fig.subplots_adjust(left=left / width, right=1.0 - right / width, bottom=bottom / height,
                        top=1.0 - top / height, **spacing)


MODEL_COLOURS = {"precise": "tab:red", "simplified": "tab:orange", "constant": "tab:blue",
                 "ptv-no-heating": "tab:green", "opensees": "black"}


def colour(name: str, index: int) -> str:
    return MODEL_COLOURS.get(name, f"C{index}")
