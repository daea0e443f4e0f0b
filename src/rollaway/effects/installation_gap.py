"""Installation gap between lining and drum (paper eq. 16b)."""
from __future__ import annotations

from rollaway.effects.base import Effect, EffectParameter


class InstallationGap(Effect):
    name = "installation_gap"
    elementwise = True
    summary = "an installation gap l_g between lining and drum (the paper's eq. 16b; Table 1 lists 1 mm)"
    physics = ("Eq. (16b): every lining thickness l_ol in eq. (16a) becomes l_ol + l_g; the series stiffness "
               "drops (−20 % at 1 mm) and the thermal coefficient of the clamp force with it.")
    signature = ("a torque level offset the friction coefficient cannot absorb: the same relative drop in both "
                 "directions (μ would change the downhill/uphill ratio), slightly smaller loss on cooling")
    reference = "Ishak et al. 2018, eq. (16b) and Table 1; McKinlay et al. 2004 (1D parking-brake model)"
    parameters = (EffectParameter("gap_m", "m", neutral=0.0, lower=0.0, upper=3e-3, initial=1e-4, typical=1e-3,
                                  description="installation gap l_g"),)

    def gap(self, state, gap_m, v):
        return gap_m + v["gap_m"]
