"""Example user effect (plugin): the lever's ratchet slips one tooth during the hold.

Use it with:  rollaway fit DATA.csv --effect-file examples/identify/ratchet_slip_effect.py --effect ratchet_slip
"""
import numpy as np

from rollaway.effects.base import Effect, EffectParameter


class RatchetSlip(Effect):
    name = "ratchet_slip"
    summary = "the ratchet pawl slips one tooth: a sudden loss of lining displacement at one moment"
    physics = "u_6 ← u_6 − δ for t ≥ t_slip (a step, unlike the smooth cable relaxation)"
    signature = "a step down in every test's torque at the same time, same absolute size at every hand force"
    reference = "bench observation (example plugin)"
    parameters = (
        EffectParameter("slip_m", "m", neutral=0.0, lower=0.0, upper=5e-5, initial=2e-6, typical=7e-6,
                        description="displacement lost when the pawl slips"),
        EffectParameter("slip_time_s", "s", neutral=1800.0, lower=0.0, upper=3600.0, initial=1650.0,
                        typical=1650.0, description="moment of the slip"),
    )
    amplitude = "slip_m"          # no loss, no effect, whatever the time constant

    def displacement(self, state, u6_m, v):
        # a steep logistic instead of a hard step keeps the fit differentiable
        return u6_m - v["slip_m"] / (1.0 + np.exp(-(state.time_s - v["slip_time_s"]) / 30.0))
