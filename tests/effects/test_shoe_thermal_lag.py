"""The lagged lining temperature: one value per sample (stacked fits) takes each branch where its samples do."""
import numpy as np

from rollaway.effects.shoe_thermal_lag import lagged_temperature_C


def _ode(t_end, t0, amb, tau, tau_l, steps=200_000):
    """dT_l/dt = (T_d − T_l)/τ_l by classical Runge–Kutta (independent of the closed form)."""
    h = t_end / steps
    drum = lambda t: amb + (t0 - amb) * np.exp(-t / tau)
    y, t = t0, 0.0
    for _ in range(steps):
        k1 = (drum(t) - y) / tau_l
        k2 = (drum(t + h / 2) - (y + h / 2 * k1)) / tau_l
        k3 = (drum(t + h / 2) - (y + h / 2 * k2)) / tau_l
        k4 = (drum(t + h) - (y + h * k3)) / tau_l
        y, t = y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4), t + h
    return y


def test_per_sample_lags_take_the_plain_equal_and_general_branches():
    t = np.array([0.0, 600.0, 1800.0, 600.0, 1800.0, 900.0])
    tau = np.full(t.size, 1200.0)
    tau_l = np.array([0.0, 0.0, 1200.0, 1200.0, 400.0, 2500.0])
    got = lagged_temperature_C(t, 180.0, 25.0, tau, tau_l)
    plain = 25.0 + 155.0 * np.exp(-t / 1200.0)
    assert np.allclose(got[:2], plain[:2], rtol=1e-14)
    for i in (2, 3, 4, 5):
        assert np.isclose(got[i], _ode(t[i], 180.0, 25.0, 1200.0, tau_l[i], steps=4000), rtol=1e-9)
    one = [float(lagged_temperature_C(t[i], 180.0, 25.0, 1200.0, tau_l[i])) for i in range(t.size)]
    assert np.allclose(got, one, rtol=1e-12)
