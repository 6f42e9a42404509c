"""Validation of the sim-to-real diagnosis (:mod:`isolator.diagnosis`) on panels of known truth.

- :mod:`validation.diagnosis.tuning`: the tuning panel (42 cases, its own numpy-only truth
  model); the thresholds are chosen on its tune half;
- :mod:`validation.diagnosis.outside`: the outside panel (48 cases), designed apart from the
  tuning and never used to choose anything;
- :mod:`validation.diagnosis.independent`: the outside panel's independent truth model,
  written from the paper and physics with numpy only;
- :mod:`validation.diagnosis.score`: diagnose a half of a panel, then read its labels;
- :mod:`validation.diagnosis.tune`: choose the thresholds on the tuning panel's tune half.

See ``README.md`` here and ``docs/diagnosis.md`` for the commands.
"""
