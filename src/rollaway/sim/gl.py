"""MuJoCo's GL backend, chosen before the first ``import mujoco`` (the package imports this first).

Off-screen rendering (no ``DISPLAY``) uses EGL unless ``MUJOCO_GL`` says otherwise.  MuJoCo
refuses to import at all under an unknown ``MUJOCO_GL``, though only rendering needs GL: the
user's value is kept in :data:`INVALID_MUJOCO_GL` for the render error message, and the
simulator imports without it.
"""
import os

if not os.environ.get("DISPLAY"):     # off-screen rendering; must precede the first `import mujoco`
    os.environ.setdefault("MUJOCO_GL", "egl")

GL_VALUES = ("egl", "osmesa", "glfw", "glx", "disable", "disabled", "off", "false", "0", "enable", "enabled",
             "on", "true", "1", "")
INVALID_MUJOCO_GL = None
if os.environ.get("MUJOCO_GL", "").strip().lower() not in GL_VALUES:
    INVALID_MUJOCO_GL = os.environ.pop("MUJOCO_GL")
    os.environ["MUJOCO_GL"] = "disable"
