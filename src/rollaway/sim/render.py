"""Off-screen renders of a simulated run: MP4 (H.264), GIF or PNG with a heads-up overlay.

Rendering replays the recorded trajectory (one state per 20 ms brake update; during a
fast-mode skip the car provably stands still, so the last state holds).  After a roll-away
the simulation's own classification window is short (:data:`rollaway.sim.outcome.POST_ROLLAWAY_S`)
and a slow brake slip has moved the car only centimetres by then, so the render goes on
integrating the same MuJoCo model with the same brake controller (:func:`extend_after_rollaway`)
until the car has rolled at least :data:`AFTER_M` metres *and* :data:`AFTER_S` seconds have
passed (at most :data:`MAX_AFTER_S`).  This extension is for the picture only; the
:class:`~rollaway.sim.run.SimResult` is not changed by it.

Camera: from the car's right side, level horizon, standing still while the car is in the
picture and then following it slowly (the car stays in the right third), so the road moves
past: the yellow start line where the rear axle stood at t = 0, a dashed centre line (1 m
dashes every 2 m) and the posts along the far kerb (every 8 m) show the motion against the
road.  White head lamps mark the front, red tail lamps the back.

Timing: a hold is shown as a time-lapse (the whole duration in :data:`TIMELAPSE_VIDEO_S`
seconds of video).  Around a roll-away the video switches to real time
:data:`REALTIME_BEFORE_S` before it; a slow roll-away is sped up so that the part after it
lasts at most :data:`MAX_AFTER_VIDEO_S` seconds of video.  The overlay shows the simulated
time and playback speed, the distance moved, the drum temperature (eq. 10), the rear-axle
brake capacity against the demand T_req (eq. 23) and the status.

Speed and memory: frames are streamed to the encoder (MP4) or kept as 8-bit palette images (GIF),
never as a list of full frames; multisampling is off by default (it costs ~3× under software GL);
the off-screen buffer is the frame's size and the shadow map is sized to it
(:func:`shadow_map_size`), which keeps a 640×480 render under 200 MB with Mesa's llvmpipe.

Off-screen GL: with no ``DISPLAY``, :mod:`rollaway.sim` sets ``MUJOCO_GL=egl`` before MuJoCo
is imported (``osmesa`` works too, set it yourself).
"""
from __future__ import annotations

import math
from pathlib import Path

import mujoco
import numpy as np

from rollaway.errors import UserError, ensure_parent_dir

RENDER_SUFFIXES = (".mp4", ".gif", ".png")
TIMELAPSE_VIDEO_S = 3.0           # video seconds for a held car, or for the time before a roll-away
REALTIME_BEFORE_S = 2.0           # real time starts this long before the roll-away
AFTER_S = 8.0                     # show at least this long after the roll-away ...
AFTER_M = 10.0                    # ... and until the car has rolled this far
MAX_AFTER_S = 90.0                # but never simulate longer than this after the roll-away
MAX_AFTER_VIDEO_S = 10.0          # the part after the roll-away lasts at most this long in the video
SIZES = {".mp4": (640, 360), ".png": (960, 540), ".gif": (480, 270)}   # (width, height)
FPS = {".mp4": 25, ".gif": 10}
_FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf"
_FONT_BOLD = "/usr/share/fonts/truetype/dejavu/DejaVuSansMono-Bold.ttf"
_STATUS = {"held": ("HELD", (40, 150, 60)), "brake_slip": ("ROLLING AWAY: the brake slips", (200, 40, 30)),
           "tyre_skid": ("SLIDING AWAY: the rear tyres skid", (220, 110, 10))}


def check_render_path(path) -> Path:
    """Validate an output path (known suffix; its folder is created) and the GL setting (UserError)."""
    from rollaway.sim.gl import INVALID_MUJOCO_GL
    if INVALID_MUJOCO_GL is not None:
        raise UserError(f"--render {path}: MUJOCO_GL={INVALID_MUJOCO_GL!r} is not a MuJoCo GL backend; "
                        f"set MUJOCO_GL=egl or MUJOCO_GL=osmesa (or unset it)")
    p = Path(path)
    if p.suffix.lower() not in RENDER_SUFFIXES:
        raise UserError(f"--render {path}: unknown file type '{p.suffix or '(none)'}'; "
                        f"use one of {', '.join(RENDER_SUFFIXES)}")
    return ensure_parent_dir(p, "--render")


def check_render_options(size=None, fps=None, after_s=AFTER_S, multisample=0, **_) -> None:
    """UserError (naming the option) for a frame rate, duration or sample count out of range."""
    if fps is not None and not (1 <= fps <= 120):
        raise UserError(f"--fps {fps:g}: give a frame rate from 1 to 120, e.g. --fps 30")
    if not (0 <= after_s <= MAX_AFTER_S):
        raise UserError(f"--after-s {after_s:g}: give 0–{MAX_AFTER_S:g} seconds, e.g. --after-s 10")
    if multisample not in (0, 2, 4, 8):
        raise UserError(f"--multisample {multisample}: give 0 (off), 2, 4 or 8")
    if size is not None and (size[0] > 3840 or size[1] > 2160):
        raise UserError(f"--size {size[0]}x{size[1]}: at most 3840x2160")


