"""The drum's radius shrinks onto the shoes as it cools."""
from __future__ import annotations

import numpy as np

from rollaway.effects.base import Effect, EffectParameter


class DrumRadialContraction(Effect):
    name = "drum_radial_contraction"
    elementwise = True
    summary = "the cooling drum's radius shrinks onto the shoes, raising the clamp force"
    physics = ("The 1D model counts only the drum *thickness* l_od in its thermal strain (eq. 16).  A cooling "
               "ring also shrinks radially by α_d·r_d·ΔT (r_d/l_od ≈ 11 times more); a fraction c_r of that "
               "interference reaches the lining through the series stiffness k_s = ∂F_l0/∂u_6: "
               "F_l0 += c_r·k_s·α_d·r_d·(−ΔT_d).")
    signature = ("torque residual grows as the drum cools (follows −ΔT), the same absolute force for every "
                 "hand force (scaled only by the direction's self-energising factor); the torque falls "
                 "less over the hour than the baseline predicts")
    shape_covariate = "drum_temp_C"
    shape_scale = 2000.0                       # its flexible form adds clamp force, 2 kN a unit [assumed]
    reference = ("Timoshenko & Goodier, Theory of Elasticity, 1951, §§ thin rings (thermal ring contraction); "
                 "Day, Braking of Road Vehicles, 2014, ch. 5 (drum distortion)")
    parameters = (EffectParameter("radial_fraction", "–", neutral=0.0, lower=0.0, upper=1.0, initial=0.02,
                                  typical=0.08,
                                  description="fraction of the free radial contraction α_d·r_d·ΔT that "
                                              "becomes lining interference"),)

    def clamp_force(self, state, force_N, v):
        p = state.params
        k_s = state.extra["series_stiffness_N_per_m"]
        return force_N + v["radial_fraction"] * k_s * p.drum_expansion_per_K * p.drum_radius_m * (
            -np.asarray(state.delta_drum_K))
