"""The fits' stacked evaluation (several value sets in one model call) gives the numbers of one call per set."""
import numpy as np
import pytest

from rollaway.effects import CATALOGUE, Effect, get_effect
from rollaway.effects.base import EffectParameter
from rollaway.identify import fitting
from rollaway.identify.calibrate import calibrate
from rollaway.identify.fitting import Problem, stack_copies
from rollaway.identify.model import BenchModel, ambient_varies
from tests.identify.bench_generator import generate


def _fit(data, effects, stacked: bool, monkeypatch):
    with monkeypatch.context() as m:
        if not stacked:
            m.setattr(fitting, "stack_copies", lambda data, copies: None)
        return calibrate(data, effects)


@pytest.mark.parametrize("seed,hidden,effects", [
    (1, ["cable_exponential"], ["cable_relaxation"]),
    (2, ["creep_power_law"], ["lining_creep", "shoe_thermal_lag"]),
    (3, ["zero_offset", "friction_linear"], ["torque_zero_offset", "friction_temperature"]),   # two families
    (4, ["radiation"], ["radiation_cooling"]),                           # a tabled cooling law, h and ε columns
    (5, ["radiation"], ["radiation_cooling"]),                           # ... towards a logged, drifting ambient
    (6, ["creep_exponential"], ["lining_creep"]),                        # eq. (10)'s ODE through a logged ambient
])
def test_stacked_fit_is_bit_identical_to_one_call_per_set(seed, hidden, effects, monkeypatch):
    """Stacked: the per-test families' steps and the Jacobian's difference quotients of the globals (each copy its
    own global values) are evaluated side by side; the fit is the one of one model call per value set."""
    data = generate(hidden, sampling="5min", seed=seed, n_forces=3, ambient_drift_C=6.0 if seed >= 5 else 0.0)
    assert ambient_varies(data) == (seed >= 5)
    a, b = (_fit(data, effects, s, monkeypatch) for s in (True, False))
    assert a.values.keys() == b.values.keys()
    for k in a.values:
        assert np.array_equal(np.asarray(a.values[k]), np.asarray(b.values[k])), k


def test_stacked_copies_are_tests_of_their_own():
    data = generate([], sampling="15min", seed=4, n_forces=2)
    s = stack_copies(data, 3)
    assert len(s) == 3 * len(data) and s.n_tests == 3 * data.n_tests
    assert np.array_equal(s.initial_temp_C, np.tile(data.initial_temp_C, 3))
    assert np.array_equal(s.test_index[len(data):2 * len(data)], data.test_index + data.n_tests)


class _Pooled(Effect):
    """A torque change read from a reduction over all samples: not elementwise (the default)."""
    name = "pooled_test_effect"
    parameters = (EffectParameter("k", "–", neutral=0.0, lower=-1.0, upper=1.0, initial=0.1),)

    def torque(self, state, torque_Nm, v):
        return torque_Nm * (1.0 + v["k"] * np.mean(state.time_s) / 3600.0)


@pytest.mark.parametrize("effects,stacks", [(["lining_creep"], True), (["radiation_cooling"], True),
                                            (["lining_creep", _Pooled()], False)])
def test_only_elementwise_effects_are_stacked(effects, stacks):
    """An effect that reads other samples (a mean over them) would see the other copies: it is not stacked."""
    data = generate([], sampling="15min", seed=5, n_forces=2)
    model = BenchModel(effects=effects)
    values = {**model.initial_values(), "initial_temp_C": data.test_initial_temp_C.copy()}
    w = np.ones(len(data))
    prob = Problem(model, data, model.parameter_names(), model.per_test_parameters(), values, w, w)
    assert (prob.stacked is not None) == stacks


