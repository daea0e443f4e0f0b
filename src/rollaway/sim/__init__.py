"""The MuJoCo simulator: a car on a tilted road held by the drum brake.

``from rollaway.sim import simulate, SimResult, build_model``.
"""
import os as _os

if not _os.environ.get("DISPLAY"):     # off-screen rendering; must precede the first `import mujoco`
    _os.environ.setdefault("MUJOCO_GL", "egl")

# MuJoCo refuses to import at all under an unknown MUJOCO_GL, though only rendering needs GL:
# keep the user's value for the render error message and let the simulator import without it.
GL_VALUES = ("egl", "osmesa", "glfw", "glx", "disable", "disabled", "off", "false", "0", "enable", "enabled",
             "on", "true", "1", "")
INVALID_MUJOCO_GL = None
if _os.environ.get("MUJOCO_GL", "").strip().lower() not in GL_VALUES:
    INVALID_MUJOCO_GL = _os.environ.pop("MUJOCO_GL")
    _os.environ["MUJOCO_GL"] = "disable"

from rollaway.sim.model import ModelInfo, build_model
from rollaway.sim.run import SimResult, simulate

__all__ = ["simulate", "SimResult", "build_model", "ModelInfo"]
