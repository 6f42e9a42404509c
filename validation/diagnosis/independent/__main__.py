"""Run the independent truth model's self-checks: ``python -m validation.diagnosis.independent``.

Prints each check's relative error (:func:`validation.diagnosis.independent.checks.checks`).
"""

from validation.diagnosis.independent.checks import checks

if __name__ == "__main__":
    checks()