@pytest.mark.parametrize("name", [n for n, e in CATALOGUE.items() if e.elementwise])
def test_an_elementwise_effect_gives_each_copy_its_own_numbers(name):
    """What ``elementwise = True`` promises: the model on stacked copies (other T_0, μ_d and effect values per
    copy, given per test) equals the model on each copy alone, bit for bit, at the effect's typical values."""
    data = generate(["creep_exponential"], sampling="15min", seed=6, n_forces=2)
    effect = get_effect(name)
    model = BenchModel(effects=[name])
    values = model.initial_values()
    values.update({f"{name}.{k}": x for k, x in effect.typical_values().items()})
    for p in effect.parameters:
        if p.per_test:
            values[f"{name}.{p.name}"] = np.linspace(-1.0, 1.0, data.n_tests) * effect.typical_values()[p.name]
    sets = [dict(values, initial_temp_C=data.test_initial_temp_C + dt) for dt in (0.0, 0.5, -3.0)]
    for k, p in ((f"{name}.{p.name}", p) for p in effect.parameters if not p.per_test):   # globals per copy too
        sets[1][k] = values[k] + 0.25 * (p.upper - values[k])
    sets[2]["mu_drum"] = values["mu_drum"] * 1.1
    stacked = {k: (np.concatenate([s[k] for s in sets]) if np.ndim(v) == 1 else
                   np.repeat([float(s[k]) for s in sets], data.n_tests) if np.ndim(v) == 0 and v is not None
                   and any(s[k] != v for s in sets) else v) for k, v in sets[0].items()}
    both = model.predict(stack_copies(data, 3), stacked)
    for channel in ("drum_temp_C", "lining_temp_C", "torque_Nm"):
        alone = np.concatenate([getattr(model.predict(data, s), channel) for s in sets])
        assert np.array_equal(getattr(both, channel), alone), channel


BRAKE = ("mu_drum", "u6_slope_m_per_N", "u6_offset_m", "shoe_arm_ratio", "heat_transfer_W_m2K")


@pytest.mark.parametrize("seed", [2, 3])
def test_a_misfit_fit_along_the_torque_scale_valley_settles_within_its_budget(seed):
    """A two-effect model in the wrong form (a lag and a linear modulus change for a quadratic friction and a
    sigmoid modulus drop) with the brake parameters free: μ_d, the arm ratio and the eq. (24) slope trade along a
    curved valley.  The fit stops in a few hundred residual calls where a fit with ten times the budget ends too
    (with MINPACK's growing column-norm scaling it crawled through 6 000–12 000 calls to the same BIC)."""
    from rollaway.identify.model import DrumPlan
    data = generate(["friction_quadratic", "modulus_sigmoid"], sampling="1min", seed=seed, n_forces=3)
    effects, plan = ["shoe_thermal_lag", "modulus_temperature"], DrumPlan(None, BRAKE)
    fit = calibrate(data, effects, plan)
    long = calibrate(data, effects, plan, max_iterations=10 * fitting.MAX_ITERATIONS)
    assert fit.fit_info["stages"][0]["nfev"] < 2000
    assert abs(fit.bic - long.bic) < 0.5


@pytest.mark.parametrize("seed,hidden,effects", [
    (0, ["friction_quadratic", "modulus_sigmoid"], ["friction_temperature"]),     # misfit: a large residual
    (1, ["creep_exponential"], ["lining_creep"]),                                   # the effect in its own form
])
def test_the_stopping_tolerance_settles_what_the_criteria_and_intervals_read(seed, hidden, effects, monkeypatch):
    """Stopped at TOLERANCE, a fit with the brake parameters free ends where a fit stopped at 1e-12 ends:
    BIC within 0.01 (the selection threshold is 10), every value within 0.05 of its standard error."""
    from rollaway.identify.model import DrumPlan
    data = generate(hidden, sampling="1min", seed=seed, n_forces=3, drum={"drum_radius_m": 0.100})
    plan = DrumPlan(None, BRAKE[:3] + BRAKE[4:])
    fit = calibrate(data, effects, plan)
    monkeypatch.setattr(fitting, "TOLERANCE", 1e-12)
    tight = calibrate(data, effects, plan)
    assert abs(fit.bic - tight.bic) < 0.01
    for name, e in tight.estimates.items():
        assert abs(fit.values[name] - e.value) <= 0.05 * e.stderr, name


