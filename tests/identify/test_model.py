import numpy as np
import pytest

from rollaway.bench import Measurements
from rollaway.identify.model import BenchModel
from rollaway.effects import CATALOGUE, get_effect
from rollaway.effects.radiation_cooling import radiative_convective_temperature_C
from rollaway.effects.shoe_thermal_lag import lagged_temperature_C
from rollaway.model.brake import drum_brake
from rollaway.errors import UserError
from rollaway.model.parameters import paper


def _data(direction="uphill", force=250.0, t0=200.0):
    t = np.arange(13) * 300.0
    n = len(t)
    return Measurements(np.array(["a"] * n), np.array([direction] * n), np.full(n, force), t, np.full(n, t0),
                        np.zeros(n))


@pytest.mark.parametrize("direction", ["downhill", "uphill"])
def test_neutral_effects_are_bit_identical_to_baseline(direction):
    d = _data(direction, 310.0, 190.0)
    ref = drum_brake(paper(), time_s=d.time_s, hand_force_N=310.0, direction=direction, initial_temp_C=190.0)
    for effects in ([], list(CATALOGUE)):
        p = BenchModel(effects=effects).predict(d)
        assert np.array_equal(p.torque_Nm, ref.torque_Nm)
        assert np.array_equal(p.drum_temp_C, ref.drum_temp_C)


def test_fitted_mu_and_h_reach_the_baseline_functions():
    d = _data("downhill")
    p = BenchModel().predict(d, {"mu_drum": 0.35, "heat_transfer_W_m2K": 30.0})
    ref = drum_brake(paper().replace(mu_drum=0.35, heat_transfer_W_m2K=30.0), time_s=d.time_s,
                     hand_force_N=250.0, direction="downhill")
    assert np.array_equal(p.torque_Nm, ref.torque_Nm)


@pytest.mark.parametrize("name", list(CATALOGUE))
def test_every_effect_changes_the_model_and_is_documented(name):
    eff = get_effect(name)
    assert eff.physics and eff.signature and eff.reference and eff.parameters
    for par in eff.parameters:
        assert par.lower <= par.neutral <= par.upper and par.unit
    m = BenchModel(effects=[name])
    d = _data()
    base = m.predict(d)
    vals = {f"{name}.{k}": v for k, v in eff.typical_values().items()}
    changed = m.predict(d, vals)
    diff = np.abs(changed.torque_Nm - base.torque_Nm).max() + np.abs(changed.drum_temp_C - base.drum_temp_C).max()
    assert diff > 1.0


def test_unknown_effect_suggests_the_closest_name():
    with pytest.raises(UserError, match="did you mean 'lining_creep'"):
        BenchModel(effects=["lining_crep"])


def test_radiation_solution_matches_an_ode_integration():
    from scipy.integrate import solve_ivp
    p = paper()
    cap = p.drum_density_kg_m3 * p.drum_specific_heat_J_kgK * p.drum_volume_m3
    t = np.arange(13) * 300.0

    def rhs(_, y):
        return [-(40 * 0.08 * (y[0] - 27) + 0.7 * 5.670374419e-8 * 0.08 * ((y[0] + 273.15) ** 4 - 300.15 ** 4)) / cap]
    ref = solve_ivp(rhs, (0, 3600), [210.0], t_eval=t, rtol=1e-10, atol=1e-10).y[0]
    ours = radiative_convective_temperature_C(t, 210.0, 27.0, 40.0, 0.7, 0.08, cap)
    assert np.abs(ours - ref).max() < 1e-3


def test_shoe_lag_solves_its_ode():
    t = np.linspace(0, 3600, 3601)
    tl = lagged_temperature_C(t, 200.0, 27.0, 1000.0, 700.0)
    td = 27.0 + 173.0 * np.exp(-t / 1000.0)
    dtl = np.gradient(tl, t)
    assert tl[0] == pytest.approx(200.0)
    assert np.abs(dtl[1:-1] - (td - tl)[1:-1] / 700.0).max() < 1e-4
    assert np.all(tl >= td - 1e-9)   # the shoe stays warmer than the drum


