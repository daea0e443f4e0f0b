"""The lining is not a linear spring: force grows faster (or slower) than displacement."""
from __future__ import annotations

import numpy as np

from rollaway.effects.base import Effect, EffectParameter

REFERENCE_DISPLACEMENT_M = 1e-4   # u_6 at ≈ 300 N (eq. 24)


class NonlinearLiningStiffness(Effect):
    name = "nonlinear_lining_stiffness"
    elementwise = True
    summary = "lining force is not linear in displacement (compaction hardening of the friction material)"
    physics = ("Secant stiffness varies with displacement: the displacement entering eq. (16) is "
               "u_6·(c + a·(x − 1) + b·(x − 1)²), x = u_6/u_ref, u_ref = 0.1 mm (≈ 300 N hand force): a second-order "
               "expansion of any smooth hardening law (power law, k₁u + k₃u³, …) over the bench's range; "
               "c = 1, a = b = 0 is the paper's linear spring.")
    signature = ("torque residual follows hand force, not time: torque against hand force is curved (low at "
                 "light forces for n > 1), the same relative pattern in both directions and at every time")
    shape_covariate = "hand_force_N"
    reference = ("Day 2014, ch. 3 (friction-material compressibility, ISO 6310); Limpert 1999 §3; "
                 "McKinlay et al. 2004 (nonlinear pad stiffness in parking-brake clamp loads)")
    parameters = (
        EffectParameter("stiffness_scale", "–", neutral=1.0, lower=0.3, upper=3.0, initial=1.0, typical=1.0,
                        description="secant stiffness at u_ref = 0.1 mm relative to the paper's (c)"),
        EffectParameter("stiffness_slope", "–", neutral=0.0, lower=-3.0, upper=3.0, initial=0.05, typical=0.5,
                        description="change of relative secant stiffness per unit x = u_6/u_ref (a)"),
        EffectParameter("stiffness_curvature", "–", neutral=0.0, lower=-5.0, upper=5.0, initial=0.0, typical=0.0,
                        description="curvature of the relative secant stiffness in x (b)"),
    )

    def displacement(self, state, u6_m, v):
        u = np.asarray(u6_m, float)
        x1 = u / REFERENCE_DISPLACEMENT_M - 1.0
        return u * np.maximum(v["stiffness_scale"] + v["stiffness_slope"] * x1 + v["stiffness_curvature"] * x1 ** 2,
                              0.0)
