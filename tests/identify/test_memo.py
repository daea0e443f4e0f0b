"""Fits kept for one diagnosis (rollaway.identify.memo): a repeated call returns the first call's numbers without
fitting again, a call that differs in anything that sets its result is fitted, and nothing is kept outside."""
import numpy as np
import pytest

from rollaway.effects import get_effect
from rollaway.identify import fitting, memo
from rollaway.identify.calibrate import calibrate
from rollaway.identify.shape import flexible_effect
from rollaway.identify.workers import fit_all
from tests.identify.bench_generator import generate


@pytest.fixture(scope="module")
def data():
    return generate(["creep_exponential"], sampling="5min", seed=21, forces=np.linspace(180.0, 360.0, 3))


@pytest.fixture
def solves(monkeypatch):
    count = {"n": 0}
    orig = fitting.Problem.solve

    def counted(self, *a, **k):
        count["n"] += 1
        return orig(self, *a, **k)
    monkeypatch.setattr(fitting.Problem, "solve", counted)
    return count


def test_a_repeated_fit_is_kept_and_a_different_one_is_not(data, solves):
    with memo.fit_memo():
        a = calibrate(data, ["lining_creep"])
        b = calibrate(data, ["lining_creep"])
        assert solves["n"] == 1 and b is not a and b.values.keys() == a.values.keys()
        assert all(np.array_equal(a.values[k], b.values[k]) for k in a.values) and a.bic == b.bic
        b.fit_info["note"] = 1                       # a copy's notes stay its own
        assert "note" not in a.fit_info and "note" not in calibrate(data, ["lining_creep"]).fit_info
        calibrate(data, ["lining_creep"], start={"mu_drum": 0.3})          # another start
        calibrate(data, ["lining_creep"], max_iterations=1)                # a budget that binds
        calibrate(data, ["cable_relaxation"])                              # another effect
        calibrate(data.subset(np.ones(len(data), bool)), ["lining_creep"])  # another data set
        assert solves["n"] == 5
        knots = [flexible_effect(get_effect("lining_creep"), data.time_s) for _ in range(2)]
        calibrate(data, [knots[0]])
        calibrate(data, [knots[1]])                  # the same base and knots, another class object: kept
        assert solves["n"] == 6
        calibrate(data, [flexible_effect(get_effect("lining_creep"), data.time_s[::2] * 0.7)])   # other knots
        assert solves["n"] == 7
    calibrate(data, ["lining_creep"])
    calibrate(data, ["lining_creep"])
    assert solves["n"] == 9                          # outside: nothing kept


def test_a_batch_sends_what_is_not_kept_once(data, monkeypatch):
    sent = []
    from rollaway.identify import workers
    orig = workers._run
    monkeypatch.setattr(workers, "_run", lambda d, calls: sent.append(len(calls)) or orig(d, calls))
    with memo.fit_memo():
        first = calibrate(data, ["lining_creep"])
        out = fit_all(data, [(["lining_creep"], None, {}), (["cable_relaxation"], None, {}),
                             (["cable_relaxation"], None, {})])
        assert sent == [1]                           # the kept fit is not sent, the twin is sent once
        assert out[0].bic == first.bic and out[1].bic == out[2].bic and out[1] is not out[2]
        assert fit_all(data, [(["cable_relaxation"], None, {})])[0].bic == out[1].bic and sent == [1, 0]


def test_the_same_model_fitted_before_is_found_whatever_its_start_and_budget(data):
    """memo.same_model: the kept fit of those effects under that plan with the lowest BIC — a short fit from a poor
    start and a full one from another start are the same model; other effects or another plan are not, and outside
    a diagnosis nothing is kept."""
    from rollaway.identify.model import DrumPlan
    plan = DrumPlan(None, ("mu_drum", "heat_transfer_W_m2K"))
    assert memo.same_model(data, ["lining_creep"], plan) is None
    with memo.fit_memo():
        assert memo.same_model(data, ["lining_creep"], plan) is None
        short = calibrate(data, ["lining_creep"], plan, start={"lining_creep.relaxed_fraction": 0.5},
                          max_iterations=1)
        full = calibrate(data, ["lining_creep"], plan)
        assert full.bic < short.bic
        found = memo.same_model(data, ["lining_creep"], plan)
        assert found is not None and found.bic == full.bic and found.values == full.values
        assert memo.same_model(data, ["cable_relaxation"], plan) is None
        assert memo.same_model(data, ["lining_creep"], DrumPlan(None, ("mu_drum",))) is None


