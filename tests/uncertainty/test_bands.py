"""Predictive bands (rollaway.uncertainty.bands, rollaway.uncertainty.predictive) on data the model code did not make.

Campaigns come from tests/identify/bench_generator.py (the paper's equations written out again,
hidden effects in the catalogue's forms, in other forms, or none; drums that are not the paper's;
random μ_d, h and T_0).  The road question is the one the band must answer: facing uphill, 250 N,
one occupant, an hour from 200 °C, on the grade where the truth's least margin is m*.
"""
from __future__ import annotations

import os

import numpy as np
import pytest
from scipy.optimize import brentq

from rollaway.errors import UserError
from rollaway.hold import required_torque
from rollaway.identify.diagnose import diagnose
from rollaway.uncertainty.predictive import extrapolation, validate
from rollaway.uncertainty.draws import rollaway_risk
from tests.identify.bench_generator import EFFECTS, OTHER_DRUMS, generate, true_torque

GRID = np.linspace(0.0, 3600.0, 721)
KINDS = {"none": [None], "exact": [k for k, v in EFFECTS.items() if v[0] == "exact" and k != "zero_offset"],
         "other": [k for k, v in EFFECTS.items() if v[0] == "other"]}


def campaign(i: int) -> dict:
    """One held-out campaign and its road answer: the truth's least margin and the model's band."""
    rng = np.random.default_rng(5000 + i)
    kind = ("none", "exact", "other")[i % 3]
    hidden = KINDS[kind][rng.integers(len(KINDS[kind]))]
    effects = [hidden] if hidden else []
    mu, h = rng.uniform(0.3, 0.45), rng.uniform(25.0, 45.0)
    drum = list(OTHER_DRUMS.values())[rng.integers(len(OTHER_DRUMS))] if rng.random() < 0.5 else {}
    model = diagnose(generate(effects, seed=700 + i, mu=mu, h=h, drum=drum)).model

    def truth(grade):
        t_req = float(required_torque(model.params, grade, 1))
        return float(np.min(2 * true_torque(250.0, GRID, "uphill", drum=drum, mu=mu, h=h, effects=effects) / t_req))
    target = 1.0 + rng.uniform(-0.1, 0.1) if i % 2 else 1.0 + rng.uniform(-0.03, 0.03)
    grade = brentq(lambda g: truth(g) - target, 0.5, 80.0)
    m_star = truth(grade)
    risk = rollaway_risk(model, hand_force_N=250.0, grade_pct=grade, direction="uphill", occupants=1,
                         duration_s=3600.0, initial_temp_C=200.0, draws=300, seed=i)
    p = risk.least_margin_percentiles
    return {"kind": kind, "m_star": m_star, "p5": p["p5"], "p95": p["p95"], "half_width": 0.5 * (p["p95"] - p["p5"]),
            "probability": risk.rollaway_probability, "covered": p["p5"] <= m_star <= p["p95"]}


def _study(n: int) -> list[dict]:
    return [campaign(i) for i in range(n)]


