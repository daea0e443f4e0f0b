"""The user's drum (rollaway.identify.drum) on bench data from drums that are not the paper's.

Data come from tests/identify/bench_generator.py, written from the paper's equations without
rollaway's model code; ``OTHER_DRUMS`` changes the radius, the normal-force arm, eq. (24),
the lining, the drum mass and the ambient — each alone and all together.
"""
from __future__ import annotations

import numpy as np
import pytest

from rollaway.identify.diagnose import diagnose
from rollaway.identify.drum import calibrate_drum
from rollaway.identify.export import calibrated_model
from rollaway.errors import UserError
from tests.identify.bench_generator import OTHER_DRUMS, generate, true_torque

PER_TEST = {"torque_zero_offset"}
TIMES = np.array([0.0, 300.0, 900.0, 1800.0, 3600.0])


def _worst_error(model, drum, directions, effects=()):
    """Largest relative torque error of *model* at unseen forces 150 N and 420 N, T_0 200 °C, over an hour."""
    worst = 0.0
    for force in (150.0, 420.0):
        for d in directions:
            pred = model.evaluate(TIMES, force, d, initial_temp_C=200.0).torque_Nm
            truth = true_torque(force, TIMES, d, drum=drum, effects=effects)
            worst = max(worst, float(np.max(np.abs(pred / truth - 1.0))))
    return worst


@pytest.mark.parametrize("drum", sorted(OTHER_DRUMS))
def test_other_drums_name_no_effect_and_predict_unseen_forces(drum):
    """No effect on a plain other drum (two seeds each), and torque at 150/420 N within 2 % (noise-limited)."""
    for seed in (3, 4):
        data = generate(drum=OTHER_DRUMS[drum], seed=seed, sampling="1min", noise_torque_Nm=4.0)
        dg = diagnose(data)
        assert dg.verdict == "none", (drum, seed, dg.verdict)
        assert not (PER_TEST & {e["effect"] for e in dg.effects})
        assert _worst_error(calibrated_model(dg.refined), OTHER_DRUMS[drum], ("downhill", "uphill")) < 0.02


def test_no_bogus_effect_across_many_seeds_and_drums():
    """Plain other drums, 5-minute sampling, heavy-tailed noise: at most 1 false effect in 24 campaigns."""
    named = []
    for seed in range(4):
        for drum in OTHER_DRUMS.values():
            dg = diagnose(generate(drum=drum, seed=100 + seed))
            if dg.verdict != "none":
                named.append(dg.verdict)
    assert len(named) <= 1, named


def test_changed_eq24_is_fitted_not_named():
    d = OTHER_DRUMS["eq24_own"]
    dc = calibrate_drum(generate(drum=d, seed=5, sampling="1min", noise_torque_Nm=3.0))
    slope, offset = dc.entries["u6_slope_m_per_N"], dc.entries["u6_offset_m"]
    assert slope.status == offset.status == "fitted"
    assert slope.ci95[0] <= d["u6_slope"] <= slope.ci95[1]
    assert offset.ci95[0] <= d["u6_offset"] <= offset.ci95[1]


def test_arm_ratio_is_fitted_from_both_directions_and_not_tested_from_one():
    d = OTHER_DRUMS["arm_80mm"]
    both = calibrate_drum(generate(drum=d, seed=6, sampling="1min", noise_torque_Nm=3.0))
    e = both.entries["shoe_arm_ratio"]
    assert e.status == "fitted"
    # μ_d·ρ is what the direction ratio measures: compare the product with the truth's
    mu = both.entries["mu_drum"].value
    assert abs(mu * e.value - 0.37 * 0.06 / 0.08) / (0.37 * 0.06 / 0.08) < 0.05
    one = calibrate_drum(generate(drum=d, seed=6, directions=("downhill",)))
    e1 = one.entries["shoe_arm_ratio"]
    assert e1.status == "not tested" and "downhill" in e1.reason and e1.prior_sd > 0
    assert "shoe_arm_ratio" not in one.free


