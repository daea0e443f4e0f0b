"""rollaway.identify.predictive_set: what a diagnosis hands the road bands, on data of the independent generator
(tests/identify/bench_generator.py)."""
import numpy as np

from rollaway.identify.calibrate import calibrate
from rollaway.identify.predictive_set import attach_predictive, has_per_test_values, has_shape_free, interval_words
from tests.identify.bench_generator import generate


def test_a_competitor_is_excluded_for_per_test_effects_only_not_for_each_tests_start_temperature():
    data = generate([], seed=3, forces=np.linspace(180.0, 360.0, 3))
    assert not has_per_test_values(calibrate(data, ["lining_creep"]))
    assert has_per_test_values(calibrate(data, ["torque_zero_offset"]))


def test_the_chosen_fit_gets_its_record_and_competitors_their_own_weights_and_records():
    """A lining creep, 5-min, 3 forces both ways: creep in catalogue form is chosen; the drum alone is far behind
    in BIC and is ruled out, creep's shape-free form competes (its own record, its weight); a zero offset per test
    never competes (its held-out score refits each held-out test's own offset)."""
    from rollaway.identify.diagnose import diagnose
    from rollaway.identify.shape import form_rivals
    data = generate(["creep_exponential"], sampling="5min", seed=31, forces=np.linspace(180.0, 360.0, 3))
    d = diagnose(data)
    assert d.verdict == "lining_creep"
    data = d.data                                      # the copy that carries the noise model (sample weights)
    refined, drum = d.refined, d.drum
    forms = form_rivals(data, refined, drum.plan)
    offset = calibrate(data, ["torque_zero_offset"], drum.plan)
    attach_predictive(data, refined, [d.baseline, offset], 1, drum, forms=forms)
    rec = refined.fit_info["predictive"]
    assert rec["model_error_rel_sd"] >= 0 and rec["tested_hand_force_N"] == [180.0, 360.0]
    alts = refined.fit_info["alternatives"]
    assert alts and all(f is not offset and f is not d.baseline for _, f in alts)
    assert all(has_shape_free(f) and "predictive" in f.fit_info and f.covariance is not None for _, f in alts)
    assert 0.0 < sum(w for w, _ in alts) < 1.0
    line = interval_words(refined, drum, alts)
    assert line.startswith("Parameter intervals count") and "lining_creep_shape" in line and "the rest" in line