def test_logged_ambient_cooling_matches_an_ode_integration_and_eq10_when_constant():
    from scipy.integrate import solve_ivp
    from rollaway.physics.cooling import drum_temperature_C, drum_temperature_logged_ambient_C
    t = np.r_[np.arange(0, 3601, 300.0), np.array([0, 45, 200, 730, 1800.0])]
    idx = np.r_[np.zeros(13, int), np.ones(5, int)]
    amb = np.r_[np.full(13, 27.0), 20 + t[13:] / 600]
    temp = drum_temperature_logged_ambient_C(t, np.r_[np.full(13, 200.0), np.full(5, 150.0)], amb, 1000.0, idx)
    assert np.abs(temp[:13] - drum_temperature_C(t[:13], 200.0, 27.0, 1000.0)).max() < 1e-9
    ref = solve_ivp(lambda s, y: -(y - (20 + s / 600)) / 1000, (0, 1800), [150.0], t_eval=t[13:], rtol=1e-11,
                    atol=1e-11).y[0]
    assert np.abs(temp[13:] - ref).max() < 1e-6


def test_hooks_see_the_test_and_per_test_parameters_take_one_value_per_test():
    d = Measurements(np.array(["a"] * 3 + ["b"] * 3), np.array(["uphill"] * 6), np.full(6, 250.0),
                     np.tile([0.0, 300.0, 600.0], 2), np.full(6, 200.0), np.zeros(6))
    m = BenchModel(effects=["torque_zero_offset"])
    assert m.per_test_parameters() == ["initial_temp_C", "torque_zero_offset.offset_Nm"]
    base = m.predict(d).torque_Nm
    shifted = m.predict(d, {"torque_zero_offset.offset_Nm": np.array([5.0, -7.0])}).torque_Nm
    assert np.allclose(shifted - base, [5, 5, 5, -7, -7, -7])
    assert m.state(d).test_ids == ["a", "b"]
    warm = m.predict(d, {"initial_temp_C": np.array([210.0, 190.0])})
    assert warm.drum_temp_C[0] == 210.0 and warm.drum_temp_C[3] == 190.0


def test_logged_ambient_cooling_in_closed_form_is_the_stepwise_recursion_for_interleaved_tests_and_fast_cooling():
    """The cumulative-sum form against the exact one-step recursion it replaces, for tests whose rows interleave, a
    fast time constant (beyond e^600 it steps sample by sample) and a dense log."""
    from rollaway.physics.cooling import _one_test, drum_temperature_logged_ambient_C
    rng = np.random.default_rng(3)
    for n, tau in ((61, 1200.0), (3601, 300.0), (400, 5.0)):
        t = np.linspace(0.0, 3600.0, n)
        amb = 25.0 + np.cumsum(rng.normal(0.0, 0.05, n))
        step = [180.0]
        for j in range(n - 1):
            dt = t[j + 1] - t[j]
            m = (amb[j + 1] - amb[j]) / dt * tau
            step.append(amb[j + 1] - m + (step[-1] - amb[j] + m) * np.exp(-dt / tau))
        np.testing.assert_allclose(_one_test(t, 180.0, amb, np.full(n, tau)), step, rtol=1e-12, atol=1e-9)
    t = np.r_[np.linspace(0, 3600, 13), np.linspace(0, 3600, 13)]
    idx = np.r_[np.zeros(13, int), np.ones(13, int)]
    amb = 20.0 + t / 900.0
    t0 = np.where(idx == 0, 250.0, 120.0)
    whole = drum_temperature_logged_ambient_C(t, t0, amb, 800.0, idx)
    inter = np.empty(26, int)                                  # the two tests' rows interleaved, time order kept
    inter[0::2], inter[1::2] = np.arange(13), np.arange(13, 26)
    mixed = drum_temperature_logged_ambient_C(t[inter], t0[inter], amb[inter], 800.0, idx[inter])
    np.testing.assert_array_equal(mixed, whole[inter])