def test_one_hand_force_leaves_the_eq24_pair_confounded():
    dc = calibrate_drum(generate(seed=7, forces=[300.0]))
    fixed = [n for n in ("u6_slope_m_per_N", "u6_offset_m") if dc.entries[n].status == "fixed"]
    assert fixed
    assert any("confounded with" in dc.entries[n].reason and dc.entries[n].confounded_with for n in fixed)
    assert all(dc.entries[n].prior_sd > 0 for n in fixed)        # their doubt is kept for the bands


def test_the_departures_include_what_the_data_could_not_identify():
    """The departures a second effect must not stand in for (:meth:`DrumCalibration.departures`): the held ones,
    the gap, and a parameter the bare drum fixed as not identifiable (one hand force: the eq. (24) pair)."""
    dc = calibrate_drum(generate(seed=7, forces=[300.0]))
    unidentified = [n for n, e in dc.entries.items() if e.status == "fixed" and "not identifiable" in e.reason]
    assert unidentified and set(unidentified) <= set(dc.departures())
    assert "gap_m" in dc.departures() and set(dc.held()) <= set(dc.departures())
    assert not set(dc.departures()) & set(dc.free)
    assert calibrate_drum(generate(seed=7, forces=[300.0]), free=["mu_drum"]).departures() == ()


def test_a_logged_ambient_is_read_not_fitted():
    dc = calibrate_drum(generate(seed=8, ambient_drift_C=2.0))
    assert dc.entries["ambient_temp_C"].status == "logged"
    assert "ambient_temp_C" not in dc.free


def test_free_and_fix_override_the_choice():
    data = generate(seed=9)
    dc = calibrate_drum(data, free=["mu_drum", "heat_transfer_W_m2K"])
    assert dc.free == ("mu_drum", "heat_transfer_W_m2K")
    assert dc.entries["u6_slope_m_per_N"].status == "fixed by you"
    dc = calibrate_drum(data, fix=["shoe_arm_ratio"])
    assert "shoe_arm_ratio" not in dc.free and dc.entries["shoe_arm_ratio"].status == "fixed by you"
    with pytest.raises(UserError, match="u6_slope_m_per_N"):
        calibrate_drum(data, free=["u6_slop"])
    with pytest.raises(UserError, match="contradict"):
        calibrate_drum(data, free=["mu_drum"], fix=["mu_drum"])


@pytest.mark.parametrize("drum,hidden,effect", [("arm_80mm", "creep_exponential", "lining_creep"),
                                                ("radius_100mm", "cable_exponential", "cable_relaxation"),
                                                ("thick_soft_lining", "friction_linear", "friction_temperature")])
def test_a_real_effect_on_another_drum_is_found_alone(drum, hidden, effect):
    dg = diagnose(generate([hidden], drum=OTHER_DRUMS[drum], seed=11))
    assert dg.verdict == effect and [e["effect"] for e in dg.effects] == [effect]
    assert _worst_error(calibrated_model(dg.refined), OTHER_DRUMS[drum], ("downhill", "uphill"), [hidden]) < 0.04


def test_per_test_offsets_make_eq24_unidentifiable_and_say_so():
    d = OTHER_DRUMS["eq24_own"]
    dg = diagnose(generate(["zero_offset"], drum=d, seed=12))
    assert dg.verdict == "torque_zero_offset"
    eq24 = {"u6_slope_m_per_N", "u6_offset_m"}
    fixed = {n for n, e in dg.drum.entries.items() if e.status == "fixed"} & eq24
    assert fixed
    assert any("torque_zero_offset" in dg.drum.entries[n].reason for n in fixed)


