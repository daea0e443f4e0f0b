"""Shoes and lining cool more slowly than the drum."""
from __future__ import annotations

import numpy as np

from rollaway.effects.base import Effect, EffectParameter


def lagged_temperature_C(time_s, initial_temp_C, ambient_C, drum_time_constant_s, lag_time_constant_s):
    """First-order lag T_l of an exponentially cooling drum, T_l(0) = T_0 [°C].

    dT_l/dt = (T_d − T_l)/τ_l with T_d = T_amb + A·e^{−t/τ}:
    T_l = T_amb + A·(τ·e^{−t/τ} − τ_l·e^{−t/τ_l})/(τ − τ_l)  (limit A·(1 + t/τ)·e^{−t/τ} at τ_l = τ).
    """
    t = np.asarray(time_s, float)
    tau = np.asarray(drum_time_constant_s, float)
    tau_l = np.asarray(lag_time_constant_s, float)
    amp = np.asarray(initial_temp_C, float) - ambient_C
    if tau.ndim == 0 and tau_l.ndim == 0 and tau_l > 0.0 and not abs(tau - tau_l) < 1e-6 * tau:
        with np.errstate(over="ignore"):    # one lag for every sample (a fit): only its branch below
            return ambient_C + amp * (tau * np.exp(-t / tau) - tau_l * np.exp(-t / tau_l)) / (tau - tau_l)
    decay = np.exp(-t / tau)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        out = ambient_C + amp * (tau * decay - tau_l * np.exp(-t / np.where(tau_l > 0, tau_l, 1.0))) / (tau - tau_l)
    equal = np.abs(tau - tau_l) < 1e-6 * tau          # each other branch only where some sample takes it
    if np.any(equal):
        out = np.where(equal, ambient_C + amp * (1.0 + t / tau) * decay, out)
    plain = tau_l <= 0.0
    if np.any(plain):
        out = np.where(plain, ambient_C + amp * decay, out)
    return out


class ShoeThermalLag(Effect):
    name = "shoe_thermal_lag"
    elementwise = True
    summary = "shoes and lining cool more slowly than the drum: the lining's thermal strain lags"
    physics = ("The lining temperature follows the drum through a first-order lag τ_l "
               "(dT_l/dt = (T_d − T_l)/τ_l, T_l(0) = T_0).  T_l replaces T_d in the lining's thermal strain "
               "α_l·ΔT_l of eq. (16) and in temperature-dependent lining properties; the measured drum "
               "temperature is unchanged.  (The lag uses the convective drum time constant.)")
    signature = ("a transient torque residual: the clamp force falls more slowly in the first half hour "
                 "than the baseline predicts and catches up later; same absolute force at every hand force; "
                 "no change in the temperature channel")
    reference = ("Incropera & DeWitt, Fundamentals of Heat and Mass Transfer, 6th ed. 2007, §5.2 "
                 "(lumped capacitance); Ishak et al. 2018 (text: 'the drum will be cooled down much faster "
                 "than the shoes')")
    parameters = (EffectParameter("lag_time_s", "s", neutral=0.0, lower=0.0, upper=20000.0, initial=300.0,
                                  typical=1500.0, description="lag time constant of the shoe/lining"),)

    def lining_temperature(self, state, temp_C, v):
        return lagged_temperature_C(state.time_s, state.initial_temp_C, state.ambient_C,
                                    state.cooling_time_constant_s, v["lag_time_s"])