def frame_times(t_end_s: float, rollaway_s: float | None, fps: float,
                max_after_video_s: float = MAX_AFTER_VIDEO_S) -> tuple[np.ndarray, np.ndarray]:
    """Simulated time of each frame and its playback speed (1 real time, > 1 time-lapse)."""
    n_tl = max(int(TIMELAPSE_VIDEO_S * fps), 1)
    if rollaway_s is None:
        t = np.linspace(0.0, t_end_s, n_tl)
        return t, np.full(t.shape, max(t_end_s / TIMELAPSE_VIDEO_S, 1.0))
    t_rt = max(rollaway_s - REALTIME_BEFORE_S, 0.0)
    speed = max(1.0, math.ceil((t_end_s - t_rt) / max_after_video_s))   # whole-number speed-up
    rt = np.arange(t_rt, t_end_s + 1e-9, speed / fps)
    if t_rt <= n_tl / fps:        # short lead-in: no time-lapse before
        rt = np.arange(0.0, t_end_s + 1e-9, speed / fps)
        return rt, np.full(rt.shape, speed)
    tl = np.linspace(0.0, t_rt, n_tl, endpoint=False)
    return np.concatenate([tl, rt]), np.concatenate([np.full(tl.shape, t_rt / TIMELAPSE_VIDEO_S),
                                                     np.full(rt.shape, speed)])


def extend_after_rollaway(runner, result, after_s: float = AFTER_S, after_m: float = AFTER_M,
                          max_after_s: float = MAX_AFTER_S):
    """Go on integrating a rolled-away run for the picture; return (time_s, qpos, displacement_m, capacity_Nm).

    The arrays continue the recorded trace, one record per brake update, until ``after_s``
    seconds after the roll-away *and* ``after_m`` metres of travel (at most ``max_after_s``).
    The brake controller keeps its capacity series (held at its last value past the run's horizon).
    """
    from rollaway.sim.brake_callback import UPDATE_STEPS
    tr = result.trace
    t, q, x, cap = [tr.time_s], [tr.qpos], [tr.displacement_m], [tr.capacity_Nm.sum(axis=1)]
    t_roll = result.rollaway_time_s
    if t_roll is None:
        return tr.time_s, tr.qpos, tr.displacement_m, cap[0]
    m, d, ctrl, info = runner.model, runner.data, runner.ctrl, runner.info
    p0, pos = runner.p0, runner.pos
    t_stop = t_roll + max(after_s, 0.0)
    t_max = t_roll + max_after_s
    ext_t, ext_q, ext_x, ext_c = [], [], [], []
    s = float(tr.displacement_m[-1])
    while d.time < t_max and (d.time < t_stop or abs(s) < after_m):
        c = ctrl.update(m, d)
        mujoco.mj_step(m, d, nstep=UPDATE_STEPS)
        s = float((d.qpos[pos] - p0) @ info.downhill_unit)
        if not np.isfinite(s):
            break
        ext_t.append(d.time)
        ext_q.append(d.qpos.copy())
        ext_x.append(s)
        ext_c.append(float(c.sum()))
    if ext_t:
        t.append(np.array(ext_t))
        q.append(np.array(ext_q))
        x.append(np.array(ext_x))
        cap.append(np.array(ext_c))
    return np.concatenate(t), np.concatenate(q), np.concatenate(x), np.concatenate(cap)


