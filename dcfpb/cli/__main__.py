"""``python -m dcfpb.cli``: the same as the ``dcfpb`` console script."""

from dcfpb.cli import console

console()
