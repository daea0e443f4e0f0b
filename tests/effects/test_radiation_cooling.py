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
