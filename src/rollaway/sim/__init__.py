"""The MuJoCo simulator: a car on a tilted road held by the drum brake.

``from rollaway.sim import simulate, SimResult, build_model``.
"""
from rollaway.sim.gl import GL_VALUES, INVALID_MUJOCO_GL  # noqa: F401  (first: sets MUJOCO_GL before mujoco)
from rollaway.sim.model import ModelInfo, build_model
from rollaway.sim.run import SimResult, simulate

__all__ = ["simulate", "SimResult", "build_model", "ModelInfo"]
