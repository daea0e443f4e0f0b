"""Clamp force relaxes with time at constant temperature (lining creep)."""
from __future__ import annotations

import numpy as np

from rollaway.effects.base import Effect, EffectParameter


class LiningCreep(Effect):
    name = "lining_creep"
    elementwise = True
    summary = "the lining creeps under the held load: the clamp force relaxes with time"
    physics = ("Viscoelastic stress relaxation at fixed strain (standard linear solid): "
               "F_l0 ← F_l0·(1 − c·(1 − e^{−t/τ_c})), c the relaxed fraction, τ_c the relaxation time.")
    signature = ("torque residual falls with time (not temperature), proportional to the torque level: the "
                 "same *relative* loss at every hand force and in both directions")
    reference = ("Findley, Lai & Onaran, Creep and Relaxation of Nonlinear Viscoelastic Materials, 1976, ch. 5; "
                 "McKinlay et al. 2004 (parking-brake clamp-force loss), Day 2014 ch. 3")
    parameters = (
        EffectParameter("relaxed_fraction", "–", neutral=0.0, lower=0.0, upper=0.6, initial=0.02, typical=0.1,
                        description="fraction of the clamp force lost after long times"),
        EffectParameter("relaxation_time_s", "s", neutral=900.0, lower=30.0, upper=36000.0, initial=900.0,
                        typical=900.0, description="relaxation time constant"),
    )
    amplitude = "relaxed_fraction"          # no loss, no effect, whatever the time constant

    def clamp_force(self, state, force_N, v):
        return force_N * (1.0 - v["relaxed_fraction"] * (1.0 - np.exp(-state.time_s / v["relaxation_time_s"])))
