"""The reference unit of the benchmarks: wall time of 300 000 raw ``mj_step`` calls of a plain car.

The plain car is ``models/car.xml`` as committed (empty car, no decorative posts) on a 20 %
road, held by its rear hinges at twice the demand, sleep off; stepped in C,
``mj_step(m, d, nstep=1000)`` 300 times.  Measured in the same run as what it normalises,
so ratios compare across machines.
"""
from __future__ import annotations

import math
import time
from pathlib import Path

import mujoco

MODEL = Path(__file__).resolve().parents[1] / "models" / "car.xml"
STEPS = 300_000


def reference_unit_s(repeat: int = 3) -> float:
    """Best-of-*repeat* wall time of :data:`STEPS` raw steps [s]."""
    spec = mujoco.MjSpec.from_file(str(MODEL))
    th = math.atan(0.2)
    spec.frame("slope").quat = [math.cos(th / 2), 0, math.sin(th / 2), 0]
    spec.option.enableflags &= ~int(mujoco.mjtEnableBit.mjENBL_SLEEP)
    m = spec.compile()
    for j in ("hinge_rl", "hinge_rr"):
        m.dof_frictionloss[m.jnt_dofadr[m.joint(j).id]] = 2 * 1250 * 9.81 * math.sin(th) * 0.3 / 2
    best = math.inf
    for _ in range(repeat):
        d = mujoco.MjData(m)
        t0 = time.perf_counter()
        for _ in range(STEPS // 1000):
            mujoco.mj_step(m, d, nstep=1000)
        best = min(best, time.perf_counter() - t0)
    return best
