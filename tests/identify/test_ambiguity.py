"""rollaway.identify.ambiguity: the held-out comparison against its closed form, which rivals are named,
and the test that would tell two calibrated models apart (on data the model code did not make)."""
import json
from types import SimpleNamespace

import numpy as np
import pytest

from rollaway.identify.ambiguity import (HELDOUT_SE, INDISTINGUISHABLE_BIC, alternative_words, heldout_difference, rivals,
                                         verdict_line)


def _fit(res_torque, tests=8):
    """A stand-in fit without free parameters (held-out residuals = residuals), σ = 1, temperatures exact."""
    n = len(res_torque)
    d = SimpleNamespace(test_index=np.repeat(np.arange(tests), n // tests), n_tests=tests, drum_temp_C=np.zeros(n),
                        torque_Nm=np.zeros(n), temp_sigma_C=np.ones(n), torque_sigma_Nm=np.ones(n))
    pred = SimpleNamespace(drum_temp_C=np.zeros(n), torque_Nm=np.asarray(res_torque, float))
    return SimpleNamespace(data=d, prediction=pred, jacobian=np.zeros((2 * n, 0)), names=[])


def test_heldout_difference_is_the_paired_log_score_difference_with_its_standard_error():
    rng = np.random.default_rng(0)
    a, b = rng.normal(0, 1.3, 80), rng.normal(0, 1.0, 80)
    delta, se = heldout_difference(_fit(a), _fit(b))
    sa = np.bincount(np.repeat(np.arange(8), 10), a * a)
    sb = np.bincount(np.repeat(np.arange(8), 10), b * b)
    d = -0.5 * (sb - sa)
    assert delta == pytest.approx(d.sum()) and se == pytest.approx(np.sqrt(8 * d.var(ddof=1)))


def test_the_paired_standard_error_is_calibrated_under_equal_models():
    """Two equally good models: |Δ| > 2 SE in about 5 % of 400 data sets (a t-ish statistic on 20 tests;
    0.02–0.12 allowed)."""
    rng = np.random.default_rng(1)
    hits = 0
    for _ in range(400):
        delta, se = heldout_difference(_fit(rng.standard_normal(200), 20), _fit(rng.standard_normal(200), 20))
        hits += abs(delta) > HELDOUT_SE * se
    assert 0.02 <= hits / 400 <= 0.12, hits / 400


def _cand(name, dbic, res, cv=1.0):
    return SimpleNamespace(effect=name, delta_bic=dbic, cv_score=cv, fit=_fit(res))


def test_rivals_need_close_evidence_or_a_disagreeing_heldout_test():
    rng = np.random.default_rng(2)
    r = rng.standard_normal(80)
    best = _cand("friction_temperature", -60.0, r)
    close = _cand("modulus_temperature", -60.0 + INDISTINGUISHABLE_BIC / 2, r + 0.01 * rng.standard_normal(80))
    far_worse = _cand("lining_creep", -30.0, 3 * r)                  # BIC and held-out both prefer the best
    disagree = _cand("cable_relaxation", -40.0, 0.5 * r)              # BIC prefers best, held-out the other
    weak = _cand("shoe_thermal_lag", -5.0, 0.5 * r)                   # does not pass the BIC threshold at all
    out = rivals(best, [best, close, far_worse, disagree, weak], -10.0)
    names = [o["effects"][0] for o in out]
    assert names == ["modulus_temperature", "cable_relaxation"]
    assert "disagrees" in out[1]["why"] and out[0]["delta_bic"] == pytest.approx(INDISTINGUISHABLE_BIC / 2)


def test_a_candidate_short_of_the_threshold_is_a_rival_only_where_the_heldout_tests_prefer_it():
    """Below WEAK_BIC (strong evidence against the drum alone) but short of the selection's threshold: a rival where
    the held-out prediction prefers it to the verdict, never for a close BIC alone; above WEAK_BIC, never."""
    from rollaway.identify.ambiguity import WEAK_BIC
    rng = np.random.default_rng(3)
    r = rng.standard_normal(80)
    best = _cand("lining_creep", -14.0, r)
    preferred = _cand("friction_temperature", WEAK_BIC - 0.2, 0.6 * r, cv=None)   # BIC 7.8 worse, predicts better
    close_only = _cand("modulus_temperature", -9.0, 1.6 * r, cv=None)             # BIC 5 worse, predicts worse
    faint = _cand("cable_relaxation", WEAK_BIC + 1.5, 0.5 * r, cv=None)          # evidence too weak to be a rival
    out = rivals(best, [best, preferred, close_only, faint], -10.0)
    assert [o["effects"][0] for o in out] == ["friction_temperature"]
    assert "disagrees" in out[0]["why"]


def test_verdict_line_names_every_alternative_and_the_test():
    alts = [{"effects": ["modulus_temperature"], "tell_apart": {"words": "a test facing uphill at 450 N would"}}]
    line = verdict_line("friction_temperature", alts)
    assert line.startswith("friction_temperature or modulus_temperature: these data cannot tell them apart; a test")
    assert verdict_line("none", []) == "none"
    assert verdict_line("none", [], structure=True).startswith("none: structure remains that no catalogue effect")


def test_two_closest_forms_the_data_separate_are_not_called_indistinguishable():
    """Two closest effects that both leave structure are named as pointers; where their better forms' BIC lie far
    apart the line says the data separate them (and which is nearer) instead of proposing a test to do it."""
    def alts(dbic_a, dbic_b):
        tell = {"words": "a test facing uphill at 405 N would", "tested_difference_Nm": 376.0}
        return [{"kind": "closest", "effects": ["friction_temperature"], "form_delta_bic": dbic_a, "tell_apart": tell,
                 "why": "ΔBIC"},
                {"kind": "closest", "effects": ["nonlinear_lining_stiffness"], "form_delta_bic": dbic_b, "why": "ΔBIC",
                 "tell_apart": tell}]
    near = verdict_line("none", alts(-84.0, -84.0 + INDISTINGUISHABLE_BIC - 0.5))
    assert "these data cannot tell them apart; a test facing uphill" in near, near
    far = verdict_line("none", alts(-83.6, -32.5))
    assert "cannot tell" not in far and "a test facing" not in far, far
    assert "these data tell them apart (BIC 51.1 apart; torques up to 376 N·m apart" in far, far
    assert far.endswith("friction_temperature is the nearer"), far
    assert "these data tell them apart" in alternative_words("none", alts(-83.6, -32.5))[0]


def test_a_form_bic_prefers_far_beyond_the_heldout_supported_one_is_named_beside_it_not_drawn():
    """With few tests each one left out is an extrapolation: a closest form the held-out tests support is joined by
    one that BIC prefers by more than INDISTINGUISHABLE_BIC — flagged as such, out of the bands, and the line says
    which evidence prefers which; one within that margin, or worse, is not added."""
    from rollaway.identify.ambiguity import _bic_beyond_heldout
    forms = {"drum_radial_contraction": (None, -170.0, False), "modulus_temperature": (None, -236.0, False),
             "shoe_thermal_lag": (None, -95.0, False), "friction_temperature": (None, -174.0, False)}
    cands = {n: _cand(n, f[1], np.zeros(16)) for n, f in forms.items()}
    supported = [cands["drum_radial_contraction"]]
    added = _bic_beyond_heldout(supported, list(cands.values()), forms)
    assert [c.effect for c in added] == ["modulus_temperature"]          # −174 is within 6 of −170: not added
    assert _bic_beyond_heldout([], list(cands.values()), forms) == []
    assert _bic_beyond_heldout(supported + [cands["shoe_thermal_lag"]], list(cands.values()), forms) == []   # full
    tell = {"words": "a test facing uphill at 405 N would", "tested_difference_Nm": 129.0}
    line = verdict_line("none", [
        {"kind": "closest", "effects": ["drum_radial_contraction"], "form_delta_bic": -170.0, "tell_apart": tell,
         "why": "ΔBIC"},
        {"kind": "closest", "effects": ["modulus_temperature"], "form_delta_bic": -236.0, "tell_apart": tell,
         "why": "ΔBIC", "bands": False}])
    assert "BIC prefers modulus_temperature (lower by 66.0), the held-out tests drum_radial_contraction" in line, line
    assert "is the nearer" not in line, line


def test_the_verdict_line_sets_every_named_effect_against_an_alternative_that_replaces_one_of_them():
    named = ["friction_temperature", "cable_relaxation"]
    alts = [{"effects": ["friction_temperature", "shoe_thermal_lag"], "why": "with a spline in time_s …",
             "tell_apart": {"words": "a test held 3600 s would"}}]
    line = verdict_line("friction_temperature", alts, named=named)
    assert line.startswith("friction_temperature + cable_relaxation or friction_temperature + shoe_thermal_lag: ")
    assert verdict_line("friction_temperature", [], named=named) == "friction_temperature + cable_relaxation"
    words = alternative_words("friction_temperature", alts, named)
    assert words[0].startswith("friction_temperature + cable_relaxation or friction_temperature + shoe_thermal_lag")


def test_friction_and_modulus_on_one_direction_are_named_together_with_the_direction_as_the_test():
    """A lining modulus falling with temperature, tested facing downhill only at two forces: friction falling
    with temperature fits as well (they differ only through the self-energising factor, which one direction
    does not show).  In most of 4 seeds both are named, and the separating test is the other direction."""
    from rollaway.identify.diagnose import diagnose
    from tests.identify.bench_generator import generate
    both = 0
    for seed in range(4):
        d = diagnose(generate(["modulus_linear"], sampling="5min", seed=300 + seed, directions=("downhill",),
                              forces=[200, 300]))
        names = {d.verdict} | {e for a in d.alternatives for e in a["effects"]}
        if {"friction_temperature", "modulus_temperature"} <= names:
            both += 1
            alt = next(a for a in d.alternatives if set(a["effects"]) & {"friction_temperature", "modulus_temperature"})
            assert alt["tell_apart"]["factor"] == "direction" and alt["tell_apart"]["test"]["direction"] == "uphill"
            assert alt["tell_apart"]["noise_sigmas"] > 3 > alt["tell_apart"]["tested_difference_Nm"] / 8.0
            assert "cannot tell them apart" in d.summary().splitlines()[0]
            assert {"effects", "delta_bic", "tell_apart"} <= set(d.as_dict()["alternatives"][0])
            saved = {tuple(f.effects) for _, f in d.refined.fit_info["alternatives"]}
            assert tuple(alt["effects"]) in saved                 # the bands carry it
    assert both >= 2, both


def test_a_form_outside_the_catalogue_names_the_closest_effects_and_clean_data_name_none():
    """A sigmoid modulus drop (a form the catalogue lacks) at 1-min on 2–4 hand forces: where structure remains,
    the verdict stays ``none`` and the closest catalogue effects are flagged (kind "closest", ≤ 2), the right
    physics among them in most of 6 seeds — or the verdict names it in form "partial"; the saved model's bands
    carry them.  Clean data from the same
    generator flag nothing in 6 seeds."""
    from rollaway.identify.diagnose import diagnose
    from tests.identify.bench_generator import generate
    hits = structured = 0
    for seed in range(6):
        d = diagnose(generate(["modulus_sigmoid"], sampling="1min", seed=410 + seed, n_forces=2 + seed % 3,
                              mu=0.32 + 0.02 * seed))
        if d.verdict == "modulus_temperature" and d.effects[0]["form"] == "partial":
            structured, hits = structured + 1, hits + 1          # the right physics named, its form marked partial
            continue
        if d.verdict != "none" or not d.remaining_structure or not any(
                c.delta_bic < -10 and c.cv_score is not None and c.cv_score < d.baseline_cv for c in d.candidates):
            continue                                          # no structure, or no candidate points anywhere
        structured += 1
        assert 1 <= len(d.alternatives) <= 2 and all(a["kind"] == "closest" for a in d.alternatives)
        hits += "modulus_temperature" in {a["effects"][0] for a in d.alternatives}
        assert d.summary().startswith("verdict: none: structure remains")
        j = json.loads(d.to_json())                  # the closest effects' shape-free fits stay out of the JSON
        assert [a["effects"] for a in j["alternatives"]] == [a["effects"] for a in d.alternatives]
        assert not any(k.endswith("fit") for a in j["alternatives"] for k in a)
        saved = {tuple(f.effects) for _, f in d.refined.fit_info["alternatives"]} | {tuple(d.refined.effects)}
        assert all(tuple(a["effects"]) in saved for a in d.alternatives)
    assert structured >= 3 and hits >= structured - 1, (structured, hits)
    for seed in range(6):
        d = diagnose(generate([], sampling="1min", seed=430 + seed, n_forces=2 + seed % 3))
        assert d.verdict == "none" and not d.alternatives


def test_a_none_verdict_names_a_suggested_effect_as_a_weak_alternative_and_clean_data_none():
    """Lining creep tested downhill only, at two forces: the drum's eq. (24) slope and offset imitate part of it and
    the verdict stays "none"; refitted with those held, lining_creep is suggested (BIC, held-out) and named as a
    weak alternative with the test that would settle it.  Clean data of the same design get no alternative."""
    from rollaway.identify.ambiguity import WEAK_BIC, WEAK_BIC_HELD
    from rollaway.identify.diagnose import diagnose
    from rollaway.identify.selection import BIC_THRESHOLD
    from tests.identify.bench_generator import generate
    hits = 0
    for seed in range(70, 79):
        d = diagnose(generate(["creep_exponential"], sampling="5min", seed=seed, directions=("downhill",), n_forces=2))
        weak = [a for a in d.alternatives if a.get("weak")]
        assert not weak or d.verdict == "none"
        assert all(a["delta_bic"] < (WEAK_BIC_HELD if a["held"] else WEAK_BIC)
                   and (a["heldout_elpd"] > 0 or a["delta_bic"] < BIC_THRESHOLD)
                   and set(a["held"]) <= set(d.drum.plan.free) and a["tell_apart"]["words"] for a in weak)
        hits += any(a["effects"] == ["lining_creep"] for a in weak)
        if weak:
            assert verdict_line(d.verdict, d.alternatives).startswith("none (suggested, not established: ")
    assert hits >= 4
    for seed in range(70, 78):
        d = diagnose(generate([], sampling="5min", seed=seed, directions=(("uphill",), ("downhill",))[seed % 2],
                              n_forces=2))
        assert d.verdict == "none" and not d.alternatives, d.summary()


def test_a_loss_the_drum_imitated_is_suggested_on_positive_evidence_and_empty_campaigns_stay_bare():
    """A logarithmic cable creep (a form the catalogue lacks) on 5-min tests facing one way: the bare drum frees
    eq. (24)'s slope and offset to imitate it, and the verdict stays "none".  Where cable_relaxation's fit holds
    them, positive evidence (ΔBIC below WEAK_BIC_HELD) with a better held-out prediction suggests it: the truth is
    the verdict or a flagged alternative in at least 4 of the first 12 such held-out campaigns (2 with strong
    evidence required whatever was held).  The campaigns with nothing hidden, at the same places in the same
    suite, flag nothing."""
    from rollaway.identify.ambiguity import WEAK_BIC, WEAK_BIC_HELD
    from rollaway.identify.diagnose import diagnose
    from tests.identify.heldout_names import HIDDEN, campaign, judge
    cable = [i for i in range(144) if HIDDEN[i % len(HIDDEN)] == "cable_log"]
    empty = [i for i in range(144) if HIDDEN[i % len(HIDDEN)] is None]
    assert len(cable) == len(empty) == 12
    hits = 0
    for i in cable:
        hidden, data = campaign(i)
        d = diagnose(data)
        hits += judge(hidden, d)["right_or_alternative"]
        for a in (a for a in d.alternatives if a.get("weak")):
            assert a["delta_bic"] < (WEAK_BIC_HELD if a["held"] else WEAK_BIC) and a["heldout_elpd"] > 0
    assert hits >= 4, hits
    for i in empty:
        hidden, data = campaign(i)
        d = diagnose(data)
        assert d.verdict == "none" and not d.alternatives, (i, d.summary())


def test_a_loss_the_free_drum_imitates_beyond_a_bic_drop_is_still_examined_and_needs_a_clear_heldout_gain():
    """Where the free drum imitates a logarithmic cable creep so well that cable_relaxation does not even lower BIC
    against it at step 1 (ΔBIC ≥ 0), its fit with eq. (24)'s slope held is still examined: two held-out campaigns
    (one direction, 5-min) name it as the weak alternative of "none", with a held-out gain beyond HELDOUT_SE
    standard errors; without the change they came out a bare "none"."""
    from rollaway.identify.diagnose import diagnose
    from tests.identify.heldout_names import campaign, judge
    for i in (203, 215):
        hidden, data = campaign(i)
        d = diagnose(data)
        step1 = {c["effect"]: c["delta_bic"] for c in d.as_dict()["candidates"]}
        assert hidden == "cable_log" and step1["cable_relaxation"] >= 0.0, (i, step1)
        assert judge(hidden, d)["right_or_alternative"] and d.verdict == "none", (i, d.summary())
        weak = [a for a in d.alternatives if a["effects"] == ["cable_relaxation"]][0]
        assert weak["held"] and weak["heldout_elpd"] > HELDOUT_SE * weak["heldout_se"], weak


def test_autocorrelated_residuals_shrink_the_bic_difference_a_rival_must_beat():
    """A rival 12 BIC behind the verdict is not named on independent residuals, but is where the verdict's residuals
    are autocorrelated (variance inflation 3: the BIC difference counts three times the samples the data hold)."""
    rng = np.random.default_rng(7)
    r = rng.standard_normal(80)
    best = _cand("friction_temperature", -60.0, r)
    other = _cand("modulus_temperature", -48.0, r + 0.01 * rng.standard_normal(80))
    assert rivals(best, [best, other], -10.0) == []
    out = rivals(best, [best, other], -10.0, inflation=3.0)
    assert [o["effects"] for o in out] == [["modulus_temperature"]] and out[0]["delta_bic"] == pytest.approx(4.0)


def test_structure_with_no_candidate_predicting_better_still_names_the_closest_and_says_so():
    """Three tests facing one way (a creep on a drum with its own eq. (24) offset, 1-min): each test left out is an
    extrapolation, no candidate predicts held-out tests better than the drum alone, yet structure remains.  The
    candidates the BIC points at are still flagged "closest" — saying the held-out prediction does not support them —
    rather than a bare "none"; clean data of the same design flag nothing."""
    from rollaway.identify.diagnose import diagnose
    from tests.identify.bench_generator import OTHER_DRUMS, generate
    named = 0
    for seed in range(4):
        data = generate(["creep_exponential"], sampling="1min", seed=9162 + seed, drum=OTHER_DRUMS["eq24_own"],
                        forces=np.linspace(170.0, 330.0, 3), directions=("downhill",))
        d = diagnose(data)
        if d.verdict != "none" or not d.remaining_structure:
            continue
        assert 1 <= len(d.alternatives) <= 2 and all(a["kind"] == "closest" for a in d.alternatives)
        if not any(c.cv_score is not None and c.cv_score < d.baseline_cv for c in d.candidates
                   if c.delta_bic < -10):
            assert all("does not support it" in a["why"] for a in d.alternatives)
            named += 1
    assert named >= 1
    for seed in range(4):
        d = diagnose(generate([], sampling="1min", seed=9172 + seed, drum=OTHER_DRUMS["eq24_own"],
                              forces=np.linspace(170.0, 330.0, 3), directions=("downhill",)))
        assert d.verdict == "none" and not d.alternatives and not d.remaining_structure


def test_the_bar_for_a_heldout_preference_grows_as_tests_get_few():
    """Two standard errors of a paired difference over n tests stand for a normal tail; with few tests the standard
    error is itself uncertain (Student's t, n − 1 dof)."""
    from rollaway.identify.ambiguity import SMALL_ELPD, preference_margin
    fit = lambda n: SimpleNamespace(data=SimpleNamespace(n_tests=n))     # noqa: E731
    assert preference_margin(fit(2), 10.0) == pytest.approx(139.0, rel=0.01)
    assert preference_margin(fit(4), 10.0) == pytest.approx(33.1, rel=0.01)
    assert 20.0 < preference_margin(fit(40), 10.0) < 21.0
    assert preference_margin(fit(8), 0.1) == SMALL_ELPD and preference_margin(fit(1), 1.0) == float("inf")


def test_two_tests_facing_one_way_name_the_temperature_laws_they_cannot_separate():
    """A linear modulus drop on a drum with its own eq. (24) law, two hand forces facing uphill at 5-min: leaving one
    of two tests out is an extrapolation, so held-out scores cannot rule a temperature law out; the truth must be the
    verdict or a flagged alternative in at least 7 of 8 seeds."""
    from rollaway.identify.diagnose import diagnose
    from tests.identify.bench_generator import OTHER_DRUMS, generate
    hits = 0
    for seed in range(8):
        d = diagnose(generate(["modulus_linear"], sampling="5min", seed=8100 + seed, forces=[200.0, 330.0],
                              directions=("uphill",), drum=OTHER_DRUMS["eq24_own"]))
        hits += d.verdict == "modulus_temperature" or any("modulus_temperature" in a["effects"] for a in d.alternatives)
        assert len(d.effects) <= 1 and len(d.alternatives) <= 2
    assert hits >= 7, hits
    from tests.identify.heldout_names import campaign        # held-out campaign 101: both laws predicted the other
    hidden, data = campaign(101)                             # test worse than the drum alone, and were not named
    d = diagnose(data)
    assert hidden == "modulus_linear" and d.data.n_tests == 2
    assert "modulus_temperature" in [d.verdict] + [e for a in d.alternatives for e in a["effects"]]


def test_a_two_effect_verdict_names_the_set_with_the_temperature_law_it_cannot_tell_apart():
    """A cable relaxation with a linear modulus drop at 1-min (12 designs of the two-effect suite): friction and
    modulus falling with temperature trade places beside the cable; the true set must be the verdict or a flagged
    alternative (each a two-effect set, the verdict line naming both sets) in at least 11 of 12."""
    from rollaway.identify.diagnose import diagnose
    from tests.identify.bench_generator import generate
    from tests.identify.validate_diagnose import kwargs_for
    truth, hits = {"cable_relaxation", "modulus_temperature"}, 0
    for i in range(12):
        d = diagnose(generate(("cable_exponential", "modulus_linear"), sampling="1min", seed=2000 + i, **kwargs_for(i)))
        got = {e["effect"] for e in d.effects}
        hits += got == truth or any(set(a["effects"]) == truth for a in d.alternatives)
        if len(got) == 2 and d.alternatives:
            assert all(len(a["effects"]) == 2 and a["kind"] == "rival" for a in d.alternatives)
            assert d.as_dict()["verdict_line"].startswith(" + ".join(e["effect"] for e in d.effects) + " or ")
    assert hits >= 11, hits


def test_a_none_verdict_names_an_effect_that_clears_the_verdicts_bar_once_the_drum_stops_imitating_it():
    """Held-out campaign 38 (independent generator): exponential lining creep, two tests facing one way, 1-min
    samples.  Against the free drum creep lowers BIC by 6.8 only (the eq. (24) slope and offset imitate it); with
    those held it lowers BIC by 13.5 — beyond the verdict's own bar — and the two held-out tests predict equally well
    (they cannot tell which).  It is named as a weak alternative ("suggested, not established"), not dropped."""
    from rollaway.identify.diagnose import diagnose
    from rollaway.identify.selection import BIC_THRESHOLD
    from tests.identify.heldout_names import campaign
    hidden, data = campaign(38)
    assert hidden == "creep_exponential"
    d = diagnose(data)
    weak = [a for a in d.alternatives if a.get("weak")]
    assert d.verdict == "none" and [a["effects"] for a in weak][:1] == [["lining_creep"]], d.summary()
    assert weak[0]["delta_bic"] < BIC_THRESHOLD and "imitates it" in weak[0]["why"]
    assert verdict_line(d.verdict, d.alternatives).startswith("none (suggested, not established: lining_creep")


def test_a_shape_free_form_that_clears_the_structure_ranks_its_effect_among_the_closest():
    """A friction that fades above 150 °C (a hinge the catalogue lacks; its friction law is linear), 1-min, one
    direction, hot and cool starts, five drums: where the verdict is "none" with structure left, the stiffness law's
    three parameters can bend further than a linear friction and win on BIC, yet only a function of temperature
    clears the structure.  The shape-free fits rank friction_temperature among the closest (≤ 2) in every such
    campaign, flagged as clearing it, and the bands carry those shape-free fits.  Where the pair with the modulus law
    is reached beside the runner-up (rollaway.identify.lookahead) and fails its own evidence, friction is named with
    the structure left said (2 of the 12)."""
    from rollaway.identify.diagnose import diagnose
    from tests.identify.bench_generator import OTHER_DRUMS, generate
    drums = [{}] + list(OTHER_DRUMS.values())
    structured = clears = named = 0
    for seed in range(600, 612):
        data = generate(["friction_fade_above"], sampling="1min", seed=seed, drum=drums[seed % len(drums)],
                        directions=(("downhill",), ("uphill",))[seed % 2], n_forces=3 + seed % 2,
                        t0_range=(110.0, 290.0))
        d = diagnose(data)
        if d.verdict == "friction_temperature" and d.remaining_structure:     # named, the structure said
            named += 1
            assert "modulus_temperature" in {e for a in d.alternatives for e in a["effects"]}, d.summary()
            continue
        if d.verdict != "none" or not d.remaining_structure:
            continue
        structured += 1
        assert 1 <= len(d.alternatives) <= 2 and all(a["kind"] == "closest" for a in d.alternatives)
        assert "friction_temperature" in {a["effects"][0] for a in d.alternatives}, d.summary()
        flagged = [a for a in d.alternatives if a.get("clears")]
        clears += bool(flagged)
        if flagged:
            assert "shape-free, " in d.summary().splitlines()[0]
            saved = [f for _, f in d.refined.fit_info["alternatives"]]
            assert all(any(f is a["shape_fit"] or f.effects == a["shape_fit"].effects for f in saved) for a in flagged)
    assert structured + named >= 6 and clears >= structured - 2, (structured, named, clears)
