"""Off-screen renders of a simulated run: MP4 (H.264), GIF or PNG with a heads-up overlay.

Rendering is a replay of the recorded trajectory (one state per 20 ms brake update; during a
fast-mode skip the car provably stands still, so the last state holds).  The camera follows
the car from its right side with a level horizon, so the tilted road, the vertical posts
along the far kerb and the wheel spokes (do the wheels turn or slide?) are visible.

Timing: a hold is shown as a time-lapse (the whole duration in :data:`TIMELAPSE_VIDEO_S`
seconds of video); around a roll-away the video switches to real time, from
:data:`REALTIME_BEFORE_S` before the roll-away to the end of the classification window.
The overlay shows the simulated time and playback speed, the drum temperature (eq. 10), the
rear-axle brake capacity against the demand T_req (eq. 23) and the status.

Off-screen GL: with no ``DISPLAY``, :mod:`rollaway.sim` sets ``MUJOCO_GL=egl`` before MuJoCo
is imported (``osmesa`` works too, set it yourself).
"""
from __future__ import annotations

from pathlib import Path

import mujoco
import numpy as np

from rollaway.errors import UserError, ensure_parent_dir

RENDER_SUFFIXES = (".mp4", ".gif", ".png")
TIMELAPSE_VIDEO_S = 4.0
REALTIME_BEFORE_S = 2.0
SIZES = {".mp4": (640, 360), ".png": (960, 540), ".gif": (480, 270)}   # (width, height)
FPS = {".mp4": 25, ".gif": 10}
_FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf"
_STATUS = {"held": ("HELD", (40, 170, 60)), "brake_slip": ("ROLLING AWAY: brake slips", (220, 50, 40)),
           "tyre_skid": ("SLIDING: rear tyres skid", (230, 120, 20))}


def check_render_path(path) -> Path:
    """Validate an output path (known suffix; its folder is created) and the GL setting (UserError)."""
    from rollaway.sim import INVALID_MUJOCO_GL
    if INVALID_MUJOCO_GL is not None:
        raise UserError(f"--render {path}: MUJOCO_GL={INVALID_MUJOCO_GL!r} is not a MuJoCo GL backend; "
                        f"set MUJOCO_GL=egl or MUJOCO_GL=osmesa (or unset it)")
    p = Path(path)
    if p.suffix.lower() not in RENDER_SUFFIXES:
        raise UserError(f"--render {path}: unknown file type '{p.suffix or '(none)'}'; "
                        f"use one of {', '.join(RENDER_SUFFIXES)}")
    return ensure_parent_dir(p, "--render")


def frame_times(t_end_s: float, rollaway_s: float | None, fps: float) -> tuple[np.ndarray, np.ndarray]:
    """Simulated time of each frame and its playback speed (×1 real time, > 1 time-lapse)."""
    n_tl = max(int(TIMELAPSE_VIDEO_S * fps), 1)
    if rollaway_s is None:
        t = np.linspace(0.0, t_end_s, n_tl)
        return t, np.full(t.shape, max(t_end_s / TIMELAPSE_VIDEO_S, 1.0))
    t_rt = max(rollaway_s - REALTIME_BEFORE_S, 0.0)
    rt = np.arange(t_rt, t_end_s + 1e-9, 1.0 / fps)
    if t_rt <= n_tl / fps:        # short lead-in: all real time
        rt = np.arange(0.0, t_end_s + 1e-9, 1.0 / fps)
        return rt, np.ones(rt.shape)
    tl = np.linspace(0.0, t_rt, n_tl, endpoint=False)
    return np.concatenate([tl, rt]), np.concatenate([np.full(tl.shape, t_rt / TIMELAPSE_VIDEO_S), np.ones(rt.shape)])


