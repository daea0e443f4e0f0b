"""Pseudo-residual noise estimates stay finite where the cooling coordinate e^{−t/τ} underflows to 0."""
import numpy as np

from rollaway.bench.noise import noise_estimate, pseudo_residuals
from rollaway.identify.synth import synth


def test_windows_where_the_cooling_coordinate_underflows_use_time():
    t = np.array([0.0, 1e4, 2e4, 7.4e5, 7.5e5, 7.6e5, 7.7e5])     # exp(−t/1000) = 0 from 7.5e5 s on
    y = np.sin(t / 3e4)
    e, level, w, c = pseudo_residuals(t, y, np.zeros(t.size, int), 1000.0, 1)
    assert np.all(np.isfinite(e)) and np.all(np.isfinite(c)) and len(e) == t.size - 2


def test_a_long_log_gives_a_finite_noise_estimate():
    d = synth([], seed=5, dt_s=600.0, duration_s=3600.0, hand_forces_N=(250.0,))
    d.time_s = d.time_s * 1000.0                      # the same log, its time read as if in ms
    n = noise_estimate(d, d.torque_Nm, 1000.0, relative=True)
    assert n is not None and np.isfinite(n.sigma)
