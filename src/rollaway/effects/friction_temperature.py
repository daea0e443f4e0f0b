"""μ varies with temperature (lining fade / recovery)."""
from __future__ import annotations

import numpy as np

from rollaway.effects.base import Effect, EffectParameter

REFERENCE_TEMP_C = 100.0   # μ_d is the friction coefficient at this lining temperature
MU_MAX_FRACTION = 0.95      # keep μ below 0.95·l_f/l_fr: the fit never enters self-locking


class FrictionTemperature(Effect):
    name = "friction_temperature"
    elementwise = True
    summary = "the shoe/drum friction coefficient μ changes with the lining temperature"
    physics = ("μ(T_l) = μ_d·(1 + k_μ·(T_l − 100 °C)); μ_d is the value at 100 °C.  μ enters both the "
               "torque (eq. 17b) and the shoe moment balance (eqs. 18–21).")
    signature = ("torque residual follows temperature (hence time), proportional to the torque level and "
                 "about twice as large (relative) facing downhill as uphill, because the self-energising "
                 "factor amplifies μ changes on the leading shoe")
    reference = ("Limpert, Brake Design and Safety, 2nd ed., SAE 1999, §3 (friction vs temperature); "
                 "Day, Braking of Road Vehicles, Butterworth-Heinemann 2014, ch. 3")
    parameters = (EffectParameter("mu_slope_per_K", "1/K", neutral=0.0, lower=-4e-3, upper=4e-3,
                                  initial=3e-4, typical=1.2e-3,
                                  description="relative change of μ per kelvin of lining temperature"),)

    def friction(self, state, mu, v):
        p = state.params
        mu_max = MU_MAX_FRACTION * p.shoe_arm_normal_m / np.maximum(p.shoe_arm_friction_m, 1e-12)   # one per car
        out = mu * (1.0 + v["mu_slope_per_K"] * (state.lining_temp_C - REFERENCE_TEMP_C))
        return np.clip(out, 1e-3, mu_max)
