"""The scorer's leave-one-effect-out runs for a diagnosis in two directions (issue 21): it has
no reselection without a refit, so the case is diagnosed again from its data with the effect
withheld; ``loo_2d=False`` reports them as not run, as before."""

from __future__ import annotations

from types import SimpleNamespace

from validation.diagnosis import score as scoring


class _Fake2D:
    """What the scorer reads of a diagnosis in two directions (no ``selection``)."""

    def __init__(self, verdict, excluded=()):
        self.verdict = list(verdict)
        self.campaign = "campaign"
        self.baseline = SimpleNamespace(spec="spec")
        self.excluded = tuple(excluded)

    def to_json(self):
        return {"chosen": None, "gap": {"value": 0.2, "noise": 0.01}}


def test_two_direction_cases_are_diagnosed_again_without_each_true_effect(monkeypatch):
    calls = []

    def fake_diagnose(campaign, spec, *, thresholds=None, exclude=()):
        calls.append((campaign, spec, tuple(exclude)))
        return _Fake2D(["unexplained"] if "heating" in exclude else ["velocity"])

    monkeypatch.setattr(scoring, "diagnose", fake_diagnose)
    labels = {"case_01": {"effects": ["heating", "velocity"], "truth": "t", "half": "tune"}}
    rows = scoring.score({"case_01": (_Fake2D(["heating", "velocity"]), 1.0)}, labels)
    assert calls == [("campaign", "spec", ("heating",)), ("campaign", "spec", ("velocity",))]
    loo = {x["withheld"]: x for x in rows[0]["loo"]}
    assert loo["heating"]["verdict"] == ["unexplained"] and loo["heating"]["right"]
    # withholding velocity gave "velocity": named although withheld, so not right
    assert loo["velocity"]["right"] is False
    assert scoring.summarize(rows)["loo_runs"] == 2

    calls.clear()
    rows = scoring.score({"case_01": (_Fake2D(["heating"]), 1.0)}, labels, loo_2d=False)
    assert not calls and all(x["right"] is None for x in rows[0]["loo"])