def test_an_answer_kept_by_tag_is_recalled_for_the_same_inputs_only(data):
    k = memo.key(data, ["lining_creep", "friction_temperature"], None, {"start": {"mu_drum": 0.3}})
    assert k is None and memo.recall("search", k) is memo.ABSENT          # nothing is kept outside a diagnosis
    with memo.fit_memo():
        k = memo.key(data, ["lining_creep", "friction_temperature"], None, {"start": {"mu_drum": 0.3}})
        other = memo.key(data, ["lining_creep", "friction_temperature"], None, {"start": {"mu_drum": 0.31}})
        assert memo.recall("search", k) is memo.ABSENT
        memo.remember("search", k, None)                  # None is an answer too
        assert memo.recall("search", k) is None
        assert memo.recall("another search", k) is memo.ABSENT and memo.recall("search", other) is memo.ABSENT
    assert memo.recall("search", k) is memo.ABSENT


def test_a_second_effect_sought_twice_beside_the_same_first_is_sought_once(data, solves, monkeypatch):
    from rollaway.identify import partner
    searches = []
    real = partner._beside_reformed
    monkeypatch.setattr(partner, "_beside_reformed", lambda *a: searches.append(a[4]) or real(*a))
    with memo.fit_memo():
        first = calibrate(data, ["lining_creep"])
        names = ["friction_temperature", "cable_relaxation"]
        once = partner.beside_reformed(data, None, "lining_creep", first, names)
        n = solves["n"]
        again = partner.beside_reformed(data, None, "lining_creep", calibrate(data, ["lining_creep"]), names)
        assert solves["n"] == n and len(searches) == 1    # the same first at the same values: no search, no fit
        assert (once is None) == (again is None) and (once is None or once[:1] == again[:1])
        partner.beside_reformed(data, None, "lining_creep", first, names[:1])    # other candidates: sought again
        partner.beside_reformed(data, None, "lining_creep", first, names, departures=("gap_m",))
        assert len(searches) == 3
    partner.beside_reformed(data, None, "lining_creep", first, names)            # outside a diagnosis: no memo
    assert len(searches) == 4


def test_a_smaller_budget_that_never_bound_is_served_by_the_larger_fit_number_for_number(data, solves):
    """MINPACK stops on its budget only: a fit whose every pass ended below a smaller budget is that budget's fit
    too.  Inside a memo block the smaller-budget call gets it without fitting (the same numbers as fitted on its
    own, outside); a budget the larger fit's passes reached is fitted."""
    big = calibrate(data, ["lining_creep"])
    peak, k = big.fit_info["stages"][0]["peak_calls"], len(big.names) + 1
    assert 0 < peak < fitting.MAX_ITERATIONS * k
    loose, tight = peak // k + 1, max(peak // k, 1)          # loose·k > peak ≥ tight·k
    assert loose < fitting.MAX_ITERATIONS and tight * k <= peak
    alone = {m: calibrate(data, ["lining_creep"], max_iterations=m) for m in (loose, tight)}
    solves["n"] = 0
    with memo.fit_memo():
        calibrate(data, ["lining_creep"])
        got = calibrate(data, ["lining_creep"], max_iterations=loose)
        assert solves["n"] == 1
        assert all(np.array_equal(got.values[n], alone[loose].values[n]) for n in got.values)
        assert got.bic == alone[loose].bic == big.bic
        bound = calibrate(data, ["lining_creep"], max_iterations=tight)
        assert solves["n"] == 2 and bound.bic == alone[tight].bic
