"""The MuJoCo simulator: a car on a tilted road held by the drum brake.

``from rollaway.sim import simulate, SimResult, build_model``.
"""
import os as _os

if not _os.environ.get("DISPLAY"):     # off-screen rendering; must precede the first `import mujoco`
    _os.environ.setdefault("MUJOCO_GL", "egl")

from rollaway.sim.model import ModelInfo, build_model
from rollaway.sim.run import SimResult, simulate

__all__ = ["simulate", "SimResult", "build_model", "ModelInfo"]
