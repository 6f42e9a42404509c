"""With nothing named, a gap in two directions is real only where it lies (issue 21).

One direction decides ``unexplained`` with nothing named from where the residual lies: the
sliding phase by the materiality rule, the transition windows by their own rule (far above the
noise there, ``transition_score``, and material over the whole test,
``transition_practical``), or a nuisance at the edge of its range. Two directions also called a
gap real when the residual was material only over the two parts summed, each within its own
bar. On the no-effect tune variant 301/11 of the bidirectional panel (rigid-plastic; a
figure-eight and a square at 500 Hz; white noise; a 1.45-sample lag) the corners of the square
leave a residual well above the noise on 1 % of the samples, 2 % of the RMS force over the
test (the transition's bar is 3 %), and the sliding phase is within its bar: the verdict was
``unexplained`` with the finding ``every sample``; by one direction's rule it is ``none``.
One diagnosis, about 15 s.
"""

from __future__ import annotations

import pytest

from isolator.diagnosis.selection import material
from isolator.diagnosis.two_directions import diagnose_2d
from validation.diagnosis.bidirectional.variants import write_variant
from validation.diagnosis.score import load_case

pytestmark = pytest.mark.slow


def test_no_gap_on_the_two_parts_summed_when_nothing_is_named(tmp_path):
    labels, case = write_variant(tmp_path, 11, seed=301, effects=())
    assert labels["effects"] == [] and "rigid-plastic" in labels["truth"]
    campaign, baseline = load_case(case)
    d = diagnose_2d(campaign, baseline)
    th, p = d.problem.th, d.problem
    every = d.data.counted
    # the case exercises the rule: material over the whole test ...
    assert material(p.score(d.base_all.prediction, every),
                    p.excess_rms(d.base_all.prediction, every), th.practical_none, th)
    # ... with the windows far above the noise but below the transition's practical bar
    score, excess = p.window_statistics(d.base_all.prediction, d.window)
    assert score >= th.transition_score and excess < th.transition_practical
    assert d.verdict == ["none"], (d.verdict, d.findings, d.notes)
    assert d.findings == ()
    assert d.to_json()["unexplained"] is None