class _Hud:
    """The overlay: a dark band with three lines, a capacity bar and the status, sized to the picture."""

    def __init__(self, width: int, height: int):
        from PIL import ImageFont
        size = max(int(min(width / 34, height / 16)), 12)
        self.font = self._font(_FONT, size)
        self.bold = self._font(_FONT_BOLD, size)
        self.small = self._font(_FONT, max(int(size * 0.8), 11))
        self.line = int(size * 1.3)

    @staticmethod
    def _font(path, size):
        from PIL import ImageFont
        try:
            return ImageFont.truetype(path, size)
        except OSError:
            return ImageFont.load_default(size=size)

    def draw(self, frame: np.ndarray, lines: list[str], status: tuple[str, tuple], margin: float,
             footer: str) -> np.ndarray:
        from PIL import Image, ImageDraw
        img = Image.fromarray(frame)
        g = ImageDraw.Draw(img, "RGBA")
        w, h, L = img.width, img.height, self.line
        g.rectangle([0, 0, w, (len(lines) + 1) * L + 10], fill=(0, 0, 0, 150))
        for i, text in enumerate(lines):
            g.text((8, 5 + i * L), text, font=self.font, fill=(255, 255, 255))
        y = 5 + len(lines) * L
        tw = int(g.textlength(status[0], font=self.bold))
        g.rectangle([4, y, 12 + tw, y + L], fill=status[1])
        g.text((8, y + 1), status[0], font=self.bold, fill=(255, 255, 255))
        # capacity bar right of the status: full width = 2 × demand, yellow mark = demand
        x0, x1 = 24 + tw, w - 8
        if x1 - x0 > 60:
            fill = int((x1 - x0) * min(max(margin, 0.0), 2.0) / 2.0)
            g.rectangle([x0, y + 3, x1, y + L - 3], outline=(255, 255, 255))
            g.rectangle([x0, y + 3, x0 + fill, y + L - 3], fill=(60, 170, 230) if margin >= 1 else (220, 50, 40))
            xm = (x0 + x1) // 2
            g.line([xm, y, xm, y + L], fill=(255, 230, 0), width=3)
        fh = int(L * 0.9)
        g.rectangle([0, h - fh - 6, w, h], fill=(0, 0, 0, 130))
        g.text((8, h - fh - 3), footer, font=self.small, fill=(255, 255, 255))
        return np.asarray(img)


def _add_geom(scene, gtype, size, pos, mat, rgba) -> None:
    if scene.ngeom >= scene.maxgeom:
        return
    mujoco.mjv_initGeom(scene.geoms[scene.ngeom], gtype, np.asarray(size, float), np.asarray(pos, float),
                        np.asarray(mat, float).ravel(), np.asarray(rgba, np.float32))
    scene.ngeom += 1


def _decorate(scene, data, info, origin: np.ndarray, s_view: float, view_half_m: float) -> None:
    """Road markings (start line, dashed centre line) and head/tail lamps, added to the scene."""
    th = info.theta_rad
    u = np.array([math.cos(th), 0.0, -math.sin(th)])              # downhill along the road
    nrm = np.array([math.sin(th), 0.0, math.cos(th)])             # road normal
    road = np.column_stack([u, [0.0, 1.0, 0.0], nrm])             # road frame as a rotation matrix
    box = mujoco.mjtGeom.mjGEOM_BOX
    base = origin - origin @ nrm * nrm + 0.004 * nrm               # on the road surface under the start point
    _add_geom(scene, box, [0.08, 4.0, 0.004], base, road, [1.0, 0.85, 0.0, 1.0])      # start line
    s0 = math.floor((s_view - view_half_m - 4) / 2.0) * 2.0
    for k in range(int((2 * view_half_m + 8) / 2.0) + 1):
        _add_geom(scene, box, [0.5, 0.06, 0.004], base + (s0 + 2.0 * k + 0.5) * u - 1.8 * np.array([0, 1.0, 0]),
                  road, [0.95, 0.95, 0.95, 1.0])
    R = data.xmat[info.car_body].reshape(3, 3)
    p = data.xpos[info.car_body]
    _add_geom(scene, box, [0.06, 0.8, 0.09], p + R @ [-3.45, 0.0, 0.5], R, [0.12, 0.12, 0.12, 1.0])   # rear bumper
    for x, z, rgba in ((0.88, 0.72, [1.0, 1.0, 0.8, 1.0]), (-3.47, 0.76, [1.0, 0.0, 0.0, 1.0])):
        for y in (0.6, -0.6):
            _add_geom(scene, box, [0.07, 0.16, 0.08], p + R @ [x, y, z], R, rgba)


def shadow_map_size(width: int, height: int) -> int:
    """Side of the shadow map in texels: the next power of two at or above the frame's longer side, 512–4096.

    The map is a square depth texture held by the GL driver (4 bytes a texel, so 64 MB at MuJoCo's
    default 4096); a map finer than the picture adds memory and no visible detail.
    """
    side = max(int(width), int(height), 512)
    return int(min(4096, 1 << (side - 1).bit_length()))


