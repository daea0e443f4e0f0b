"""Lining stiffness falls with temperature."""
from __future__ import annotations

import numpy as np

from rollaway.effects.base import Effect, EffectParameter


class ModulusTemperature(Effect):
    name = "modulus_temperature"
    elementwise = True
    summary = "the lining's Young's modulus E_l falls as it gets hot (resin softening)"
    physics = ("E_l(T_l) = E_l·max(1 − k_E·(T_l − T_amb), 0.05) in eq. (16); with the displacement fixed by the "
               "lever, the clamp force is nearly proportional to E_l.")
    signature = ("torque residual rises as the drum cools (the lining stiffens), proportional to the torque level: "
                 "the same relative change in both directions; low at the hot start")
    reference = ("Day 2014, ch. 3 (friction-material properties vs temperature); Wolff 2010 (lining modulus); "
                 "Limpert 1999 §3")
    parameters = (EffectParameter("modulus_slope_per_K", "1/K", neutral=0.0, lower=0.0, upper=4e-3, initial=2e-4,
                                  typical=1e-3, description="relative loss of lining modulus per kelvin above "
                                                            "ambient"),)

    def lining_modulus(self, state, modulus_Pa, v):
        return modulus_Pa * np.maximum(1.0 - v["modulus_slope_per_K"] * (state.lining_temp_C - state.ambient_C),
                                       0.05)
