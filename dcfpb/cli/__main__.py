"""``python -m dcfpb.cli``: the same as the ``dcfpb`` console script."""

import sys

from dcfpb.cli import main

sys.exit(main())
