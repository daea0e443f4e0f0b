"""The lining is not a linear spring: force grows faster (or slower) than displacement."""
from __future__ import annotations

import numpy as np

from rollaway.bench.effects.base import Effect, EffectParameter

REFERENCE_DISPLACEMENT_M = 1e-4   # u_6 at ≈ 300 N (eq. 24): the nonlinearity changes nothing there


class NonlinearLiningStiffness(Effect):
    name = "nonlinear_lining_stiffness"
    summary = "lining force is not linear in displacement (compaction hardening of the friction material)"
    physics = ("Power-law spring: the displacement entering eq. (16) is u_ref·(u_6/u_ref)^n with "
               "u_ref = 0.1 mm (≈ 300 N hand force); n > 1 hardens, n = 1 is the paper's linear spring.")
    signature = ("torque residual follows hand force, not time: torque against hand force is curved (low at "
                 "light forces for n > 1), the same pattern in both directions and at every time")
    reference = ("Day 2014, ch. 3 (friction-material compressibility, ISO 6310); Limpert 1999 §3; "
                 "McKinlay et al. 2004 (nonlinear pad stiffness in parking-brake clamp loads)")
    parameters = (EffectParameter("stiffness_exponent", "–", neutral=1.0, lower=0.4, upper=2.5, initial=1.05,
                                  typical=1.4, description="exponent n of the force–displacement law"),)

    def displacement(self, state, u6_m, v):
        u = np.maximum(np.asarray(u6_m, float), 0.0)
        return REFERENCE_DISPLACEMENT_M * (u / REFERENCE_DISPLACEMENT_M) ** v["stiffness_exponent"]
