"""rollaway.uncertainty.predictive: the error of a hold longer than the bench's tests (hold_sd) on the change the
model carries unseen (rollaway.uncertainty.draws.unseen_hold_change), against the truth of the independent
generator's short-test campaigns (tests/uncertainty/band_questions.py: 12 s to 20-min tests, hidden creep,
relaxation and radiating drums in forms the catalogue lacks)."""
import os

import numpy as np
import pytest

from rollaway.model.drum_model import DrumModel
from rollaway.uncertainty.draws import hold_error, rollaway_risk, unseen_hold_change
from rollaway.uncertainty.predictive import HOLD_SD_CAP, UNSEEN_HOLD_SHARE, hold_sd, model_error_sd
from tests.uncertainty.band_questions import campaign, confident_wrong

RECORD = {"model_error_rel_sd": 0.002, "model_error_dof": 7, "model_error_floor_rel_sd": 0.0005,
          "tested_hand_force_N": [180.0, 360.0], "tested_initial_temp_C": [100.0, 250.0],
          "tested_directions": ["downhill", "uphill"]}
QUESTION = dict(hand_force_N=270.0, grade_pct=20.0, direction="uphill", occupants=1, duration_s=3600.0,
                initial_temp_C=200.0)


def paper_tested_for(seconds: float) -> DrumModel:
    return DrumModel("paper", predictive={**RECORD, "tested_duration_s": seconds})


def test_no_unseen_change_within_the_tested_hold():
    assert unseen_hold_change(paper_tested_for(3600.0), 270.0, -1.0, 200.0, 3600.0) == 0.0
    assert unseen_hold_change(paper_tested_for(3580.0), 270.0, -1.0, 200.0, 3600.0) == 0.0   # within 2 %


def test_the_unseen_change_is_the_models_own_torque_change_after_the_bench_stopped():
    m = paper_tested_for(120.0)
    t = np.linspace(120.0, 3600.0, 4001)
    torque = m.evaluate(t, 270.0, "uphill", initial_temp_C=200.0).torque_Nm
    expected = float(np.max(np.abs(torque - torque[0]) / torque))    # against the torque left where it is decided
    got = unseen_hold_change(m, 270.0, -1.0, 200.0, 3600.0)
    assert got == pytest.approx(expected, rel=0.02)
    assert got > float(np.max(np.abs(torque / torque[0] - 1.0)))      # the torque falls: more than of the start's
    assert got > 0.05                                    # the drum cools on for an hour: the torque moves
    assert unseen_hold_change(paper_tested_for(1200.0), 270.0, -1.0, 200.0, 3600.0) < got   # less left unseen


def test_a_light_pull_whose_torque_the_cooling_nearly_takes_counts_the_loss_against_what_is_left():
    """At 135 N the hour's cooling takes most of the clamp the 2-min bench saw: the share of that loss the law may
    err by is several times the torque left, so the hold's error reaches the cap, and the band reaches several times
    the model's margin (the independent generator's 135 N truths kept 2.5–4 times what such models did)."""
    m = paper_tested_for(120.0)
    light = unseen_hold_change(m, 135.0, -1.0, 200.0, 3600.0)
    firm = unseen_hold_change(m, 270.0, -1.0, 200.0, 3600.0)
    assert light > 3.0 * firm
    torque = m.evaluate(np.linspace(120.0, 3600.0, 61), 135.0, "uphill", initial_temp_C=200.0).torque_Nm
    lost = 1.0 - torque.min() / torque[0]                 # the loss as a share of the torque the bench saw
    assert hold_error(m, 135.0, -1.0, 200.0, 3600.0) == pytest.approx(min(hold_sd(light), HOLD_SD_CAP))
    assert hold_error(m, 135.0, -1.0, 200.0, 3600.0) > 2.0 * hold_sd(lost)
    r = rollaway_risk(m, hand_force_N=135.0, grade_pct=10.0, direction="uphill", occupants=1, duration_s=3600.0,
                      initial_temp_C=200.0, draws=2000, seed=5)
    p = r.brake_margin_percentiles
    assert p["p95"] > 1.5 * p["p50"]
    assert r.detail["hold_error_sd"] == pytest.approx(hold_error(m, 135.0, -1.0, 200.0, 3600.0))


