"""Noise of a high-rate log: noise correlated between samples (a DAQ low-pass) widens the window means' standard
errors by what the window means' own scatter shows; independent noise leaves them at σ/√n."""
import numpy as np
import pytest
from scipy import signal

from rollaway.identify.calibrate import calibrate
from rollaway.bench.reduction import reduce_measurements
from rollaway.identify.synth import synth


def _log(rho: float, seed: int = 5):
    d = synth(["lining_creep"], seed=seed, dt_s=0.1, duration_s=1200.0, hand_forces_N=(200.0, 320.0),
              noise_torque_Nm=0.0, noise_temp_C=0.0)
    rng = np.random.default_rng(seed)
    for name, sigma in (("torque_Nm", 8.0), ("drum_temp_C", 1.5)):
        e = signal.lfilter([np.sqrt(1 - rho ** 2)], [1, -rho], rng.normal(0.0, sigma, len(d)))   # AR(1), var σ²
        setattr(d, name, getattr(d, name) + e)
    return d


@pytest.mark.parametrize("rho", [0.0, 0.8])
def test_window_standard_errors_follow_the_noise_correlation(rho):
    red = reduce_measurements(_log(rho))
    nq, nt = red.reduction.noise_torque, red.reduction.noise_temp
    if rho == 0.0:
        assert nq.mean_factor == nt.mean_factor == 1.0
    else:
        # σ from consecutive samples sees only the fast part of AR(1) noise; the window means need
        # σ_true·√((1+ρ)/(1−ρ))/√n = 8·3/√n: the factor makes up the difference
        assert nq.sigma * nq.mean_factor == pytest.approx(8.0 * 3.0, rel=0.2)
        assert nt.sigma * nt.mean_factor == pytest.approx(1.5 * 3.0, rel=0.2)
        assert any("correlated between samples" in n for n in red.notes)
    fit = calibrate(red, ["lining_creep"])
    for ch in ("torque", "temperature"):
        assert 0.75 < fit.variance_factor[ch] < 1.35, (ch, fit.variance_factor)