@pytest.mark.parametrize("base", ["lining_creep", "friction_temperature", "radiation_cooling"])
def test_a_spline_gives_each_copy_its_own_numbers_with_its_ordinates_per_copy(base):
    """The flexible forms are elementwise too: ordinates that differ between stacked copies (a Jacobian's columns)
    give each copy the numbers it has alone."""
    from rollaway.effects.shape_free import spline_effect
    data = generate(["creep_exponential"], sampling="15min", seed=7, n_forces=2)
    flex = spline_effect(get_effect(base), [0.0, 900.0, 1800.0, 3600.0] if base != "friction_temperature"
                         else [20.0, 120.0, 220.0, 320.0])()
    model = BenchModel(effects=[flex])
    values = {**model.initial_values(), "initial_temp_C": data.test_initial_temp_C.copy()}
    sets = [dict(values) for _ in range(3)]
    sets[1][f"{flex.name}.c0"], sets[2][f"{flex.name}.c1"] = -0.1, 0.05
    stacked = {k: (np.concatenate([s[k] for s in sets]) if np.ndim(v) == 1 else
                   np.repeat([float(s[k]) for s in sets], data.n_tests) if any(s[k] != v for s in sets) else v)
               for k, v in sets[0].items()}
    both = model.predict(stack_copies(data, 3), stacked)
    for channel in ("drum_temp_C", "torque_Nm"):
        alone = np.concatenate([getattr(model.predict(data, s), channel) for s in sets])
        assert np.array_equal(getattr(both, channel), alone), channel
    assert not np.array_equal(both.torque_Nm[:len(data)], both.torque_Nm[len(data):2 * len(data)]) or \
        not np.array_equal(both.drum_temp_C[:len(data)], both.drum_temp_C[len(data):2 * len(data)])


class _NumbersOnly(Effect):
    """A plugin that says it is elementwise but reads its value as one number (``float``)."""
    name = "numbers_only_test_effect"
    elementwise = True
    parameters = (EffectParameter("k", "–", neutral=0.0, lower=-0.5, upper=0.5, initial=0.1),)

    def torque(self, state, torque_Nm, v):
        return torque_Nm * (1.0 + float(v["k"]))


def test_a_plugin_that_takes_its_values_as_numbers_only_is_fitted_one_call_per_set():
    """Its globals cannot be given per copy: the fit falls back to one call per value set, with the numbers of a fit
    that never stacked."""
    data = generate(["creep_exponential"], sampling="15min", seed=8, n_forces=2)
    fit = calibrate(data, [_NumbersOnly()])
    with pytest.MonkeyPatch.context() as m:
        m.setattr(fitting, "stack_copies", lambda data, copies: None)
        plain = calibrate(data, [_NumbersOnly()])
    assert fit.bic == plain.bic and fit.values["numbers_only_test_effect.k"] == plain.values["numbers_only_test_effect.k"]


def _exact_quotients(monkeypatch):
    """The fits' Jacobian from the exact projected residual at every point (a copy per family and point)."""
    monkeypatch.setattr(Problem, "linearised_profiles", lambda self, base, many: self.profiles(many))


