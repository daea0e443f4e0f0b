"""Renders: small sizes and few frames to keep the suite quick."""
import imageio.v3 as iio
import numpy as np
import pytest

from rollaway.sim import render, simulate
from rollaway.sim.render import frame_times
from tests.sim.conftest import make_scenario


@pytest.fixture
def small(monkeypatch):
    monkeypatch.setattr(render, "SIZES", {".mp4": (160, 96), ".png": (192, 108), ".gif": (128, 72)})
    monkeypatch.setattr(render, "FPS", {".mp4": 5, ".gif": 4})
    monkeypatch.setattr(render, "TIMELAPSE_VIDEO_S", 1.0)


def test_frame_times_timelapse_then_real_time():
    t, speed = frame_times(1000.0, None, 10)
    assert t[0] == 0 and t[-1] == 1000 and (speed > 1).all()
    t, speed = frame_times(908.0, 900.0, 10)
    assert (np.diff(t) > 0).all()
    assert speed[-1] == 1 and speed[0] > 1
    assert t[speed == 1][0] == pytest.approx(898.0)
    t, speed = frame_times(9.0, 1.0, 10)
    assert (speed == 1).all()


@pytest.mark.parametrize("suffix", [".png", ".gif", ".mp4"])
def test_render_files(small, tmp_path, suffix):
    path = tmp_path / f"skid{suffix}"
    s = make_scenario(grade_pct=20, tyre_road_mu=0.3, duration_s=3)
    r = simulate(s, render=path)
    assert r.outcome == "tyre_skid"
    frames = iio.imread(path, index=None) if suffix != ".png" else iio.imread(path)[None]
    assert frames.shape[0] >= 1
    w, h = render.SIZES[suffix]
    assert frames.shape[1:3] == (h, w)
    assert frames.std() > 10                       # not a blank picture
    if suffix != ".png":
        assert frames.shape[0] > 5


def test_render_options_and_rollaway_shown(tmp_path):
    """--size/--fps are obeyed and the video goes on after the roll-away until the car has visibly moved."""
    s = make_scenario(grade_pct=20, tyre_road_mu=0.3, duration_s=3)
    path = tmp_path / "r.gif"
    r = simulate(s, render=path, render_options={"size": (96, 64), "fps": 5, "after_s": 8.0})
    frames = iio.imread(path, index=None)
    assert frames.shape[1:3] == (64, 96)
    t_end = r.rollaway_time_s + 8.0
    assert frames.shape[0] >= int(5 * (t_end - max(r.rollaway_time_s - render.REALTIME_BEFORE_S, 0))
                                  / max(1, np.ceil(t_end / render.MAX_AFTER_VIDEO_S))) - 1


def test_frame_times_speeds_up_a_long_rollaway():
    t, speed = frame_times(100.0, 10.0, 10)
    assert speed[-1] == np.ceil(92.0 / render.MAX_AFTER_VIDEO_S) and t[-1] <= 100.0
    assert (speed[t >= 8.0] > 1).all()


def test_extension_keeps_the_result(tmp_path):
    s = make_scenario(grade_pct=20, tyre_road_mu=0.3, duration_s=3)
    a = simulate(s)
    b = simulate(s, render=tmp_path / "x.png")
    # the rendered run uses the car with its decorative geoms: the same physics to within one brake update
    assert a.outcome == b.outcome and a.rollaway_time_s == pytest.approx(b.rollaway_time_s, abs=0.02)


def test_shadow_map_is_sized_to_the_frame():
    """A power of two at or above the longer side (512–4096): 1024 for 640×480 keeps the driver's map at 4 MB."""
    assert render.shadow_map_size(640, 480) == 1024
    assert render.shadow_map_size(1920, 1080) == 2048
    assert render.shadow_map_size(96, 64) == 512
    assert render.shadow_map_size(3840, 2160) == 4096 and render.shadow_map_size(1024, 768) == 1024


def test_render_buffers_fit_the_frame(tmp_path, monkeypatch):
    """The off-screen buffer is the frame's size (not the model's 1280×720) and the shadow map follows it."""
    seen = {}
    real = render.mujoco.Renderer

    def spy(model, *a, **k):
        seen.update(off=(model.vis.global_.offwidth, model.vis.global_.offheight),
                    shadow=model.vis.quality.shadowsize)
        return real(model, *a, **k)
    monkeypatch.setattr(render.mujoco, "Renderer", spy)
    simulate(make_scenario(grade_pct=20, tyre_road_mu=0.3, duration_s=3), render=tmp_path / "r.png",
             render_options={"size": (320, 200)})
    assert seen == {"off": (320, 200), "shadow": 512}
