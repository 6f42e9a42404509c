"""Write the tuning panel: ``python -m validation.diagnosis.tuning FOLDER``.

Options: ``--seed 2026``, ``--half tune|test``
(:func:`validation.diagnosis.tuning.write.main`).
"""

from validation.diagnosis.tuning.write import main

if __name__ == "__main__":
    raise SystemExit(main())
