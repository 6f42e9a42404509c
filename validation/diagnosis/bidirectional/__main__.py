"""``python -m validation.diagnosis.bidirectional [FOLDER] [--checks]``: write the bidirectional
panel to FOLDER, or run the truth's self-checks (:func:`~.write.main`)."""

from validation.diagnosis.bidirectional.write import main

if __name__ == "__main__":
    raise SystemExit(main())