def test_each_competing_effect_set_carries_its_own_unseen_change():
    """A part of the predictive mixture errs beyond the bench's hold by its own law's unseen change, not by the
    calibrated model's: on the same 2-min bench, a mixture whose heavy part is a drum that has cooled within the
    bench's tests (its torque no longer moves) is as narrow as that part alone, and far narrower than the
    calibrated model alone, whose drum cools on for the hour."""
    slow = paper_tested_for(120.0)
    fast = paper_tested_for(120.0).replace_params(heat_transfer_W_m2K=4000.0)
    mixed = DrumModel("paper", predictive={**RECORD, "tested_duration_s": 120.0}, alternatives=[(0.98, fast)])
    q = dict(QUESTION, hand_force_N=200.0)
    risks = {k: rollaway_risk(m, draws=2000, seed=3, **q) for k, m in (("slow", slow), ("fast", fast),
                                                                         ("mixed", mixed))}
    width = {k: r.detail["half_width"] for k, r in risks.items()}
    assert hold_error(slow, 200.0, -1.0, 200.0, 3600.0) > 0.05 > 10 * hold_error(fast, 200.0, -1.0, 200.0, 3600.0)
    assert width["mixed"] < 0.5 * width["slow"], width
    assert width["mixed"] == pytest.approx(width["fast"], rel=0.25), width
    sets = risks["mixed"].detail["hold_error_sd_sets"]                 # said in the words, part by part
    assert sets == pytest.approx([hold_error(m, 200.0, -1.0, 200.0, 3600.0) for m in (mixed, fast)])
    assert "for the competing effect sets, each by its own law" in risks["mixed"].band_words()
    assert "competing effect sets" not in risks["slow"].band_words()


def test_the_hold_error_adds_in_quadrature():
    pred = {**RECORD, "tested_duration_s": 120.0}
    base = model_error_sd(pred, 1.0)
    assert hold_sd(0.2) == pytest.approx(UNSEEN_HOLD_SHARE * 0.2)
    assert hold_sd(-1.0) == 0.0
    assert model_error_sd(pred, 1.0, hold=0.03) == pytest.approx(np.hypot(base, 0.03))


def test_a_short_bench_widens_the_hour_band_and_says_why():
    long, short = (rollaway_risk(paper_tested_for(s), draws=2000, seed=3, **QUESTION) for s in (3600.0, 120.0))
    assert long.detail["unseen_hold_change"] == 0.0
    assert short.detail["unseen_hold_change"] > 0.05
    assert short.detail["half_width"] > 3.0 * long.detail["half_width"]
    assert any("longer than the bench" in f for f in short.detail["flags"])
    pred = {**RECORD, "tested_duration_s": 120.0}
    assert short.detail["model_error_rel_sd"] == pytest.approx(np.hypot(
        model_error_sd(pred, short.detail["extrapolation_factor"]), hold_sd(short.detail["unseen_hold_change"])))
    assert short.detail["hold_error_sd"] == pytest.approx(hold_sd(short.detail["unseen_hold_change"]))


def _short_study(campaigns) -> list[dict]:
    return [r for i in campaigns for r in campaign(i, draws=200, short=True)]


def test_two_minute_creep_tests_give_no_confident_answer_about_an_hour():
    """Creep laws and a radiating drum fitted on 2-min tests at 10 Hz (campaigns whose hour-long bands once sat
    wholly on the wrong side of 1): the hour's band holds the truth or at least is not sure of the wrong answer."""
    rows = _short_study([2, 6, 10])
    assert not [r for r in rows if confident_wrong(r)], rows
    assert np.mean([r["covered"] for r in rows]) >= 0.75, rows


@pytest.mark.skipif(not os.environ.get("ROLLAWAY_SLOW"), reason="48 campaigns (~4 min); set ROLLAWAY_SLOW=1")
def test_short_tests_bands_cover_the_hour_in_every_setting():
    """48 short-test campaigns, every hidden kind in every setting (12 s at 100 Hz to 1200 s at 1 Hz): coverage
    ≥ 0.88 overall and ≥ 0.8 in each setting; no band sure that the car holds where it rolls away, and few sure of
    a roll-away that does not happen (at 135 N, where the torque nearly vanishes, a law carried from 2 minutes
    can take it all)."""
    from tests.uncertainty.band_questions import SHORT
    rows = _short_study(range(48))
    assert np.mean([r["covered"] for r in rows]) >= 0.88
    wrong = [r for r in rows if confident_wrong(r)]
    assert not [r for r in wrong if r["m_star"] < 1.0], wrong
    assert len(wrong) <= len(rows) // 30, wrong
    for k in range(len(SHORT)):
        sub = [r for r in rows if (r["campaign"] // 12) % len(SHORT) == k]
        assert np.mean([r["covered"] for r in sub]) >= 0.8, SHORT[k]