def _check(rows, min_coverage):
    cov = np.mean([r["covered"] for r in rows])
    hw = float(np.median([r["half_width"] for r in rows]))
    wrong = sum((r["probability"] >= 0.95 and r["m_star"] >= 1.0) or (r["probability"] <= 0.05 and r["m_star"] < 1.0)
                for r in rows)
    assert cov >= min_coverage, (cov, rows)
    assert hw <= 0.02, hw
    assert wrong <= max(1, len(rows) // 30), wrong
    return cov, hw


def test_band_covers_the_truth_in_a_small_calibration_study():
    """12 campaigns, four of each kind: coverage ≥ 75 % (nominal 90 %), median half-width ≤ 0.02."""
    _check(_study(12), 0.75)


@pytest.mark.skipif(not os.environ.get("ROLLAWAY_SLOW"), reason="60 campaigns (~3 min); set ROLLAWAY_SLOW=1")
def test_band_covers_the_truth_in_each_kind_and_the_probability_is_reliable():
    rows = _study(60)
    _check(rows, 0.85)
    for kind in KINDS:
        sub = [r for r in rows if r["kind"] == kind]
        assert np.mean([r["covered"] for r in sub]) >= 0.8, kind
    # reliability: among answers with p in a bin, the share that rolls away is near the bin's mean p
    p = np.array([r["probability"] for r in rows])
    rolled = np.array([r["m_star"] < 1.0 for r in rows])
    for lo, hi in ((0.0, 0.2), (0.2, 0.8), (0.8, 1.0001)):
        m = (p >= lo) & (p < hi)
        if m.sum() >= 8:
            assert abs(rolled[m].mean() - p[m].mean()) < 0.3, (lo, hi, rolled[m].mean(), p[m].mean())


def test_clean_data_give_narrow_bands():
    widths = []
    for seed in range(4):
        model = diagnose(generate(seed=900 + seed, sampling="1min")).model
        risk = rollaway_risk(model, hand_force_N=250.0, grade_pct=12.0, direction="uphill", occupants=1,
                             duration_s=3600.0, initial_temp_C=200.0, draws=300)
        p = risk.least_margin_percentiles
        widths.append(0.5 * (p["p95"] - p["p5"]) / p["p50"])
        assert not risk.flags
    assert np.median(widths) <= 0.02


def test_questions_beyond_the_data_are_flagged_and_widened():
    model = diagnose(generate(seed=910, directions=("downhill",))).model
    kw = dict(grade_pct=12.0, occupants=1, initial_temp_C=200.0, draws=300)
    inside = rollaway_risk(model, hand_force_N=250.0, direction="downhill", duration_s=3600.0, **kw)
    assert not inside.flags
    cases = {"hand force": dict(hand_force_N=450.0, direction="downhill", duration_s=3600.0),
             "was not tested": dict(hand_force_N=250.0, direction="uphill", duration_s=3600.0),
             "longer than the bench": dict(hand_force_N=250.0, direction="downhill", duration_s=7200.0)}
    width = lambda r: r.brake_margin_percentiles["p95"] - r.brake_margin_percentiles["p5"]  # noqa: E731
    for words, q in cases.items():
        out = rollaway_risk(model, **q, **kw)
        assert any(words in f for f in out.flags), (words, out.flags)
        assert "BEYOND THE DATA" in out.band_words()
        assert out.detail["model_error_rel_sd"] > 1.2 * inside.detail["model_error_rel_sd"], words   # widened
        rel = width(out) / out.brake_margin_percentiles["p50"]       # (the parameters' share may shrink at 450 N)
        assert rel > 0.9 * width(inside) / inside.brake_margin_percentiles["p50"], words


def test_extrapolation_factor_grows_with_distance():
    pred = {"tested_hand_force_N": [200.0, 300.0], "tested_initial_temp_C": [150.0, 250.0],
            "tested_duration_s": 3600.0, "tested_directions": ["downhill", "uphill"]}
    base = dict(direction="uphill", initial_temp_C=200.0, duration_s=3600.0)
    f = [extrapolation(pred, hand_force_N=x, **base)[0] for x in (250.0, 320.0, 400.0, 500.0)]
    assert f[0] == 1.0 and f[0] < f[1] < f[2] < f[3]


def test_below_the_tested_forces_the_distance_follows_the_torque_level():
    """Below the tested hand forces a relative error grows as the torque falls towards zero (eq. 24's u₆ = 0
    at F₀): the distance is at least (F_lo − F₀)/(F − F₀) − 1, capped where no torque is left."""
    pred = {"tested_hand_force_N": [180.0, 360.0]}
    base = dict(direction="uphill", initial_temp_C=200.0, duration_s=3600.0)
    span_only = extrapolation(pred, hand_force_N=135.0, **base)[0]
    level = extrapolation(pred, hand_force_N=135.0, zero_torque_force_N=40.0, **base)[0]
    assert span_only == 1.25 and abs(level - (1.0 + 140.0 / 95.0 - 1.0)) < 1e-12
    above = [extrapolation(pred, hand_force_N=450.0, zero_torque_force_N=f0, **base)[0] for f0 in (None, 40.0)]
    assert above[0] == above[1] == 1.5                    # above the tested forces the span rules
    assert extrapolation(pred, hand_force_N=30.0, zero_torque_force_N=40.0, **base)[0] <= 11.0


def test_the_torque_level_below_the_tested_forces_counts_the_thermal_terms_and_effects():
    """After an hour's cooling from 200 °C the clamp force the drum's contraction takes leaves far less torque at
    135 N than eq. (24)'s u₆ alone says: the distance follows the model's own least torque, and a question where that
    torque nearly vanishes gets the band it needs (the generator's drum: two cable relaxations, one exponential and
    one logarithmic, that one catalogue form takes; at 135 N the truth holds 0.7 % of grade)."""
    from rollaway.uncertainty.draws import torque_level_ratio, zero_torque_force
    from tests.uncertainty.band_questions import GRID as HOUR, two_effect_data
    effects, drum, mu, h, one, data, _ = two_effect_data(346)
    model = diagnose(data).model
    tested = model.predictive["tested_hand_force_N"]
    f0 = zero_torque_force(model)
    by_u6 = (tested[0] - f0) / (135.0 - f0)
    level = torque_level_ratio(model, 135.0, tested, -1.0, 200.0, 3600.0)
    assert level > 2.0 * by_u6 and torque_level_ratio(model, 200.0, tested, -1.0, 200.0, 3600.0) is None
    truth_torque = np.min(true_torque(135.0, HOUR, "uphill", drum=drum, mu=mu, h=h, t0=200.0, effects=effects))
    grade = brentq(lambda g: 2 * truth_torque / float(required_torque(model.params, g, 1)) - 1.0, 0.05, 80.0)
    band = rollaway_risk(model, hand_force_N=135.0, grade_pct=grade, direction="uphill", occupants=1,
                         duration_s=3600.0, initial_temp_C=200.0, draws=400, seed=3).brake_margin_percentiles
    assert band["p5"] <= 1.0 <= band["p95"], band


def test_saved_model_keeps_the_predictive_record_and_bad_tables_are_one_line_errors(tmp_path):
    from rollaway.model.drum_model import DrumModel
    d = diagnose(generate(["creep_exponential"], seed=920))
    path = d.save_model(tmp_path / "m.toml")
    m = DrumModel(path)
    assert m.predictive["model_error_rel_sd"] >= 0 and m.predictive["tested_directions"] == ["downhill", "uphill"]
    assert m.predictive["model_error_edge_low"] == pytest.approx(d.refined.fit_info["predictive"]["model_error_edge_low"])
    assert m.predictive["model_error_start"] == pytest.approx(d.refined.fit_info["predictive"]["model_error_start"])
    for w, alt in m.alternatives:
        assert 0 < w < 1 and alt.covariance is not None
    with pytest.raises(UserError, match="predictive.tested_hand_force_N"):
        validate({"tested_hand_force_N": [300.0, 200.0]}, "m.toml")
    with pytest.raises(UserError, match="unknown key 'predictive.model_eror_rel_sd'"):
        validate({"model_eror_rel_sd": 0.1}, "m.toml")
    with pytest.raises(UserError, match=r"predictive.model_error_edge_low' must be \[relative error"):
        validate({"model_error_edge_low": [0.01, 0.0]}, "m.toml")
    with pytest.raises(UserError, match=r"predictive.model_error_start' must be \[relative error"):
        validate({"model_error_start": [0.01, 300.0, 120.0]}, "m.toml")
    with pytest.raises(UserError, match="does not exist"):
        validate({"alternatives": [{"weight": 0.2, "file": "gone.toml"}]}, "m.toml", tmp_path)


@pytest.mark.skipif(not os.environ.get("ROLLAWAY_SLOW"), reason="48 campaigns (~2 min); set ROLLAWAY_SLOW=1")
def test_bands_beyond_the_tested_forces_temperatures_and_direction_cover():
    """tests/uncertainty/band_questions.py at 1-min sampling: 135 N and 450 N after tests at 180–360 N, T_0 280 °C
    after ≤ 250 °C, the untested direction; ≥ 0.9 overall, ≥ 0.85 per question and per kind of hidden effect, no
    band wholly on the wrong side.  48 campaigns (32 questions of each kind, 16 facing the untested way): with 16 a
    band of exactly 90 % falls below 0.85 one time in five."""
    from tests.uncertainty.band_questions import QUESTIONS, campaign, summary
    rows = [r for i in range(48) for r in campaign(i, sampling="1min")]
    s = summary(rows)
    assert s["coverage"] >= 0.9 and s["confident_wrong"] == 0, s
    for q in QUESTIONS:
        assert s[q]["coverage"] >= 0.85, (q, s[q])
    for kind in ("exact", "other"):          # per kind of hidden effect: the catalogue's form, another form
        sub = [r["covered"] for r in rows if r["hidden"] and EFFECTS[r["hidden"]][0] == kind]
        assert np.mean(sub) >= 0.85, (kind, np.mean(sub), len(sub))


@pytest.mark.skipif(not os.environ.get("ROLLAWAY_SLOW"), reason="48 campaigns (~5 min); set ROLLAWAY_SLOW=1")
def test_bands_cover_when_every_hidden_kind_is_asked_every_question():
    """tests/uncertainty/band_questions.py's rotated campaigns (5-min): in :func:`campaign` four kinds of hidden effect
    (the exponential creep, the linear modulus, the friction fade above 150 °C, the logarithmic cable creep) only ever
    meet one-direction benches and the untested-direction question; here each kind is asked every question, on
    drums of OTHER_DRUMS and MORE_DRUMS.  Measured: 0.994 of 154, no band wholly on the wrong side, every kind
    ≥ 0.92 (5-min; 0.987 at 1-min).  A kind's 13 questions come from four campaigns: one campaign's miscalibration
    misses two or three together, hence 0.75 per kind."""
    from tests.uncertainty.band_questions import campaign, summary
    rows = [r for i in range(48) for r in campaign(i, sampling="5min", rotated=True)]
    s = summary(rows)
    assert s["coverage"] >= 0.9 and s["confident_wrong"] == 0, s
    for q in ("inside", "force_low", "force_high", "hotter"):
        assert s[q]["coverage"] >= 0.85, (q, s[q])
    for kind in {r["hidden"] for r in rows}:
        sub = [r["covered"] for r in rows if r["hidden"] == kind]
        assert np.mean(sub) >= 0.75, (kind, np.mean(sub), len(sub))


def test_an_alternative_must_pin_its_brake_parameters_within_their_assumed_spread():
    from types import SimpleNamespace as NS

    from rollaway.uncertainty.bands import sized
    est = lambda v, s: NS(value=v, stderr=s, at_bound=False)   # noqa: E731
    good = NS(estimates={"mu_drum": est(0.4, 0.01), "u6_offset_m": est(-1e-5, 1e-6), "lining_creep.c": est(1.0, 0.1)})
    assert sized(good)
    assert not sized(NS(estimates={**good.estimates, "u6_offset_m": est(5.6e-5, 2.6)}))     # offset ± 2.6 m
    assert not sized(NS(estimates={**good.estimates, "mu_drum": est(0.4, float("nan"))}))
    assert not sized(NS(estimates={**good.estimates, "lining_creep.c": est(1.0, 0.5)}))


def test_no_alternative_with_per_test_values_or_unpinned_brake_parameters():
    """A fit with a zero offset per test refits the held-out test's own offset: its held-out score flatters it, and
    on one held-out campaign it took 94 % of the mixture with the eq. (24) offset at ± 2.6 m (bands 0–22)."""
    from rollaway.model.drum_parameters import FREE_PARAMETERS
    from tests.uncertainty.band_questions import campaign as question_campaign
    for i in (43, 31):                      # a quadratic friction fade on the paper's drum and on another
        rows = question_campaign(i, draws=100)
        assert rows and all(r["half_width"] < 1.0 for r in rows), rows
    data = generate(["friction_quadratic"], seed=7743, mu=0.343, h=38.2, forces=np.linspace(180.0, 360.0, 4),
                    t0_range=(100.0, 250.0))
    for w, alt in diagnose(data).model.alternatives:
        assert not any("zero_offset" in e for e in alt.name.split(" + ")), alt.name
        fitted = alt.fitted_values()
        for n, var in zip(alt.covariance.names, np.diag(alt.covariance.matrix)):
            if n in FREE_PARAMETERS:
                assert np.sqrt(var) <= 1.5 * FREE_PARAMETERS[n].spread(fitted[n]), (alt.name, n)


def test_edge_error_sees_a_wrong_force_scaling_and_not_a_right_one():
    """The lowest tested force predicted from the others: on a drum whose eq. (24) offset is not the paper's, the
    calibration that holds the paper's slope and offset (μ_d takes up the mean) errs there by more than 10 %, the
    one that frees them by little; the error at the question's distance scales from the edge's."""
    from rollaway.identify.calibrate import calibrate
    from rollaway.identify.model import DrumPlan
    from rollaway.model.parameters import load_parameters
    from rollaway.uncertainty.bands import edge_error
    from rollaway.uncertainty.predictive import edge_sd
    paper = load_parameters("paper")
    right, wrong = [], []
    for seed in range(4):
        data = generate([], seed=300 + seed, drum=OTHER_DRUMS["eq24_own"], forces=np.linspace(150.0, 400.0, 4))
        data.torque_sigma_Nm, data.temp_sigma_C = np.full(len(data), 8.0), np.full(len(data), 1.5)
        free = ("mu_drum", "heat_transfer_W_m2K", "shoe_arm_ratio")
        for out, plan in ((right, free + ("u6_slope_m_per_N", "u6_offset_m")), (wrong, free)):
            out.append(edge_error(calibrate(data, (), DrumPlan(paper, plan)), "low")["rel_sd"])
    assert min(wrong) > 0.1 and np.median(right) < 0.03 and np.mean(right) < 0.5 * np.mean(wrong), (right, wrong)
    pred = {"tested_hand_force_N": [150.0, 400.0], "model_error_edge_low": [0.1, 0.5]}
    assert edge_sd(pred, 250.0) == 0.0 and edge_sd(pred, 500.0) == 0.0       # inside; above: no high edge measured
    assert edge_sd(pred, 100.0) == pytest.approx(0.1 * (50.0 / 250.0) / 0.5)
    assert edge_sd(pred, 100.0, 50.0) == pytest.approx(0.1 * (1.0 / 0.5) ** 2)  # torque level: (150−50)/(100−50) − 1;
    #                                                                             twice the edge's distance: 4×


def test_the_low_edge_counts_the_unseen_share_of_its_resolution_and_the_high_edge_what_it_measured():
    """Below the tested forces an error in the clamp that does not scale with the force grows relative to the
    torque: an edge prediction within its noise is no proof of none, and the low edge's error counts the share
    UNSEEN of its resolution beside its measured excess.  Above them such an error shrinks, and the high edge
    counts only what it measured (0 for a right model on most seeds)."""
    from rollaway.identify.calibrate import calibrate
    from rollaway.identify.model import DrumPlan
    from rollaway.model.parameters import load_parameters
    from rollaway.uncertainty.bands import edge_error
    from rollaway.uncertainty.predictive import UNSEEN
    paper = load_parameters("paper")
    plan = ("mu_drum", "heat_transfer_W_m2K", "shoe_arm_ratio", "u6_slope_m_per_N", "u6_offset_m")
    zero_high = 0
    for seed in range(4):
        data = generate([], seed=310 + seed, forces=np.linspace(150.0, 400.0, 4))
        data.torque_sigma_Nm, data.temp_sigma_C = np.full(len(data), 8.0), np.full(len(data), 1.5)
        fit = calibrate(data, (), DrumPlan(paper, plan))
        low, high = edge_error(fit, "low"), edge_error(fit, "high")
        assert low["floor_rel_sd"] > 0.0 and high["floor_rel_sd"] > 0.0
        assert low["rel_sd"] == pytest.approx(np.sqrt(max(low["excess_ms"], 0.0) + (UNSEEN * low["floor_rel_sd"]) ** 2))
        assert low["rel_sd"] >= UNSEEN * low["floor_rel_sd"]
        assert high["rel_sd"] == pytest.approx(np.sqrt(max(high["excess_ms"], 0.0)))
        zero_high += high["rel_sd"] == 0.0
    assert zero_high >= 1, zero_high


def test_the_chosen_effect_in_the_datas_own_form_competes_in_the_bands(monkeypatch):
    """A power-law lining creep (12 % at an hour, t^0.35) on 5-min samples: the catalogue's exponential creep leaves
    no structure the residual tests see, but it flattens after a few minutes and leaves the later loss to the cooling
    law, μ_d 25 % high against the eq. (24) slope.  Its shape-free form predicts the held-out tests as well and takes
    part of the mixture; the bands then hold the truth at 135 N, 450 N and 280 °C (the catalogue form alone: 28 % low
    at 135 N, and missed all three).  Campaign 46 of tests/uncertainty/band_questions.py."""
    from tests.uncertainty.band_questions import campaign as question_campaign
    import rollaway.identify.diagnose as dg
    seen, original = [], dg.diagnose
    monkeypatch.setattr(dg, "diagnose", lambda *a, **k: seen.append(original(*a, **k)) or seen[-1])
    rows = question_campaign(46, draws=300)
    alts = seen[0].model.alternatives
    assert seen[0].verdict == "lining_creep" and any("lining_creep_shape" in m.name for _, m in alts), alts
    assert len(rows) == 4 and all(r["covered"] for r in rows), rows


def test_a_rival_the_data_cannot_tell_from_the_verdict_keeps_its_bic_weight_in_the_bands():
    """A lining modulus falling with temperature, tested downhill only (campaign 41 of band_questions): friction and
    modulus have the same BIC (+0.1) and a held-out difference inside the preference margin (−4.0 ± 2.3 over 4
    tests); the Bayesian bootstrap of those 4 scores gave modulus 5 % of the mixture, its BIC weight is ~½.  (Facing
    one way, time and temperature fall together: a lining creep spline, 10 behind the verdict, may stand second.)"""
    from tests.uncertainty.band_questions import campaign_data
    hidden, *_, data, _ = campaign_data(41)
    d = diagnose(data)
    assert hidden == "modulus_linear" and d.verdict == "friction_temperature"
    assert [a["effects"] for a in d.alternatives][0] == ["modulus_temperature"], d.alternatives
    weights = {m.name: w for w, m in d.model.alternatives}
    assert weights.get("paper + modulus_temperature", 0.0) >= 0.25, weights


def test_each_effect_set_in_the_mixture_draws_its_own_model_error():
    """A competing set that predicted its held-out tests exactly carries no model error of its own; one without a
    record of its own draws the saved model's."""
    from rollaway.model.drum_model import DrumModel
    pred = {"model_error_rel_sd": 0.05, "model_error_dof": 5, "model_error_floor_rel_sd": 0.0}

    def band(alt_pred):
        model = DrumModel(predictive=pred, alternatives=[(0.98, DrumModel(predictive=alt_pred))])
        return rollaway_risk(model, hand_force_N=300.0, grade_pct=20.0, direction="uphill", occupants=1,
                             duration_s=600.0, draws=400, seed=1).detail["half_width"]
    own = band({**pred, "model_error_rel_sd": 0.0})
    assert own < 0.1 * band({}) and band({}) == pytest.approx(band(pred))


def test_where_the_verdict_leaves_structure_a_spline_of_the_other_quantity_competes(monkeypatch):
    """A sigmoid modulus drop with radiation on another drum (1-min, campaign 15 of band_questions' two-effect
    campaigns): the catalogue forms of friction and modulus both leave structure.  A friction spline clears it, yet
    it is friction, not modulus, and 15 % optimistic at a hot uphill start; a spline of the lining modulus (same
    covariate, the other quantity) predicts the held-out tests better.  The modulus — the verdict since the exchange
    step refits the brake parameters with each swap (friction was, with the modulus spline at 0.89) — keeps near half
    the mixture in its shape-free form beside the catalogue friction; the shape-free sets draw their own held-out
    error, the catalogue forms no less than the verdict's, and the bands hold the truth.  With the friction spline
    alone on its own error they were wholly above the truth at 450 N and 280 °C."""
    from tests.uncertainty.band_questions import campaign as question_campaign
    import rollaway.identify.diagnose as dg
    seen, original = [], dg.diagnose
    monkeypatch.setattr(dg, "diagnose", lambda *a, **k: seen.append(original(*a, **k)) or seen[-1])
    rows = question_campaign(15, two=True)
    d = seen[0]
    rel = d.model.predictive["model_error_rel_sd"]
    assert d.remaining_structure or any(e["form"] != "exact" for e in d.effects)
    weights = {m.name: w for w, m in d.model.alternatives}
    modulus = sum(w for n, w in weights.items() if "modulus" in n) + (
        1.0 - sum(weights.values()) if d.verdict == "modulus_temperature" else 0.0)
    assert modulus > 0.4 and weights.get("paper + modulus_temperature_shape", 0.0) > 0.4, weights
    said = next(e for e in d.as_dict()["evidence"] if e.startswith("Parameter intervals count"))
    assert "also in the bands: " in said and "modulus_temperature_shape 4" in said, said   # it says what they draw
    for _, m in d.model.alternatives:
        own = m.predictive["model_error_rel_sd"]
        assert own < rel if m.name.endswith("_shape") else own >= rel, (m.name, own, rel)
    assert rows[0]["hidden"] == "modulus_sigmoid+radiation" and all(r["covered"] for r in rows), rows


def test_a_spline_of_the_right_quantity_errs_by_its_own_held_out_record():
    """A sigmoid modulus drop on another drum, 5-min samples (campaign 9 of band_questions): the catalogue's linear
    modulus law leaves structure (held-out error 7 %, widened); the modulus spline predicts the held-out tests at
    the noise and takes the mixture.  The bands hold the truth at a fifth of the half-width that drawing the
    catalogue form's error gave (0.15–0.26 at 270 N, 450 N and 280 °C)."""
    from tests.uncertainty.band_questions import campaign as question_campaign
    rows = question_campaign(9)
    assert rows[0]["hidden"] == "modulus_sigmoid" and len(rows) == 4, rows
    assert all(r["covered"] for r in rows), rows
    assert max(r["half_width"] for r in rows if r["question"] != "force_low") < 0.08, rows


def test_where_no_catalogue_form_clears_the_structure_the_closest_effects_shapes_compete(monkeypatch):
    """A sigmoid modulus drop with a friction fade above 150 °C on another drum (1-min, two-effect campaign 343 of
    band_questions): no catalogue effect clears the structure ("none", closest modulus or friction).  The catalogue
    forms alone, their error ×4, gave bands above the truth at 270 N, 450 N and 280 °C (from 0.93–1.05, the truth
    0.91–1.00); the closest effects' shape-free forms compete too, the modulus spline takes the mixture and the
    bands hold the truth."""
    from tests.uncertainty.band_questions import campaign as question_campaign
    import rollaway.identify.diagnose as dg
    seen, original = [], dg.diagnose
    monkeypatch.setattr(dg, "diagnose", lambda *a, **k: seen.append(original(*a, **k)) or seen[-1])
    rows = question_campaign(343, two=True)
    d = seen[0]
    assert d.verdict == "none" and d.remaining_structure
    assert any(m.name.endswith("_shape") for _, m in d.model.alternatives), d.model.alternatives
    assert len(rows) == 4 and all(r["covered"] for r in rows), rows


def test_a_bench_record_carries_the_transducer_gain_that_no_held_out_test_sees():
    """A record measured on a bench carries the torque transducer's gain uncertainty beside what the held-out tests
    measured; a model without one (no bench) gets none.  On a 1 Hz log of a power-law lining creep (campaign 22 of
    band_questions) the creep's shape-free form predicts its held-out tests at the noise and the bands at 270 N and
    from 280 °C were ±0.07 % and missed the truth by 0.04 %; with the gain they hold it."""
    from rollaway.uncertainty.predictive import TRANSDUCER_REL_SD, model_error_sd
    from tests.uncertainty.band_questions import campaign as question_campaign
    assert model_error_sd({}, 2.0) == 0.0
    assert model_error_sd({"model_error_rel_sd": 0.0}, 1.0) == pytest.approx(TRANSDUCER_REL_SD)
    assert model_error_sd({"model_error_rel_sd": 0.004}, 1.0) == pytest.approx(np.hypot(0.004, TRANSDUCER_REL_SD))
    rows = question_campaign(22, sampling="1Hz")
    assert rows[0]["hidden"] == "creep_power_law" and len(rows) == 4, rows
    assert all(r["covered"] for r in rows) and max(r["half_width"] for r in rows) < 0.01, rows


def test_the_benchs_own_force_extrapolation_grows_with_the_square_of_the_distance(monkeypatch):
    """A power-law creep with an installation gap (5-min, two-effect campaign 28 of band_questions): no catalogue effect
    clears the structure; the model's torque falls 2.6–3.0× from 180 N to 135 N after an hour from 200 °C, the
    truth's 2.3×.  Predicting the 180 N tests from 270–360 N erred by 3–4 % at distance 1; scaled linearly to the
    question's distance 1.6–2.0 the band at 135 N was 0.74–0.98 against a truth of 1.05 (wholly pessimistic); with
    the square it holds it."""
    from tests.uncertainty.band_questions import campaign as question_campaign
    rows = question_campaign(28, two=True)
    low = next(r for r in rows if r["question"] == "force_low")
    assert low["hidden"] == "creep_power_law+gap" and low["covered"], low


def test_in_the_untested_direction_the_effect_sets_weights_move_toward_even(monkeypatch):
    """A sigmoid modulus drop with a linear friction rise tested downhill only (5-min, two-effect campaign 320 of
    band_questions): the held-out tests (downhill) gave a modulus law with μ_d = 0.77 ± 0.13 (truth 0.44) 98 % of the
    mixture, and its uphill band 0.12–0.75 lay wholly below the truth 1.07.  Downhill scores do not rank how the sets
    carry over uphill; with the weights halfway to even the band reaches the truth's side of 1."""
    from rollaway.model.drum_model import DrumModel
    from rollaway.uncertainty.direction import UNTESTED_DIRECTION_SHARE, mixture_parts
    from tests.uncertainty.band_questions import campaign as question_campaign
    import rollaway.identify.diagnose as dg
    seen, original = [], dg.diagnose
    monkeypatch.setattr(dg, "diagnose", lambda *a, **k: seen.append(original(*a, **k)) or seen[-1])
    rows = question_campaign(320, two=True)
    model = seen[0].model
    tested = [w for w, _ in mixture_parts(model, "downhill")]
    other = [w for w, _ in mixture_parts(model, "uphill")]
    assert len(tested) >= 2 and sum(other) == pytest.approx(1.0)
    assert other == pytest.approx([UNTESTED_DIRECTION_SHARE * w + (1 - UNTESTED_DIRECTION_SHARE) / len(tested)
                                   for w in tested])
    assert [w for w, _ in mixture_parts(DrumModel("paper"), "uphill")] == [1.0]
    (row,) = [r for r in rows if r["question"] == "direction"]
    assert row["p95"] >= 1.0 > row["p5"], row            # not wholly on the wrong side of the truth (1.07)


def test_a_start_the_held_out_tests_miss_widens_the_questions_it_decides(monkeypatch):
    """A sigmoid modulus drop with a relaxing cable, 5-min samples (two-effect campaign 106 of band_questions): the
    modulus spline predicts each test's least-torque samples at the noise (model error 0), but a test's hot start
    from the others' 5–22 % off (start error ≥ 5 %).  At 450 N and at 280 °C the least margin falls at the start:
    there the band drew only the whole-hold error and sat above the truth (1.080–1.167 over 1.050; 1.054–1.130 over
    1.046); with the start's error both hold it, and a question decided an hour later keeps its half-width."""
    import rollaway.identify.diagnose as dg
    from tests.uncertainty.band_questions import campaign as question_campaign
    seen, original = [], dg.diagnose
    monkeypatch.setattr(dg, "diagnose", lambda *a, **k: seen.append(original(*a, **k)) or seen[-1])
    rows = {r["question"]: r for r in question_campaign(106, two=True)}
    spline = next(m for _, m in seen[0].model.alternatives if "modulus_temperature_shape" in m.name)
    start = spline.predictive["model_error_start"]
    assert start[0] > 0.05 > spline.predictive["model_error_rel_sd"] and start[1] == 0.0 and start[2] == 300.0
    assert rows["force_high"]["covered"] and rows["hotter"]["covered"], rows
    from rollaway.uncertainty.draws import rollaway_risk
    risk = rollaway_risk(seen[0].model, hand_force_N=450.0, grade_pct=20.0, direction="uphill", occupants=1,
                         duration_s=3600.0, initial_temp_C=200.0, draws=300, seed=0)
    assert risk.detail["start_decided"] > 0.1 and "the start of the hold decides" in risk.band_words()


def test_the_start_error_fades_between_the_start_samples_and_the_next():
    from rollaway.uncertainty.predictive import StartError, start_error_draws, start_weight
    assert list(start_weight([0.0, 60.0, 120.0, 210.0, 300.0, 900.0], [0.02, 60.0, 300.0])) == [1, 1, 0.75, 0.375, 0, 0]
    assert list(start_weight([0.0, 1.0], [0.02, 0.0, 0.0])) == [1, 0]
    pred = {"model_error_rel_sd": 0.01, "model_error_dof": 5, "model_error_start": [0.05, 0.0, 300.0]}
    rng = np.random.default_rng(0)
    extra = start_error_draws(pred, 20000, 1.0, rng)
    from rollaway.uncertainty.predictive import model_error_sd
    expect = np.sqrt(0.05 ** 2 - model_error_sd(pred, 1.0) ** 2) * np.sqrt(5 / 3)     # Student-t(5) sd
    assert abs(np.std(extra) / expect - 1) < 0.05
    assert start_error_draws({**pred, "model_error_start": [0.005, 0.0, 300.0]}, 10, 1.0, rng) is None
    assert start_error_draws({"model_error_rel_sd": 0.01}, 10, 1.0, rng) is None
    fn = StartError(lambda t, i, f=None: np.ones(np.broadcast_shapes(np.shape(t), np.shape(i))), np.array([0.1, -0.2]),
                    [0.05, 0.0, 300.0])
    np.testing.assert_allclose(fn(np.array([[0.0, 150.0, 600.0]]), np.array([[0], [1]])),
                               [[1.1, 1.05, 1.0], [0.8, 0.9, 1.0]])


def test_a_hot_start_beyond_the_tested_ones_draws_how_far_the_temperature_law_goes_on(monkeypatch):
    """A sigmoid modulus drop at 15-min samples whose hottest test started at 182 °C (campaign 93 of
    band_questions): the mixture's friction spline still fell at its hottest knot.  Flat beyond it, the bands from
    200 °C sat wholly above the truth (1.025–1.121 over 1.011 inside; 1.013–1.189 over 0.961 at 450 N: sure of a
    hold that fails).  Each draw now continues the last slope by a share in 0–1: both questions are covered and
    no band is sure of the wrong answer.  The share is in the spline's covariance at about its assumed spread (the
    data hardly see it), not fitted."""
    import rollaway.identify.diagnose as dg
    from rollaway.effects.shape_free import BEYOND_PRIOR_SD
    from tests.uncertainty.band_questions import campaign as question_campaign, confident_wrong
    seen, original = [], dg.diagnose
    monkeypatch.setattr(dg, "diagnose", lambda *a, **k: seen.append(original(*a, **k)) or seen[-1])
    rows = {r["question"]: r for r in question_campaign(93, sampling="15min")}
    spline = next(m for _, m in seen[0].model.alternatives if m.name.endswith("_temperature_shape"))
    c = spline.covariance
    k = next(i for i, n in enumerate(c.names) if n.endswith("_shape.beyond"))
    assert 0.9 * BEYOND_PRIOR_SD < np.sqrt(c.matrix[k, k]) <= BEYOND_PRIOR_SD     # hardly a sample lies beyond
    assert rows["inside"]["covered"] and rows["force_high"]["covered"], rows
    assert not any(confident_wrong(r) for r in rows.values()), rows


def test_where_two_splines_along_different_covariates_clear_the_structure_they_carry_the_bands(monkeypatch):
    """A cable relaxation with a friction fade above a temperature (1-min, two-effect campaign 31 of
    band_questions): no catalogue form clears the structure, and the bands drew the drum's own error ×4
    (half-widths 0.13–0.16 at 270 N, 450 N and 280 °C).  A friction spline beside a cable spline clears it and
    predicts the held-out tests at the noise: it takes the mixture with its own error, and the bands hold the
    truth at a tenth of that width."""
    from tests.uncertainty.band_questions import campaign as question_campaign
    import rollaway.identify.diagnose as dg
    seen, original = [], dg.diagnose
    monkeypatch.setattr(dg, "diagnose", lambda *a, **k: seen.append(original(*a, **k)) or seen[-1])
    rows = question_campaign(31, two=True)
    d = seen[0]
    assert d.verdict == "none" and d.remaining_structure
    pair = [(w, m) for w, m in d.model.alternatives if m.name.count("_shape") == 2]
    assert pair and pair[0][0] > 0.5, d.model.alternatives
    assert pair[0][1].predictive["model_error_rel_sd"] < d.model.predictive["model_error_rel_sd"] / 4
    assert len(rows) == 4 and all(r["covered"] for r in rows), rows
    assert max(r["half_width"] for r in rows if r["question"] != "force_low") < 0.05, rows


def test_a_start_predicted_within_its_noise_still_carries_the_unseen_share_of_its_resolution(monkeypatch):
    """A sigmoid modulus drop sampled every 15 minutes (band campaign 45: one start sample a test): the friction
    spline that carries most of the mixture predicts its held-out starts within the noise (no measured excess), yet
    between the start and the first sample at 900 s it is 4–10 % high facing uphill.  The start's error counts the
    share UNSEEN of its noise's resolution, as the hold's does: the band inside, decided at the start, lay wholly
    above the truth (1.005–1.065 over 0.968) and now reaches below 1."""
    import rollaway.identify.diagnose as dg
    from rollaway.uncertainty.predictive import UNSEEN
    from tests.uncertainty.band_questions import campaign as question_campaign, confident_wrong
    seen, original = [], dg.diagnose
    monkeypatch.setattr(dg, "diagnose", lambda *a, **k: seen.append(original(*a, **k)) or seen[-1])
    rows = {r["question"]: r for r in question_campaign(45, sampling="15min")}
    weight, heaviest = max(seen[0].model.alternatives, key=lambda a: a[0])
    start = heaviest.predictive["model_error_start"]
    assert weight > 0.5 and "_shape" in heaviest.name
    pred = heaviest.predictive
    assert start[0] > UNSEEN * pred["model_error_floor_rel_sd"] and pred["model_error_rel_sd"] == 0.0
    assert rows["inside"]["p5"] < 1.0 and not confident_wrong(rows["inside"]), rows["inside"]