def render_run(runner, result, path, size: tuple[int, int] | None = None, fps: float | None = None,
               after_s: float = AFTER_S, after_m: float = AFTER_M, multisample: int = 0) -> Path:
    """Render a finished :class:`rollaway.sim.run._Run` with its :class:`SimResult` to *path*."""
    path = check_render_path(path)
    check_render_options(size=size, fps=fps, after_s=after_s, multisample=multisample)
    suffix = path.suffix.lower()
    width, height = size or SIZES[suffix]
    fps = float(fps or FPS.get(suffix, 10))
    ctrl, info, sc = runner.ctrl, runner.info, runner.scenario
    t_rec, q_rec, x_rec, cap_rec = extend_after_rollaway(runner, result, after_s, after_m)
    t_roll = result.rollaway_time_s
    if suffix == ".png":
        t_key = min(t_roll + 3.0, t_rec[-1]) if t_roll is not None else t_rec[-1]
        times, speed = np.array([t_key]), np.array([0.0])          # 0: a still picture
    else:
        times, speed = frame_times(float(t_rec[-1]), t_roll, fps)
    model = runner.model
    model.vis.quality.offsamples = int(multisample)
    model.vis.quality.shadowsize = shadow_map_size(width, height)
    model.vis.global_.offwidth, model.vis.global_.offheight = width, height   # buffers no larger than the frame
    data = mujoco.MjData(model)
    try:
        renderer = mujoco.Renderer(model, height=height, width=width, max_geom=2000)
    except Exception as exc:  # no GL context: say how to get one
        raise UserError(f"cannot render off-screen ({exc}); set MUJOCO_GL=egl or MUJOCO_GL=osmesa "
                        f"(apt-get install libegl1 or libosmesa6)") from None
    cam = mujoco.MjvCamera()
    cam.type = mujoco.mjtCamera.mjCAMERA_FREE
    aspect = width / height
    travel = float(np.max(np.abs(x_rec)))
    view_half = 7.0                                   # half the road length in the picture [m]
    cam.distance = view_half / (math.tan(math.radians(model.vis.global_.fovy / 2)) * aspect)
    cam.azimuth, cam.elevation = 90.0, -8.0
    opt = mujoco.MjvOption()
    hud = _Hud(width, height)
    sign = 1.0 if travel == 0 or x_rec[np.argmax(np.abs(x_rec))] >= 0 else -1.0
    origin = None
    writer = _Writer(path, suffix, fps)
    try:
        for t, sp in zip(times, speed):
            r = max(int(np.searchsorted(t_rec, t, side="right")) - 1, 0)
            data.qpos[:] = q_rec[r]
            mujoco.mj_forward(model, data)
            car = data.subtree_com[info.car_body].copy()
            if origin is None:
                origin = car.copy()
                rear0 = data.xpos[info.car_body] + data.xmat[info.car_body].reshape(3, 3) @ [-2.6, 0.0, 0.0]
            # camera: still while the car is within 55 % of the half view, then it follows (car in the outer third)
            s_cam = sign * max(abs(x_rec[r]) - 0.55 * view_half, 0.0)
            cam.lookat[:] = origin + s_cam * info.downhill_unit + [0.0, 0.0, 0.9]
            renderer.update_scene(data, camera=cam, scene_option=opt)
            _decorate(renderer.scene, data, info, rear0, s_cam, view_half)
            k = ctrl.index(min(t, ctrl.time_s[-1]))
            cap = float(cap_rec[r])
            rolled = t_roll is not None and t >= t_roll
            status = _STATUS[result.outcome if rolled else "held"]
            play = ("snapshot" if sp == 0 else "real time" if sp == 1.0 else
                    f"{sp:.0f}x speed" if sp < 20 else f"time-lapse {sp:.0f}x")
            lines = [f"t = {t:6.1f} s ({play})   moved {x_rec[r]:+.2f} m",
                     f"drum {ctrl.drum_temp_C[k]:5.1f} °C  brake {cap:.0f} of {info.demand_axle_Nm:.0f} N·m needed"]
            footer = (f"{info.grade_pct:g} % grade, facing {info.facing}, {sc.hand_force_N:g} N on the lever · "
                      f"white lamps: front")
            writer.append(hud.draw(renderer.render(), lines, status, cap / info.demand_axle_Nm, footer))
    finally:
        renderer.close()
        writer.close()
    return path


class _Writer:
    """Streams frames to the file: MP4 through ffmpeg, GIF as palette images, PNG one frame."""

    def __init__(self, path: Path, suffix: str, fps: float):
        self.path, self.suffix, self.fps = path, suffix, fps
        self.gif: list = []
        self.mp4 = None
        if suffix == ".mp4":
            import imageio.v2 as imageio
            self.mp4 = imageio.get_writer(path, fps=fps, codec="libx264", quality=7, macro_block_size=8,
                                          ffmpeg_log_level="error", output_params=["-preset", "veryfast"])

    def append(self, frame: np.ndarray) -> None:
        if self.suffix == ".mp4":
            self.mp4.append_data(frame)
        elif self.suffix == ".gif":
            from PIL import Image
            self.gif.append(Image.fromarray(frame).quantize(colors=128, method=Image.Quantize.MEDIANCUT))
        else:
            import imageio.v2 as imageio
            imageio.imwrite(self.path, frame)

    def close(self) -> None:
        if self.mp4 is not None:
            self.mp4.close()
            self.mp4 = None
        if self.gif:
            self.gif[0].save(self.path, save_all=True, append_images=self.gif[1:], loop=0,
                             duration=int(round(1000.0 / self.fps)), optimize=False)
            self.gif = []
