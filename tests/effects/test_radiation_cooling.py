"""Convection + radiation cooling against an accurate ODE solution, above and below the ambient."""
import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rollaway.effects.radiation_cooling import STEFAN_BOLTZMANN_W_m2K4, radiative_convective_temperature_C

C_J_K, AREA_m2, H_W_m2K, EMISSIVITY, AMBIENT_C = 20_000.0, 0.05, 40.0, 0.8, 27.0


def reference(t_s, t0_C):
    def rate(_, T):
        return [(-H_W_m2K * AREA_m2 * (T[0] - AMBIENT_C) - EMISSIVITY * STEFAN_BOLTZMANN_W_m2K4 * AREA_m2
                 * ((T[0] + 273.15) ** 4 - (AMBIENT_C + 273.15) ** 4)) / C_J_K]
    return solve_ivp(rate, [0, t_s[-1]], [t0_C], t_eval=t_s, rtol=1e-12, atol=1e-12, method="DOP853").y[0]


@pytest.mark.parametrize("t0_C", [-30.0, 0.0, 20.0, 80.0, 300.0])
def test_the_drum_relaxes_to_the_ambient_from_either_side(t0_C):
    t_s = np.array([0.0, 30.0, 300.0, 1200.0, 3600.0])
    got = radiative_convective_temperature_C(t_s, t0_C, AMBIENT_C, H_W_m2K, EMISSIVITY, AREA_m2, C_J_K)
    want = reference(t_s, t0_C)
    assert got == pytest.approx(want, abs=1e-4 * abs(t0_C - AMBIENT_C) + 1e-3)


def test_samples_on_both_sides_in_one_call():
    t_s = np.array([600.0, 600.0])
    got = radiative_convective_temperature_C(t_s, np.array([-10.0, 150.0]), AMBIENT_C, H_W_m2K, EMISSIVITY,
                                             AREA_m2, C_J_K)
    assert got[0] < AMBIENT_C < got[1]
    assert got == pytest.approx([reference(np.array([0.0, 600.0]), -10.0)[1],
                                 reference(np.array([0.0, 600.0]), 150.0)[1]], abs=2e-3)


def test_kept_answers_are_the_answers_shaped_like_the_inputs_and_read_only():
    """The last answers are kept (a fit asks for the same cooling again): a repeat returns the same numbers, a
    change of any input another answer, a single instant a single value."""
    t_s = np.array([0.0, 600.0, 3600.0])
    first = radiative_convective_temperature_C(t_s, 200.0, AMBIENT_C, H_W_m2K, EMISSIVITY, AREA_m2, C_J_K)
    again = radiative_convective_temperature_C(t_s.copy(), 200.0, AMBIENT_C, H_W_m2K, EMISSIVITY, AREA_m2, C_J_K)
    assert np.array_equal(first, again) and not again.flags.writeable
    hotter = radiative_convective_temperature_C(t_s, 201.0, AMBIENT_C, H_W_m2K, EMISSIVITY, AREA_m2, C_J_K)
    assert np.all(hotter[1:] > first[1:])
    other_h = radiative_convective_temperature_C(t_s, 200.0, AMBIENT_C, H_W_m2K * 1.01, EMISSIVITY, AREA_m2, C_J_K)
    assert np.all(other_h[1:] < first[1:])
    one = radiative_convective_temperature_C(600.0, 200.0, AMBIENT_C, H_W_m2K, EMISSIVITY, AREA_m2, C_J_K)
    assert np.shape(one) == () and float(one) == pytest.approx(first[1], rel=1e-12)
    column = radiative_convective_temperature_C(t_s[:, None], 200.0, AMBIENT_C, H_W_m2K, EMISSIVITY, AREA_m2, C_J_K)
    assert column.shape == (3, 1) and np.array_equal(column[:, 0], first)


def test_a_logged_ambient_is_cooled_between_tables_on_an_ambient_grid():
    """One reading of the ambient per sample (a drifting 10 s log): tables 0.25 K apart, each sample linear between
    the two around its ambient — within 5 mK of one table per distinct ambient; a few ambients keep one table each."""
    import numpy as np
    import rollaway.effects.radiation_cooling as R
    rng = np.random.default_rng(0)
    t = np.tile(np.linspace(0.0, 3600.0, 361), 6)
    t0 = np.repeat(rng.uniform(100.0, 300.0, 6), 361)
    amb = 24.0 + t / 900.0 + rng.normal(0.0, 0.05, t.size)
    exact = R._tabled_C(t, t0, amb, 30.0, 0.8, 0.1, 4000.0, 1500)
    assert np.abs(R._cooling_C(t, t0, amb, 30.0, 0.8, 0.1, 4000.0, 1500) - exact).max() < 5e-3
    few = np.repeat([22.0, 25.0], t.size // 2)
    np.testing.assert_array_equal(R._cooling_C(t, t0, few, 30.0, 0.8, 0.1, 4000.0, 1500),
                                  R._tabled_C(t, t0, few, 30.0, 0.8, 0.1, 4000.0, 1500))
