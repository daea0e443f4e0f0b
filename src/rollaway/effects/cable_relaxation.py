"""Cable and lever stretch: the lining displacement is lost little by little."""
from __future__ import annotations

import numpy as np

from rollaway.effects.base import Effect, EffectParameter


class CableRelaxation(Effect):
    name = "cable_relaxation"
    elementwise = True
    summary = "cable/lever stretch (creep, seating of the ratchet and strands) loses lining displacement"
    physics = ("u_6 ← u_6 − δ·(1 − e^{−t/τ_r}): the displacement set by the lever (eq. 24) is lost towards δ "
               "with time constant τ_r.")
    signature = ("torque residual falls with time (not temperature) by the same absolute amount at every hand "
                 "force (a displacement, not a fraction, is lost), so the light-force tests lose the largest "
                 "share")
    reference = ("Feyrer, Wire Ropes: Tension, Endurance, Reliability, Springer 2007, §1.3 (rope elongation and "
                 "creep); Limpert 1999 §7 (parking-brake cable losses)")
    parameters = (
        EffectParameter("displacement_loss_m", "m", neutral=0.0, lower=0.0, upper=6e-5, initial=1e-6,
                        typical=8e-6, description="displacement lost after long times"),
        EffectParameter("relaxation_time_s", "s", neutral=600.0, lower=30.0, upper=36000.0, initial=600.0,
                        typical=600.0, description="time constant of the loss"),
    )
    amplitude = "displacement_loss_m"          # no loss, no effect, whatever the time constant
    shape_scale = 1e-5                         # its flexible form loses displacement, 10 µm a unit [assumed]

    def displacement(self, state, u6_m, v):
        return u6_m - v["displacement_loss_m"] * (1.0 - np.exp(-state.time_s / v["relaxation_time_s"]))