@pytest.mark.parametrize("seed,hidden,effects", [
    (11, ["creep_power_law"], ["lining_creep"]),                                  # a form the catalogue lacks
    (12, ["friction_quadratic", "modulus_sigmoid"], ["modulus_temperature"]),      # misfit: a large residual
    (13, ["zero_offset", "friction_linear"], ["torque_zero_offset", "friction_temperature"]),   # two families
    (14, ["creep_exponential", "radiation"], ["lining_creep", "radiation_cooling"]),
    (15, ["cable_exponential"], ["cable_relaxation"]),
])
def test_kaufmans_jacobian_ends_the_fit_where_the_exact_quotients_do(seed, hidden, effects, monkeypatch):
    """Kaufman's Jacobian (Problem.linearised_profiles) drops only the term proportional to the projected
    residual: the fit with the brake parameters free ends at the BIC of the exact quotients' fit within 0.05 (the
    selection threshold is 10), every value within 0.02 of its standard error and every standard error within
    0.5 % — with fewer evaluations of the data, summed over the cases of a seed's drum."""
    from rollaway.identify.model import DrumPlan
    data = generate(hidden, sampling=("1min", "5min")[seed % 2], seed=seed, n_forces=3,
                    drum={"drum_radius_m": 0.095 + 0.002 * (seed % 5)})
    plan = DrumPlan(None, BRAKE[:3] + BRAKE[4:])
    fast = calibrate(data, effects, plan)
    with monkeypatch.context() as m:
        _exact_quotients(m)
        exact = calibrate(data, effects, plan)
    assert abs(fast.bic - exact.bic) < 0.05
    for name, e in exact.estimates.items():
        assert abs(fast.values[name] - e.value) <= 0.02 * e.stderr, name
        assert fast.estimates[name].stderr == pytest.approx(e.stderr, rel=5e-3), name
    rows = [f.fit_info["stages"][0]["nfev"] for f in (fast, exact)]
    assert rows[0] < rows[1]


def test_kaufmans_columns_are_the_exact_ones_where_the_model_fits():
    """For data the model fits (its own effect, noise only) the projected residual is small and the dropped term
    with it: each column of Kaufman's Jacobian is the exact quotient's to 2 % of its norm (measured: 0.1–0.4 %; a
    misfit model's, up to 13 %; the columns without the projection, 50–200 %)."""
    data = generate(["creep_exponential"], sampling="5min", seed=16, n_forces=3)
    fit = calibrate(data, ["lining_creep"])
    model = fit.model
    names, families = fit.names, model.per_test_parameters()
    w = 1.0 / np.full(len(data), 2.0)
    prob = Problem(model, data, names, families, dict(fit.values), w, w)
    base = dict(fit.values)
    steps = [1e-4 * (model.bounds(n)[1] - model.bounds(n)[0]) for n in names]
    many = [{**base, n: base[n] + h} for n, h in zip(names, steps)]
    f0 = prob.profile(base)[0]
    exact = [(r - f0) / h for r, h in zip(prob.profiles(many), steps)]
    prob.profile(base)
    fast = [(r - f0) / h for r, h in zip(prob.linearised_profiles(base, many), steps)]
    for name, a, b in zip(names, exact, fast):
        assert np.linalg.norm(a - b) <= 0.02 * np.linalg.norm(a), name


@pytest.mark.parametrize("seed", [7, 8])
def test_passes_caps_the_passes_between_the_per_test_updates(seed, monkeypatch):
    """``calibrate(..., passes=1)`` runs the globals' solver once (a fold's refit, which starts where the full fit
    ended, needs no more); by default a fit whose per-test T_0 moved runs it again from the updated T_0, and both
    end near each other."""
    data = generate(["radiation"], sampling="5min", seed=seed)
    runs = []
    real = fitting.levenberg_marquardt
    monkeypatch.setattr(fitting, "levenberg_marquardt", lambda *a, **k: runs.append(1) or real(*a, **k))
    full = calibrate(data, ["radiation_cooling"])
    n_full, runs[:] = len(runs), []
    one = calibrate(data, ["radiation_cooling"], passes=1)
    assert n_full >= 2 and len(runs) == 1
    assert one.bic == pytest.approx(full.bic, abs=0.5)     # equal to 0.01 measured
    assert one.values["mu_drum"] == pytest.approx(full.values["mu_drum"], rel=1e-3)
