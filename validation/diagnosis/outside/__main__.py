"""Write the outside panel: ``python -m validation.diagnosis.outside FOLDER``.

Options: ``--seed 2026``, ``--half tune|test``, ``--no-opensees``
(:func:`validation.diagnosis.outside.write.main`).
"""

from validation.diagnosis.outside.write import main

if __name__ == "__main__":
    raise SystemExit(main())