class _Hud:
    def __init__(self, width: int):
        from PIL import ImageFont
        size = max(int(width / 40), 9)
        try:
            self.font = ImageFont.truetype(_FONT, size)
        except OSError:
            self.font = ImageFont.load_default(size=size)
        self.line = int(size * 1.25)

    def draw(self, frame: np.ndarray, lines: list[str], status: tuple[str, tuple], margin: float) -> np.ndarray:
        from PIL import Image, ImageDraw
        img = Image.fromarray(frame)
        g = ImageDraw.Draw(img, "RGBA")
        w = img.width
        n = len(lines) + 2
        g.rectangle([0, 0, w, n * self.line + 8], fill=(0, 0, 0, 120))
        for i, text in enumerate(lines):
            g.text((6, 4 + i * self.line), text, font=self.font, fill=(255, 255, 255))
        y = 4 + len(lines) * self.line
        bar_w = int(w * 0.45)          # capacity bar: full width = 2 × demand, the mark = demand
        g.rectangle([6, y + 2, 6 + bar_w, y + self.line - 2], outline=(255, 255, 255))
        fill = int(bar_w * min(max(margin, 0.0), 2.0) / 2.0)
        g.rectangle([6, y + 2, 6 + fill, y + self.line - 2], fill=(60, 170, 230) if margin >= 1 else (220, 50, 40))
        g.line([6 + bar_w // 2, y, 6 + bar_w // 2, y + self.line], fill=(255, 255, 0), width=2)
        g.text((12 + bar_w, y), "capacity / demand", font=self.font, fill=(255, 255, 255))
        tw = int(g.textlength(status[0], font=self.font))
        g.rectangle([4, y + self.line + 1, 10 + tw, y + 2 * self.line + 2], fill=status[1])
        g.text((7, y + self.line), status[0], font=self.font, fill=(255, 255, 255))
        return np.asarray(img)


def render_run(runner, result, path, size: tuple[int, int] | None = None) -> Path:
    """Render a finished :class:`rollaway.sim.run._Run` with its :class:`SimResult` to *path*."""
    path = check_render_path(path)
    suffix = path.suffix.lower()
    width, height = size or SIZES[suffix]
    tr, ctrl, info, sc = result.trace, runner.ctrl, runner.info, runner.scenario
    model, data = runner.model, mujoco.MjData(runner.model)
    if suffix == ".png":
        t_key = (min(result.rollaway_time_s + 3.0, result.sim_time_s) if result.rollaway_time_s is not None
                 else result.sim_time_s)
        times, speed = np.array([t_key]), np.array([0.0])          # 0: a still picture
    else:
        times, speed = frame_times(result.sim_time_s, result.rollaway_time_s, FPS[suffix])
    try:
        renderer = mujoco.Renderer(model, height=height, width=width)
    except Exception as exc:  # no GL context: say how to get one
        raise UserError(f"cannot render off-screen ({exc}); set MUJOCO_GL=egl or MUJOCO_GL=osmesa "
                        f"(apt-get install libegl1 or libosmesa6)") from None
    cam = mujoco.MjvCamera()
    cam.type = mujoco.mjtCamera.mjCAMERA_FREE
    cam.azimuth, cam.elevation, cam.distance = 90.0, -4.0, 8.5
    opt = mujoco.MjvOption()
    hud = _Hud(width)
    frames = []
    for t, sp in zip(times, speed):
        r = max(int(np.searchsorted(tr.time_s, t, side="right")) - 1, 0)
        data.qpos[:] = tr.qpos[r]
        data.qvel[:] = tr.qvel[r]
        mujoco.mj_forward(model, data)
        cam.lookat[:] = data.subtree_com[info.car_body] + [0.0, 0.0, 0.7]   # car below the overlay
        renderer.update_scene(data, camera=cam, scene_option=opt)
        k = ctrl.index(t)
        cap = float(ctrl.torque_Nm[(tr.sense[r] > 0).astype(int), k].sum())
        rolled = result.rollaway_time_s is not None and t >= result.rollaway_time_s
        status = _STATUS[result.outcome if rolled else "held"]
        play = "snapshot" if sp == 0 else "real time" if sp <= 1.0 else f"time-lapse x{sp:.0f}"
        lines = [f"{sc.name}: {info.grade_pct:g} % grade, facing {info.facing}, {sc.hand_force_N:g} N",
                 f"t = {t:8.1f} s  ({play})   moved {tr.displacement_m[r] * 100:+.1f} cm",
                 f"drum {ctrl.drum_temp_C[k]:5.1f} °C   brake {cap:6.0f} / demand {info.demand_axle_Nm:.0f} N·m"]
        frames.append(hud.draw(renderer.render(), lines, status, cap / info.demand_axle_Nm))
    renderer.close()
    _write(path, frames, suffix)
    return path


def _write(path: Path, frames: list[np.ndarray], suffix: str) -> None:
    import imageio.v2 as imageio
    if suffix == ".png":
        imageio.imwrite(path, frames[0])
    elif suffix == ".gif":
        imageio.mimsave(path, frames, duration=1000.0 / FPS[".gif"], loop=0)
    else:
        with imageio.get_writer(path, fps=FPS[".mp4"], codec="libx264", quality=7, macro_block_size=8,
                                ffmpeg_log_level="error") as w:
            for f in frames:
                w.append_data(f)
