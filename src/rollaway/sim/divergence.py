"""Numerical failure of a MuJoCo run: what ends it as ``diverged`` instead of a verdict.

A run that failed is never reported ``held`` (nor as a roll-away).  After every brake update
(:data:`rollaway.sim.brake_callback.UPDATE_STEPS` steps) the run is checked for:

* MuJoCo warnings (``d.warning`` counters): bad ``qacc``/``qpos``/``qvel`` (MuJoCo then resets
  the state), constraint or contact buffers full, bad inertia;
* a state reset (simulated time going backwards) and non-finite positions or velocities;
* energy: the car's speed along the road may not exceed what the height it lost can give,
  v² ≤ 2·g·|Δx|·sin θ, with a factor :data:`ENERGY_FACTOR` and :data:`SPEED_SLACK_M_S` of slack
  [assumed] (a blow-up that throws the car 100 km in a millisecond fails this at once);
* the car leaving the road surface: its origin moving more than :data:`MAX_NORMAL_M` along
  the road normal [assumed].
"""
from __future__ import annotations

import math

import mujoco
import numpy as np

ENERGY_FACTOR = 4.0          # [assumed] allowed v² over 2 g |Δx| sin θ (wheels' and numerical energy)
SPEED_SLACK_M_S = 0.01       # [assumed] speed always allowed (settling, creep)
MAX_NORMAL_M = 0.5           # [assumed] travel along the road normal that means the car left the road
_WARNINGS = {mujoco.mjtWarning.mjWARN_BADQACC: "NaN, Inf or huge value in qacc (MuJoCo reset the state)",
             mujoco.mjtWarning.mjWARN_BADQPOS: "NaN, Inf or huge value in qpos (MuJoCo reset the state)",
             mujoco.mjtWarning.mjWARN_BADQVEL: "NaN, Inf or huge value in qvel (MuJoCo reset the state)",
             mujoco.mjtWarning.mjWARN_CNSTRFULL: "constraint buffer full",
             mujoco.mjtWarning.mjWARN_CONTACTFULL: "contact buffer full",
             mujoco.mjtWarning.mjWARN_INERTIA: "bad inertia"}


class DivergenceGuard:
    """Checks one run's state; :meth:`check` returns the reason it diverged, or None."""

    def __init__(self, data: mujoco.MjData, gravity_m_s2: float, theta_rad: float):
        self.counts = {w: data.warning[int(w)].number for w in _WARNINGS}
        self.time_s = data.time
        self.g_sin = abs(gravity_m_s2) * math.sin(theta_rad)

    def check(self, data: mujoco.MjData, travel_m: float, speed_m_s: float, normal_m: float) -> str | None:
        for w, text in _WARNINGS.items():
            if data.warning[int(w)].number > self.counts[w]:
                return f"MuJoCo warning: {text} at t = {self.time_s:.3f} s"
        if data.time < self.time_s:
            return f"state reset: simulated time went back from {self.time_s:.3f} s to {data.time:.3f} s"
        self.time_s = data.time
        if not (np.isfinite(data.qpos).all() and np.isfinite(data.qvel).all()):
            return f"non-finite state at t = {data.time:.3f} s"
        allowed = math.sqrt(ENERGY_FACTOR * 2.0 * self.g_sin * abs(travel_m)) + SPEED_SLACK_M_S
        if abs(speed_m_s) > allowed:
            return (f"energy: speed {abs(speed_m_s):.3g} m/s after {abs(travel_m):.3g} m of travel exceeds "
                    f"what gravity can give ({allowed:.3g} m/s) at t = {data.time:.3f} s")
        if abs(normal_m) > MAX_NORMAL_M:
            return f"the car left the road surface ({normal_m:+.3g} m along its normal) at t = {data.time:.3f} s"
        return None