def test_report_text_json_and_model_file_carry_the_identifiability(tmp_path):
    from rollaway.model.drum_model import load_model
    dg = diagnose(generate(drum=OTHER_DRUMS["all_together"], seed=13, directions=("downhill",)))
    text = dg.summary()
    assert "Your drum" in text and "not tested" in text and "shoe_arm_ratio" in text
    js = dg.as_dict()["drum"]["parameters"]
    assert js["shoe_arm_ratio"]["status"] == "not tested" and js["mu_drum"]["status"] == "fitted"
    held = dg.as_dict()["refined"]["held"]          # a held parameter keeps its assumed spread as its interval
    assert js["shoe_arm_ratio"]["ci95_from"] == "assumed spread" and js["mu_drum"]["ci95_from"] == "fit"
    assert held["shoe_arm_ratio"]["ci95"] == js["shoe_arm_ratio"]["ci95"] and "mu_drum" not in held
    lo, hi = held["shoe_arm_ratio"]["ci95"]
    assert lo < 0.06 / 0.08 < hi and "95 % [" in text
    path = dg.save_model(tmp_path / "m.toml")
    model = load_model(path)
    assert model.calibration["shoe_arm_ratio"].startswith("not tested")
    assert model.calibration["mu_drum"].startswith("fitted")
    assert "shoe_arm_ratio" in model.covariance.names        # its doubt travels with the model
    html = tmp_path / "r.html"
    dg.report(html)
    assert "Your drum" in html.read_text(encoding="utf-8")


def test_untested_direction_band_covers_the_truth():
    """Downhill-only data from drums with other arms: the uphill 5–95 % margin band covers the truth."""
    from rollaway.uncertainty.draws import rollaway_risk
    from rollaway.hold import required_torque
    covered = 0
    cases = [("arm_80mm", 20), ("all_together", 21), ("thick_soft_lining", 22), ("radius_100mm", 23)]
    for drum, seed in cases:
        d = OTHER_DRUMS[drum]
        model = calibrated_model(diagnose(generate(drum=d, seed=seed, directions=("downhill",))).refined)
        risk = rollaway_risk(model, hand_force_N=250.0, grade_pct=12.0, direction="uphill", occupants=1,
                             duration_s=3600.0, initial_temp_C=200.0, draws=400)
        t_req = float(required_torque(model.params, 12.0, 1))
        grid = np.linspace(0.0, 3600.0, 721)
        truth = float(np.min(2 * true_torque(250.0, grid, "uphill", drum=d) / t_req))
        p = risk.brake_margin_percentiles
        covered += p["p5"] <= truth <= p["p95"]
    assert covered >= len(cases) - 1


def test_the_gap_is_held_with_its_spread_unless_freed_or_its_effect_is_fitted():
    """gap_m is never freed by the automatic choice (torque logs cannot tell it from μ_d): it is held with its
    spread, which widens μ_d's interval; --free frees it; a fitted installation_gap effect replaces its prior."""
    from rollaway.effects import get_effect
    from rollaway.identify.calibrate import calibrate
    from rollaway.identify.drum import predictive_covariance
    data = generate(seed=21)
    dc = calibrate_drum(data)
    e = dc.entries["gap_m"]
    assert e.status == "fixed" and e.value == 0.0 and e.prior_sd == pytest.approx(6e-4)
    assert e.confounded_with == ["mu_drum"] and "gap_m" not in dc.free
    with_gap = predictive_covariance(dc.fit, dc.fixed_priors())
    without = predictive_covariance(dc.fit, {k: v for k, v in dc.fixed_priors().items() if k != "gap_m"})
    assert with_gap.stderr["mu_drum"] > 2.0 * without.stderr["mu_drum"]
    assert with_gap.stderr["gap_m"] <= 6e-4
    fit = calibrate(data, [get_effect("installation_gap")], dc.plan, start=dc.fit.values)
    assert "gap_m" not in predictive_covariance(fit, dc.fixed_priors()).names
    assert "gap_m" in calibrate_drum(data, free=["mu_drum", "gap_m"]).free
